// ngspice's messages in bounded memory and what they say; see ngspice_messages.hpp.
#include "ngspice_messages.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <sstream>

#include "emnet/core/terminal_text.hpp"

namespace emnet {

namespace {

// Memory of one message besides its text, counted against the log's limit.
constexpr std::size_t kMessageOverheadBytes = sizeof(NgspiceMessage);

}  // namespace

std::string ngspice_lower_case(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string_view ngspice_trimmed(std::string_view text) {
  const auto is_space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

std::string ngspice_seconds_text(double seconds) {
  std::ostringstream text;
  text << seconds;
  return text.str();
}

std::string ngspice_signal_text(int signal_number) {
  const char* name = strsignal(signal_number);
  return "signal " + std::to_string(signal_number) + (name ? std::string(", ") + name : "");
}

bool is_ngspice_error_line(const NgspiceMessage& message) {
  if (message.stream != NgspiceStream::err) return false;
  const std::string text = ngspice_lower_case(std::string(ngspice_trimmed(message.text)));
  // "doAnalyses: TRAN:  Timestep too small" ends the run early with the vectors so far; the
  // result must not pass for a whole run.
  return text.rfind("error", 0) == 0 || text.find("timestep too small") != std::string::npos ||
         text.find("simulation(s) aborted") != std::string::npos;
}

bool has_ngspice_error_line(const std::vector<NgspiceMessage>& messages) {
  return std::any_of(messages.begin(), messages.end(), is_ngspice_error_line);
}

std::string ngspice_error_excerpt(const std::vector<NgspiceMessage>& messages) {
  const auto starts_with = [](const NgspiceMessage& message, const char* prefix) {
    return ngspice_lower_case(std::string(ngspice_trimmed(message.text))).rfind(prefix, 0) == 0;
  };
  auto first = std::find_if(messages.begin(), messages.end(), is_ngspice_error_line);
  const bool has_error = first != messages.end();
  if (!has_error) first = messages.begin();
  std::string text;
  int count = 0;
  bool in_note = false;
  for (auto it = first; it != messages.end(); ++it) {
    // A note and its indented continuation lines are left out.
    const bool continuation =
        !it->text.empty() && std::isspace(static_cast<unsigned char>(it->text.front())) != 0;
    in_note = starts_with(*it, "note:") || (in_note && continuation);
    if (ngspice_trimmed(it->text).empty() || in_note) continue;
    if (has_error ? it->stream != NgspiceStream::err : !starts_with(*it, "warning")) continue;
    if (++count > 20) {
      text += "\n  ...";
      break;
    }
    text += "\n  " + std::string(ngspice_trimmed(it->text));
  }
  return text.empty() ? std::string() : ":" + text;
}

// ---- MessageLog ---------------------------------------------------------------------------

MessageLog::MessageLog(std::size_t byte_limit)
    : head_limit_(byte_limit - byte_limit / 4), tail_limit_(byte_limit / 4) {}

void MessageLog::add(NgspiceStream stream, std::string_view line, std::uint64_t bytes_cut) {
  if (line.size() > kNgspiceMaxLineBytes) {
    bytes_cut += line.size() - kNgspiceMaxLineBytes;
    line = line.substr(0, kNgspiceMaxLineBytes);
  }
  NgspiceMessage message{stream, terminal_text(line)};
  if (bytes_cut > 0)
    message.text += " [... " + std::to_string(bytes_cut) + " more bytes of this line left out]";
  const std::size_t cost = message.text.size() + kMessageOverheadBytes;
  if (tail_.empty() && head_bytes_ + cost <= head_limit_) {
    head_bytes_ += cost;
    head_.push_back(std::move(message));
    return;
  }
  tail_bytes_ += cost;
  tail_.push_back(std::move(message));
  while (!tail_.empty() && tail_bytes_ > tail_limit_) {
    NgspiceMessage& oldest = tail_.front();
    tail_bytes_ -= oldest.text.size() + kMessageOverheadBytes;
    ++left_out_lines_;
    left_out_bytes_ += oldest.text.size() + 1;
    if (!first_left_out_error_ && is_ngspice_error_line(oldest))
      first_left_out_error_ = std::move(oldest);
    tail_.pop_front();
  }
}

std::vector<NgspiceMessage> MessageLog::messages() const {
  std::vector<NgspiceMessage> all = head_;
  if (left_out_lines_ > 0) {
    all.push_back({NgspiceStream::err, "[... " + std::to_string(left_out_lines_) + " lines (" +
                                           std::to_string(left_out_bytes_) +
                                           " bytes) of ngspice's output left out here: at most " +
                                           std::to_string(head_limit_ + tail_limit_) +
                                           " bytes of it are kept (max_message_bytes) ...]"});
    if (first_left_out_error_) all.push_back(*first_left_out_error_);
  }
  all.insert(all.end(), tail_.begin(), tail_.end());
  return all;
}

// ---- LineCollector ------------------------------------------------------------------------

void LineCollector::add(const char* data, std::size_t size) {
  const char* const end = data + size;
  while (data < end) {
    const char* newline =
        static_cast<const char*>(std::memchr(data, '\n', static_cast<std::size_t>(end - data)));
    const char* const stop = newline ? newline : end;
    const std::size_t length = static_cast<std::size_t>(stop - data);
    const std::size_t room =
        kNgspiceMaxLineBytes + 1 - std::min(pending_.size(), kNgspiceMaxLineBytes + 1);
    pending_.append(data, std::min(room, length));
    cut_ += length - std::min(room, length);
    if (!newline) break;
    push();
    data = newline + 1;
  }
}

void LineCollector::finish() {
  if (!pending_.empty() || cut_ > 0) push();
}

void LineCollector::push() {
  if (cut_ == 0 && !pending_.empty() && pending_.back() == '\r') pending_.pop_back();
  log_.add(stream_, pending_, cut_);
  pending_.clear();
  cut_ = 0;
}

}  // namespace emnet
