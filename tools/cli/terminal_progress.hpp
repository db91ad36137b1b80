// The command line's side of emnet::Progress (include/emnet/core/progress.hpp): a progress line on
// standard error and Ctrl-C.
//
// The analyses report each step (done, total, what); a thread of this reporter prints the
// latest state at its own rate, so a step costs one mutex lock and printing never slows the
// loop down. On a terminal the line is rewritten in place (carriage return, cut to the
// terminal's width) four times a second, from one second after the start, so commands that
// take less than a second print nothing; the line is cleared before the result is printed.
// `--progress` prints also when standard error is not a terminal: a line when a step begins and
// one a second; `--quiet` prints nothing. A line says what is being done, how far it is, the
// time so far and the estimated time left (the current step's rate since it began):
//   emnet ac: AC frequencies 1234/50000 (2.5 %), 3.1 s, about 2 min left
// A step without counts (a dense eigen-decomposition) shows its time so far only.
//
// Signals: InterruptHandler blocks SIGINT, SIGTERM and SIGHUP in every thread (it is made before
// any other thread starts, and threads inherit the mask) and takes them in one watcher thread
// (sigwait), so no handler runs inside the analyses. When Ctrl-C cancels (every command but
// `crosscheck`, whose ngspice runs poll nothing), the first SIGINT only sets a flag, which
// cancelled() returns: the analysis stops at its next step with the Status "cancelled", a
// running gnuplot is stopped, and the command exits with status 130 without writing any output
// file. Any other of these signals (a second Ctrl-C, during a step that cannot stop such as an
// eigen-decomposition; SIGTERM; SIGHUP; Ctrl-C in `crosscheck`) removes the temporary files and
// directories still registered (include/emnet/core/temporary_files.hpp: output files not yet
// renamed into place, gnuplot's and ngspice's private directories) and then ends the program by
// the signal's default action. Programs it started die with it (include/emnet/core/process.hpp).
// A signal that was ignored when the program started (SIGINT of a background job, SIGHUP under
// nohup) stays ignored.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "emnet/core/progress.hpp"

namespace emnet_cli {

class InterruptHandler {
 public:
  // `interrupt_cancels`: the first SIGINT sets the flag (else it ends the program at once, as
  // the other signals do). Lives as long as the program: the watcher thread is never stopped.
  explicit InterruptHandler(bool interrupt_cancels);
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;
  // True once SIGINT was received and cancels.
  static bool interrupted();
};

// The text of a progress line, without the carriage return: `elapsed` seconds since the command
// started; `step_seconds` and `step_done` since the current step (`what`) began, for the
// estimate of the time left (shown once the step has run 0.2 s and done something).
std::string progress_line(const std::string& command, const std::string& what, long done,
                          long total, double elapsed, double step_seconds, long step_done,
                          bool interrupted);

class TerminalProgress : public emnet::Progress {
 public:
  enum class Mode { automatic, forced, quiet };
  // `command` names the line ("emnet ac: ...").
  TerminalProgress(std::string command, Mode mode);
  ~TerminalProgress() override;  // finish()
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

  void report(long done, long total, std::string_view what) override;
  bool cancelled() const override { return InterruptHandler::interrupted(); }
  // A step without counts.
  void phase(std::string_view what) { report(0, 0, what); }
  // Stops printing and clears the line (on a terminal); for the result or a message to follow.
  // Later reports are ignored.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  void print_loop();

  const std::string command_;
  const Mode mode_;
  const bool terminal_;
  const Clock::time_point start_ = Clock::now();
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  bool any_report_ = false;
  long done_ = 0, total_ = 0;
  std::string what_;
  Clock::time_point step_start_ = start_;
  long step_start_done_ = 0;
  size_t shown_width_ = 0;  // characters of the line on the terminal now
  // --progress: the line of each step that began, as it began, until the printer writes it, so
  // that no step goes without its line however quickly the next one follows.
  std::vector<std::string> step_lines_;
  std::thread printer_;
};

}  // namespace emnet_cli
