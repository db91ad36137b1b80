// run_process: the caller's side (emnet/core/process.hpp). It prepares everything the
// supervisor needs as plain C data, forks it (src/core/process_supervisor.cpp runs in the
// copy), and then, on the calling thread, writes the program's standard input, reads its
// output and the supervisor's reports, all through one poll loop that looks at the clock
// between bounded reads and writes.
#include "emnet/core/process.hpp"

#include <poll.h>
#include <pthread.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/syscall.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "posix_handles.hpp"
#include "process_supervisor.hpp"

extern char** environ;

namespace emnet {

namespace {

constexpr std::size_t kChunkBytes = 65536;
constexpr double kSupervisorGraceSeconds = 2.0;

double seconds_between(std::int64_t from, std::int64_t to) {
  return static_cast<double>(to - from) * 1e-9;
}

// The value of NAME for the program: from the additions, else this process's.
const char* program_environment_value(const ProcessOptions& options, const std::string& name) {
  for (auto it = options.environment_additions.rbegin(); it != options.environment_additions.rend();
       ++it)
    if (it->first == name) return it->second.c_str();
  return std::getenv(name.c_str());
}

// The program's path as execvp finds it: a name with '/' as it is, else the first executable
// regular file in PATH (default "/bin:/usr/bin", an empty entry being the working directory).
bool find_program(const std::string& name, const char* search, std::string& path, int& error) {
  if (name.empty()) {
    error = ENOENT;
    return false;
  }
  if (name.find('/') != std::string::npos) {
    path = name;
    return true;
  }
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

// This process's environment with the additions in place of (or besides) its own values.
std::vector<std::string> program_environment(const ProcessOptions& options) {
  std::vector<std::string> entries;
  const auto added = [&](const char* entry) {
    for (const auto& [name, value] : options.environment_additions)
      if (std::strncmp(entry, name.c_str(), name.size()) == 0 && entry[name.size()] == '=')
        return true;
    return false;
  };
  for (char** entry = environ; entry && *entry; ++entry)
    if (!added(*entry)) entries.emplace_back(*entry);
  // The last addition of a name wins.
  for (std::size_t k = 0; k < options.environment_additions.size(); ++k) {
    const std::string& name = options.environment_additions[k].first;
    bool overridden = false;
    for (std::size_t later = k + 1; later < options.environment_additions.size(); ++later)
      overridden = overridden || options.environment_additions[later].first == name;
    if (!overridden) entries.push_back(name + "=" + options.environment_additions[k].second);
  }
  return entries;
}

std::vector<char*> pointers_to(std::vector<std::string>& texts) {
  std::vector<char*> pointers;
  for (std::string& text : texts) pointers.push_back(text.data());
  pointers.push_back(nullptr);
  return pointers;
}

// write(2) to a pipe whose reader may be gone, without SIGPIPE: the signal is blocked in this
// thread for the call (a broken pipe raises it in the writing thread), and one that the call
// raised is taken back before the mask is restored.
ssize_t write_without_broken_pipe_signal(int descriptor, const char* data, std::size_t size) {
  sigset_t pipe_signal, previous, pending;
  ::sigemptyset(&pipe_signal);
  ::sigaddset(&pipe_signal, SIGPIPE);
  ::pthread_sigmask(SIG_BLOCK, &pipe_signal, &previous);
  ::sigpending(&pending);
  const bool already_pending = ::sigismember(&pending, SIGPIPE) == 1;
  ssize_t written;
  do {
    written = ::write(descriptor, data, size);
  } while (written < 0 && errno == EINTR);
  const int error = errno;
  if (written < 0 && error == EPIPE && !already_pending) {
    const timespec no_wait{0, 0};
    while (::sigtimedwait(&pipe_signal, nullptr, &no_wait) < 0 && errno == EINTR) {
    }
  }
  ::pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  errno = error;
  return written;
}

// A fork that runs none of this process's fork handlers (pthread_atfork: a host such as Python
// registers handlers that take locks and allocate, which the supervisor must not run): _Fork
// (glibc 2.34, async-signal-safe), else the clone system call itself.
pid_t fork_without_handlers() {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 34))
  return ::_Fork();
#else
  return static_cast<pid_t>(::syscall(SYS_clone, SIGCHLD, nullptr, nullptr, nullptr, nullptr));
#endif
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
  // The supervisor closed its end: it has exited or is exiting.
  void supervisor_closed_control() {
    control_.reset();
    exiting_ = true;
  }
  void set_program(pid_t program) { program_ = program; }

  // Asks the supervisor to end (killing the tree) and waits for it, at most the grace time.
  void stop() {
    control_.reset();
    if (!process_.running()) return;
    if (exiting_) {  // its descriptors are closed only when it exits
      process_.wait_blocking();
      return;
    }
    const std::int64_t give_up =
        monotonic_nanoseconds() + static_cast<std::int64_t>(kSupervisorGraceSeconds * 1e9);
    while (!process_.try_wait()) {
      if (monotonic_nanoseconds() > give_up) {
        if (program_ > 0) ::kill(-program_, SIGKILL);
        process_.kill();
        process_.wait_blocking();
        return;
      }
      ::usleep(200);
    }
  }

 private:
  ChildProcess process_;
  FileDescriptor control_;
  pid_t program_ = -1;
  bool exiting_ = false;
};

// An output stream's pipe (none when discarded) and what becomes of what it carries.
struct OutputPipe {
  const ProcessOutput* handling;
  std::string* captured;
  std::uint64_t* left_out;
  Pipe pipe;

  // Hands on one chunk; false when a callback asks to stop.
  bool take(const char* data, std::size_t size) {
    if (handling->kind == ProcessOutput::Kind::callback)
      return !handling->callback || handling->callback(data, size);
    const std::size_t room =
        handling->capture_limit - std::min(handling->capture_limit, captured->size());
    captured->append(data, std::min(room, size));
    *left_out += size - std::min(room, size);
    return true;
  }
};

std::string signal_description(int signal_number) {
  const char* name = ::strsignal(signal_number);
  return std::to_string(signal_number) + (name ? std::string(" (") + name + ")" : "");
}

}  // namespace

std::string ProcessResult::description() const {
  switch (how) {
    case How::exited:
      return "exited with status " + std::to_string(exit_status);
    case How::signalled:
      return "killed by signal " + signal_description(signal_number);
    case How::timed_out:
      return "timed out: killed with everything it started";
    case How::stopped:
      return "stopped: killed with everything it started";
    case How::not_started:
      return "could not be started: " + errno_text(error_number);
    case How::failed:
      break;
  }
  return "could not be run: " + problem;
}

ProcessResult run_process(const ProcessOptions& options) {
  ProcessResult result;
  const std::int64_t call_start = monotonic_nanoseconds();
  const auto finish = [&]() -> ProcessResult {
    result.total_seconds = seconds_between(call_start, monotonic_nanoseconds());
    return std::move(result);
  };
  const auto failed = [&](std::string why, int error_number = 0) {
    result.how = ProcessResult::How::failed;
    result.problem = std::move(why);
    result.error_number = error_number;
    return finish();
  };
  if (options.arguments.empty()) return failed("no program given");
  std::string path;
  if (!find_program(options.arguments.front(), program_environment_value(options, "PATH"), path,
                    result.error_number)) {
    result.how = ProcessResult::How::not_started;
    return finish();
  }
  if (!options.working_directory.empty() && path.front() != '/') {
    // Found relative to this process's working directory, not the program's.
    char* here = ::getcwd(nullptr, 0);
    if (!here) return failed("cannot read the working directory: " + errno_text(errno), errno);
    path = std::string(here) + "/" + path;
    std::free(here);
  }
  std::vector<std::string> arguments = options.arguments;
  std::vector<char*> argument_pointers = pointers_to(arguments);
  std::vector<std::string> environment = program_environment(options);
  std::vector<char*> environment_pointers = pointers_to(environment);

  Pipe input;
  OutputPipe outputs[2] = {
      {&options.standard_output,
       &result.standard_output,
       &result.standard_output_bytes_left_out,
       {}},
      {&options.standard_error, &result.standard_error, &result.standard_error_bytes_left_out, {}}};
  std::string why;
  if (options.standard_input && !open_pipe(input, why)) return failed(why, errno);
  for (OutputPipe& output : outputs)
    if (output.handling->kind != ProcessOutput::Kind::discard && !open_pipe(output.pipe, why))
      return failed(why, errno);
  int control_ends[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, control_ends) != 0)
    return failed("cannot create a socket pair: " + errno_text(errno), errno);
  FileDescriptor control(control_ends[0]), supervisor_control(control_ends[1]);

  SupervisorPlan plan;
  plan.path = path.c_str();
  plan.arguments = argument_pointers.data();
  plan.environment = environment_pointers.data();
  plan.working_directory =
      options.working_directory.empty() ? nullptr : options.working_directory.c_str();
  plan.input = input.read_end.get();
  plan.output = outputs[0].pipe.write_end.get();
  plan.error = outputs[1].pipe.write_end.get();
  plan.control = supervisor_control.get();
  plan.file_size_limit = options.file_size_limit >= RLIM_INFINITY
                             ? RLIM_INFINITY
                             : static_cast<rlim_t>(options.file_size_limit);

  // The supervisor never flushes this process's stdio buffers (it ends with _exit or exec).
  const pid_t process_id = fork_without_handlers();
  if (process_id < 0) return failed("cannot start the supervisor: " + errno_text(errno), errno);
  if (process_id == 0) run_supervisor(plan);
  Supervisor supervisor(process_id, std::move(control));
  input.read_end.reset();
  for (OutputPipe& output : outputs) output.pipe.write_end.reset();
  supervisor_control.reset();
  const std::string empty;
  const std::string& input_bytes = options.standard_input ? *options.standard_input : empty;
  std::size_t input_written = 0;
  if (input.write_end.is_open()) {
    if (input_bytes.empty())
      input.write_end.reset();
    else
      ::fcntl(input.write_end.get(), F_SETFL, O_NONBLOCK);
  }

  // Until the program's pipes and the supervisor's socket are closed, the time is up or a
  // callback says stop.
  const double timeout = std::min(std::max(0.0, options.timeout_seconds), 1e9);
  const std::int64_t deadline = call_start + static_cast<std::int64_t>(timeout * 1e9);
  std::string chunk(kChunkBytes, '\0');
  SupervisorReport report;
  std::size_t report_bytes = 0;
  bool reported_end = false, timed_out = false, stopped = false;
  std::int64_t program_start = 0, program_end = 0;
  while (outputs[0].pipe.read_end.is_open() || outputs[1].pipe.read_end.is_open() ||
         supervisor.control() >= 0) {
    const std::int64_t now = monotonic_nanoseconds();
    if (now >= deadline) {
      timed_out = true;
      break;
    }
    if (options.stop_requested && options.stop_requested()) {
      stopped = true;
      break;
    }
    pollfd descriptors[4] = {{outputs[0].pipe.read_end.get(), POLLIN, 0},
                             {outputs[1].pipe.read_end.get(), POLLIN, 0},
                             {supervisor.control(), POLLIN, 0},
                             {input.write_end.get(), POLLOUT, 0}};
    const double remaining = seconds_between(now, deadline);
    const double wait = std::min(remaining, options.stop_requested ? 0.1 : 1.0);
    const int ready = ::poll(descriptors, 4, static_cast<int>(std::ceil(wait * 1000)));
    if (ready < 0 && errno != EINTR) return failed("poll failed: " + errno_text(errno), errno);
    if (ready <= 0) continue;
    if (descriptors[3].revents) {
      const ssize_t written = write_without_broken_pipe_signal(
          input.write_end.get(), input_bytes.data() + input_written,
          std::min(kChunkBytes, input_bytes.size() - input_written));
      if (written > 0) input_written += static_cast<std::size_t>(written);
      // Done, or the program closed its end (EPIPE): end of file for it, or nothing to do.
      if (input_written == input_bytes.size() || (written < 0 && errno != EAGAIN))
        input.write_end.reset();
    }
    for (int stream = 0; stream < 2 && !stopped; ++stream) {
      if (!(descriptors[stream].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      FileDescriptor& read_end = outputs[stream].pipe.read_end;
      const std::size_t count = read_chunk(read_end.get(), chunk.data(), chunk.size());
      if (count == 0)
        read_end.reset();
      else if (!outputs[stream].take(chunk.data(), count))
        stopped = true;
    }
    if (stopped) break;
    if (descriptors[2].revents & (POLLIN | POLLHUP | POLLERR)) {
      char* bytes = reinterpret_cast<char*>(&report);
      const std::size_t count =
          read_chunk(supervisor.control(), bytes + report_bytes, sizeof report - report_bytes);
      if (count == 0) {
        supervisor.supervisor_closed_control();
        continue;
      }
      report_bytes += count;
      if (report_bytes < sizeof report) continue;
      report_bytes = 0;
      if (report.kind == SupervisorReportKind::started) {
        supervisor.set_program(report.value);
        program_start = report.monotonic_nanoseconds;
      } else if (report.kind == SupervisorReportKind::not_executed) {
        result.how = ProcessResult::How::not_started;
        result.error_number = report.value;
        program_start = program_end = report.monotonic_nanoseconds;
        reported_end = true;
      } else if (report.kind == SupervisorReportKind::ended) {
        const int status = report.value;
        result.how =
            WIFSIGNALED(status) ? ProcessResult::How::signalled : ProcessResult::How::exited;
        result.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : 0;
        result.signal_number = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
        program_end = report.monotonic_nanoseconds;
        reported_end = true;
      }
    }
  }
  const std::int64_t kill_time = monotonic_nanoseconds();
  supervisor.stop();  // at the time limit or a stop: kills the tree; else it has ended already
  if (timed_out || stopped) {
    result.how = timed_out ? ProcessResult::How::timed_out : ProcessResult::How::stopped;
    result.exit_status = result.signal_number = 0;
    result.seconds = seconds_between(program_start > 0 ? program_start : call_start, kill_time);
    return finish();
  }
  if (!reported_end) return failed("the supervisor of the program ended without a report");
  result.seconds = seconds_between(program_start, program_end);
  return finish();
}

}  // namespace emnet
