// A program under a supervisor that kills everything it started; see supervised_program.hpp.
//
// The supervisor talks to this process over a socket pair, in reports of two ints
// (kind, value), at most three of them: started (the program's pid), not executed (errno of
// execve), ended (the program's wait status). This process sends nothing: closing its end is
// the request to stop.
#include "supervised_program.hpp"

#include <dirent.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/syscall.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "posix_handles.hpp"

extern char** environ;

namespace emnet {

namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kChunkBytes = 65536;
constexpr double kSupervisorGraceSeconds = 2.0;

enum ReportKind : int { report_started = 1, report_not_executed = 2, report_ended = 3 };

// ---- in the supervisor and the program, after fork: system calls only ------------------

void write_report(int control, int kind, int value) {
  const int report[2] = {kind, value};
  // MSG_NOSIGNAL: the parent may be gone; the report is then simply lost.
  while (::send(control, report, sizeof report, MSG_NOSIGNAL) < 0 && errno == EINTR) {
  }
}

// `descriptor` moved to a number above the standard streams (the program's 0, 1 and 2 are
// set from it later), closing the original.
int above_standard_streams(int descriptor) {
  if (descriptor > STDERR_FILENO) return descriptor;
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
      const unsigned end =
          static_cast<unsigned>(std::min<rlim_t>(last, std::min<rlim_t>(limit.rlim_cur, 1u << 20)));
      for (unsigned descriptor = first; descriptor <= end; ++descriptor) ::close(descriptor);
    }
    if (k < count) first = static_cast<unsigned>(keep[k]) + 1;
  }
}

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

// SIGKILL to every process whose parent is this one.
void kill_own_children() {
  const int proc = ::open("/proc", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (proc < 0) return;
  const pid_t self = ::getpid();
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

void on_child_signal(int) {}

[[noreturn]] void run_program_child(const char* path, char* const* argv, char* const* envp,
                                    int output, int error, int exec_report, rlim_t size_limit) {
  ::setpgid(0, 0);
  const int null_input = ::open("/dev/null", O_RDONLY);
  if (null_input >= 0 && null_input != STDIN_FILENO) {
    ::dup2(null_input, STDIN_FILENO);
    ::close(null_input);
  }
  ::dup2(output, STDOUT_FILENO);
  ::dup2(error, STDERR_FILENO);
  const rlimit file_size{size_limit, size_limit};
  ::setrlimit(RLIMIT_FSIZE, &file_size);
  reset_signal_handling();
  ::execve(path, argv, envp);
  const int exec_error = errno;
  write_fully(exec_report, &exec_error, sizeof exec_error);
  ::_exit(127);
}

[[noreturn]] void supervisor_main(const char* path, char* const* argv, char* const* envp,
                                  int output, int error, int control, rlim_t size_limit) {
  // Terminal signals and a broken pipe must not end the supervisor before it has cleaned
  // up; the end of this process shows on the control socket.
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

  output = above_standard_streams(output);
  error = above_standard_streams(error);
  control = above_standard_streams(control);
  int keep[3] = {output, error, control};
  std::sort(keep, keep + 3);
  close_other_descriptors(keep, 3);

  int exec_report[2];
  if (::pipe2(exec_report, O_CLOEXEC) != 0) {
    write_report(control, report_not_executed, errno);
    ::_exit(0);
  }
  const pid_t program = ::fork();
  if (program < 0) {
    write_report(control, report_not_executed, errno);
    ::_exit(0);
  }
  if (program == 0) {
    ::close(control);
    ::close(exec_report[0]);
    run_program_child(path, argv, envp, output, error, exec_report[1], size_limit);
  }
  ::setpgid(program, program);  // also here: the group must exist before any kill of it
  ::close(output);
  ::close(error);
  ::close(exec_report[1]);
  write_report(control, report_started, program);

  bool ended = false;
  int wait_status = 0, exec_error = 0;
  const auto reap_ready = [&] {
    int status;
    for (pid_t pid; (pid = ::waitpid(-1, &status, WNOHANG)) > 0;)
      if (pid == program) {
        ended = true;
        wait_status = status;
      }
  };
  int exec_pipe = exec_report[0];
  const auto read_exec_report = [&] {
    int value;
    if (read_chunk(exec_pipe, reinterpret_cast<char*>(&value), sizeof value) == sizeof value)
      exec_error = value;
    ::close(exec_pipe);
    exec_pipe = -1;
  };
  for (;;) {
    reap_ready();
    if (ended) break;
    pollfd descriptors[2] = {{control, POLLIN, 0}, {exec_pipe, POLLIN, 0}};
    if (::ppoll(descriptors, 2, nullptr, &unblocked) <= 0) continue;  // SIGCHLD: reap
    if (descriptors[0].revents) break;  // this process asks to stop (or is gone)
    if (descriptors[1].revents) read_exec_report();
  }
  if (exec_pipe >= 0 && ended) read_exec_report();  // the program is gone: no blocking

  // Everything that is left: the program's group, then every process re-parented here,
  // until no child is left.
  ::kill(-program, SIGKILL);
  for (;;) {
    kill_own_children();
    int status;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid == program && !ended) {
      ended = true;
      wait_status = status;
    }
    if (pid < 0 && errno != EINTR) break;  // ECHILD: none left
  }
  if (exec_error != 0)
    write_report(control, report_not_executed, exec_error);
  else
    write_report(control, report_ended, wait_status);
  ::_exit(0);
}

// ---- in this process ----------------------------------------------------------------------

// The program's path as execvp finds it: a name with '/' as it is, else the first executable
// regular file in PATH (default "/bin:/usr/bin", an empty entry being the working directory).
bool find_program(const std::string& name, std::string& path, int& error) {
  if (name.empty()) {
    error = ENOENT;
    return false;
  }
  if (name.find('/') != std::string::npos) {
    path = name;
    return true;
  }
  const char* search = std::getenv("PATH");
  const std::string directories = search ? search : "/bin:/usr/bin";
  error = ENOENT;
  for (std::size_t begin = 0;;) {
    const std::size_t end = std::min(directories.find(':', begin), directories.size());
    const std::string directory = directories.substr(begin, end - begin);
    const std::string candidate = (directory.empty() ? "." : directory) + "/" + name;
    struct stat status {};
    if (::stat(candidate.c_str(), &status) == 0 && S_ISREG(status.st_mode)) {
      if (::access(candidate.c_str(), X_OK) == 0) {
        path = candidate;
        return true;
      }
      error = EACCES;
    }
    if (end >= directories.size()) return false;
    begin = end + 1;
  }
}

// `seconds` as a duration of the clock, at most 1e9 s (30 years: no overflow of the clock's
// 64-bit nanoseconds).
Clock::duration clock_duration(double seconds) {
  return std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(std::min(seconds, 1e9)));
}

// The supervisor as a handle: stopping it (closing the control socket) makes it kill the
// program's tree; one that does not end within the grace time is killed itself, with the
// program's process group.
class Supervisor {
 public:
  Supervisor(pid_t process_id, FileDescriptor control)
      : process_(process_id, /*leads_process_group=*/false), control_(std::move(control)) {}
  Supervisor(const Supervisor&) = delete;
  Supervisor& operator=(const Supervisor&) = delete;
  ~Supervisor() { stop(); }

  int control() const { return control_.get(); }
  void close_control() { control_.reset(); }
  void set_program(pid_t program) { program_ = program; }

  // Asks the supervisor to end (killing the tree) and waits for it, at most the grace time.
  void stop() {
    control_.reset();
    if (!process_.running()) return;
    const Clock::time_point give_up = Clock::now() + clock_duration(kSupervisorGraceSeconds);
    while (!process_.try_wait()) {
      if (Clock::now() > give_up) {
        if (program_ > 0) ::kill(-program_, SIGKILL);
        process_.kill();
        process_.wait_blocking();
        return;
      }
      ::usleep(1000);
    }
  }

 private:
  ChildProcess process_;
  FileDescriptor control_;
  pid_t program_ = -1;
};

}  // namespace

SupervisedProgramEnd run_supervised_program(
    const SupervisedProgramOptions& options,
    const std::function<void(ProgramStream, const char*, std::size_t)>& output) {
  SupervisedProgramEnd end;
  const auto failed = [&](std::string why) {
    end.how = SupervisedProgramEnd::How::failed;
    end.problem = std::move(why);
    return end;
  };
  if (options.arguments.empty()) return failed("no program given");
  std::string path;
  if (!find_program(options.arguments.front(), path, end.start_error)) {
    end.how = SupervisedProgramEnd::How::not_started;
    return end;
  }
  std::vector<std::string> arguments = options.arguments;
  std::vector<char*> argument_pointers;
  for (std::string& argument : arguments) argument_pointers.push_back(argument.data());
  argument_pointers.push_back(nullptr);
  const rlim_t size_limit = options.file_size_limit >= RLIM_INFINITY
                                ? RLIM_INFINITY
                                : static_cast<rlim_t>(options.file_size_limit);

  Pipe out, err;
  std::string why;
  if (!open_pipe(out, why) || !open_pipe(err, why)) return failed(why);
  int control_ends[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, control_ends) != 0)
    return failed("cannot create a socket pair: " + errno_text(errno));
  FileDescriptor control(control_ends[0]), supervisor_control(control_ends[1]);

  std::fflush(nullptr);  // the supervisor must not inherit unwritten output
  const Clock::time_point start = Clock::now();
  const pid_t process_id = ::fork();
  if (process_id < 0) return failed("cannot start the supervisor: " + errno_text(errno));
  if (process_id == 0) {
    ::close(out.read_end.get());
    ::close(err.read_end.get());
    ::close(control.get());
    supervisor_main(path.c_str(), argument_pointers.data(), environ, out.write_end.get(),
                    err.write_end.get(), supervisor_control.get(), size_limit);
  }
  Supervisor supervisor(process_id, std::move(control));
  out.write_end.reset();
  err.write_end.reset();
  supervisor_control.reset();

  // Read until the program's pipes and the supervisor's socket are closed or the time is up.
  const Clock::time_point deadline = start + clock_duration(std::max(0.0, options.timeout_seconds));
  std::string chunk(kChunkBytes, '\0');
  int report[2];
  std::size_t report_bytes = 0;
  bool reported_end = false;
  bool timed_out = false;
  while (out.read_end.is_open() || err.read_end.is_open() || supervisor.control() >= 0) {
    const double remaining = std::chrono::duration<double>(deadline - Clock::now()).count();
    if (remaining <= 0) {
      timed_out = true;
      break;
    }
    pollfd descriptors[3] = {{out.read_end.get(), POLLIN, 0},
                             {err.read_end.get(), POLLIN, 0},
                             {supervisor.control(), POLLIN, 0}};
    const int ready =
        ::poll(descriptors, 3, static_cast<int>(std::ceil(std::min(remaining, 1.0) * 1000)));
    if (ready < 0 && errno != EINTR) return failed("poll failed: " + errno_text(errno));
    if (ready <= 0) continue;
    const auto forward = [&](const pollfd& descriptor, FileDescriptor& end_of_pipe,
                             ProgramStream stream) {
      if (!(descriptor.revents & (POLLIN | POLLHUP | POLLERR))) return;
      const std::size_t count = read_chunk(end_of_pipe.get(), chunk.data(), chunk.size());
      if (count == 0)
        end_of_pipe.reset();
      else
        output(stream, chunk.data(), count);
    };
    forward(descriptors[0], out.read_end, ProgramStream::standard_output);
    forward(descriptors[1], err.read_end, ProgramStream::standard_error);
    if (descriptors[2].revents & (POLLIN | POLLHUP | POLLERR)) {
      char* bytes = reinterpret_cast<char*>(report);
      const std::size_t count =
          read_chunk(supervisor.control(), bytes + report_bytes, sizeof report - report_bytes);
      if (count == 0) {
        supervisor.close_control();  // the supervisor has ended
        continue;
      }
      report_bytes += count;
      if (report_bytes < sizeof report) continue;
      report_bytes = 0;
      if (report[0] == report_started) {
        supervisor.set_program(report[1]);
      } else if (report[0] == report_not_executed) {
        end.how = SupervisedProgramEnd::How::not_started;
        end.start_error = report[1];
        reported_end = true;
      } else if (report[0] == report_ended) {
        const int status = report[1];
        end.how = WIFSIGNALED(status) ? SupervisedProgramEnd::How::signalled
                                      : SupervisedProgramEnd::How::exited;
        end.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : 0;
        end.signal_number = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
        reported_end = true;
      }
    }
  }
  supervisor.stop();  // at the time limit: kills the tree; else it has ended already
  end.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (timed_out) {
    end.how = SupervisedProgramEnd::How::timed_out;
    return end;
  }
  if (!reported_end) return failed("the supervisor of the program ended without a report");
  return end;
}

}  // namespace emnet
