// emnet._emnet: the compiled part of the Python module (python/emnet/__init__.py is the public
// face). Scenes, every analysis and the design study, over the library (include/emnet/).
//
// Errors: emnet::InputError → emnet.InputError (a ValueError, with .where and .key; an
// OptionError names the keyword argument, convert.hpp's Keywords; an override's where is "set");
// a failed analysis Status → emnet.NumericalError (a RuntimeError). Every solve runs with the GIL
// released; the library keeps no global state, so calls from several threads run at once.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/version.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"

namespace emnet_python {

namespace {

SceneHandle read_handle(const std::string& text, const std::string& name,
                        const std::vector<std::string>& overrides, const emnet::SceneFiles& files) {
  SceneHandle handle;
  {
    py::gil_scoped_release release;
    handle.scene = emnet::read_scene_text(text, name, overrides, files);
    handle.files = emnet::scene_files(handle.scene);
  }
  handle.text = text;
  handle.name = name;
  handle.overrides = overrides;
  return handle;
}

}  // namespace

}  // namespace emnet_python

using namespace emnet_python;

PYBIND11_MODULE(_emnet, module) {
  module.doc() = "emnet's compiled core; use the package emnet (help(emnet)).";
  module.attr("__version__") = emnet::version();

  static py::exception<emnet::InputError> input_error(module, "InputError", PyExc_ValueError);
  static py::exception<NumericalFailure> numerical_error(module, "NumericalError",
                                                         PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr pointer) {
    try {
      if (pointer) std::rethrow_exception(pointer);
    } catch (const emnet::InputError& error) {
      // A value an override wrote (the library's where "override") came from Scene's `set`.
      const bool from_override = error.where() == "override";
      const std::string where = from_override ? "set" : error.where();
      py::object type = py::reinterpret_borrow<py::object>(input_error.ptr());
      py::object instance =
          type(from_override ? emnet::input_error_message(where, error.key(),
                                                          emnet::input_error_reason(error))
                             : std::string(error.what()));
      instance.attr("where") = where;
      instance.attr("key") = error.key();
      PyErr_SetObject(input_error.ptr(), instance.ptr());
    } catch (const NumericalFailure& error) {
      PyErr_SetString(numerical_error.ptr(), error.what());
    }
  });

  py::class_<SceneHandle>(module, "SceneHandle")
      .def_static(
          "read",
          [](const std::string& path, const std::vector<std::string>& overrides) {
            std::string text;
            {
              py::gil_scoped_release release;
              text = emnet::read_scene_file(path);
            }
            return read_handle(text, path, overrides, {});
          },
          py::arg("path"), py::arg("overrides") = std::vector<std::string>{})
      .def_static("parse", &read_handle, py::arg("text"), py::arg("name"),
                  py::arg("overrides") = std::vector<std::string>{},
                  py::arg("files") = emnet::SceneFiles{})
      .def("copy", [](const SceneHandle& handle) { return handle; })
      .def("get", [](const SceneHandle& handle,
                     const std::string& key) { return emnet::get_parameter(handle.scene, key); })
      .def("set",
           [](SceneHandle& handle, const std::string& key, double value) {
             emnet::set_parameter(handle.scene, key, value);
             handle.sets.emplace_back(key, value);
           })
      .def("canonical_key",
           [](const SceneHandle& handle, const std::string& key) {
             return emnet::find_scene_parameter_address(handle.scene, key, "key").key;
           })
      .def("unit",
           [](const SceneHandle& handle, const std::string& key) {
             const auto address = emnet::find_scene_parameter_address(handle.scene, key, "key");
             return emnet::parameter_unit(*address.info, handle.scene, address.entry);
           })
      .def("numeric_keys",
           [](const SceneHandle& handle) {
             std::vector<std::string> keys;
             for (const auto& address : emnet::scene_numeric_parameters(handle.scene))
               keys.push_back(address.key);
             return keys;
           })
      .def_property_readonly("name", [](const SceneHandle& h) { return h.scene.name; })
      .def_property_readonly("title", [](const SceneHandle& h) { return h.scene.title; })
      .def_property_readonly("file", [](const SceneHandle& h) { return h.name; })
      .def_property_readonly("text", [](const SceneHandle& h) { return h.text; })
      .def_property_readonly("overrides", [](const SceneHandle& h) { return h.overrides; })
      .def_property_readonly("sets", [](const SceneHandle& h) { return h.sets; })
      .def_property_readonly("files", [](const SceneHandle& h) { return h.files; });

  bind_analyses(module);
  bind_studies(module);
}
