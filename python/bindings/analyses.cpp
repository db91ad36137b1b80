// The analyses of one scene, for Python: each builds the scene's model as the command of the
// same name does, runs the library's study with the GIL released, and returns the result's JSON
// (emnet/report/, the keys the command's --json prints) as a dict (to_python: numpy arrays for
// numbers along a sweep, time or beam). Units are in the keys' names (x_m, frequency_hz) or
// beside the values ("unit").
#include <cmath>
#include <optional>

#include "convert.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/report/ac_json.hpp"
#include "emnet/report/crosscheck_json.hpp"
#include "emnet/report/describe.hpp"
#include "emnet/report/identify_json.hpp"
#include "emnet/report/json.hpp"
#include "emnet/report/mismatch_json.hpp"
#include "emnet/report/spice_deck_json.hpp"
#include "emnet/report/switching_sweep_json.hpp"
#include "emnet/report/transient_json.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/studies/ac_study.hpp"
#include "emnet/studies/identify.hpp"
#include "emnet/studies/mismatch.hpp"
#include "emnet/studies/modes_study.hpp"
#include "emnet/studies/prepared_model.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/sensitivity.hpp"
#include "emnet/studies/static_study.hpp"
#include "emnet/studies/switching_sweep.hpp"
#include "emnet/studies/transient_study.hpp"
#include "emnet/verification/crosscheck.hpp"

namespace emnet_python {

namespace {

using emnet::InputError;
using emnet::Json;

using emnet::prepare_options_for_probes;

// The scene with beam.segments = "auto" resolved once (as the command line does), so that every
// model a study builds from it has the same N.
emnet::Scene with_segments(const emnet::Scene& scene) {
  return emnet::resolve_segments(scene);
}

// A result's JSON (emnet/report/) as the Python objects the functions return.
py::dict to_dict(const Json& json) {
  return to_python(json).cast<py::dict>();
}

std::vector<emnet::Probe> parse_probes(const emnet::Model& model,
                                       const std::vector<std::string>& texts) {
  if (texts.empty()) return model.probes;
  std::vector<emnet::Probe> probes;
  for (const auto& text : texts) probes.push_back(model.parse_probe(text));
  return probes;
}

emnet::PreparedModel prepare(const emnet::Scene& scene, const std::vector<std::string>& probes,
                             bool require_static, emnet::Progress* progress = nullptr) {
  emnet::OperatingPointOptions options;
  options.require_static = require_static;
  options.static_options.progress = progress;
  emnet::PrepareOptions prepare = prepare_options_for_probes(probes);
  // The static analysis requires the static state (and takes an inextensible beam with large
  // kinematics); AC, the other analysis here, linearises about it.
  prepare.large_kinematics = require_static ? emnet::LargeKinematicsUse::static_state
                                            : emnet::LargeKinematicsUse::dynamics;
  emnet::PreparedModel p = emnet::prepare_at_rest(with_segments(scene), prepare, options);
  require(p.status, "");
  return p;
}

// The keyword arguments that differ from the library's field names (convert.hpp's Keywords).
const Keywords kProbesKeywords = {{"probe", "probes"}};
const Keywords kAcKeywords = {{"probe", "probes"}, {"band", "band_hz"}};
const Keywords kOutputsKeywords = {{"probe", "outputs"}};
const Keywords kSweepKeywords = {
    {"probe", "outputs"}, {"from", "from_hz"}, {"to", "to_hz"}, {"step", "step_hz"}};
const Keywords kIdentifyKeywords = {{"mode_number", "mode"}};

// ---- static -------------------------------------------------------------------------------

py::dict run_static(const SceneHandle& handle, const std::vector<std::string>& probe_texts) {
  emnet::Stopwatch stopwatch;
  emnet::PreparedModel p;
  std::vector<emnet::Probe> probes;
  emnet::StaticStudyValues values;
  run_interruptible(kProbesKeywords, [&](emnet::Progress* progress) {
    p = prepare(handle.scene, probe_texts, true, progress);
    probes = parse_probes(p.model, probe_texts);
    values = emnet::static_study_values(p.model, p.system, p.rest, probes);
  });
  return to_dict(emnet::to_json(p.model, p.rest, values.nodes, probes, values.probe_values,
                                values.validity, stopwatch.seconds()));
}

// ---- modes --------------------------------------------------------------------------------

py::dict run_modes(const SceneHandle& handle, int count, bool dense, bool error_estimate,
                   bool shapes, const std::vector<std::string>& probe_texts) {
  emnet::Stopwatch stopwatch;
  emnet::ModesStudyResult study;
  std::vector<emnet::Probe> probes;
  run_interruptible(kProbesKeywords, [&](emnet::Progress* progress) {
    emnet::ModesStudyOptions options;
    options.count = count;
    options.dense = dense;
    options.error_estimate = error_estimate;
    options.shapes = shapes;
    options.prepare = prepare_options_for_probes(probe_texts);
    options.progress = progress;
    study = emnet::run_modes_study(with_segments(handle.scene), options);
    require(study.status, "modes: ");
    probes = parse_probes(study.model, probe_texts);
  });
  return to_dict(emnet::to_json(study, probes, stopwatch.seconds()));
}

// ---- ac -----------------------------------------------------------------------------------

py::dict run_ac(const SceneHandle& handle, std::optional<double> from_hz,
                std::optional<double> to_hz, std::optional<int> points, std::optional<bool> log,
                const std::vector<std::string>& probe_texts, bool reduce,
                std::optional<double> tolerance, std::optional<double> band_hz,
                const std::string& method) {
  emnet::Stopwatch stopwatch;
  emnet::PreparedModel p;
  std::vector<emnet::Probe> probes;
  emnet::AcStudyResult result;
  std::string input;
  run_interruptible(kAcKeywords, [&](emnet::Progress* progress) {
    emnet::AcSpec spec = handle.scene.ac;
    if (from_hz) spec.from = *from_hz;
    if (to_hz) spec.to = *to_hz;
    if (points) spec.points = *points;
    if (log) spec.log = *log;
    if (spec.points == 1 && !to_hz) spec.to = spec.from;
    if (spec.points < 1 || spec.points > 1000000)
      throw InputError("points", "points", "must be from 1 to 1000000 (inclusive)");
    if (!(spec.from >= 0.0) || !std::isfinite(spec.from))
      throw InputError("from_hz", "from_hz", "must be >= 0 Hz");
    if (!std::isfinite(spec.to) || (spec.points > 1 && !(spec.to > spec.from)) ||
        (spec.points == 1 && spec.to != spec.from))
      throw InputError("to_hz", "to_hz", "must be above from_hz (or equal to it with points = 1)");
    if (spec.log && !(spec.from > 0.0))
      throw InputError("from_hz", "from_hz", "a log scale needs from_hz > 0");
    if (method != "auto" && method != "full" && method != "reduced")
      throw InputError("method", "method",
                       "must be 'auto', 'full' or 'reduced', got '" + method + "'");
    if (reduce && method == "full")
      throw InputError("reduce", "method", "reduce=True contradicts method='full'");
    const emnet::AcSweepMethod sweep_method = reduce || method == "reduced"
                                                  ? emnet::AcSweepMethod::reduced
                                              : method == "full" ? emnet::AcSweepMethod::full
                                                                 : emnet::AcSweepMethod::automatic;
    if (sweep_method == emnet::AcSweepMethod::full && (tolerance || band_hz))
      throw InputError("tolerance/band_hz", "method",
                       "tolerance and band_hz set the modal reduction, which method='full' does "
                       "not use");
    p = prepare(handle.scene, probe_texts, false, progress);
    probes = parse_probes(p.model, probe_texts);
    emnet::require_ac_input(p.model, p.system);
    emnet::AcStudyOptions options;
    options.sweep = spec;
    options.probes = probes;
    options.progress = progress;
    options.method = sweep_method;
    if (sweep_method == emnet::AcSweepMethod::reduced || tolerance || band_hz) {
      emnet::ReductionOptions reduction;
      reduction.tolerance = tolerance.value_or(p.model.scene.model.tolerance);
      reduction.band = band_hz.value_or(spec.to);
      emnet::validate(reduction);
      options.reduction = reduction;
    }
    result = emnet::run_ac_study(p.model, p.system, p.rest.operating_point, options);
    require(result.status, result.failed_stage == emnet::AcStudyStage::reduction
                               ? "ac (modal reduction): "
                               : "ac: ");
    input = emnet::ac_input_description(p.model.scene, spec.to);
  });
  py::dict out = to_dict(emnet::to_json(result, p.model, probes, input, stopwatch.seconds()));
  // The complex responses themselves, beside magnitude and phase: [probe][frequency].
  const auto rows = static_cast<py::ssize_t>(result.ac.values.size());
  const auto columns = static_cast<py::ssize_t>(result.ac.frequencies.size());
  py::array_t<std::complex<double>> values({rows, columns});
  auto view = values.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < rows; ++i)
    for (py::ssize_t j = 0; j < columns; ++j) view(i, j) = result.ac.values[i][j];
  out["phasors"] = values;
  return out;
}

// ---- tran ---------------------------------------------------------------------------------

py::dict run_tran(const SceneHandle& handle, double periods, std::optional<double> switching_hz,
                  const std::string& method, double rtol, double atol, double max_step,
                  const std::string& start, int points_per_period,
                  const std::vector<std::string>& outputs, int shape_instants) {
  emnet::TransientStudyResult study;
  emnet::TransientStudyOptions options;
  run_interruptible(kOutputsKeywords, [&](emnet::Progress* progress) {
    if (method != "ida" && method != "exact")
      throw InputError("method", "method", "must be 'ida' or 'exact', got '" + method + "'");
    if (start != "rest" && start != "static")
      throw InputError("start", "start", "must be 'rest' or 'static', got '" + start + "'");
    options.switching_hz = switching_hz;
    options.periods = periods;
    options.points_per_period = points_per_period;
    options.method =
        method == "exact" ? emnet::TransientMethod::exact : emnet::TransientMethod::ida;
    options.rtol = rtol;
    options.atol = atol;
    options.max_step = max_step;
    options.start = start == "static" ? emnet::StartState::static_ : emnet::StartState::rest;
    options.outputs = outputs;
    options.shape_instants = shape_instants;
    options.prepare = prepare_options_for_probes(outputs);
    options.progress = progress;
    study = emnet::run_transient_study(with_segments(handle.scene), options);
    require(study.status, "");
  });
  const emnet::TransientRunDescription run{study.model.scene.name,
                                           study.model.automatic_choices,
                                           study.start_text,
                                           study.frequency_hz,
                                           periods,
                                           rtol,
                                           study.validity,
                                           study.seconds,
                                           study.shape};
  return to_dict(emnet::to_json(study.result, study.outputs, run));
}

// ---- sweep-switching ----------------------------------------------------------------------

py::dict run_sweep(const SceneHandle& handle, std::vector<double> frequencies, double from_hz,
                   double to_hz, double step_hz, const std::string& method, int samples,
                   double rtol, const std::vector<std::string>& outputs,
                   const std::vector<std::string>& sources, int shape_instants) {
  emnet::Stopwatch stopwatch;
  emnet::SwitchingSweepResult result;
  emnet::SweptModel swept;
  run_interruptible(kSweepKeywords, [&](emnet::Progress* progress) {
    if (method != "auto" && method != "exact" && method != "shooting")
      throw InputError("method", "method",
                       "must be 'auto', 'exact' or 'shooting', got '" + method + "'");
    emnet::SwitchingSweepOptions options;
    options.frequencies = frequencies;
    options.from = from_hz;
    options.to = to_hz;
    options.step = step_hz;
    options.method = method == "shooting" ? emnet::SwitchingSweepMethod::shooting
                     : method == "exact"  ? emnet::SwitchingSweepMethod::exact
                                          : emnet::SwitchingSweepMethod::automatic;
    options.samples = samples;
    options.rtol = rtol;
    options.sources = sources;
    options.shape_instants = shape_instants;
    options.validate();
    const auto grid = emnet::switching_frequencies(options);
    swept = emnet::prepare_swept_model(with_segments(handle.scene), options.method, outputs,
                                       prepare_options_for_probes(outputs),
                                       *std::max_element(grid.begin(), grid.end()));
    options.outputs = emnet::switching_sweep_outputs(swept.model, outputs);
    options.progress = progress;
    result = emnet::run_switching_sweep(swept.model, swept.scene, options);
    require(result.status, "sweep_switching: ");
  });
  std::vector<std::string> notes = swept.notes;
  notes.insert(notes.end(), result.notes.begin(), result.notes.end());
  return to_dict(emnet::to_json(result, swept.model, notes, stopwatch.seconds()));
}

// ---- identify, sensitivity, mismatch ------------------------------------------------------

py::dict run_identify(const SceneHandle& handle, double target_hz, const std::string& parameter,
                      int mode) {
  emnet::Stopwatch stopwatch;
  emnet::IdentifyResult result;
  emnet::IdentifyOptions options;
  emnet::Scene scene;
  run_interruptible(kIdentifyKeywords, [&](emnet::Progress* progress) {
    options.target_hz = target_hz;
    options.parameter = parameter;
    options.mode_number = mode;
    options.progress = progress;
    scene = with_segments(handle.scene);
    result = emnet::identify(scene, options);
    require(result.status, "identify: ");
  });
  // The call that re-identifies the values, for the scene's [provenance].
  const std::string command = "emnet.identify(" + Json(handle.name).dump() + ", " +
                              emnet::format_number("%.6g", target_hz) +
                              ", parameter=" + Json(parameter).dump() +
                              ", mode=" + std::to_string(mode) + ")";
  const emnet::IdentifyReportContext context{scene.automatic_choices, command, stopwatch.seconds()};
  return to_dict(emnet::to_json(result, options, context));
}

py::dict run_sensitivity(const SceneHandle& handle, int modes,
                         const std::vector<std::string>& parameters, bool check) {
  emnet::Stopwatch stopwatch;
  emnet::SensitivityResult result;
  emnet::Scene scene;
  run_interruptible([&](emnet::Progress* progress) {
    scene = with_segments(handle.scene);
    if (modes < 1) throw InputError("modes", "modes", "must be >= 1");
    emnet::SensitivityOptions options;
    options.modes = modes;
    options.check = check;
    options.progress = progress;
    result = emnet::run_sensitivity(scene, parameters, options);
    require(result.status, "sensitivity: ");
  });
  return to_dict(emnet::to_json(result, scene, check, stopwatch.seconds()));
}

py::dict run_mismatch(const SceneHandle& handle, std::optional<double> frequency_hz,
                      const std::string& output, double change) {
  emnet::Stopwatch stopwatch;
  emnet::MismatchResult result;
  emnet::Scene scene;
  run_interruptible([&](emnet::Progress* progress) {
    emnet::MismatchOptions options;
    options.frequency_hz = frequency_hz;
    options.output = output;
    options.change = change;
    options.progress = progress;
    scene = with_segments(handle.scene);
    result = emnet::run_mismatch(scene, options);
    require(result.status, "mismatch: ");
  });
  return to_dict(emnet::to_json(result, scene.automatic_choices, stopwatch.seconds()));
}

// ---- netlist and crosscheck -----------------------------------------------------------------

py::dict run_netlist(const SceneHandle& handle, const std::string& analysis, double periods,
                     int points_per_period, double rtol, bool control) {
  emnet::SpiceDeck deck;
  emnet::Model model;
  {
    py::gil_scoped_release release;
    emnet::SpiceDeckOptions options;
    if (analysis == "op") {
      options.analysis = emnet::SpiceAnalysis::op;
    } else if (analysis == "ac") {
      options.analysis = emnet::SpiceAnalysis::ac;
    } else if (analysis == "tran") {
      options.analysis = emnet::SpiceAnalysis::tran;
    } else {
      throw InputError("analysis", "analysis",
                       "must be 'op', 'ac' or 'tran', got '" + analysis + "'");
    }
    model = emnet::prepare_model(with_segments(handle.scene));
    if (options.analysis == emnet::SpiceAnalysis::tran) {
      if (!(model.scene.drive.frequency > 0.0))
        throw InputError(model.scene.file, "drive.frequency",
                         "a transient deck needs a drive with a frequency > 0");
      if (!(periods > 0.0) || periods > 1e6)
        throw InputError("periods", "periods", "must be > 0 and at most 1e6");
      if (points_per_period < 2 || points_per_period > 100000)
        throw InputError("points_per_period", "points_per_period", "must be from 2 to 100000");
      const double period = 1.0 / model.scene.drive.frequency;
      options.end_time = periods * period;
      options.output_step = period / points_per_period;
    }
    options.relative_tolerance = rtol;
    options.control = control;
    options.overrides = handle.overrides;
    deck = emnet::write_spice_deck(model, options);
  }
  py::dict out;
  out["text"] = deck.text;
  for (auto item : to_dict(emnet::to_json(deck, model))) out[item.first] = item.second;
  return out;
}

py::dict run_crosscheck(const SceneHandle& handle, const std::string& analyses, double timeout,
                        const std::string& worker) {
  emnet::CrosscheckReport report;
  emnet::Model model;
  emnet::Stopwatch stopwatch;
  {
    py::gil_scoped_release release;
    emnet::CrosscheckOptions options;
    options.analyses = emnet::parse_crosscheck_analyses(analyses);
    if (!(timeout > 0.0) || timeout > 86400.0)
      throw InputError("timeout", "timeout", "must be > 0 s and at most 86400 s (inclusive)");
    options.ngspice.timeout_seconds = timeout;
    options.ngspice.worker_program = worker;
    options.overrides = handle.overrides;
    model = emnet::prepare_model(with_segments(handle.scene));
    report = emnet::run_crosscheck(model, options);
    require(report.status, "crosscheck: ");
  }
  return to_dict(emnet::to_json(report, model, stopwatch.seconds()));
}

}  // namespace

void bind_analyses(py::module_& m) {
  using py::arg;
  const std::vector<std::string> none;
  m.def("static", &run_static, arg("scene"), arg("probes") = none);
  m.def("modes", &run_modes, arg("scene"), arg("count") = 0, arg("dense") = false,
        arg("error_estimate") = true, arg("shapes") = false, arg("probes") = none);
  m.def("ac", &run_ac, arg("scene"), arg("from_hz") = py::none(), arg("to_hz") = py::none(),
        arg("points") = py::none(), arg("log") = py::none(), arg("probes") = none,
        arg("reduce") = false, arg("tolerance") = py::none(), arg("band_hz") = py::none(),
        arg("method") = "auto");
  m.def("tran", &run_tran, arg("scene"), arg("periods") = 10.0, arg("switching_hz") = py::none(),
        arg("method") = "ida", arg("rtol") = 1e-6, arg("atol") = 0.0, arg("max_step") = 0.0,
        arg("start") = "rest", arg("points_per_period") = 100, arg("outputs") = none,
        arg("shape_instants") = 0);
  m.def("sweep_switching", &run_sweep, arg("scene"), arg("frequencies") = std::vector<double>{},
        arg("from_hz") = 1.0, arg("to_hz") = 7.0, arg("step_hz") = 0.1, arg("method") = "exact",
        arg("samples") = 0, arg("rtol") = 1e-9, arg("outputs") = none, arg("sources") = none,
        arg("shape_instants") = 0);
  m.def("identify", &run_identify, arg("scene"), arg("target_hz"),
        arg("parameter") = "beam.bending_stiffness", arg("mode") = 1);
  m.def("sensitivity", &run_sensitivity, arg("scene"), arg("modes") = 3, arg("parameters") = none,
        arg("check") = false);
  m.def("mismatch", &run_mismatch, arg("scene"), arg("frequency_hz") = py::none(),
        arg("output") = "", arg("change") = 0.05);
  m.def("netlist", &run_netlist, arg("scene"), arg("analysis") = "op", arg("periods") = 2.0,
        arg("points_per_period") = 2000, arg("rtol") = 1e-6, arg("control") = false);
  // worker: the emnet-ngspice-worker program (an installed package's own); empty: the
  // library's search (NgspiceOptions::worker_program).
  m.def("crosscheck", &run_crosscheck, arg("scene"), arg("analyses") = "all", arg("timeout") = 60.0,
        arg("worker") = "");
}

}  // namespace emnet_python
