// Runs a program to its end under a time limit, so that nothing it starts outlives the run:
// the one way emnet starts a process (the ngspice worker and program, gnuplot, the benchmark's
// whole-process runs).
//
// Options in: the program and its arguments (no shell), variables added to the environment,
// standard input (/dev/null, or bytes written to it), what happens to standard output and
// standard error (discarded, captured up to a number of bytes, or handed to a callback as they
// arrive), a working directory, a time limit and a limit on the size of any file the program
// writes. Result out: how it ended (exited, signalled, timed out, stopped by a callback, not
// started, failed), its exit status, signal or errno, the captured text and its duration.
//
// The program does not run as this process's child but as the child of a small supervisor: a
// forked copy of this process that only makes system calls (it runs after a fork of a process
// that may have other threads, so it takes no lock and allocates nothing; the fork runs none of
// the process's fork handlers, pthread_atfork, either). This is the only fork emnet makes.
//
//   * The supervisor makes itself a "child subreaper" (Linux prctl PR_SET_CHILD_SUBREAPER): a
//     process the program starts and leaves behind (a grandchild that called setsid and so
//     left the program's process group and session, or the child of a process that already
//     ended) is re-parented to the supervisor instead of to init, so the supervisor can always
//     find it: it is one of its own children.
//   * The program runs in its own process group, with default signal handling, its standard
//     streams as asked, and a limit on the size of any file it writes (RLIMIT_FSIZE; past it
//     the program gets SIGXFSZ). The supervisor starts it with vfork (no copy of its memory),
//     so a large calling process costs one fork, not two.
//   * When the program ends, or when this process asks (it closes the control socket: at the
//     time limit, when a callback says stop, or because it is itself ending), the supervisor
//     kills the program's process group and then, until it has no child left, every process
//     whose parent it is (listed in /proc) with SIGKILL, reaping each; every descendant becomes
//     its child when its own parent dies. Then it reports the program's wait status and exits.
//   * The supervisor ignores the terminal's signals (SIGINT, SIGTERM, SIGHUP, ...): when this
//     process dies for any reason its end of the control socket closes, and the supervisor
//     kills the tree as above.
//
// No root, no cgroup and no extra package is needed. Without the subreaper (a kernel without
// it) the process group is still killed. The caller's deadline is checked between reads of at
// most 64 KiB, however fast the program writes; after the deadline, killing the tree takes
// milliseconds, and a supervisor that has not ended within 2 s more is killed itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace emnet {

/// One of the program's two output streams.
enum class ProcessStream { standard_output, standard_error };

/// What happens to one of the program's output streams.
struct ProcessOutput {
  /// Where the stream goes.
  enum class Kind {
    discard,   ///< the stream is /dev/null
    capture,   ///< kept in the result, at most `capture_limit` bytes (the first ones)
    callback,  ///< handed to `callback` as it arrives, at most 64 KiB per call
  };
  Kind kind = Kind::discard;
  std::size_t capture_limit = 0;  ///< Kind::capture: bytes kept at most
  /// Returns false to stop the program: it is killed with everything it started, and the
  /// result says `stopped`. Called on the calling thread; it may throw (the tree is killed).
  std::function<bool(const char* data, std::size_t size)> callback;

  /// To /dev/null.
  static ProcessOutput discarded() { return {}; }
  /// Captured, at most `byte_limit` bytes.
  static ProcessOutput captured(std::size_t byte_limit) {
    return {Kind::capture, byte_limit, nullptr};
  }
  /// Handed to `function` as it arrives.
  static ProcessOutput to_callback(std::function<bool(const char*, std::size_t)> function) {
    return {Kind::callback, 0, std::move(function)};
  }
};

/// What run_process runs, and how.
struct ProcessOptions {
  /// The program and its arguments; the program is searched in PATH when it has no '/'.
  std::vector<std::string> arguments;
  /// NAME, VALUE pairs set in the program's environment (replacing this process's value of
  /// NAME); every other variable of this process is passed on as it is.
  std::vector<std::pair<std::string, std::string>> environment_additions;
  /// Standard input: /dev/null when absent, else these bytes, then end of file. Bytes the
  /// program does not read are dropped when it ends.
  std::optional<std::string> standard_input;
  ProcessOutput standard_output = ProcessOutput::discarded();
  ProcessOutput standard_error = ProcessOutput::discarded();
  /// The program's working directory; empty: this process's.
  std::string working_directory;
  double timeout_seconds = 60.0;  ///< the time limit [s]
  /// RLIMIT_FSIZE of the program and of everything it starts, in bytes.
  std::uint64_t file_size_limit = UINT64_MAX;
  /// Asked at least every 100 ms while the program runs (on the calling thread); true stops it
  /// like an output callback's false: killed with everything it started, the result `stopped`.
  /// E.g. a Ctrl-C flag. Empty: never asked.
  std::function<bool()> stop_requested;
};

/// How a program run by run_process ended, and what it wrote.
struct ProcessResult {
  /// How the program ended; each names the field that says more.
  enum class How {
    exited,       ///< `exit_status`
    signalled,    ///< `signal_number`
    timed_out,    ///< still running at the time limit: killed with everything it started
    stopped,      ///< an output callback returned false or stop_requested() true: killed with
                  ///< everything it started
    not_started,  ///< `error_number`: not found in PATH, or exec failed
    failed,       ///< `problem` (and `error_number` when a system call failed): no pipe, no fork
  };
  How how = How::failed;
  int exit_status = 0;
  int signal_number = 0;
  int error_number = 0;
  std::string problem;  ///< what failed, when `how` is failed
  /// Captured output (ProcessOutput::Kind::capture), and the bytes beyond the limit, counted.
  std::string standard_output, standard_error;
  std::uint64_t standard_output_bytes_left_out = 0, standard_error_bytes_left_out = 0;
  /// The program's run as its supervisor saw it: from just before it was started to the moment
  /// it was reaped (or killed: time limit, stop), without starting the supervisor or cleaning
  /// up after the program. `total_seconds`: the whole call.
  double seconds = 0.0;
  double total_seconds = 0.0;

  /// Whether the program exited with `status`.
  bool exited_with(int status) const { return how == How::exited && exit_status == status; }
  /// "exited with status 3", "killed by signal 11 (Segmentation fault)", "timed out after 2 s",
  /// "not started: No such file or directory", ...
  std::string description() const;
};

/// Runs the program of `options` to its end under its time limit (see above).
/// @throws what an output callback throws (the program and everything it started are killed)
ProcessResult run_process(const ProcessOptions& options);

}  // namespace emnet
