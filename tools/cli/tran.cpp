// The tran command (tran.hpp): its options, their checks and the call of the transient
// analysis; tran_report.cpp prints the result. Also the outputs of a transient, shared with
// sweep-switching (common.hpp: transient_outputs, plotted_outputs).
#include "cli/tran.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <memory>

#include "emnet/analysis/transient.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/studies/transient_study.hpp"

namespace emnet_cli {

using emnet::InputError;

// The outputs of tran and sweep-switching: with --probe those, each an output name of the
// scene's recorded outputs (dx4, u_A, ...) or any probe of parse_probe; else the recorded outputs
// (emnet/studies/transient_study.hpp).
std::vector<emnet::Probe> transient_outputs(const emnet::Model& model,
                                            const CommonOptions& options) {
  return emnet::transient_outputs(model, options.probes);
}

// The outputs a --plot draws, on one axis: the deflections by default; with --probe every probe,
// which must then share a unit (refused before computing otherwise). Deflections in mm.
PlottedOutputs plotted_outputs(const std::vector<emnet::Probe>& probes,
                               const CommonOptions& options, const std::string& quantity) {
  PlottedOutputs plotted;
  for (size_t k = 0; k < probes.size(); ++k)
    if (!options.probes.empty() || probes[k].unit == "m") plotted.indices.push_back(k);
  if (plotted.indices.empty()) return plotted;
  const emnet::Probe& first = probes[plotted.indices.front()];
  for (size_t k : plotted.indices)
    if (probes[k].unit != first.unit)
      throw InputError("--plot", "--probe",
                       "a plot has one axis, but probe '" + probes[k].name + "' is in " +
                           probes[k].unit + " and '" + first.name + "' in " + first.unit +
                           ": plot probes of one unit per run (--csv and --json take any mix)");
  plotted.unit = first.unit;
  if (first.unit == "m") {
    plotted.scale = 1e3;
    plotted.axis_label = quantity + "deflection [mm]";
  } else {
    plotted.axis_label = quantity + "value [" + first.unit + "]";
  }
  return plotted;
}

int run_tran_command(CommonOptions options, const TranOptions& tran) {
  const emnet::Stopwatch stopwatch;
  if (tran.switching) {
    if (!(*tran.switching > 0.0) || !std::isfinite(*tran.switching))
      throw InputError("--switching", "--switching", "must be a positive frequency in Hz (> 0)");
    options.overrides.push_back("drive.frequency=" + format("%.17g", *tran.switching));
  }
  emnet::TransientStudyOptions study_options;
  study_options.periods = tran.periods;
  study_options.points_per_period = tran.points_per_period;
  study_options.method =
      tran.method == "exact" ? emnet::TransientMethod::exact : emnet::TransientMethod::ida;
  study_options.rtol = tran.rtol;
  study_options.atol = tran.atol;
  study_options.max_step = tran.max_step;
  study_options.start =
      tran.start == "static" ? emnet::StartState::static_ : emnet::StartState::rest;
  study_options.outputs = options.probes;
  study_options.prepare.electrical_probe_requested = electrical_probe_requested(options);
  study_options.progress = progress_of(options);
  show_phase(options, "building the network");
  // --plot's outputs are checked before the integration.
  study_options.check_outputs = [&](const std::vector<emnet::Probe>& probes) {
    if (!tran.plot.empty()) plotted_outputs(probes, options, "");
  };
  const emnet::TransientStudyResult study =
      emnet::run_transient_study(load_scene(options), study_options);
  if (!study.status.ok) throw NumericalFailure(study.status.message);
  const PlottedOutputs plotted =
      tran.plot.empty() ? PlottedOutputs{} : plotted_outputs(study.outputs, options, "");
  const double total = stopwatch.seconds();
  end_progress(options);
  return report_tran({options, tran, study.model, study.system, study.outputs, plotted,
                      study.result, study.validity, study.start_text, study.end_time, total});
}

Command add_tran_command(CLI::App& app, CommonOptions& options) {
  auto tran_options = std::make_shared<TranOptions>();
  auto* tran_command = app.add_subcommand(
      "tran",
      "time response to the scene's drive (square-wave DEA switching) with SUNDIALS IDA, or\n"
      "exactly (--method exact) for linear networks under piecewise-linear sources (any rise\n"
      "time)");
  add_common(tran_command, options);
  tran_command->add_option("--switching", tran_options->switching,
                           "switching frequency [Hz] (default: the scene's drive.frequency)");
  tran_command->add_option("--periods", tran_options->periods, "number of periods (default 10)");
  tran_command->add_option("--rtol", tran_options->rtol, "IDA relative tolerance (default 1e-6)");
  tran_command->add_option("--atol", tran_options->atol,
                           "IDA absolute tolerance for every unknown (default: rtol times a "
                           "scale per kind of unknown from the static state)");
  tran_command->add_option("--max-step", tran_options->max_step,
                           "IDA's largest step [s] (default 0: no limit)");
  tran_command->add_option("--method", tran_options->method, "ida or exact")
      ->check(CLI::IsMember({"ida", "exact"}));
  tran_command
      ->add_option("--start", tran_options->start,
                   "rest (default) or static (the static state under the first "
                   "half-period's drive)")
      ->check(CLI::IsMember({"rest", "static"}));
  tran_command->add_option("--points-per-period", tran_options->points_per_period,
                           "output points per period (default 100)");
  tran_command->add_option("--plot", tran_options->plot,
                           "write a plot of the deflections (PNG/SVG)");

  return {tran_command,
          [tran_options, &options] { return run_tran_command(options, *tran_options); }};
}

}  // namespace emnet_cli
