// The ngspice runner; see include/emnet/spice/ngspice_runner.hpp for what it does and why.
//
// Layout of this file:
//   small helpers, a temporary directory, waiting for the worker;
//   ngspice's messages in bounded memory (MessageLog, LineCollector);
//   deck preparation and ngspice's error lines;
//   the process's one libngspice (dlopen, dlsym, ngSpice_Init once, C callbacks that hand
//   every event to the sink of the run in progress and never throw);
//   one deck through the library (shared by the worker and the in-this-process mode);
//   the forked worker and its record stream;
//   the ngspice program as a subprocess (emnet/core/process.hpp) and the rawfile parser;
//   run_ngspice, which picks the backend and falls back.
//
// The worker's record stream, child to parent, one record after another:
//   tag (1 byte) · payload length (8 bytes) · payload
// with the payload of a vector record
//   flags (1 byte: 1 scale, 2 complex) · name length (4 bytes) · name · count (8 bytes) ·
//   count doubles (real) or count (real, imaginary) pairs
// and of a message record
//   bytes cut from the line (8 bytes) · the line's first bytes (at most kMaxLineBytes)
// all in the machine's own byte order: both ends are the same program on the same machine,
// and raw doubles carry every bit. The parent checks each record's length against what its
// tag may hold (a vector: what is left of max_result_bytes) before it keeps a byte of it.
#include "emnet/spice/ngspice_runner.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <ngspice/sharedspice.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <system_error>
#include <utility>

#include "core/posix_handles.hpp"
#include "emnet/core/process.hpp"
#include "emnet/core/terminal_text.hpp"

namespace emnet {

namespace {

using Clock = std::chrono::steady_clock;

// A line of ngspice's output longer than this is cut (the rest counted, not kept).
constexpr std::size_t kMaxLineBytes = 4096;
// Memory of one message besides its text, counted against max_message_bytes.
constexpr std::size_t kMessageOverheadBytes = sizeof(NgspiceMessage);
// Reads from the worker: at most this much per wake-up.
constexpr std::size_t kReadChunkBytes = 65536;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string signal_text(int signal_number) {
  const char* name = strsignal(signal_number);
  return "signal " + std::to_string(signal_number) + (name ? std::string(", ") + name : "");
}

std::string lower_case(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string_view trimmed(std::string_view text) {
  const auto is_space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

std::string format_seconds(double seconds) {
  std::ostringstream text;
  text << seconds;
  return text.str();
}

// Waits for `child` until `timeout` seconds after `start` (not at all when `timed_out`
// already), then kills it. Returns whether the time ran out.
bool finish_or_kill(ChildProcess& child, Clock::time_point start, double timeout, bool timed_out) {
  while (!timed_out && !child.try_wait()) {
    if (seconds_since(start) > timeout) {
      timed_out = true;
      break;
    }
    ::usleep(1000);
  }
  if (timed_out) {
    child.kill();
    child.wait_blocking();
  }
  return timed_out;
}

class TemporaryDirectory {
 public:
  bool create(std::string& why) {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/emnet-ngspice-XXXXXX";
    if (!::mkdtemp(pattern.data())) {
      why = "cannot create a temporary directory (" + pattern + "): " + errno_text(errno);
      return false;
    }
    path_ = pattern;
    return true;
  }
  ~TemporaryDirectory() {
    if (path_.empty()) return;
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// ---- ngspice's messages, in bounded memory ------------------------------------------------

bool is_error_line(const NgspiceMessage& message);

// The messages of one run in at most `byte_limit` bytes (each message's text plus
// kMessageOverheadBytes): the first three quarters keep the first lines, the last quarter the
// most recent ones. The lines that fall between are counted and left out, marked by one line
// (on the error stream, so that status messages show it); the first error line among them is
// kept after the mark, for the error checks and the status message. Every line is cut at
// kMaxLineBytes and made printable (emnet/core/terminal_text.hpp) before it is stored.
class MessageLog {
 public:
  explicit MessageLog(std::size_t byte_limit)
      : head_limit_(byte_limit - byte_limit / 4), tail_limit_(byte_limit / 4) {}

  // One line, without its newline; `bytes_cut`: bytes of it already left out by the caller.
  void add(NgspiceStream stream, std::string_view line, std::uint64_t bytes_cut = 0) {
    if (line.size() > kMaxLineBytes) {
      bytes_cut += line.size() - kMaxLineBytes;
      line = line.substr(0, kMaxLineBytes);
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
      if (!first_left_out_error_ && is_error_line(oldest))
        first_left_out_error_ = std::move(oldest);
      tail_.pop_front();
    }
  }

  std::vector<NgspiceMessage> messages() const {
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
// kMaxLineBytes (+1, for a carriage return before the newline); the rest of a longer line is
// counted.
class LineCollector {
 public:
  LineCollector(NgspiceStream stream, MessageLog& log) : stream_(stream), log_(log) {}
  void add(const char* data, std::size_t size) {
    const char* const end = data + size;
    while (data < end) {
      const char* newline =
          static_cast<const char*>(std::memchr(data, '\n', static_cast<std::size_t>(end - data)));
      const char* const stop = newline ? newline : end;
      const std::size_t length = static_cast<std::size_t>(stop - data);
      const std::size_t room = kMaxLineBytes + 1 - std::min(pending_.size(), kMaxLineBytes + 1);
      pending_.append(data, std::min(room, length));
      cut_ += length - std::min(room, length);
      if (!newline) break;
      push();
      data = newline + 1;
    }
  }
  void finish() {
    if (!pending_.empty() || cut_ > 0) push();
  }

 private:
  void push() {
    if (cut_ == 0 && !pending_.empty() && pending_.back() == '\r') pending_.pop_back();
    log_.add(stream_, pending_, cut_);
    pending_.clear();
    cut_ = 0;
  }
  NgspiceStream stream_;
  MessageLog& log_;
  std::string pending_;
  std::uint64_t cut_ = 0;
};

// ---- the deck and ngspice's error lines -------------------------------------------------

// The deck's lines, `.end` last. Refuses a NUL byte (lines go to C strings) and any
// `.control` / `.endc` line (no control commands through this runner).
bool prepare_deck(const std::string& deck_text, std::vector<std::string>& lines, std::string& why) {
  if (deck_text.find('\0') != std::string::npos) {
    why = "the deck contains a NUL character";
    return false;
  }
  std::istringstream stream(deck_text);
  for (std::string line; std::getline(stream, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
  }
  if (lines.empty()) {
    why = "the deck is empty";
    return false;
  }
  const auto first_word = [](const std::string& line) {
    const std::string_view text = trimmed(line);
    return lower_case(std::string(text.substr(0, text.find_first_of(" \t"))));
  };
  for (std::size_t index = 1; index < lines.size(); ++index) {
    const std::string word = first_word(lines[index]);
    if (word == ".control" || word == ".endc") {
      why = "the deck has a " + word + " line (line " + std::to_string(index + 1) +
            "); the runner runs the deck's own analyses and takes no control commands: "
            "write the deck without its .control block";
      return false;
    }
  }
  std::size_t last = lines.size();
  while (last > 1 && trimmed(lines[last - 1]).empty()) --last;
  if (last <= 1 || first_word(lines[last - 1]) != ".end") lines.push_back(".end");
  return true;
}

bool is_error_line(const NgspiceMessage& message) {
  if (message.stream != NgspiceStream::err) return false;
  const std::string text = lower_case(std::string(trimmed(message.text)));
  // "doAnalyses: TRAN:  Timestep too small" ends the run early with the vectors so far; the
  // result must not pass for a whole run.
  return text.rfind("error", 0) == 0 || text.find("timestep too small") != std::string::npos ||
         text.find("simulation(s) aborted") != std::string::npos;
}

bool has_error_line(const std::vector<NgspiceMessage>& messages) {
  return std::any_of(messages.begin(), messages.end(), is_error_line);
}

// For a status message: ngspice's standard-error lines from its first error on, or when it
// printed no error its warnings; "Note:" lines left out, at most 20 lines.
std::string error_excerpt(const std::vector<NgspiceMessage>& messages) {
  const auto starts_with = [](const NgspiceMessage& message, const char* prefix) {
    return lower_case(std::string(trimmed(message.text))).rfind(prefix, 0) == 0;
  };
  auto first = std::find_if(messages.begin(), messages.end(), is_error_line);
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
    if (trimmed(it->text).empty() || in_note) continue;
    if (has_error ? it->stream != NgspiceStream::err : !starts_with(*it, "warning")) continue;
    if (++count > 20) {
      text += "\n  ...";
      break;
    }
    text += "\n  " + std::string(trimmed(it->text));
  }
  return text.empty() ? std::string() : ":" + text;
}

// Rawfile names as ngspice names its vectors: "v(out)" -> "out", "i(v1)" -> "v1#branch".
std::string vector_name_from_rawfile(const std::string& rawfile_name) {
  std::string name = lower_case(rawfile_name);
  if (name.size() > 3 && name.back() == ')') {
    if (name.rfind("v(", 0) == 0) return name.substr(2, name.size() - 3);
    if (name.rfind("i(", 0) == 0) return name.substr(2, name.size() - 3) + "#branch";
  }
  return name;
}

// ---- the process's libngspice ------------------------------------------------------------

struct LibraryPlotInfo {
  std::string name;        // "Transient Analysis"
  std::string type;        // "tran1": ngspice's handle on the plot
  std::string scale_name;  // "time"
};

// Receives the callbacks of one run. `message` must not throw.
class LibraryRunSink {
 public:
  virtual ~LibraryRunSink() = default;
  virtual void message(NgspiceStream stream, std::string text) noexcept = 0;

  std::mutex mutex;
  std::condition_variable changed;
  std::vector<LibraryPlotInfo> plots;
  bool controlled_exit = false;
  int controlled_exit_status = 0;
  int background_thread_exits = 0;
};

std::atomic<LibraryRunSink*> current_sink{nullptr};

// The callbacks: C signatures, called from ngspice's threads; nothing may escape them.
int on_send_char(char* text, int, void*) {
  try {
    LibraryRunSink* sink = current_sink.load();
    if (!sink || !text) return 0;
    std::string_view line(text);
    NgspiceStream stream = NgspiceStream::out;
    if (line.rfind("stderr ", 0) == 0) {
      stream = NgspiceStream::err;
      line.remove_prefix(7);
    } else if (line.rfind("stdout ", 0) == 0) {
      line.remove_prefix(7);
    }
    sink->message(stream, std::string(line));
  } catch (...) {
  }
  return 0;
}

int on_send_status(char*, int, void*) {
  return 0;
}

int on_controlled_exit(int exit_status, NG_BOOL, NG_BOOL, int, void*) {
  try {
    if (LibraryRunSink* sink = current_sink.load()) {
      std::lock_guard<std::mutex> lock(sink->mutex);
      sink->controlled_exit = true;
      sink->controlled_exit_status = exit_status;
      sink->changed.notify_all();
    }
  } catch (...) {
  }
  return 0;
}

int on_send_init_data(pvecinfoall plot, int, void*) {
  try {
    LibraryRunSink* sink = current_sink.load();
    if (!sink || !plot) return 0;
    LibraryPlotInfo info;
    info.name = plot->name ? plot->name : "";
    info.type = plot->type ? plot->type : "";
    for (int index = 0; index < plot->veccount; ++index) {
      const pvecinfo vector = plot->vecs[index];
      if (vector && vector->pdvec && vector->pdvec == vector->pdvecscale && vector->vecname)
        info.scale_name = vector->vecname;
    }
    std::lock_guard<std::mutex> lock(sink->mutex);
    sink->plots.push_back(std::move(info));
  } catch (...) {
  }
  return 0;
}

// ngspice passes true when its background thread has ended, false when it starts.
int on_background_thread(NG_BOOL thread_ended, int, void*) {
  try {
    LibraryRunSink* sink = current_sink.load();
    if (!sink || !thread_ended) return 0;
    std::lock_guard<std::mutex> lock(sink->mutex);
    ++sink->background_thread_exits;
    sink->changed.notify_all();
  } catch (...) {
  }
  return 0;
}

class NgspiceLibrary {
 public:
  // The process's libngspice, loaded and initialised on first use from the first of `names`
  // that loads; nullptr with `why` when none does. Reused while it is one of `names`; when it
  // is not, `may_replace` (a worker, which owns its process) sets it aside and loads anew.
  static NgspiceLibrary* acquire(const std::vector<std::string>& names, std::string& why,
                                 bool may_replace) {
    if (instance_ && may_replace && !instance_->matches_one_of(names)) {
      instance_->handle_ = nullptr;  // left loaded: its code may still be referenced
      instance_.reset();
    }
    if (instance_) {
      if (instance_->matches_one_of(names)) return instance_.get();
      why = "libngspice is already loaded in this process from " + instance_->loaded_name_ +
            ", which is not among the library names asked for";
      return nullptr;
    }
    std::string reasons;
    for (const std::string& name : names) {
      std::unique_ptr<NgspiceLibrary> library(new NgspiceLibrary);
      std::string reason;
      if (library->load(name, reason)) {
        instance_ = std::move(library);
        return instance_.get();
      }
      reasons += (reasons.empty() ? "" : "; ") + reason;
    }
    why = reasons.empty() ? "no library name given" : reasons;
    return nullptr;
  }
  // Unloads the library (after it asked to be detached); the next acquire loads it afresh.
  static void unload() { instance_.reset(); }

  NgspiceLibrary(const NgspiceLibrary&) = delete;
  NgspiceLibrary& operator=(const NgspiceLibrary&) = delete;
  ~NgspiceLibrary() {
    if (handle_ && !busy) ::dlclose(handle_);  // a busy library's thread still runs its code
  }

  const std::string& loaded_name() const { return loaded_name_; }
  // True when one of `names` loads as this very library.
  bool matches_one_of(const std::vector<std::string>& names) const {
    for (const std::string& name : names) {
      void* handle = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NOLOAD);
      if (!handle) continue;
      const bool same = handle == handle_;
      ::dlclose(handle);
      if (same) return true;
    }
    return false;
  }
  int command(const char* text) { return command_(const_cast<char*>(text)); }

  decltype(&ngSpice_Circ) circuit = nullptr;
  decltype(&ngSpice_AllVecs) all_vectors = nullptr;
  decltype(&ngGet_Vec_Info) vector_info = nullptr;
  // Set when a run could not be stopped: the library is unusable in this process.
  bool busy = false;

 private:
  NgspiceLibrary() = default;

  template <class Function>
  bool find_symbol(const char* symbol, Function& function, std::string& why) {
    function = reinterpret_cast<Function>(::dlsym(handle_, symbol));
    if (!function) why = loaded_name_ + " has no " + symbol;
    return function != nullptr;
  }

  bool load(const std::string& name, std::string& why) {
    ::dlerror();
    handle_ = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle_) {
      const char* error = ::dlerror();
      why = error ? error : name + ": cannot be loaded";
      return false;
    }
    loaded_name_ = name;
    decltype(&ngSpice_Init) initialise = nullptr;
    if (!find_symbol("ngSpice_Init", initialise, why) ||
        !find_symbol("ngSpice_Command", command_, why) ||
        !find_symbol("ngSpice_Circ", circuit, why) ||
        !find_symbol("ngSpice_AllVecs", all_vectors, why) ||
        !find_symbol("ngGet_Vec_Info", vector_info, why))
      return false;
    // ngSpice_Init installs its own SIGINT handler; keep the process's.
    struct sigaction interrupt_action {};
    ::sigaction(SIGINT, nullptr, &interrupt_action);
    const int result = initialise(on_send_char, on_send_status, on_controlled_exit, nullptr,
                                  on_send_init_data, on_background_thread, nullptr);
    ::sigaction(SIGINT, &interrupt_action, nullptr);
    if (result != 0) {
      why = loaded_name_ + ": ngSpice_Init failed (" + std::to_string(result) + ")";
      return false;
    }
    return true;
  }

  void* handle_ = nullptr;
  std::string loaded_name_;
  decltype(&ngSpice_Command) command_ = nullptr;
  static std::unique_ptr<NgspiceLibrary> instance_;
};

std::unique_ptr<NgspiceLibrary> NgspiceLibrary::instance_;

// ---- one deck through the library -------------------------------------------------------

struct LibraryRun {
  Status status;
  std::vector<std::string> plot_names;
  std::vector<NgspiceVector> vectors;
  double ngspice_seconds = 0.0;
  bool library_asked_to_be_detached = false;
};

// Loads `lines`, runs them and reads the last plot back. `in_background`: run with bg_run and
// stop it with bg_halt after `timeout_seconds` (in this process); otherwise a plain `run`
// (in the worker, whose parent keeps the time limit). `messages` gives the run's messages
// so far, for the error checks.
template <class Messages>
LibraryRun run_deck_in_library(NgspiceLibrary& library, LibraryRunSink& sink,
                               const std::vector<std::string>& lines, bool in_background,
                               double timeout_seconds, Messages messages) {
  LibraryRun run;
  const Clock::time_point start = Clock::now();
  const auto controlled_exit = [&] {
    std::lock_guard<std::mutex> lock(sink.mutex);
    return sink.controlled_exit;
  };
  const auto fail = [&](const std::string& what) {
    run.library_asked_to_be_detached = controlled_exit();
    run.status = Status::failure(what + error_excerpt(messages()) +
                                 (run.library_asked_to_be_detached
                                      ? "\n  (libngspice stopped and asked to be detached)"
                                      : ""));
    run.ngspice_seconds = seconds_since(start);
    return run;
  };

  std::vector<std::string> copies = lines;
  std::vector<char*> line_pointers;
  for (std::string& line : copies) line_pointers.push_back(line.data());
  line_pointers.push_back(nullptr);
  if (library.circuit(line_pointers.data()) != 0 || controlled_exit() || has_error_line(messages()))
    return fail("ngspice could not read the deck");

  if (!in_background) {
    if (library.command("run") != 0 || controlled_exit() || has_error_line(messages()))
      return fail("ngspice failed on the deck");
  } else {
    if (library.command("bg_run") != 0) return fail("ngspice could not start the run");
    const auto deadline =
        start + std::chrono::duration_cast<Clock::duration>(
                    std::chrono::duration<double>(std::max(0.0, timeout_seconds)));
    bool ended;
    {
      std::unique_lock<std::mutex> lock(sink.mutex);
      ended = sink.changed.wait_until(
          lock, deadline, [&] { return sink.background_thread_exits > 0 || sink.controlled_exit; });
    }
    if (!ended) {
      library.command("bg_halt");  // waits up to a second for the thread to stop
      std::unique_lock<std::mutex> lock(sink.mutex);
      if (!sink.changed.wait_for(lock, std::chrono::seconds(2),
                                 [&] { return sink.background_thread_exits > 0; }))
        library.busy = true;
      lock.unlock();
      run.status = Status::failure(
          "ngspice timed out: still running after " + format_seconds(timeout_seconds) +
          " s (timeout_seconds) and was stopped" +
          (library.busy ? "; it did not stop, so libngspice is unusable in this process" : ""));
      run.ngspice_seconds = seconds_since(start);
      return run;
    }
    if (controlled_exit() || has_error_line(messages())) return fail("ngspice failed on the deck");
  }

  LibraryPlotInfo plot;
  {
    std::lock_guard<std::mutex> lock(sink.mutex);
    for (const LibraryPlotInfo& info : sink.plots) run.plot_names.push_back(info.name);
    if (!sink.plots.empty()) plot = sink.plots.back();
  }
  if (plot.type.empty())
    return fail("ngspice produced no analysis results (has the deck an analysis line?)");

  std::vector<std::string> names;
  if (char** all = library.all_vectors(plot.type.data()))
    for (char** name = all; *name; ++name) names.emplace_back(*name);
  std::reverse(names.begin(), names.end());  // ngspice lists the plot's vectors last first
  for (const std::string& name : names) {
    std::string qualified = plot.type + "." + name;
    const pvector_info info = library.vector_info(qualified.data());
    if (!info) continue;
    NgspiceVector vector;
    vector.name = name;
    vector.is_scale = name == plot.scale_name;
    const std::size_t length = static_cast<std::size_t>(std::max(0, info->v_length));
    if (info->v_realdata) {
      vector.real_values.assign(info->v_realdata, info->v_realdata + length);
    } else if (info->v_compdata) {
      vector.is_complex = true;
      vector.complex_values.reserve(length);
      for (std::size_t k = 0; k < length; ++k)
        vector.complex_values.emplace_back(info->v_compdata[k].cx_real,
                                           info->v_compdata[k].cx_imag);
    }
    run.vectors.push_back(std::move(vector));
  }
  std::stable_partition(run.vectors.begin(), run.vectors.end(),
                        [](const NgspiceVector& v) { return v.is_scale; });
  run.ngspice_seconds = seconds_since(start);
  if (run.vectors.empty()) return fail("ngspice's last plot (" + plot.type + ") has no vectors");
  run.status = Status::success();
  return run;
}

// ---- libngspice in this process -----------------------------------------------------------

// Keeps the run's messages in a MessageLog (bounded, printable).
class CollectingSink : public LibraryRunSink {
 public:
  explicit CollectingSink(std::size_t max_message_bytes) : log_(max_message_bytes) {}
  void message(NgspiceStream stream, std::string text) noexcept override {
    try {
      std::lock_guard<std::mutex> lock(mutex);
      log_.add(stream, text);
    } catch (...) {
    }
  }
  std::vector<NgspiceMessage> snapshot() {
    std::lock_guard<std::mutex> lock(mutex);
    return log_.messages();
  }

 private:
  MessageLog log_;
};

// What an attempt at a backend gave: `available` false means it could not be started at all
// (with `unavailable_reason`); then the caller may fall back.
struct BackendAttempt {
  bool available = false;
  std::string unavailable_reason;
  NgspiceResult result;
};

std::mutex in_process_mutex;  // one circuit state per process

BackendAttempt run_library_in_this_process(const std::vector<std::string>& lines,
                                           const NgspiceOptions& options) {
  BackendAttempt attempt;
  std::lock_guard<std::mutex> guard(in_process_mutex);
  NgspiceLibrary* library = NgspiceLibrary::acquire(
      options.library_names, attempt.unavailable_reason, /*may_replace=*/false);
  if (!library) return attempt;
  attempt.available = true;
  NgspiceResult& result = attempt.result;
  result.backend_used = NgspiceBackend::library;
  result.backend_description = "libngspice in-process (" + terminal_text(library->loaded_name()) +
                               ", in emnet's own process)";
  if (library->busy) {
    result.status = Status::failure(
        "libngspice is still busy with an earlier deck that could not be stopped; run the "
        "deck in a worker (library_in_this_process = false)");
    return attempt;
  }
  CollectingSink sink(options.max_message_bytes);
  current_sink.store(&sink);
  LibraryRun run = run_deck_in_library(*library, sink, lines, /*in_background=*/true,
                                       options.timeout_seconds, [&] { return sink.snapshot(); });
  if (!library->busy && !run.library_asked_to_be_detached) {
    CollectingSink discard(0);  // clean-up chatter is not the deck's
    current_sink.store(&discard);
    library->command("remcirc");
    library->command("destroy all");
  }
  current_sink.store(nullptr);
  if (run.library_asked_to_be_detached && !library->busy) NgspiceLibrary::unload();
  result.status = run.status;
  result.plot_names = std::move(run.plot_names);
  result.vectors = std::move(run.vectors);
  result.ngspice_seconds = run.ngspice_seconds;
  result.messages = sink.snapshot();
  return attempt;
}

// ---- libngspice in a forked worker ------------------------------------------------------

enum class RecordTag : std::uint8_t {
  message_out = 1,
  message_err = 2,
  library_loaded = 3,       // payload: the library's name
  library_unavailable = 4,  // payload: why
  plot_name = 5,
  vector = 6,
  status = 7,  // payload: ok byte, message
  ngspice_seconds = 8,
};

class RecordWriter {
 public:
  explicit RecordWriter(int descriptor) : descriptor_(descriptor) {}
  void write(RecordTag tag, const std::string& payload) {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::uint64_t length = payload.size();
    std::string record(1, static_cast<char>(tag));
    record.append(reinterpret_cast<const char*>(&length), sizeof length);
    write_fully(descriptor_, record.data(), record.size());
    write_fully(descriptor_, payload.data(), payload.size());
  }

 private:
  int descriptor_;
  std::mutex mutex_;
};

constexpr std::size_t kRecordHeaderBytes = 1 + sizeof(std::uint64_t);
// The longest payload of a record of text (a library name or why it did not load; a status
// message: at most 20 lines of ngspice's, each at most kMaxLineBytes made printable).
constexpr std::size_t kMaxTextRecordBytes = std::size_t{1} << 20;

template <class T>
void append_raw(std::string& bytes, const T& value) {
  bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

std::string encode_vector(const NgspiceVector& vector) {
  std::string bytes;
  append_raw(bytes,
             static_cast<std::uint8_t>((vector.is_scale ? 1 : 0) | (vector.is_complex ? 2 : 0)));
  append_raw(bytes, static_cast<std::uint32_t>(vector.name.size()));
  bytes += vector.name;
  append_raw(bytes, static_cast<std::uint64_t>(vector.size()));
  if (vector.is_complex)
    bytes.append(reinterpret_cast<const char*>(vector.complex_values.data()),
                 vector.complex_values.size() * sizeof(std::complex<double>));
  else
    bytes.append(reinterpret_cast<const char*>(vector.real_values.data()),
                 vector.real_values.size() * sizeof(double));
  return bytes;
}

// A message record's payload: the count of bytes cut, then at most kMaxLineBytes of the line.
std::string encode_message(const std::string& text) {
  std::string bytes;
  const std::size_t kept = std::min(text.size(), kMaxLineBytes);
  append_raw(bytes, static_cast<std::uint64_t>(text.size() - kept));
  bytes.append(text, 0, kept);
  return bytes;
}

template <class T>
bool read_raw(const std::string& bytes, std::size_t& position, T& value) {
  if (bytes.size() - position < sizeof value) return false;
  std::memcpy(&value, bytes.data() + position, sizeof value);
  position += sizeof value;
  return true;
}

bool decode_vector(const std::string& bytes, NgspiceVector& vector) {
  std::size_t position = 0;
  std::uint8_t flags;
  std::uint32_t name_length;
  std::uint64_t count;
  if (!read_raw(bytes, position, flags) || !read_raw(bytes, position, name_length) ||
      bytes.size() - position < name_length)
    return false;
  vector.name = terminal_text(std::string_view(bytes).substr(position, name_length));
  position += name_length;
  if (!read_raw(bytes, position, count)) return false;
  vector.is_scale = (flags & 1) != 0;
  vector.is_complex = (flags & 2) != 0;
  const std::size_t element = vector.is_complex ? sizeof(std::complex<double>) : sizeof(double);
  // The count is checked against the payload's actual size before anything is allocated.
  if ((bytes.size() - position) / element != count || (bytes.size() - position) % element != 0)
    return false;
  if (vector.is_complex) {
    vector.complex_values.resize(count);
    std::memcpy(vector.complex_values.data(), bytes.data() + position, count * element);
  } else {
    vector.real_values.resize(count);
    std::memcpy(vector.real_values.data(), bytes.data() + position, count * element);
  }
  return true;
}

// The worker's records, decoded as they arrive: the buffer holds at most one record (and
// one read), and each record's claimed length is checked against what its tag may hold before
// any byte of it is kept; the vectors together may hold at most `result_byte_limit` bytes.
class RecordReader {
 public:
  explicit RecordReader(std::uint64_t result_byte_limit)
      : result_byte_limit_(result_byte_limit), result_bytes_left_(result_byte_limit) {}

  // Adds bytes and calls `handle(tag, payload)` for each record they complete. False, with
  // `problem()`, when a record breaks the rules; the stream is then unusable.
  template <class Handle>
  bool add(const char* data, std::size_t size, Handle&& handle) {
    buffer_.append(data, size);
    std::size_t position = 0;
    bool ok = true;
    while (buffer_.size() - position >= kRecordHeaderBytes) {
      const auto tag = static_cast<RecordTag>(buffer_[position]);
      std::uint64_t length;
      std::memcpy(&length, buffer_.data() + position + 1, sizeof length);
      if (!allowed(tag, length)) {
        ok = false;
        break;
      }
      if (buffer_.size() - position - kRecordHeaderBytes < length) break;
      if (tag == RecordTag::vector) result_bytes_left_ -= length;
      handle(tag, buffer_.substr(position + kRecordHeaderBytes, length));
      position += kRecordHeaderBytes + length;
    }
    buffer_.erase(0, position);
    return ok;
  }
  const std::string& problem() const { return problem_; }

 private:
  bool allowed(RecordTag tag, std::uint64_t length) {
    std::uint64_t limit = 0;
    switch (tag) {
      case RecordTag::message_out:
      case RecordTag::message_err:
        limit = sizeof(std::uint64_t) + kMaxLineBytes;
        break;
      case RecordTag::plot_name:
        limit = kMaxLineBytes;
        break;
      case RecordTag::library_loaded:
      case RecordTag::library_unavailable:
      case RecordTag::status:
        limit = kMaxTextRecordBytes + 1;
        break;
      case RecordTag::ngspice_seconds:
        limit = sizeof(double);
        break;
      case RecordTag::vector:
        if (length > result_bytes_left_) {
          problem_ = "ngspice's results are larger than max_result_bytes (" +
                     std::to_string(result_byte_limit_) + " bytes)";
          return false;
        }
        return true;
      default:
        problem_ = "the ngspice worker sent a record of unknown kind " +
                   std::to_string(static_cast<int>(tag));
        return false;
    }
    if (length <= limit) return true;
    problem_ = "the ngspice worker sent a record of kind " + std::to_string(static_cast<int>(tag)) +
               " of " + std::to_string(length) + " bytes, more than the " + std::to_string(limit) +
               " it may hold";
    return false;
  }
  std::uint64_t result_byte_limit_, result_bytes_left_;
  std::string buffer_;
  std::string problem_;
};

// Collects like CollectingSink and also streams every message to the parent.
class StreamingSink : public CollectingSink {
 public:
  StreamingSink(RecordWriter& writer, std::size_t max_message_bytes)
      : CollectingSink(max_message_bytes), writer_(writer) {}
  void message(NgspiceStream stream, std::string text) noexcept override {
    try {
      writer_.write(stream == NgspiceStream::err ? RecordTag::message_err : RecordTag::message_out,
                    encode_message(text));
    } catch (...) {
    }
    CollectingSink::message(stream, std::move(text));
  }

 private:
  RecordWriter& writer_;
};

// At most `limit` bytes of `text`, for a record of text.
std::string cut_to(const std::string& text, std::size_t limit) {
  return text.size() <= limit ? text : text.substr(0, limit);
}

// The worker's whole life, in the forked child. Never returns.
[[noreturn]] void worker_main(int record_descriptor, int output_descriptor,
                              const std::vector<std::string>& lines,
                              const NgspiceOptions& options) {
  // Anything printed past the callbacks goes to the parent, not to emnet's own output.
  ::dup2(output_descriptor, STDOUT_FILENO);
  ::dup2(output_descriptor, STDERR_FILENO);
  const int null_input = ::open("/dev/null", O_RDONLY);
  if (null_input >= 0) ::dup2(null_input, STDIN_FILENO);
  ::signal(SIGPIPE, SIG_DFL);
  ::signal(SIGINT, SIG_DFL);
  try {
    RecordWriter writer(record_descriptor);
    std::string why;
    NgspiceLibrary* library =
        NgspiceLibrary::acquire(options.library_names, why, /*may_replace=*/true);
    if (!library) {
      writer.write(RecordTag::library_unavailable, cut_to(why, kMaxTextRecordBytes));
      ::_exit(0);
    }
    writer.write(RecordTag::library_loaded, cut_to(library->loaded_name(), kMaxTextRecordBytes));
    StreamingSink sink(writer, options.max_message_bytes);
    current_sink.store(&sink);
    const LibraryRun run =
        run_deck_in_library(*library, sink, lines, /*in_background=*/false, options.timeout_seconds,
                            [&] { return sink.snapshot(); });
    for (const std::string& name : run.plot_names)
      writer.write(RecordTag::plot_name, cut_to(name, kMaxLineBytes));
    for (const NgspiceVector& vector : run.vectors)
      writer.write(RecordTag::vector, encode_vector(vector));
    std::string seconds;
    append_raw(seconds, run.ngspice_seconds);
    writer.write(RecordTag::ngspice_seconds, seconds);
    writer.write(RecordTag::status, std::string(1, run.status.ok ? '\1' : '\0') +
                                        cut_to(run.status.message, kMaxTextRecordBytes));
  } catch (...) {
    ::_exit(3);
  }
  ::_exit(0);
}

BackendAttempt run_library_in_worker(const std::vector<std::string>& lines,
                                     const NgspiceOptions& options) {
  BackendAttempt attempt;
  NgspiceResult& result = attempt.result;
  Pipe records, output;
  std::string why;
  if (!open_pipe(records, why) || !open_pipe(output, why)) {
    attempt.available = true;
    result.status = Status::failure(why);
    return attempt;
  }
  std::fflush(nullptr);  // the child must not inherit unwritten output
  const Clock::time_point start = Clock::now();
  const pid_t process_id = ::fork();
  if (process_id < 0) {
    attempt.available = true;
    result.status = Status::failure("cannot start the ngspice worker: " + errno_text(errno));
    return attempt;
  }
  if (process_id == 0) {
    records.read_end.reset();
    output.read_end.reset();
    worker_main(records.write_end.get(), output.write_end.get(), lines, options);
  }
  ChildProcess worker(process_id, /*leads_process_group=*/false);
  records.write_end.reset();
  output.write_end.reset();

  // The records and the worker's own output (as standard-error lines) in one bounded log,
  // in the order they come.
  MessageLog log(options.max_message_bytes);
  LineCollector output_lines(NgspiceStream::err, log);
  RecordReader reader(options.max_result_bytes);
  bool library_loaded = false, library_unavailable = false, have_status = false;
  const auto handle = [&](RecordTag tag, std::string payload) {
    switch (tag) {
      case RecordTag::message_out:
      case RecordTag::message_err: {
        std::size_t position = 0;
        std::uint64_t cut = 0;
        if (!read_raw(payload, position, cut)) break;
        log.add(tag == RecordTag::message_err ? NgspiceStream::err : NgspiceStream::out,
                std::string_view(payload).substr(position), cut);
        break;
      }
      case RecordTag::library_loaded:
        library_loaded = true;
        result.backend_description =
            "libngspice in-process (" + terminal_text(payload) + ", in a forked worker process)";
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
        if (payload.size() == sizeof(double))
          std::memcpy(&result.ngspice_seconds, payload.data(), sizeof(double));
        break;
      case RecordTag::status:
        have_status = !payload.empty();
        if (have_status)
          result.status =
              payload[0] ? Status::success() : Status::failure(terminal_text(payload.substr(1)));
        break;
    }
  };

  // Read both pipes until they close, the time is up or the records break the rules; each
  // wake-up reads at most one chunk from each pipe.
  std::string chunk(kReadChunkBytes, '\0');
  const double timeout = std::max(0.0, options.timeout_seconds);
  bool timed_out = false;
  std::string record_problem;
  while ((records.read_end.is_open() || output.read_end.is_open()) && record_problem.empty()) {
    const double remaining = timeout - seconds_since(start);
    if (remaining <= 0) {
      timed_out = true;
      break;
    }
    pollfd descriptors[2] = {{records.read_end.get(), POLLIN, 0},
                             {output.read_end.get(), POLLIN, 0}};
    const int ready =
        ::poll(descriptors, 2, static_cast<int>(std::ceil(std::min(remaining, 1.0) * 1000)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    if (descriptors[0].revents & (POLLIN | POLLHUP | POLLERR)) {
      const std::size_t count = read_chunk(records.read_end.get(), chunk.data(), chunk.size());
      if (count == 0)
        records.read_end.reset();
      else if (!reader.add(chunk.data(), count, handle))
        record_problem = reader.problem();
    }
    if (descriptors[1].revents & (POLLIN | POLLHUP | POLLERR)) {
      const std::size_t count = read_chunk(output.read_end.get(), chunk.data(), chunk.size());
      if (count == 0)
        output.read_end.reset();
      else
        output_lines.add(chunk.data(), count);
    }
  }
  output_lines.finish();
  // The pipes are closed: the worker is ending; give it the rest of the time to do so. A
  // worker whose records broke the rules is killed at once.
  if (!record_problem.empty()) {
    worker.kill();
    worker.wait_blocking();
  } else {
    timed_out = finish_or_kill(worker, start, timeout, timed_out);
  }
  result.seconds = seconds_since(start);
  result.messages = log.messages();
  if (library_unavailable && record_problem.empty()) return attempt;

  const int status = worker.status();
  const bool signalled = !worker.reap_failed() && WIFSIGNALED(status) && record_problem.empty();
  if (!library_loaded && !timed_out && signalled) {
    attempt.unavailable_reason =
        "the worker died of " + signal_text(WTERMSIG(status)) + " while loading libngspice";
    return attempt;
  }
  attempt.available = true;
  result.backend_used = NgspiceBackend::library;
  if (result.backend_description.empty())
    result.backend_description = "libngspice in-process (in a forked worker process)";
  if (timed_out) {
    result.vectors.clear();
    result.status =
        Status::failure("ngspice timed out: still running after " + format_seconds(timeout) +
                        " s (timeout_seconds); its worker process was killed");
  } else if (!record_problem.empty()) {
    result.vectors.clear();
    result.status = Status::failure(record_problem + "; the worker process was killed");
  } else if (signalled) {
    result.vectors.clear();
    result.status = Status::failure("ngspice crashed (" + signal_text(WTERMSIG(status)) +
                                    ") on the deck" + error_excerpt(result.messages));
  } else if (!have_status) {
    result.vectors.clear();
    result.status =
        Status::failure("the ngspice worker ended without a result (exit status " +
                        std::to_string(worker.reap_failed() ? -1 : WEXITSTATUS(status)) + ")" +
                        error_excerpt(result.messages));
  }
  if (result.ngspice_seconds == 0.0) result.ngspice_seconds = result.seconds;
  return attempt;
}

// Reads the file at `path` into `bytes` when it holds at most `limit` bytes; a missing file
// gives no bytes. The size is the file's own (fstat), never a claim inside it.
bool read_file_bounded(const std::string& path, std::uint64_t limit, std::string& bytes,
                       std::string& why) {
  bytes.clear();
  FileDescriptor file(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (!file.is_open()) {
    if (errno == ENOENT) return true;
    why = "cannot open the rawfile: " + errno_text(errno);
    return false;
  }
  struct stat status {};
  if (::fstat(file.get(), &status) != 0 || !S_ISREG(status.st_mode)) {
    why = "the rawfile is not a regular file";
    return false;
  }
  const auto size = static_cast<std::uint64_t>(status.st_size);
  if (size > limit) {
    why = "the rawfile is " + std::to_string(size) + " bytes, more than max_result_bytes (" +
          std::to_string(limit) + ")";
    return false;
  }
  bytes.resize(static_cast<std::size_t>(size));
  std::size_t filled = 0;
  while (filled < bytes.size()) {
    const std::size_t count = read_chunk(file.get(), bytes.data() + filled, bytes.size() - filled);
    if (count == 0) break;
    filled += count;
  }
  bytes.resize(filled);
  return true;
}

// ---- the ngspice program ------------------------------------------------------------------

BackendAttempt run_program(const std::vector<std::string>& lines, const NgspiceOptions& options) {
  BackendAttempt attempt;
  NgspiceResult& result = attempt.result;
  const auto fail_here = [&](const std::string& why) {
    attempt.available = true;
    result.status = Status::failure(why);
    return attempt;
  };
  TemporaryDirectory directory;
  std::string why;
  if (!directory.create(why)) return fail_here(why);
  const std::string deck_path = directory.path() + "/deck.cir";
  const std::string rawfile_path = directory.path() + "/deck.raw";
  {
    std::ofstream deck(deck_path, std::ios::binary);
    for (const std::string& line : lines) deck << line << '\n';
    if (!deck.flush()) return fail_here("cannot write the deck to " + deck_path);
  }
  MessageLog log(options.max_message_bytes);
  LineCollector out_lines(NgspiceStream::out, log);
  LineCollector err_lines(NgspiceStream::err, log);
  bool printed_anything = false;
  const auto collect = [&](LineCollector& collector) {
    return ProcessOutput::to_callback([&](const char* data, std::size_t size) {
      printed_anything = true;
      collector.add(data, size);
      return true;
    });
  };
  ProcessOptions program;
  program.arguments = {options.program, "-b", "-r", rawfile_path, deck_path};
  program.standard_output = collect(out_lines);
  program.standard_error = collect(err_lines);
  program.timeout_seconds = options.timeout_seconds;
  program.file_size_limit = options.max_result_bytes;
  const ProcessResult end = run_process(program);
  out_lines.finish();
  err_lines.finish();
  result.messages = log.messages();
  result.ngspice_seconds = end.seconds;

  using How = ProcessResult::How;
  if (end.how == How::not_started) {
    attempt.unavailable_reason =
        "cannot run '" + terminal_text(options.program) + "': " + errno_text(end.error_number);
    return attempt;
  }
  if (end.how == How::failed) return fail_here("cannot run ngspice: " + end.problem);
  attempt.available = true;
  result.backend_used = NgspiceBackend::program;
  result.backend_description = "ngspice program as a subprocess";

  if (end.how == How::timed_out)
    return fail_here("ngspice timed out: still running after " +
                     format_seconds(std::max(0.0, options.timeout_seconds)) +
                     " s (timeout_seconds); the program and everything it started were killed");
  if (end.how == How::signalled && end.signal_number == SIGXFSZ)
    return fail_here("ngspice was stopped: a file it wrote (its rawfile) reached the limit of " +
                     std::to_string(options.max_result_bytes) + " bytes (max_result_bytes)" +
                     error_excerpt(result.messages));
  if (end.how == How::signalled)
    return fail_here("ngspice crashed (" + signal_text(end.signal_number) + ") on the deck" +
                     error_excerpt(result.messages));
  if (end.exit_status != 0) {
    if (end.exit_status == 127 && !printed_anything) {
      attempt.available = false;
      attempt.unavailable_reason = "'" + terminal_text(options.program) + "' could not be executed";
      return attempt;
    }
    return fail_here("ngspice failed on the deck (exit status " + std::to_string(end.exit_status) +
                     ")" + error_excerpt(result.messages));
  }
  if (has_error_line(result.messages))
    return fail_here("ngspice failed on the deck" + error_excerpt(result.messages));

  std::string bytes;
  if (!read_file_bounded(rawfile_path, options.max_result_bytes, bytes, why))
    return fail_here("ngspice wrote no readable results (" + why + ")" +
                     error_excerpt(result.messages));
  std::vector<NgspiceRawPlot> plots;
  if (bytes.empty() || !parse_ngspice_rawfile(bytes, plots, why) || plots.empty())
    return fail_here(
        "ngspice wrote no readable results" +
        (bytes.empty() ? std::string(" (has the deck an analysis line?)") : " (" + why + ")") +
        error_excerpt(result.messages));
  for (const NgspiceRawPlot& plot : plots)
    result.plot_names.push_back(terminal_text(plot.plot_name));
  result.vectors = std::move(plots.back().vectors);
  for (NgspiceVector& vector : result.vectors)
    vector.name = terminal_text(vector_name_from_rawfile(vector.name));
  result.status = Status::success();
  return attempt;
}

}  // namespace

// ---- rawfile ------------------------------------------------------------------------------

bool parse_ngspice_rawfile(const std::string& bytes, std::vector<NgspiceRawPlot>& plots,
                           std::string& why) {
  std::size_t position = 0;
  const auto next_line = [&](std::string& line) {
    if (position >= bytes.size()) return false;
    std::size_t end = bytes.find('\n', position);
    if (end == std::string::npos) end = bytes.size();
    line = bytes.substr(position, end - position);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    position = end + 1;
    return true;
  };
  const auto parse_count = [](std::string_view text, std::size_t& count) {
    text = trimmed(text);
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), count);
    return error == std::errc() && end == text.data() + text.size();
  };
  const auto parse_double = [](std::string_view text, double& value) {
    text = trimmed(text);
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    return error == std::errc() && end == text.data() + text.size();
  };

  while (position < bytes.size()) {
    NgspiceRawPlot plot;
    std::size_t variable_count = 0, point_count = 0;
    bool have_variables = false, have_points = false, binary = false, values = false;
    std::string line;
    while (next_line(line)) {
      if (trimmed(line).empty()) continue;
      const std::size_t colon = line.find(':');
      const std::string key = colon == std::string::npos ? line : line.substr(0, colon);
      const std::string value =
          colon == std::string::npos ? "" : std::string(trimmed(line.substr(colon + 1)));
      if (key == "Title") {
        plot.title = value;
      } else if (key == "Plotname") {
        plot.plot_name = value;
      } else if (key == "Flags") {
        plot.flags = value;
      } else if (key == "No. Variables") {
        have_variables = parse_count(value, variable_count);
      } else if (key == "No. Points") {
        have_points = parse_count(value, point_count);
      } else if (key == "Variables") {
        if (!have_variables) {
          why = "'Variables:' before 'No. Variables:'";
          return false;
        }
        for (std::size_t index = 0; index < variable_count; ++index) {
          if (!next_line(line)) {
            why = "the variable list ends early";
            return false;
          }
          std::istringstream fields(line);
          std::string number, name;
          if (!(fields >> number >> name)) {
            why = "cannot read variable line '" + terminal_excerpt(line, 200) + "'";
            return false;
          }
          NgspiceVector vector;
          vector.name = name;
          vector.is_scale = index == 0;
          plot.vectors.push_back(std::move(vector));
        }
      } else if (key == "Binary") {
        binary = true;
        break;
      } else if (key == "Values") {
        values = true;
        break;
      }
    }
    if (!binary && !values) {
      if (plots.empty()) why = "no 'Binary:' or 'Values:' section";
      return !plots.empty();
    }
    const std::string plot_label = "plot '" + terminal_excerpt(plot.plot_name, 200) + "'";
    if (!have_variables || !have_points || plot.vectors.size() != variable_count) {
      why = plot_label + " lacks its variable or point count";
      return false;
    }
    if (variable_count == 0) {
      why = plot_label + " has no variables (not even its scale)";
      return false;
    }
    // The header's claim against what the file holds, before anything is allocated: a binary
    // value takes 8 bytes (16 complex), an ASCII one at least 2 (a digit and a newline, which
    // the file's last value may lack).
    const bool complex = plot.flags.find("complex") != std::string::npos;
    const std::size_t per_value =
        binary ? (complex ? 2 * sizeof(double) : sizeof(double)) : std::size_t{2};
    const std::size_t available = position <= bytes.size() ? bytes.size() - position : 0;
    const std::size_t most_points = (available + (binary ? 0 : 1)) / per_value / variable_count;
    if (point_count > most_points) {
      why = plot_label + " is truncated: its header claims " + std::to_string(point_count) +
            " points of " + std::to_string(variable_count) + " variables, the " +
            std::to_string(available) + " bytes after it hold at most " +
            std::to_string(most_points);
      return false;
    }
    for (NgspiceVector& vector : plot.vectors) {
      vector.is_complex = complex;
      if (complex)
        vector.complex_values.resize(point_count);
      else
        vector.real_values.resize(point_count);
    }
    if (binary) {
      const std::size_t needed = point_count * variable_count * per_value;  // <= available
      if (bytes.size() - position < needed) {
        why = plot_label + " is truncated";
        return false;
      }
      for (std::size_t point = 0; point < point_count; ++point)
        for (NgspiceVector& vector : plot.vectors) {
          double parts[2] = {0.0, 0.0};
          std::memcpy(parts, bytes.data() + position, per_value);
          position += per_value;
          if (complex)
            vector.complex_values[point] = {parts[0], parts[1]};
          else
            vector.real_values[point] = parts[0];
        }
    } else {
      // ASCII: "index<TAB>value" then one value per line; complex values as "re,im".
      for (std::size_t point = 0; point < point_count; ++point)
        for (std::size_t index = 0; index < variable_count; ++index) {
          std::string text;
          do {
            if (!next_line(text)) {
              why = plot_label + " is truncated";
              return false;
            }
          } while (trimmed(text).empty());
          if (index == 0) {
            const std::string_view rest = trimmed(text);
            const std::size_t gap = rest.find_first_of(" \t");
            text = gap == std::string_view::npos ? "" : std::string(rest.substr(gap));
          }
          const std::size_t comma = text.find(',');
          double real = 0.0, imaginary = 0.0;
          const bool ok =
              comma == std::string::npos
                  ? parse_double(text, real)
                  : parse_double(std::string_view(text).substr(0, comma), real) &&
                        parse_double(std::string_view(text).substr(comma + 1), imaginary);
          if (!ok) {
            why = "cannot read value '" + terminal_excerpt(text, 200) + "' in " + plot_label;
            return false;
          }
          NgspiceVector& vector = plot.vectors[index];
          if (complex)
            vector.complex_values[point] = {real, imaginary};
          else
            vector.real_values[point] = real;
        }
    }
    // The scale of a complex plot is a real frequency; ngspice 39 writes uninitialised bytes
    // in its imaginary half in binary rawfiles. It is zero, as libngspice reports it.
    if (complex && !plot.vectors.empty())
      for (std::complex<double>& value : plot.vectors.front().complex_values) value.imag(0.0);
    plots.push_back(std::move(plot));
  }
  return true;
}

// ---- the result -----------------------------------------------------------------------------

const NgspiceVector* NgspiceResult::find(std::string_view name) const {
  const std::string wanted = vector_name_from_rawfile(std::string(trimmed(name)));
  for (const NgspiceVector& vector : vectors)
    if (lower_case(vector.name) == wanted) return &vector;
  return nullptr;
}

const NgspiceVector* NgspiceResult::scale() const {
  for (const NgspiceVector& vector : vectors)
    if (vector.is_scale) return &vector;
  return nullptr;
}

std::string NgspiceResult::messages_text() const {
  std::string text;
  for (const NgspiceMessage& message : messages)
    text += (message.stream == NgspiceStream::err ? "stderr: " : "") + message.text + "\n";
  return text;
}

// ---- run_ngspice ------------------------------------------------------------------------

NgspiceResult run_ngspice(const std::string& deck_text, const NgspiceOptions& options) {
  const Clock::time_point start = Clock::now();
  const auto finish = [&](NgspiceResult result) {
    result.seconds = seconds_since(start);
    return result;
  };
  NgspiceResult result;
  std::vector<std::string> lines;
  std::string why;
  if (!prepare_deck(deck_text, lines, why)) {
    result.status = Status::failure("the deck was not run: " + why);
    result.backend_description = "none (the deck was refused)";
    return finish(std::move(result));
  }

  std::string library_reason;
  if (options.backend != NgspiceBackend::program) {
    BackendAttempt attempt = options.library_in_this_process
                                 ? run_library_in_this_process(lines, options)
                                 : run_library_in_worker(lines, options);
    if (attempt.available) return finish(std::move(attempt.result));
    library_reason = terminal_text(attempt.unavailable_reason);  // dlerror's text, paths
    if (options.backend == NgspiceBackend::library) {
      result.status = Status::failure("libngspice could not be loaded (" + library_reason +
                                      "); install the Debian package libngspice0");
      result.backend_description = "none (libngspice not available)";
      return finish(std::move(result));
    }
  }

  BackendAttempt attempt = run_program(lines, options);
  if (attempt.available) {
    if (options.backend == NgspiceBackend::automatic)
      attempt.result.backend_description += " (libngspice not available: " + library_reason + ")";
    return finish(std::move(attempt.result));
  }
  if (options.backend == NgspiceBackend::automatic) {
    result.status = Status::failure(
        "ngspice is not available: libngspice could not be loaded (" + library_reason +
        ") and the ngspice program could not be run (" + attempt.unavailable_reason +
        "); install the Debian packages libngspice0 and ngspice");
  } else {
    result.status =
        Status::failure("the ngspice program could not be run (" + attempt.unavailable_reason +
                        "); install the Debian package ngspice");
  }
  result.backend_description = "none (ngspice not available)";
  return finish(std::move(result));
}

}  // namespace emnet
