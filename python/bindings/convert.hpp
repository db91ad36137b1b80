// Conversions shared by the bindings: results to Python objects, failures to exceptions.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "emnet/core/errors.hpp"
#include "emnet/report/json.hpp"
#include "emnet/scene/scene.hpp"

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

// The scene a binding works on: the read (and possibly changed) Scene, with how it was made, so
// that it can be pickled and rebuilt in another process (Dask workers).
struct SceneHandle {
  emnet::Scene scene;
  std::string text;                                  // the TOML text it was read from
  std::string name;                                  // the file it was read from, or "<text>"
  std::vector<std::string> overrides;                // applied when read
  std::vector<std::pair<std::string, double>> sets;  // set_parameter calls after reading, in order
};

// The bindings of each part, called by the module's definition.
void bind_analyses(py::module_& module);
void bind_studies(py::module_& module);

}  // namespace emnet_python
