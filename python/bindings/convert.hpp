// Conversions shared by the bindings: results to Python objects, failures to exceptions.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "emnet/core/errors.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/report/json.hpp"
#include "emnet/scene/scene.hpp"
#include "emnet/scene/scene_reader.hpp"

namespace emnet_python {

namespace py = pybind11;

// A numerical failure of an analysis (its Status): raised in Python as emnet.NumericalError.
class NumericalFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws NumericalFailure with `prefix` + the status's message when it failed.
void require(const emnet::Status& status, const std::string& prefix);

// A result's JSON as Python objects: objects become dicts; an array of numbers a 1-D numpy array;
// an array of equally long arrays of numbers a 2-D one; an array of objects (records) a dict of
// columns, one per key: a key of every record converted by the same rules (numbers to an array),
// a key some records lack a list with None where it is missing.
py::object to_python(const emnet::Json& json);

py::array_t<double> to_array(const std::vector<double>& values);

// Ctrl-C (or any Python signal handler's exception) while an analysis runs with the GIL released.
// cancelled() is asked by the analysis at each step: on the thread that released the GIL, at most
// every 50 ms, it takes the GIL and runs Python's pending signal handlers (PyErr_CheckSignals,
// which only the main thread may do); an exception from them (KeyboardInterrupt) is kept, and
// the analysis stops at its next step. Reports go on to `forward` (a progress line), if any.
class PythonInterrupts : public emnet::Progress {
 public:
  explicit PythonInterrupts(emnet::Progress* forward = nullptr);
  void report(long done, long total, std::string_view what) override;
  bool cancelled() const override;
  // With the GIL held, after the analysis: raises the kept exception (py::error_already_set).
  void raise_if_interrupted();

 private:
  emnet::Progress* forward_;
  std::thread::id owner_;
  mutable std::atomic<bool> interrupted_{false};
  mutable std::chrono::steady_clock::time_point last_check_;
  mutable PyObject* type_ = nullptr;
  mutable PyObject* value_ = nullptr;
  mutable PyObject* traceback_ = nullptr;
};

// Runs `body(progress)` with the GIL released, `progress` a PythonInterrupts forwarding to
// `forward`: Ctrl-C stops the analysis at its next step and raises KeyboardInterrupt here, in
// place of the result or of the failure the stop caused.
template <class Body>
void run_interruptible(Body&& body, emnet::Progress* forward = nullptr) {
  PythonInterrupts interrupts(forward);
  try {
    py::gil_scoped_release release;
    body(static_cast<emnet::Progress*>(&interrupts));
  } catch (...) {
    interrupts.raise_if_interrupted();
    throw;
  }
  interrupts.raise_if_interrupted();
}

// The keyword arguments of a binding by the library Options fields they set ({"from", "from_hz"}):
// an emnet::OptionError (which names fields) is raised as emnet.InputError naming the keyword
// argument instead. A field not listed keeps its own name, the keyword of most.
using Keywords = std::map<std::string, std::string>;

// `error` worded with `keywords`: an InputError whose where and key are the keyword arguments.
emnet::InputError with_keywords(const emnet::OptionError& error, const Keywords& keywords);

// Runs `body()`; an OptionError it throws is thrown again worded with `keywords`.
template <class Body>
void naming_keywords(const Keywords& keywords, Body&& body) {
  try {
    body();
  } catch (const emnet::OptionError& error) {
    throw with_keywords(error, keywords);
  }
}

// run_interruptible with the OptionErrors of `body` worded with `keywords`.
template <class Body>
void run_interruptible(const Keywords& keywords, Body&& body, emnet::Progress* forward = nullptr) {
  naming_keywords(keywords, [&] { run_interruptible(std::forward<Body>(body), forward); });
}

// The scene a binding works on: the read (and possibly changed) Scene, with how it was made, so
// that it can be pickled and rebuilt in another process (Dask workers).
struct SceneHandle {
  emnet::Scene scene;
  std::string text;                                  // the TOML text it was read from
  std::string name;                                  // the file it was read from, or "<text>"
  std::vector<std::string> overrides;                // applied when read
  std::vector<std::pair<std::string, double>> sets;  // set_parameter calls after reading, in order
  emnet::SceneFiles files;  // the files it read (pwl CSV), as data: a rebuilt scene reads these
};

// The bindings of each part, called by the module's definition.
void bind_analyses(py::module_& module);
void bind_studies(py::module_& module);

}  // namespace emnet_python
