// The design study for Python (emnet/studies/design_study.hpp): variants from KEY=SPEC texts or
// a CSV file, and a chunk of variants run on a pool of threads with the GIL released. The
// package (python/emnet/_study.py) makes the DataFrame and sends chunks to Dask workers.
#include <chrono>
#include <cstdio>
#include <memory>
#include <mutex>

#include "convert.hpp"
#include "emnet/report/design_study.hpp"
#include "emnet/studies/design_study.hpp"

namespace emnet_python {

namespace {

// Progress on standard error: "emnet study: 120/1000 variants", one line rewritten in place.
class StderrProgress : public emnet::Progress {
 public:
  void report(long done, long total, std::string_view what) override {
    std::fprintf(stderr, "\remnet study: %ld/%ld %.*s", done, total, static_cast<int>(what.size()),
                 what.data());
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }
  bool cancelled() const override { return false; }
};

// Progress to a Python callable, progress(done, total, what), at most every 0.1 s and at the
// end: a tqdm bar in a terminal or a notebook (python/emnet/_study.py). Reports come from the
// study's threads, each taking the GIL for the call; a callable that raises is not called again
// (the study goes on: progress is not the result), except for Ctrl-C, which stops the study.
class CallbackProgress : public emnet::Progress {
 public:
  explicit CallbackProgress(py::object callback) : callback_(std::move(callback)) {}
  void report(long done, long total, std::string_view what) override {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      const auto now = std::chrono::steady_clock::now();
      if (failed_ || (done != total && now - last_ < std::chrono::milliseconds(100))) return;
      last_ = now;
    }
    const py::gil_scoped_acquire gil;
    try {
      callback_(done, total, std::string(what));
    } catch (py::error_already_set& error) {
      // Ctrl-C reaches Python inside the callback as often as not (it runs Python code while
      // the study runs): it is handed back as a pending interrupt, which the study's
      // cancellation check (PythonInterrupts) then sees, not swallowed with the callback's
      // own failures.
      if (error.matches(PyExc_KeyboardInterrupt)) {
        PyErr_SetInterrupt();
        return;
      }
      const std::lock_guard<std::mutex> lock(mutex_);
      failed_ = true;
    }
  }
  bool cancelled() const override { return false; }

 private:
  py::object callback_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point last_{};
  bool failed_ = false;
};

// The reporter a study's `progress` asks for: a callable's, standard error's for true, none.
std::unique_ptr<emnet::Progress> progress_reporter(const py::object& progress) {
  if (PyCallable_Check(progress.ptr())) return std::make_unique<CallbackProgress>(progress);
  if (py::bool_(progress)) return std::make_unique<StderrProgress>();
  return nullptr;
}

py::tuple variants_tuple(const emnet::VariantTable& table) {
  const auto rows = static_cast<py::ssize_t>(table.rows.size());
  const auto columns = static_cast<py::ssize_t>(table.keys.size());
  py::array_t<double> values({rows, columns});
  auto view = values.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < rows; ++i)
    for (py::ssize_t j = 0; j < columns; ++j) view(i, j) = table.rows[i][j];
  return py::make_tuple(table.keys, values);
}

py::tuple make_variants(const SceneHandle& handle, const std::vector<std::string>& vary,
                        std::size_t samples, std::uint64_t seed) {
  emnet::VariantTable table;
  naming_keywords({{"variations", "vary"}}, [&] {
    py::gil_scoped_release release;
    std::vector<emnet::Variation> variations;
    for (const auto& text : vary) variations.push_back(emnet::parse_variation(handle.scene, text));
    table = emnet::make_variants(variations, samples, seed);
  });
  return variants_tuple(table);
}

py::tuple read_variants(const SceneHandle& handle, const std::string& path) {
  emnet::VariantTable table;
  {
    py::gil_scoped_release release;
    table = emnet::read_variants_csv(handle.scene, path);
  }
  return variants_tuple(table);
}

py::dict run_study(const SceneHandle& handle, const std::vector<std::string>& keys,
                   py::array_t<double, py::array::c_style | py::array::forcecast> values,
                   const std::string& analyses, int modes,
                   const std::vector<double>& sweep_frequencies,
                   const std::vector<double>& report_frequencies, int threads,
                   const py::object& progress) {
  if (values.ndim() != 2 || static_cast<std::size_t>(values.shape(1)) != keys.size())
    throw emnet::InputError(
        "values", "values",
        "expected a 2-D array of one column per key (" + std::to_string(keys.size()) + ")");
  emnet::VariantTable table;
  table.keys = keys;
  auto view = values.unchecked<2>();
  for (py::ssize_t i = 0; i < values.shape(0); ++i) {
    std::vector<double> row;
    for (py::ssize_t j = 0; j < values.shape(1); ++j) row.push_back(view(i, j));
    table.rows.push_back(std::move(row));
  }
  emnet::DesignStudyResult result;
  const std::unique_ptr<emnet::Progress> reporter = progress_reporter(progress);
  run_interruptible(
      Keywords{{"mode_count", "modes"}, {"variations", "vary"}, {"report_frequencies", "at"}},
      [&](emnet::Progress* interrupts) {
        emnet::DesignStudyOptions options;
        options.analyses = emnet::parse_study_analyses(analyses);
        options.mode_count = modes;
        options.sweep_frequencies = sweep_frequencies;
        options.report_frequencies = report_frequencies;
        options.threads = threads;
        options.progress = interrupts;
        result = emnet::run_design_study(handle.scene, table, options);
      },
      reporter.get());
  const auto rows = static_cast<py::ssize_t>(result.rows.size());
  const auto columns = static_cast<py::ssize_t>(result.columns.size());
  py::array_t<double> results({rows, columns});
  auto out = results.mutable_unchecked<2>();
  std::vector<std::string> status, validity;
  py::dict cost;
  std::vector<double> seconds;
  for (py::ssize_t i = 0; i < rows; ++i) {
    const auto& row = result.rows[static_cast<std::size_t>(i)];
    status.push_back(row.status.ok() ? std::string("ok") : "failed: " + row.status.message);
    validity.push_back(emnet::validity_text(row));
    for (py::ssize_t j = 0; j < columns; ++j)
      out(i, j) = row.status.ok() ? row.values[static_cast<std::size_t>(j)] : NAN;
    seconds.push_back(row.cost.total());
  }
  py::dict dict;
  dict["keys"] = result.keys;
  dict["key_units"] = result.key_units;
  dict["columns"] = result.columns;
  dict["units"] = result.units;
  dict["results"] = results;
  dict["status"] = status;
  dict["validity"] = validity;
  dict["outside_validity"] = result.outside_validity;
  dict["failed"] = result.failed;
  dict["segments"] = result.segments;
  dict["unknowns"] = result.unknowns;
  dict["threads"] = result.threads;
  dict["cost"] = py::dict(py::arg("build_seconds") = result.cost.build,
                          py::arg("operating_point_seconds") = result.cost.operating_point,
                          py::arg("modes_seconds") = result.cost.modes,
                          py::arg("static_seconds") = result.cost.static_state,
                          py::arg("sweep_seconds") = result.cost.sweep,
                          py::arg("work_seconds") = result.cost.total(),
                          py::arg("wall_seconds") = result.seconds);
  dict["variant_seconds"] = to_array(seconds);
  dict["notes"] = result.notes;
  return dict;
}

}  // namespace

void bind_studies(py::module_& m) {
  using py::arg;
  m.def("make_variants", &make_variants, arg("scene"), arg("vary"), arg("samples") = 0,
        arg("seed") = 1);
  m.def("read_variants", &read_variants, arg("scene"), arg("path"));
  m.def("run_study", &run_study, arg("scene"), arg("keys"), arg("values"),
        arg("analyses") = "modes", arg("modes") = 1,
        arg("sweep_frequencies") = std::vector<double>{},
        arg("report_frequencies") = std::vector<double>{}, arg("threads") = 0,
        arg("progress") = py::bool_(false));
}

}  // namespace emnet_python
