// The supervisor of run_process: see process_supervisor.hpp for its reports and
// emnet/core/process.hpp for what it guarantees. System calls only from here on: this code
// runs after a fork of a process that may have other threads.
//
// The program is started with vfork: it shares the supervisor's memory until its exec, so the
// fork copies no page tables (the supervisor is a copy of a calling process that may be
// large). Until the exec the child only makes system calls on values prepared before the fork
// and on its own stack frame; every signal is blocked across the vfork so that no handler can
// run in the shared memory, and the child sets default handling before it unblocks them.
#include "process_supervisor.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "posix_handles.hpp"

namespace emnet {

std::int64_t monotonic_nanoseconds() {
  timespec now{};
  ::clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<std::int64_t>(now.tv_sec) * 1000000000 + now.tv_nsec;
}

namespace {

void send_report(int control, SupervisorReportKind kind, int value, std::int64_t time) {
  SupervisorReport report;
  std::memset(&report, 0, sizeof report);
  report.kind = kind;
  report.value = value;
  report.monotonic_nanoseconds = time;
  const char* bytes = reinterpret_cast<const char*>(&report);
  std::size_t left = sizeof report;
  while (left > 0) {
    // MSG_NOSIGNAL: the caller may be gone; the report is then simply lost.
    const ssize_t sent = ::send(control, bytes, left, MSG_NOSIGNAL);
    if (sent < 0) {
      if (errno == EINTR) continue;
      return;
    }
    bytes += sent;
    left -= static_cast<std::size_t>(sent);
  }
}

// `descriptor` moved to a number above the standard streams (the program's 0, 1 and 2 are
// set from it later), closing the original; -1 stays -1.
int above_standard_streams(int descriptor) {
  if (descriptor < 0 || descriptor > STDERR_FILENO) return descriptor;
  const int moved = ::fcntl(descriptor, F_DUPFD_CLOEXEC, STDERR_FILENO + 1);
  ::close(descriptor);
  return moved;
}

// Closes every descriptor from 3 on except those in `keep` (sorted, each above 2).
void close_other_descriptors(const int* keep, int count) {
  unsigned first = STDERR_FILENO + 1;
  for (int k = 0; k <= count; ++k) {
    const unsigned last = k < count ? static_cast<unsigned>(keep[k]) - 1 : ~0U;
    if (first <= last && ::syscall(SYS_close_range, first, last, 0) != 0) {
      // Kernels before 5.9: one close per descriptor up to the limit (there is no other).
      rlimit limit{};
      ::getrlimit(RLIMIT_NOFILE, &limit);
      rlim_t end = limit.rlim_cur < (rlim_t{1} << 20) ? limit.rlim_cur : (rlim_t{1} << 20);
      if (end > last) end = last;
      for (unsigned descriptor = first; descriptor <= end; ++descriptor) ::close(descriptor);
    }
    if (k < count) first = static_cast<unsigned>(keep[k]) + 1;
  }
}

// Every handler back to the default, then every signal unblocked.
void reset_signal_handling() {
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  ::sigemptyset(&default_action.sa_mask);
  for (int signal_number = 1; signal_number < NSIG; ++signal_number)
    ::sigaction(signal_number, &default_action, nullptr);  // fails harmlessly for KILL, STOP
  sigset_t none;
  ::sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
}

// The decimal digits of `number` (>= 0) written at `out`; returns the end.
char* append_decimal(char* out, long number) {
  char digits[24];
  int count = 0;
  do {
    digits[count++] = static_cast<char>('0' + number % 10);
    number /= 10;
  } while (number > 0);
  while (count > 0) *out++ = digits[--count];
  return out;
}

// The parent pid in /proc/<pid>/stat ("pid (comm) state ppid ..."; comm may hold spaces and
// parentheses, so the fields after the last ')'); -1 when unreadable.
pid_t parent_of(const char* pid_text) {
  char path[64] = "/proc/";
  std::size_t length = 6;
  for (const char* c = pid_text; *c && length < 50; ++c) path[length++] = *c;
  std::memcpy(path + length, "/stat", 6);
  const int descriptor = ::open(path, O_RDONLY | O_CLOEXEC);
  if (descriptor < 0) return -1;
  char stat[512];
  const std::size_t count = read_chunk(descriptor, stat, sizeof stat - 1);
  ::close(descriptor);
  stat[count] = '\0';
  const char* close_parenthesis = nullptr;
  for (const char* c = stat; *c; ++c)
    if (*c == ')') close_parenthesis = c;
  if (!close_parenthesis) return -1;
  const char* c = close_parenthesis + 1;
  while (*c == ' ') ++c;
  if (!*c) return -1;
  ++c;  // the state letter
  while (*c == ' ') ++c;
  pid_t parent = 0;
  if (*c < '0' || *c > '9') return -1;
  for (; *c >= '0' && *c <= '9'; ++c) parent = parent * 10 + (*c - '0');
  return parent;
}

// SIGKILL to every process whose parent is this one, found by a scan of every /proc/<pid>.
void kill_own_children_by_scan(pid_t self) {
  const int proc = ::open("/proc", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (proc < 0) return;
  alignas(8) char entries[8192];
  for (;;) {
    const long count = ::syscall(SYS_getdents64, proc, entries, sizeof entries);
    if (count <= 0) break;
    for (long offset = 0; offset < count;) {
      // struct linux_dirent64: inode (8), offset (8), record length (2), type (1), name.
      unsigned short record_length;
      std::memcpy(&record_length, entries + offset + 16, sizeof record_length);
      const char* name = entries + offset + 19;
      offset += record_length;
      bool is_pid = *name != '\0';
      pid_t pid = 0;
      for (const char* c = name; *c; ++c) {
        if (*c < '0' || *c > '9') is_pid = false;
        pid = pid * 10 + (*c - '0');
      }
      if (is_pid && pid != self && parent_of(name) == self) ::kill(pid, SIGKILL);
    }
  }
  ::close(proc);
}

// SIGKILL to every process whose parent is this one: the list in
// /proc/<pid>/task/<pid>/children (the supervisor has one thread), or, on a kernel without
// that file, a scan of every process's parent.
void kill_own_children() {
  const pid_t self = ::getpid();
  char path[96] = "/proc/";
  char* end = append_decimal(path + 6, self);
  std::memcpy(end, "/task/", 6);
  end = append_decimal(end + 6, self);
  std::memcpy(end, "/children", 10);
  const int children = ::open(path, O_RDONLY | O_CLOEXEC);
  if (children < 0) {
    kill_own_children_by_scan(self);
    return;
  }
  char text[4096];
  pid_t pid = 0;
  bool in_number = false;
  for (std::size_t count; (count = read_chunk(children, text, sizeof text)) > 0;) {
    for (std::size_t k = 0; k < count; ++k) {
      if (text[k] >= '0' && text[k] <= '9') {
        pid = pid * 10 + (text[k] - '0');
        in_number = true;
      } else if (in_number) {
        if (pid > 0) ::kill(pid, SIGKILL);
        pid = 0;
        in_number = false;
      }
    }
  }
  if (in_number && pid > 0) ::kill(pid, SIGKILL);
  ::close(children);
}

void on_child_signal(int) {}

// `descriptor` (or /dev/null opened with `flags` when it is -1) as the standard stream
// `target`.
void set_standard_stream(int descriptor, int target, int flags) {
  if (descriptor >= 0) {
    ::dup2(descriptor, target);
    return;
  }
  const int null_device = ::open("/dev/null", flags);
  if (null_device >= 0 && null_device != target) {
    ::dup2(null_device, target);
    ::close(null_device);
  }
}

// In the vfork child, until its exec: system calls on prepared values only.
[[noreturn]] void run_program(const SupervisorPlan& plan, int input, int output, int error,
                              int exec_report) {
  ::setpgid(0, 0);
  set_standard_stream(input, STDIN_FILENO, O_RDONLY);
  set_standard_stream(output, STDOUT_FILENO, O_WRONLY);
  set_standard_stream(error, STDERR_FILENO, O_WRONLY);
  int failure = 0;
  if (plan.working_directory && ::chdir(plan.working_directory) != 0) failure = errno;
  if (failure == 0) {
    const rlimit file_size{plan.file_size_limit, plan.file_size_limit};
    ::setrlimit(RLIMIT_FSIZE, &file_size);
    reset_signal_handling();
    ::execve(plan.path, plan.arguments, plan.environment);
    failure = errno;
  }
  write_fully(exec_report, &failure, sizeof failure);
  ::_exit(127);
}

}  // namespace

[[noreturn]] void run_supervisor(const SupervisorPlan& plan) {
  // Terminal signals and a broken pipe must not end the supervisor before it has cleaned
  // up; the end of the caller shows on the control socket.
  reset_signal_handling();
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  for (const int signal_number :
       {SIGINT, SIGQUIT, SIGTERM, SIGHUP, SIGPIPE, SIGTSTP, SIGTTIN, SIGTTOU, SIGUSR1, SIGUSR2})
    ::sigaction(signal_number, &ignore, nullptr);
  struct sigaction child_action {};
  child_action.sa_handler = on_child_signal;
  child_action.sa_flags = SA_NOCLDSTOP;
  ::sigaction(SIGCHLD, &child_action, nullptr);
  sigset_t child_only, unblocked;
  ::sigemptyset(&child_only);
  ::sigaddset(&child_only, SIGCHLD);
  ::sigprocmask(SIG_BLOCK, &child_only, &unblocked);
  ::sigdelset(&unblocked, SIGCHLD);
  ::prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0);  // without it: the process group only

  const int input = above_standard_streams(plan.input);
  const int output = above_standard_streams(plan.output);
  const int error = above_standard_streams(plan.error);
  const int control = above_standard_streams(plan.control);
  int keep[4];
  int kept = 0;
  for (const int descriptor : {input, output, error, control})
    if (descriptor >= 0) {
      int at = kept++;  // insertion into the sorted list
      for (; at > 0 && keep[at - 1] > descriptor; --at) keep[at] = keep[at - 1];
      keep[at] = descriptor;
    }
  close_other_descriptors(keep, kept);

  int exec_report[2];
  if (::pipe2(exec_report, O_CLOEXEC) != 0) {
    send_report(control, SupervisorReportKind::not_executed, errno, monotonic_nanoseconds());
    ::_exit(0);
  }
  sigset_t every_signal, before;
  ::sigfillset(&every_signal);
  ::sigprocmask(SIG_SETMASK, &every_signal, &before);
  const std::int64_t start = monotonic_nanoseconds();
  const pid_t program = ::vfork();
  if (program == 0) run_program(plan, input, output, error, exec_report[1]);
  const int vfork_error = errno;
  ::sigprocmask(SIG_SETMASK, &before, nullptr);
  if (program < 0) {
    send_report(control, SupervisorReportKind::not_executed, vfork_error, start);
    ::_exit(0);
  }
  ::setpgid(program, program);  // also here: the group must exist before any kill of it
  for (const int descriptor : {input, output, error, exec_report[1]})
    if (descriptor >= 0) ::close(descriptor);
  // The child has run its exec (or failed and ended) when vfork returns: the pipe holds its
  // errno, or is at its end.
  int exec_error = 0;
  if (read_chunk(exec_report[0], reinterpret_cast<char*>(&exec_error), sizeof exec_error) !=
      sizeof exec_error)
    exec_error = 0;
  ::close(exec_report[0]);
  if (exec_error != 0) {
    int status;
    while (::waitpid(program, &status, 0) < 0 && errno == EINTR) {
    }
    send_report(control, SupervisorReportKind::not_executed, exec_error, start);
    ::_exit(0);
  }
  send_report(control, SupervisorReportKind::started, program, start);

  bool ended = false;
  int wait_status = 0;
  std::int64_t end = 0;
  for (;;) {
    int status;
    for (pid_t pid; (pid = ::waitpid(-1, &status, WNOHANG)) > 0;)
      if (pid == program) {
        end = monotonic_nanoseconds();
        ended = true;
        wait_status = status;
      }
    if (ended) break;
    pollfd descriptor = {control, POLLIN, 0};
    if (::ppoll(&descriptor, 1, nullptr, &unblocked) <= 0) continue;  // SIGCHLD: reap
    if (descriptor.revents) break;  // the caller asks to stop (or is gone)
  }

  // Everything that is left: the program's group, then every process re-parented here,
  // until no child is left.
  ::kill(-program, SIGKILL);
  for (;;) {
    kill_own_children();
    int status;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid == program && !ended) {
      end = monotonic_nanoseconds();
      ended = true;
      wait_status = status;
    }
    if (pid < 0 && errno != EINTR) break;  // ECHILD: none left
  }
  send_report(control, SupervisorReportKind::ended, wait_status, end);
  ::_exit(0);
}

}  // namespace emnet
