// The binding to libngspice (dlopen, dlsym, ngSpice_Init once, the C callbacks) and one deck
// through it; see ngspice_library.hpp.
#include "ngspice_library.hpp"

#include <dlfcn.h>
#include <ngspice/sharedspice.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>

namespace emnet {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

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

// ngspice's background threads that have reported their end (the callback runs on the thread
// itself) and may still be running the library's code on their way out: the library must not
// be unloaded under them.
std::mutex ending_threads_mutex;
std::vector<pid_t> ending_threads;

bool thread_alive(pid_t thread) {
  struct stat status {};
  return ::stat(("/proc/self/task/" + std::to_string(thread)).c_str(), &status) == 0;
}

// Waits until every background thread that reported its end has ended, at most `seconds`;
// false when one is still there.
bool wait_for_ending_threads(double seconds) {
  const auto give_up = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::duration<double>(seconds));
  std::lock_guard<std::mutex> lock(ending_threads_mutex);
  for (;;) {
    ending_threads.erase(std::remove_if(ending_threads.begin(), ending_threads.end(),
                                        [](pid_t thread) { return !thread_alive(thread); }),
                         ending_threads.end());
    if (ending_threads.empty()) return true;
    if (Clock::now() > give_up) return false;
    ::usleep(200);
  }
}

// ngspice passes true when its background thread has ended, false when it starts.
int on_background_thread(NG_BOOL thread_ended, int, void*) {
  try {
    if (thread_ended) {
      std::lock_guard<std::mutex> lock(ending_threads_mutex);
      ending_threads.push_back(static_cast<pid_t>(::syscall(SYS_gettid)));
    }
    LibraryRunSink* sink = current_sink.load();
    if (!sink || !thread_ended) return 0;
    std::lock_guard<std::mutex> lock(sink->mutex);
    ++sink->background_thread_exits;
    sink->changed.notify_all();
  } catch (...) {
  }
  return 0;
}

}  // namespace

void set_library_run_sink(LibraryRunSink* sink) {
  current_sink.store(sink);
}

// ---- CollectingSink -------------------------------------------------------------------------

void CollectingSink::message(NgspiceStream stream, std::string text) noexcept {
  try {
    std::lock_guard<std::mutex> lock(mutex);
    log_.add(stream, text);
  } catch (...) {
  }
}

std::vector<NgspiceMessage> CollectingSink::snapshot() {
  std::lock_guard<std::mutex> lock(mutex);
  return log_.messages();
}

// ---- NgspiceLibrary -------------------------------------------------------------------------

struct NgspiceLibrary::Functions {
  decltype(&ngSpice_Command) command = nullptr;
  decltype(&ngSpice_Circ) circuit = nullptr;
  decltype(&ngSpice_AllVecs) all_vectors = nullptr;
  decltype(&ngGet_Vec_Info) vector_info = nullptr;
};

// Never destroyed: at the process's exit the library stays loaded. ngspice's background thread
// runs on in the library's code for a moment after it reports its end (the last run's), and a
// dlclose among the static destructors could unmap that code under it (a crash at exit).
std::unique_ptr<NgspiceLibrary>& NgspiceLibrary::instance_ = *new std::unique_ptr<NgspiceLibrary>;

NgspiceLibrary* NgspiceLibrary::acquire(const std::vector<std::string>& names, std::string& why,
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

void NgspiceLibrary::unload() {
  // A background thread still on its way out of the library's code: it stays loaded (set
  // aside, as in acquire), rather than unmapped under that thread.
  if (instance_ && !wait_for_ending_threads(2.0)) instance_->handle_ = nullptr;
  instance_.reset();
}

NgspiceLibrary::~NgspiceLibrary() {
  if (handle_ && !busy) ::dlclose(handle_);  // a busy library's thread still runs its code
}

bool NgspiceLibrary::matches_one_of(const std::vector<std::string>& names) const {
  for (const std::string& name : names) {
    void* handle = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NOLOAD);
    if (!handle) continue;
    const bool same = handle == handle_;
    ::dlclose(handle);
    if (same) return true;
  }
  return false;
}

int NgspiceLibrary::command(const char* text) {
  return functions_->command(const_cast<char*>(text));
}

int NgspiceLibrary::load_circuit(std::vector<std::string> lines) {
  std::vector<char*> line_pointers;
  for (std::string& line : lines) line_pointers.push_back(line.data());
  line_pointers.push_back(nullptr);
  return functions_->circuit(line_pointers.data());
}

std::vector<std::string> NgspiceLibrary::vector_names(const std::string& plot_type) {
  std::string type = plot_type;
  std::vector<std::string> names;
  if (char** all = functions_->all_vectors(type.data()))
    for (char** name = all; *name; ++name) names.emplace_back(*name);
  std::reverse(names.begin(), names.end());  // ngspice lists the plot's vectors last first
  return names;
}

bool NgspiceLibrary::read_vector(const std::string& plot_type, const std::string& name,
                                 NgspiceVector& vector) {
  std::string qualified = plot_type + "." + name;
  const pvector_info info = functions_->vector_info(qualified.data());
  if (!info) return false;
  vector.name = name;
  const std::size_t length = static_cast<std::size_t>(std::max(0, info->v_length));
  if (info->v_realdata) {
    vector.real_values.assign(info->v_realdata, info->v_realdata + length);
  } else if (info->v_compdata) {
    vector.is_complex = true;
    vector.complex_values.reserve(length);
    for (std::size_t k = 0; k < length; ++k)
      vector.complex_values.emplace_back(info->v_compdata[k].cx_real, info->v_compdata[k].cx_imag);
  }
  return true;
}

template <class Function>
bool NgspiceLibrary::find_symbol(const char* symbol, Function& function, std::string& why) {
  function = reinterpret_cast<Function>(::dlsym(handle_, symbol));
  if (!function) why = loaded_name_ + " has no " + symbol;
  return function != nullptr;
}

bool NgspiceLibrary::load(const std::string& name, std::string& why) {
  ::dlerror();
  handle_ = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle_) {
    const char* error = ::dlerror();
    why = error ? error : name + ": cannot be loaded";
    return false;
  }
  loaded_name_ = name;
  functions_ = std::make_unique<Functions>();
  decltype(&ngSpice_Init) initialise = nullptr;
  if (!find_symbol("ngSpice_Init", initialise, why) ||
      !find_symbol("ngSpice_Command", functions_->command, why) ||
      !find_symbol("ngSpice_Circ", functions_->circuit, why) ||
      !find_symbol("ngSpice_AllVecs", functions_->all_vectors, why) ||
      !find_symbol("ngGet_Vec_Info", functions_->vector_info, why))
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

// ---- one deck through the library -------------------------------------------------------

LibraryRun run_deck_in_library(NgspiceLibrary& library, LibraryRunSink& sink,
                               const std::vector<std::string>& lines, bool in_background,
                               double timeout_seconds,
                               const std::function<std::vector<NgspiceMessage>()>& messages) {
  LibraryRun run;
  const Clock::time_point start = Clock::now();
  const auto controlled_exit = [&] {
    std::lock_guard<std::mutex> lock(sink.mutex);
    return sink.controlled_exit;
  };
  const auto fail = [&](const std::string& what) {
    run.library_asked_to_be_detached = controlled_exit();
    run.status = Status::failure(what + ngspice_error_excerpt(messages()) +
                                 (run.library_asked_to_be_detached
                                      ? "\n  (libngspice stopped and asked to be detached)"
                                      : ""));
    run.ngspice_seconds = seconds_since(start);
    return run;
  };

  if (library.load_circuit(lines) != 0 || controlled_exit() || has_ngspice_error_line(messages()))
    return fail("ngspice could not read the deck");

  if (!in_background) {
    if (library.command("run") != 0 || controlled_exit() || has_ngspice_error_line(messages()))
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
          "ngspice timed out: still running after " + ngspice_seconds_text(timeout_seconds) +
          " s (timeout_seconds) and was stopped" +
          (library.busy ? "; it did not stop, so libngspice is unusable in this process" : ""));
      run.ngspice_seconds = seconds_since(start);
      return run;
    }
    if (controlled_exit() || has_ngspice_error_line(messages()))
      return fail("ngspice failed on the deck");
  }

  LibraryPlotInfo plot;
  {
    std::lock_guard<std::mutex> lock(sink.mutex);
    for (const LibraryPlotInfo& info : sink.plots) run.plot_names.push_back(info.name);
    if (!sink.plots.empty()) plot = sink.plots.back();
  }
  if (plot.type.empty())
    return fail("ngspice produced no analysis results (has the deck an analysis line?)");

  for (const std::string& name : library.vector_names(plot.type)) {
    NgspiceVector vector;
    if (!library.read_vector(plot.type, name, vector)) continue;
    vector.is_scale = name == plot.scale_name;
    run.vectors.push_back(std::move(vector));
  }
  std::stable_partition(run.vectors.begin(), run.vectors.end(),
                        [](const NgspiceVector& v) { return v.is_scale; });
  run.ngspice_seconds = seconds_since(start);
  if (run.vectors.empty()) return fail("ngspice's last plot (" + plot.type + ") has no vectors");
  run.status = Status::success();
  return run;
}

}  // namespace emnet
