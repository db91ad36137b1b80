// Progress line on standard error and Ctrl-C for the command line; see terminal_progress.hpp.
#include "terminal_progress.hpp"

#include <pthread.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "emnet/core/temporary_files.hpp"
#include "emnet/core/terminal_text.hpp"

namespace emnet_cli {

namespace {

std::atomic<bool> interrupt_received{false};

// Removes the registered temporaries, then lets `signal_number` take its default action on this
// thread: the program ends by it (a shell reports 128 + N).
[[noreturn]] void end_by_signal(int signal_number) {
  emnet::remove_registered_temporaries();
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  ::sigaction(signal_number, &default_action, nullptr);
  sigset_t just_this;
  sigemptyset(&just_this);
  sigaddset(&just_this, signal_number);
  ::pthread_sigmask(SIG_UNBLOCK, &just_this, nullptr);
  ::raise(signal_number);
  std::_Exit(128 + signal_number);  // a signal whose default action does not end the program
}

void watch_signals(sigset_t watched, bool interrupt_cancels) {
  for (;;) {
    int signal_number = 0;
    if (::sigwait(&watched, &signal_number) != 0) continue;
    if (signal_number == SIGINT && interrupt_cancels && !interrupt_received.exchange(true))
      continue;
    end_by_signal(signal_number);
  }
}

bool ignored_at_start(int signal_number) {
  struct sigaction current {};
  return ::sigaction(signal_number, nullptr, &current) == 0 && current.sa_handler == SIG_IGN;
}

// A duration as it is read: "3.1 s", "4 min 05 s", "2 h 13 min".
std::string duration_text(double seconds) {
  char text[48];
  if (seconds < 10.0) {
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  } else if (seconds < 60.0) {
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  } else if (seconds < 3600.0) {
    const long whole = static_cast<long>(seconds);
    std::snprintf(text, sizeof text, "%ld min %02ld s", whole / 60, whole % 60);
  } else {
    const long minutes = static_cast<long>(seconds / 60.0);
    std::snprintf(text, sizeof text, "%ld h %02ld min", minutes / 60, minutes % 60);
  }
  return text;
}

void write_stderr(const std::string& text) {
  size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(STDERR_FILENO, text.data() + written, text.size() - written);
    if (n <= 0) return;  // nothing to be done about a lost progress line
    written += static_cast<size_t>(n);
  }
}

size_t terminal_width() {
  struct winsize size {};
  if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

}  // namespace

std::string progress_line(const std::string& command, const std::string& what, long done,
                          long total, double elapsed, double step_seconds, long step_done,
                          bool interrupted) {
  std::string text = command + ": ";
  if (interrupted) return text + "interrupted, stopping (Ctrl-C again: at once)";
  text += emnet::terminal_text(what);
  if (total > 0) {
    char counts[96];
    std::snprintf(counts, sizeof counts, " %ld/%ld (%.1f %%)", done, total,
                  100.0 * static_cast<double>(done) / static_cast<double>(total));
    text += counts;
  }
  text += ", " + duration_text(elapsed);
  if (total > 0 && step_done > 0 && step_seconds >= 0.2) {
    const double left = step_seconds * static_cast<double>(total - done) / step_done;
    text += ", about " + duration_text(left) + " left";
  }
  return text;
}

InterruptHandler::InterruptHandler(bool interrupt_cancels) {
  sigset_t watched;
  sigemptyset(&watched);
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP})
    if (!ignored_at_start(signal_number)) sigaddset(&watched, signal_number);
  if (::pthread_sigmask(SIG_BLOCK, &watched, nullptr) != 0) return;  // default actions stay
  std::thread(watch_signals, watched, interrupt_cancels).detach();
}

bool InterruptHandler::interrupted() {
  return interrupt_received.load();
}

TerminalProgress::TerminalProgress(std::string command, Mode mode)
    : command_(std::move(command)), mode_(mode), terminal_(::isatty(STDERR_FILENO) == 1) {
  const bool shown = mode_ == Mode::forced || (mode_ == Mode::automatic && terminal_);
  if (shown) printer_ = std::thread([this] { print_loop(); });
}

TerminalProgress::~TerminalProgress() {
  finish();
}

void TerminalProgress::report(long done, long total, std::string_view what) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (stopping_) return;
  const bool new_step = what != what_;
  if (new_step || done < done_) {
    what_.assign(what.data(), what.size());
    step_start_ = Clock::now();
    step_start_done_ = done;
  }
  done_ = done;
  total_ = total;
  any_report_ = true;
  if (new_step && mode_ == Mode::forced) {  // --progress: a line per step, as it begins
    step_lines_.push_back(progress_line(command_, what_, done, total,
                                        std::chrono::duration<double>(step_start_ - start_).count(),
                                        0.0, 0, InterruptHandler::interrupted()));
    wake_.notify_one();
  }
}

void TerminalProgress::finish() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) return;
    stopping_ = true;
  }
  wake_.notify_one();
  if (printer_.joinable()) printer_.join();
}

void TerminalProgress::print_loop() {
  const auto first_delay = std::chrono::seconds(1);
  const auto interval =
      terminal_ ? std::chrono::milliseconds(250) : std::chrono::milliseconds(1000);
  std::unique_lock<std::mutex> lock(mutex_);
  Clock::time_point last_print{};
  bool printed = false;
  // Writes `text` as the line (the lock held on entry and on return, released while writing).
  auto print_line = [&](std::string text, Clock::time_point now) {
    if (terminal_) {
      const size_t width = terminal_width();
      if (text.size() >= width) text.resize(width - 1);  // a wrapped line cannot be rewritten
      const size_t previous = shown_width_;
      shown_width_ = text.size();
      if (previous > text.size()) text.append(previous - text.size(), ' ');
      text = "\r" + text;
    } else {
      text += "\n";
    }
    lock.unlock();
    write_stderr(text);
    lock.lock();
    last_print = now;
    printed = true;
  };
  // The lines of the steps that began since the last wake-up (--progress), in their order.
  auto print_step_lines = [&] {
    std::vector<std::string> lines;
    lines.swap(step_lines_);
    for (std::string& line : lines) print_line(std::move(line), Clock::now());
  };
  while (!stopping_) {
    wake_.wait_for(lock, std::chrono::milliseconds(100));
    if (stopping_ || !any_report_) continue;
    if (!step_lines_.empty()) {
      print_step_lines();
      continue;
    }
    const Clock::time_point now = Clock::now();
    const bool due = printed ? now - last_print >= interval
                             : mode_ == Mode::automatic && now - start_ >= first_delay;
    if (due) {
      print_line(progress_line(command_, what_, done_, total_,
                               std::chrono::duration<double>(now - start_).count(),
                               std::chrono::duration<double>(now - step_start_).count(),
                               done_ - step_start_done_, InterruptHandler::interrupted()),
                 now);
    }
  }
  print_step_lines();  // steps that began after the last wake-up still get their line
  if (terminal_ && shown_width_ > 0) write_stderr("\r" + std::string(shown_width_, ' ') + "\r");
}

}  // namespace emnet_cli
