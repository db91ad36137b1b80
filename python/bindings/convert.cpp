// Conversions shared by the bindings (convert.hpp).
#include "convert.hpp"

#include <algorithm>

#include "emnet/core/option_error.hpp"

namespace emnet_python {

void require(const emnet::Status& status, const std::string& prefix) {
  if (!status.ok()) throw NumericalFailure(prefix + status.message);
}

emnet::InputError with_keywords(const emnet::OptionError& error, const Keywords& keywords) {
  const auto keyword = [&keywords](const std::string& field) {
    const auto found = keywords.find(field);
    return found == keywords.end() ? field : found->second;
  };
  return emnet::InputError(error.where_with(keyword), error.key_with(keyword),
                           error.reason_with(keyword));
}

py::array_t<double> to_array(const std::vector<double>& values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

namespace {

bool all_numbers(const emnet::Json& json) {
  if (!json.is_array() || json.empty()) return false;
  for (const auto& item : json)
    if (!item.is_number()) return false;
  return true;
}

// Equally long arrays of numbers.
bool matrix_of_numbers(const emnet::Json& json) {
  if (!json.is_array() || json.empty()) return false;
  for (const auto& item : json)
    if (!all_numbers(item) || item.size() != json.front().size()) return false;
  return true;
}

// Objects (records).
bool table_of_objects(const emnet::Json& json) {
  if (!json.is_array() || json.empty()) return false;
  for (const auto& item : json)
    if (!item.is_object()) return false;
  return true;
}

}  // namespace

py::object to_python(const emnet::Json& json) {
  if (json.is_null()) return py::none();
  if (json.is_boolean()) return py::bool_(json.get<bool>());
  if (json.is_number_integer()) return py::int_(json.get<long long>());
  if (json.is_number_unsigned()) return py::int_(json.get<unsigned long long>());
  if (json.is_number()) return py::float_(json.get<double>());
  if (json.is_string()) return py::str(json.get<std::string>());
  if (json.is_object()) {
    py::dict dict;
    for (auto it = json.begin(); it != json.end(); ++it)
      dict[py::str(it.key())] = to_python(it.value());
    return std::move(dict);
  }
  if (all_numbers(json)) return to_array(json.get<std::vector<double>>());
  if (matrix_of_numbers(json)) {
    const auto rows = static_cast<py::ssize_t>(json.size());
    const auto columns = static_cast<py::ssize_t>(json.front().size());
    py::array_t<double> array({rows, columns});
    auto view = array.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < rows; ++i)
      for (py::ssize_t j = 0; j < columns; ++j) view(i, j) = json[i][j].get<double>();
    return std::move(array);
  }
  if (table_of_objects(json)) {
    // Columns over the union of the records' keys, in first-seen order: a key every record has
    // is converted as an array of its own (numbers: a numpy array); one some records lack is a
    // list with None where it is missing.
    std::vector<std::string> keys;
    for (const auto& row : json)
      for (auto it = row.begin(); it != row.end(); ++it)
        if (std::find(keys.begin(), keys.end(), it.key()) == keys.end()) keys.push_back(it.key());
    py::dict columns;
    for (const auto& key : keys) {
      bool everywhere = true;
      for (const auto& row : json) everywhere = everywhere && row.contains(key);
      if (everywhere) {
        emnet::Json column = emnet::Json::array();
        for (const auto& row : json) column.push_back(row[key]);
        columns[py::str(key)] = to_python(column);
      } else {
        py::list column;
        for (const auto& row : json)
          column.append(row.contains(key) ? to_python(row[key]) : py::none());
        columns[py::str(key)] = column;
      }
    }
    return std::move(columns);
  }
  py::list list;
  for (const auto& item : json) list.append(to_python(item));
  return std::move(list);
}

PythonInterrupts::PythonInterrupts(emnet::Progress* forward)
    : forward_(forward),
      owner_(std::this_thread::get_id()),
      last_check_(std::chrono::steady_clock::now()) {}

void PythonInterrupts::report(long done, long total, std::string_view what) {
  if (forward_ != nullptr) forward_->report(done, total, what);
}

bool PythonInterrupts::cancelled() const {
  if (interrupted_.load()) return true;
  if (std::this_thread::get_id() != owner_) return false;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_check_ < std::chrono::milliseconds(50)) return false;
  last_check_ = now;
  const py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) {
    PyErr_Fetch(&type_, &value_, &traceback_);
    interrupted_.store(true);
  }
  return interrupted_.load();
}

void PythonInterrupts::raise_if_interrupted() {
  if (!interrupted_.load() || type_ == nullptr) return;
  PyErr_Restore(type_, value_, traceback_);
  type_ = value_ = traceback_ = nullptr;
  throw py::error_already_set();
}

}  // namespace emnet_python
