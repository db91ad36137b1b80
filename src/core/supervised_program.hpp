// Runs a program under a time limit so that nothing it starts outlives the run, and hands its
// standard output and error to the caller as they arrive, in chunks of bounded size.
//
// The program does not run as this process's child but as the child of a small supervisor:
// a forked copy of this process that only makes system calls (it runs after a fork of a
// process that may have other threads, so it takes no lock and allocates nothing).
//
//   * The supervisor makes itself a "child subreaper" (Linux prctl PR_SET_CHILD_SUBREAPER): a
//     process the program starts and leaves behind (a grandchild that called setsid and so
//     left the program's process group and session, or the child of a process that already
//     ended) is re-parented to the supervisor instead of to init, so the supervisor can always
//     find it: it is one of its own children.
//   * The program runs in its own process group, with standard input from /dev/null, its
//     output on two pipes, default signal handling, and a limit on the size of any file it
//     writes (RLIMIT_FSIZE; past it the program gets SIGXFSZ).
//   * When the program ends, or when this process asks (it closes the control socket: at the
//     time limit, or because it is itself ending), the supervisor kills the program's process
//     group and then, until it has no child left, every process whose parent it is
//     (found in /proc/<pid>/stat) with SIGKILL, reaping each; every descendant becomes its
//     child when its own parent dies. Then it reports the program's wait status and exits.
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
#include <string>
#include <vector>

namespace emnet {

enum class ProgramStream { standard_output, standard_error };

struct SupervisedProgramOptions {
  // The program and its arguments; the program is searched in PATH when it has no '/'.
  std::vector<std::string> arguments;
  double timeout_seconds = 60.0;
  // RLIMIT_FSIZE of the program and of everything it starts, in bytes.
  std::uint64_t file_size_limit = UINT64_MAX;
};

struct SupervisedProgramEnd {
  enum class How {
    exited,       // `exit_status`
    signalled,    // `signal_number`
    timed_out,    // still running at the time limit: killed with everything it started
    not_started,  // `start_error`: not found in PATH, or exec failed (errno)
    failed,       // `problem`: the supervision itself failed (no pipe, no fork, ...)
  };
  How how = How::failed;
  int exit_status = 0;
  int signal_number = 0;
  int start_error = 0;
  std::string problem;
  double seconds = 0.0;  // from the start of the program to its end (or to the kill)
};

// Runs the program; `output` receives its output as it comes, at most 64 KiB per call.
SupervisedProgramEnd run_supervised_program(
    const SupervisedProgramOptions& options,
    const std::function<void(ProgramStream, const char* data, std::size_t size)>& output);

}  // namespace emnet
