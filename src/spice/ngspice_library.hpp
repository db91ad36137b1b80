// The binding to libngspice: the process's one copy of the library, loaded at run time with
// dlopen (never linked at build time, so emnet starts and falls back when it is missing), its
// C callbacks, and one deck run through its shared-library API (ngSpice_Init with output
// callbacks, ngSpice_Circ with the deck's lines, ngSpice_Command("run"), ngSpice_AllVecs /
// ngGet_Vec_Info for the results).
//
// Two users: the ngspice worker program (ngspice_worker_main.cpp), which owns its process,
// and the runner's `library_in_this_process` mode (ngspice_in_this_process.cpp), which runs
// the library inside the caller's.
//
// libngspice keeps one circuit state per process in global variables; its callbacks come from
// its own threads. They hand every event to the sink of the run in progress and never throw.
#pragma once

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "emnet/core/errors.hpp"
#include "emnet/spice/ngspice_runner.hpp"
#include "ngspice_messages.hpp"

namespace emnet {

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

// The sink the callbacks report to (nullptr: events are dropped).
void set_library_run_sink(LibraryRunSink* sink);

// Keeps the run's messages in a MessageLog (bounded, printable).
class CollectingSink : public LibraryRunSink {
 public:
  explicit CollectingSink(std::size_t max_message_bytes) : log_(max_message_bytes) {}
  void message(NgspiceStream stream, std::string text) noexcept override;
  std::vector<NgspiceMessage> snapshot();

 private:
  MessageLog log_;
};

class NgspiceLibrary {
 public:
  // The process's libngspice, loaded and initialised on first use from the first of `names`
  // that loads; nullptr with `why` when none does. Reused while it is one of `names`; when it
  // is not, `may_replace` (a worker, which owns its process) sets it aside and loads anew.
  static NgspiceLibrary* acquire(const std::vector<std::string>& names, std::string& why,
                                 bool may_replace);
  // Unloads the library (after it asked to be detached); the next acquire loads it afresh.
  static void unload();

  NgspiceLibrary(const NgspiceLibrary&) = delete;
  NgspiceLibrary& operator=(const NgspiceLibrary&) = delete;
  ~NgspiceLibrary();

  const std::string& loaded_name() const { return loaded_name_; }
  // True when one of `names` loads as this very library.
  bool matches_one_of(const std::vector<std::string>& names) const;
  int command(const char* text);
  int load_circuit(std::vector<std::string> lines);
  // The names of the vectors of `plot_type` ("tran1"), in ngspice's order.
  std::vector<std::string> vector_names(const std::string& plot_type);
  // The vector `plot_type`.`name`; false when ngspice has no such vector.
  bool read_vector(const std::string& plot_type, const std::string& name, NgspiceVector& vector);

  // Set when a run could not be stopped: the library is unusable in this process.
  bool busy = false;

 private:
  NgspiceLibrary() = default;
  bool load(const std::string& name, std::string& why);
  template <class Function>
  bool find_symbol(const char* symbol, Function& function, std::string& why);

  void* handle_ = nullptr;
  std::string loaded_name_;
  struct Functions;
  std::unique_ptr<Functions> functions_;
  static std::unique_ptr<NgspiceLibrary>& instance_;
};

struct LibraryRun {
  Status status;
  std::vector<std::string> plot_names;
  std::vector<NgspiceVector> vectors;
  double ngspice_seconds = 0.0;
  bool library_asked_to_be_detached = false;
};

// Loads `lines`, runs them and reads the last plot back. `in_background`: run with bg_run and
// stop it with bg_halt after `timeout_seconds` (in the caller's process); otherwise a plain
// `run` (in the worker, whose starter keeps the time limit). `messages` gives the run's
// messages so far, for the error checks. The sink must be set (set_library_run_sink).
LibraryRun run_deck_in_library(NgspiceLibrary& library, LibraryRunSink& sink,
                               const std::vector<std::string>& lines, bool in_background,
                               double timeout_seconds,
                               const std::function<std::vector<NgspiceMessage>()>& messages);

}  // namespace emnet
