// The runner's library backend: libngspice in the worker program (ngspice_worker_main.cpp),
// started through the process helper (emnet/core/process.hpp) with the deck on its standard
// input, its records read as they come (ngspice_worker_protocol.hpp), under the run's time
// limit; the worker and everything it started are killed at the limit, when its records break
// the rules, and when it ends.
//
// Where the worker program is: NgspiceOptions::worker_program, else the environment variable
// EMNET_NGSPICE_WORKER, each taken as given (one that names no executable file is an error,
// not a reason to look elsewhere: a caller who names a worker means that one); else the first
// executable file named emnet-ngspice-worker in the running program's directory, at the path
// the build puts it (EMNET_NGSPICE_WORKER_BUILD_PATH) and at the installed path
// (EMNET_NGSPICE_WORKER_INSTALL_PATH, in libexec). When there is none the backend is not
// available, and the reason names every place looked at.
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>

#include "core/posix_handles.hpp"
#include "emnet/core/process.hpp"
#include "emnet/core/terminal_text.hpp"
#include "ngspice_backends.hpp"
#include "ngspice_messages.hpp"
#include "ngspice_worker_protocol.hpp"

namespace emnet {

namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kWorkerEnvironmentVariable = "EMNET_NGSPICE_WORKER";

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Why `path` is not an executable regular file; empty when it is one.
std::string not_executable_reason(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) return errno_text(errno);
  if (S_ISDIR(status.st_mode)) return "a directory";
  if (!S_ISREG(status.st_mode)) return "not a regular file";
  if (::access(path.c_str(), X_OK) != 0) return errno_text(errno);
  return "";
}

// The directory of the running program (/proc/self/exe), empty when unknown.
std::string running_program_directory() {
  std::string path(4096, '\0');
  const ssize_t length = ::readlink("/proc/self/exe", path.data(), path.size());
  if (length <= 0 || static_cast<std::size_t>(length) >= path.size()) return "";
  path.resize(static_cast<std::size_t>(length));
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? "" : path.substr(0, slash);
}

// See the header comment for the order; false with `why` when no worker was found.
bool find_ngspice_worker(const NgspiceOptions& options, std::string& path, std::string& why) {
  const auto given = [&](const std::string& candidate, const std::string& where) {
    if (const std::string reason = not_executable_reason(candidate); !reason.empty()) {
      why = "the ngspice worker program given in " + where + ", '" + terminal_text(candidate) +
            "', is not an executable file (" + reason + ")";
      return false;
    }
    path = candidate;
    return true;
  };
  if (!options.worker_program.empty())
    return given(options.worker_program, "NgspiceOptions::worker_program");
  if (const char* variable = std::getenv(kWorkerEnvironmentVariable); variable && *variable)
    return given(variable, std::string("the environment variable ") + kWorkerEnvironmentVariable);

  std::vector<std::pair<std::string, std::string>> candidates;  // path, what it is
  if (const std::string directory = running_program_directory(); !directory.empty())
    candidates.push_back({directory + "/" + kNgspiceWorkerName, "beside the running program"});
#ifdef EMNET_NGSPICE_WORKER_BUILD_PATH
  candidates.push_back({EMNET_NGSPICE_WORKER_BUILD_PATH, "where the build puts it"});
#endif
#ifdef EMNET_NGSPICE_WORKER_INSTALL_PATH
  candidates.push_back({EMNET_NGSPICE_WORKER_INSTALL_PATH, "where it is installed"});
#endif
  std::string looked_at;
  for (const auto& [candidate, what] : candidates) {
    if (not_executable_reason(candidate).empty()) {
      path = candidate;
      return true;
    }
    looked_at += (looked_at.empty() ? "" : ", ") + terminal_text(candidate) + " (" + what + ")";
  }
  why = std::string("the ngspice worker program ") + kNgspiceWorkerName +
        " was not found; looked at " + (looked_at.empty() ? "no place" : looked_at) +
        "; give its path in NgspiceOptions::worker_program or in the environment variable " +
        kWorkerEnvironmentVariable;
  return false;
}

// The worker's own standard-error lines (its complaints, not ngspice's), for a status message.
std::string worker_lines(const std::vector<NgspiceMessage>& messages) {
  std::string text;
  int count = 0;
  for (const NgspiceMessage& message : messages)
    if (message.stream == NgspiceStream::err &&
        message.text.rfind(std::string(kNgspiceWorkerName) + ":", 0) == 0 && ++count <= 5)
      text += "\n  " + message.text;
  return text.empty() ? text : ":" + text;
}

// What the worker's records say, gathered as they come: its messages into the log, its
// vectors, plot names, times and status into the attempt's result.
struct WorkerRecords {
  BackendAttempt& attempt;
  MessageLog& log;
  const std::string& worker_path;
  bool library_loaded = false, library_unavailable = false, have_status = false;

  void handle(RecordTag tag, const std::string& payload) {
    NgspiceResult& result = attempt.result;
    switch (tag) {
      case RecordTag::message_out:
      case RecordTag::message_err: {
        std::string line;
        std::uint64_t cut = 0;
        if (decode_message(payload, line, cut))
          log.add(tag == RecordTag::message_err ? NgspiceStream::err : NgspiceStream::out, line,
                  cut);
        break;
      }
      case RecordTag::library_loaded:
        library_loaded = true;
        result.backend_description = "libngspice in-process (" + terminal_text(payload) +
                                     ", in the worker process " + terminal_text(worker_path) + ")";
        break;
      case RecordTag::library_unavailable:
        library_unavailable = true;
        attempt.unavailable_reason = terminal_text(payload);
        break;
      case RecordTag::plot_name:
        result.plot_names.push_back(terminal_text(payload));
        break;
      case RecordTag::vector: {
        NgspiceVector vector;
        if (decode_vector(payload, vector)) result.vectors.push_back(std::move(vector));
        break;
      }
      case RecordTag::ngspice_seconds:
        decode_seconds(payload, result.ngspice_seconds);
        break;
      case RecordTag::status:
        have_status = decode_status(payload, result.status);
        break;
    }
  }
};

// The run's status from how the worker ended, once the library was there: a failure, with no
// vectors, unless the worker ended by itself after its status record.
void set_worker_run_status(const ProcessResult& end, const WorkerRecords& records,
                           const std::string& record_problem, const NgspiceOptions& options,
                           NgspiceResult& result) {
  using How = ProcessResult::How;
  const double timeout = std::max(0.0, options.timeout_seconds);
  if (end.how == How::failed) {
    result.vectors.clear();
    result.status = Status::failure("cannot run the ngspice worker: " + end.problem);
  } else if (end.how == How::timed_out) {
    result.vectors.clear();
    result.status =
        Status::failure("ngspice timed out: still running after " + ngspice_seconds_text(timeout) +
                        " s (timeout_seconds); its worker process was killed");
  } else if (end.how == How::stopped) {
    result.vectors.clear();
    result.status = Status::failure(record_problem + "; the worker process was killed");
  } else if (end.how == How::signalled) {
    result.vectors.clear();
    result.status = Status::failure("ngspice crashed (" + ngspice_signal_text(end.signal_number) +
                                    ") on the deck" + ngspice_error_excerpt(result.messages));
  } else if (!records.have_status) {
    result.vectors.clear();
    result.status = Status::failure("the ngspice worker ended without a result (exit status " +
                                    std::to_string(end.exit_status) + ")" +
                                    (end.exit_status == kNgspiceWorkerUsageExitStatus
                                         ? worker_lines(result.messages)
                                         : ngspice_error_excerpt(result.messages)));
  }
}

}  // namespace

BackendAttempt run_library_in_worker(const std::vector<std::string>& lines,
                                     const NgspiceOptions& options) {
  BackendAttempt attempt;
  NgspiceResult& result = attempt.result;
  const Clock::time_point start = Clock::now();
  std::string worker_path;
  if (!find_ngspice_worker(options, worker_path, attempt.unavailable_reason)) {
    attempt.missing_worker = true;
    return attempt;
  }

  // The records and the worker's own output (as standard-error lines) in one bounded log,
  // in the order they come.
  MessageLog log(options.max_message_bytes);
  LineCollector output_lines(NgspiceStream::err, log);
  RecordReader reader(options.max_result_bytes);
  WorkerRecords records{attempt, log, worker_path};
  std::string record_problem;
  const auto handle = [&](RecordTag tag, const std::string& payload) {
    records.handle(tag, payload);
  };

  ProcessOptions process;
  process.arguments = ngspice_worker_arguments(
      worker_path, NgspiceWorkerRequest{options.library_names, options.max_message_bytes});
  process.standard_input = ngspice_worker_input(lines);
  process.standard_output = ProcessOutput::to_callback([&](const char* data, std::size_t size) {
    if (reader.add(data, size, handle)) return true;
    record_problem = reader.problem();
    return false;  // the worker is killed at once
  });
  process.standard_error = ProcessOutput::to_callback([&](const char* data, std::size_t size) {
    output_lines.add(data, size);
    return true;
  });
  process.timeout_seconds = options.timeout_seconds;
  const ProcessResult end = run_process(process);
  output_lines.finish();
  result.seconds = seconds_since(start);
  result.messages = log.messages();

  using How = ProcessResult::How;
  if (end.how == How::not_started) {
    attempt.missing_worker = true;
    attempt.unavailable_reason = "the ngspice worker program '" + terminal_text(worker_path) +
                                 "' could not be started: " + errno_text(end.error_number);
    return attempt;
  }
  if (records.library_unavailable && record_problem.empty()) return attempt;
  if (!records.library_loaded && end.how == How::signalled) {
    attempt.unavailable_reason = "the worker died of " + ngspice_signal_text(end.signal_number) +
                                 " while loading libngspice";
    return attempt;
  }
  attempt.available = true;
  result.backend_used = NgspiceBackend::library;
  if (result.backend_description.empty())
    result.backend_description =
        "libngspice in-process (in the worker process " + terminal_text(worker_path) + ")";
  set_worker_run_status(end, records, record_problem, options, result);
  if (result.ngspice_seconds == 0.0) result.ngspice_seconds = result.seconds;
  return attempt;
}

}  // namespace emnet
