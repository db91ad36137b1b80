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
#include <optional>

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

namespace {

// One call of run_process, phase by phase: find the program, open its pipes, fork the
// supervisor, then exchange data with the program until its pipes and the supervisor's socket
// are closed, the time is up or a callback says stop.
class ProcessRun {
 public:
  explicit ProcessRun(const ProcessOptions& options)
      : options_(options),
        call_start_(monotonic_nanoseconds()),
        outputs_{{&options.standard_output,
                  &result_.standard_output,
                  &result_.standard_output_bytes_left_out,
                  {}},
                 {&options.standard_error,
                  &result_.standard_error,
                  &result_.standard_error_bytes_left_out,
                  {}}} {}

  ProcessResult run() {
    if (options_.arguments.empty()) return failed("no program given");
    if (!locate_program()) return finish();
    if (!open_pipes()) return finish();
    if (!start_supervisor()) return finish();
    const Ending ending = exchange_until_the_end();
    if (ending == Ending::failed) return finish();
    const std::int64_t kill_time = monotonic_nanoseconds();
    supervisor_->stop();  // at the time limit or a stop: kills the tree; else it has ended
    if (ending != Ending::ended) {
      result_.how =
          ending == Ending::timed_out ? ProcessResult::How::timed_out : ProcessResult::How::stopped;
      result_.exit_status = result_.signal_number = 0;
      result_.seconds =
          seconds_between(program_start_ > 0 ? program_start_ : call_start_, kill_time);
      return finish();
    }
    if (!reported_end_) return failed("the supervisor of the program ended without a report");
    result_.seconds = seconds_between(program_start_, program_end_);
    return finish();
  }

 private:
  enum class Ending { ended, timed_out, stopped, failed };

  ProcessResult finish() {
    result_.total_seconds = seconds_between(call_start_, monotonic_nanoseconds());
    return std::move(result_);
  }
  ProcessResult failed(std::string why, int error_number = 0) {
    record_failure(std::move(why), error_number);
    return finish();
  }
  void record_failure(std::string why, int error_number) {
    result_.how = ProcessResult::How::failed;
    result_.problem = std::move(why);
    result_.error_number = error_number;
  }

  // The program's path as the supervisor will exec it; false (not started) when not found.
  bool locate_program() {
    if (!find_program(options_.arguments.front(), program_environment_value(options_, "PATH"),
                      path_, result_.error_number)) {
      result_.how = ProcessResult::How::not_started;
      return false;
    }
    if (!options_.working_directory.empty() && path_.front() != '/') {
      // Found relative to this process's working directory, not the program's.
      char* here = ::getcwd(nullptr, 0);
      if (!here) {
        record_failure("cannot read the working directory: " + errno_text(errno), errno);
        return false;
      }
      path_ = std::string(here) + "/" + path_;
      std::free(here);
    }
    return true;
  }

  bool open_pipes() {
    std::string why;
    if (options_.standard_input && !open_pipe(input_, why)) {
      record_failure(why, errno);
      return false;
    }
    for (OutputPipe& output : outputs_)
      if (output.handling->kind != ProcessOutput::Kind::discard && !open_pipe(output.pipe, why)) {
        record_failure(why, errno);
        return false;
      }
    return true;
  }

  // Forks the supervisor with everything it needs as plain C data, then closes this side's
  // copies of the ends it took.
  bool start_supervisor() {
    int control_ends[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, control_ends) != 0) {
      record_failure("cannot create a socket pair: " + errno_text(errno), errno);
      return false;
    }
    FileDescriptor control(control_ends[0]), supervisor_control(control_ends[1]);
    std::vector<std::string> arguments = options_.arguments;
    std::vector<char*> argument_pointers = pointers_to(arguments);
    std::vector<std::string> environment = program_environment(options_);
    std::vector<char*> environment_pointers = pointers_to(environment);
    SupervisorPlan plan;
    plan.path = path_.c_str();
    plan.arguments = argument_pointers.data();
    plan.environment = environment_pointers.data();
    plan.working_directory =
        options_.working_directory.empty() ? nullptr : options_.working_directory.c_str();
    plan.input = input_.read_end.get();
    plan.output = outputs_[0].pipe.write_end.get();
    plan.error = outputs_[1].pipe.write_end.get();
    plan.control = supervisor_control.get();
    plan.file_size_limit = options_.file_size_limit >= RLIM_INFINITY
                               ? RLIM_INFINITY
                               : static_cast<rlim_t>(options_.file_size_limit);
    // The supervisor never flushes this process's stdio buffers (it ends with _exit or exec).
    const pid_t process_id = fork_without_handlers();
    if (process_id < 0) {
      record_failure("cannot start the supervisor: " + errno_text(errno), errno);
      return false;
    }
    if (process_id == 0) run_supervisor(plan);
    supervisor_.emplace(process_id, std::move(control));
    input_.read_end.reset();
    for (OutputPipe& output : outputs_) output.pipe.write_end.reset();
    supervisor_control.reset();
    if (input_.write_end.is_open()) {
      if (input_bytes().empty())
        input_.write_end.reset();
      else
        ::fcntl(input_.write_end.get(), F_SETFL, O_NONBLOCK);
    }
    return true;
  }

  const std::string& input_bytes() const {
    static const std::string empty;
    return options_.standard_input ? *options_.standard_input : empty;
  }

  // The poll loop: bounded reads and writes, the clock and the stop callback between them.
  Ending exchange_until_the_end() {
    const double timeout = std::min(std::max(0.0, options_.timeout_seconds), 1e9);
    const std::int64_t deadline = call_start_ + static_cast<std::int64_t>(timeout * 1e9);
    while (outputs_[0].pipe.read_end.is_open() || outputs_[1].pipe.read_end.is_open() ||
           supervisor_->control() >= 0) {
      const std::int64_t now = monotonic_nanoseconds();
      if (now >= deadline) return Ending::timed_out;
      if (options_.stop_requested && options_.stop_requested()) return Ending::stopped;
      pollfd descriptors[4] = {{outputs_[0].pipe.read_end.get(), POLLIN, 0},
                               {outputs_[1].pipe.read_end.get(), POLLIN, 0},
                               {supervisor_->control(), POLLIN, 0},
                               {input_.write_end.get(), POLLOUT, 0}};
      const double wait =
          std::min(seconds_between(now, deadline), options_.stop_requested ? 0.1 : 1.0);
      const int ready = ::poll(descriptors, 4, static_cast<int>(std::ceil(wait * 1000)));
      if (ready < 0 && errno != EINTR) {
        record_failure("poll failed: " + errno_text(errno), errno);
        return Ending::failed;
      }
      if (ready <= 0) continue;
      if (descriptors[3].revents) write_some_input();
      if (!read_outputs(descriptors)) return Ending::stopped;
      if (descriptors[2].revents & (POLLIN | POLLHUP | POLLERR)) read_supervisor_report();
    }
    return Ending::ended;
  }

  void write_some_input() {
    const std::string& bytes = input_bytes();
    const ssize_t written =
        write_without_broken_pipe_signal(input_.write_end.get(), bytes.data() + input_written_,
                                         std::min(kChunkBytes, bytes.size() - input_written_));
    if (written > 0) input_written_ += static_cast<std::size_t>(written);
    // Done, or the program closed its end (EPIPE): end of file for it, or nothing to do.
    if (input_written_ == bytes.size() || (written < 0 && errno != EAGAIN))
      input_.write_end.reset();
  }

  // One chunk from each ready output; false when a callback asks to stop.
  bool read_outputs(const pollfd* descriptors) {
    for (int stream = 0; stream < 2; ++stream) {
      if (!(descriptors[stream].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      FileDescriptor& read_end = outputs_[stream].pipe.read_end;
      const std::size_t count = read_chunk(read_end.get(), chunk_.data(), chunk_.size());
      if (count == 0)
        read_end.reset();
      else if (!outputs_[stream].take(chunk_.data(), count))
        return false;
    }
    return true;
  }

  // Reads (part of) the supervisor's next fixed-size report and records what it says.
  void read_supervisor_report() {
    char* bytes = reinterpret_cast<char*>(&report_);
    const std::size_t count =
        read_chunk(supervisor_->control(), bytes + report_bytes_, sizeof report_ - report_bytes_);
    if (count == 0) {
      supervisor_->supervisor_closed_control();
      return;
    }
    report_bytes_ += count;
    if (report_bytes_ < sizeof report_) return;
    report_bytes_ = 0;
    if (report_.kind == SupervisorReportKind::started) {
      supervisor_->set_program(report_.value);
      program_start_ = report_.monotonic_nanoseconds;
    } else if (report_.kind == SupervisorReportKind::not_executed) {
      result_.how = ProcessResult::How::not_started;
      result_.error_number = report_.value;
      program_start_ = program_end_ = report_.monotonic_nanoseconds;
      reported_end_ = true;
    } else if (report_.kind == SupervisorReportKind::ended) {
      const int status = report_.value;
      result_.how =
          WIFSIGNALED(status) ? ProcessResult::How::signalled : ProcessResult::How::exited;
      result_.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : 0;
      result_.signal_number = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
      program_end_ = report_.monotonic_nanoseconds;
      reported_end_ = true;
    }
  }

  const ProcessOptions& options_;
  ProcessResult result_;
  const std::int64_t call_start_;
  std::string path_;
  Pipe input_;
  OutputPipe outputs_[2];
  std::optional<Supervisor> supervisor_;
  std::size_t input_written_ = 0;
  std::string chunk_ = std::string(kChunkBytes, '\0');
  SupervisorReport report_{};
  std::size_t report_bytes_ = 0;
  bool reported_end_ = false;
  std::int64_t program_start_ = 0, program_end_ = 0;
};

}  // namespace

ProcessResult run_process(const ProcessOptions& options) {
  return ProcessRun(options).run();
}

}  // namespace emnet
