// ngspice's messages: kept in bounded memory and made printable (MessageLog, LineCollector),
// and read for what they say (which lines are errors, the excerpt a failed status quotes).
// Shared by every backend of the ngspice runner and by the ngspice worker program.
//
// The heuristics: a standard-error line is an error when it starts with "error", or tells of
// "timestep too small" or "simulation(s) aborted" (ngspice then ends the run early with the
// vectors so far, which must not pass for a whole run). A status message quotes ngspice's
// standard-error lines from its first error on, or when it printed no error its warnings;
// "Note:" lines and their indented continuations are left out, at most 20 lines are quoted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "emnet/spice/ngspice_runner.hpp"

namespace emnet {

// A line of ngspice's output longer than this is cut (the rest counted, not kept).
constexpr std::size_t kNgspiceMaxLineBytes = 4096;

// Small text helpers of the runner.
std::string ngspice_lower_case(std::string text);
std::string_view ngspice_trimmed(std::string_view text);
std::string ngspice_seconds_text(double seconds);    // "60", "0.5"
std::string ngspice_signal_text(int signal_number);  // "signal 11, Segmentation fault"

bool is_ngspice_error_line(const NgspiceMessage& message);
bool has_ngspice_error_line(const std::vector<NgspiceMessage>& messages);
// For a status message: ": " and the quoted lines, each on its own indented line; empty when
// there is nothing to quote.
std::string ngspice_error_excerpt(const std::vector<NgspiceMessage>& messages);

// The messages of one run in at most `byte_limit` bytes (each message's text plus
// sizeof(NgspiceMessage)): the first three quarters keep the first lines, the last quarter the
// most recent ones. The lines that fall between are counted and left out, marked by one line
// (on the error stream, so that status messages show it); the first error line among them is
// kept after the mark, for the error checks and the status message. Every line is cut at
// kNgspiceMaxLineBytes and made printable (emnet/core/terminal_text.hpp) before it is stored.
class MessageLog {
 public:
  explicit MessageLog(std::size_t byte_limit);

  // One line, without its newline; `bytes_cut`: bytes of it already left out by the caller.
  void add(NgspiceStream stream, std::string_view line, std::uint64_t bytes_cut = 0);
  std::vector<NgspiceMessage> messages() const;

 private:
  std::size_t head_limit_, tail_limit_;
  std::size_t head_bytes_ = 0, tail_bytes_ = 0;
  std::vector<NgspiceMessage> head_;
  std::deque<NgspiceMessage> tail_;
  std::uint64_t left_out_lines_ = 0, left_out_bytes_ = 0;
  std::optional<NgspiceMessage> first_left_out_error_;
};

// Splits a stream's output into lines as it arrives and hands each to a MessageLog, so that
// the lines of two streams keep the order in which they came. Holds at most one line of
// kNgspiceMaxLineBytes (+1, for a carriage return before the newline); the rest of a longer
// line is counted.
class LineCollector {
 public:
  LineCollector(NgspiceStream stream, MessageLog& log) : stream_(stream), log_(log) {}
  void add(const char* data, std::size_t size);
  // The last line, when the output did not end with a newline.
  void finish();

 private:
  void push();
  NgspiceStream stream_;
  MessageLog& log_;
  std::string pending_;
  std::uint64_t cut_ = 0;
};

}  // namespace emnet
