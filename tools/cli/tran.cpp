// The tran command (tran.hpp): its options, their checks and the call of the transient
// analysis; tran_report.cpp prints the result. Also the outputs of a transient, shared with
// sweep-switching (common.hpp: transient_outputs, plotted_outputs).
#include "cli/tran.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>

#include "cli/option_names.hpp"
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

// The outputs a --plot draws: with --probe every probe; else the deflections and the DEA
// voltages. The plot gives each unit its own panel, so any mix of units can be plotted.
PlottedOutputs plotted_outputs(const std::vector<emnet::Probe>& probes,
                               const CommonOptions& options) {
  PlottedOutputs plotted;
  for (size_t k = 0; k < probes.size(); ++k)
    if (!options.probes.empty() || probes[k].unit == "m" ||
        probes[k].quantity == emnet::ProbeQuantity::dea_voltage)
      plotted.indices.push_back(k);
  return plotted;
}

namespace {

// The DEA voltages u_X a --plot shows under the response when --probe does not name them: every
// DEA's, when the scene gives the DEAs their electrical model outright (drive.electrical_dynamics
// = true, not "auto", whose choice is made when the model is built); they are computed with the
// probes and only plotted.
std::vector<std::string> plot_only_outputs(const emnet::Scene& scene,
                                           const CommonOptions& options) {
  std::vector<std::string> extra;
  if (options.probes.empty() || !scene.drive.electrical_dynamics ||
      scene.drive.electrical_dynamics_auto)
    return extra;
  for (const emnet::DeaSpec& dea : scene.deas) {
    // By its probe text, which every scene parses ("u_X" is an output name only where no
    // scene probe already shows that voltage under a name of its own).
    const std::string text = "dea_voltage:" + dea.name;
    if (std::find(options.probes.begin(), options.probes.end(), "u_" + dea.name) ==
            options.probes.end() &&
        std::find(options.probes.begin(), options.probes.end(), text) == options.probes.end())
      extra.push_back(text);
  }
  return extra;
}

}  // namespace

int run_tran_command(CommonOptions options, const TranOptions& tran) {
  const emnet::Stopwatch stopwatch;
  check_plot_options(tran.plot, tran.plot_script);
  if (tran.switching) {
    if (!(*tran.switching > 0.0) || !std::isfinite(*tran.switching))
      throw InputError("--switching", "--switching", "must be a positive frequency in Hz (> 0)");
  }
  emnet::TransientStudyOptions study_options;
  // The drive's and the circuit's periodic sources' frequency (emnet::set_switching_frequency).
  study_options.switching_hz = tran.switching;
  study_options.periods = tran.periods;
  study_options.points_per_period = tran.points_per_period;
  study_options.method =
      tran.method == "exact" ? emnet::TransientMethod::exact : emnet::TransientMethod::ida;
  study_options.rtol = tran.rtol;
  study_options.atol = tran.atol;
  study_options.max_step = tran.max_step;
  study_options.start =
      tran.start == "static" ? emnet::StartState::static_ : emnet::StartState::rest;
  emnet::Scene scene = load_scene(options);
  const std::vector<std::string> plot_only =
      tran.plot.empty() ? std::vector<std::string>{} : plot_only_outputs(scene, options);
  study_options.outputs = options.probes;
  study_options.outputs.insert(study_options.outputs.end(), plot_only.begin(), plot_only.end());
  study_options.prepare.electrical_probe_requested = electrical_probe_requested(options);
  study_options.shape_instants = shape_instants(tran.shape);
  study_options.progress = progress_of(options);
  show_phase(options, "building the network");
  emnet::TransientStudyResult study = emnet::run_transient_study(std::move(scene), study_options);
  if (!study.status.ok()) throw NumericalFailure(study.status.message);
  // The table, --csv and --json show the outputs asked for; the plot also the plot-only ones,
  // whose values are moved out of the result (not copied).
  const size_t shown = study.outputs.size() - plot_only.size();
  const std::vector<emnet::Probe> shown_probes(study.outputs.begin(),
                                               study.outputs.begin() + shown);
  auto& values = study.result.values;
  std::vector<std::vector<double>> plot_only_values(
      std::make_move_iterator(values.begin() + static_cast<std::ptrdiff_t>(shown)),
      std::make_move_iterator(values.end()));
  values.resize(shown);
  PlottedOutputs plotted;
  if (!tran.plot.empty()) {
    plotted = plotted_outputs(shown_probes, options);
    for (size_t k = shown; k < study.outputs.size(); ++k) plotted.indices.push_back(k);
  }
  const double total = stopwatch.seconds();
  end_progress(options);
  return report_tran({options, tran, study.model, study.system, shown_probes, study.outputs,
                      plotted, study.result, study.shape, plot_only_values, study.validity,
                      study.start_text, study.end_time, total});
}

Command add_tran_command(CLI::App& app, CommonOptions& options) {
  auto tran_options = std::make_shared<TranOptions>();
  auto* tran_command = app.add_subcommand(
      "tran",
      "time response to the scene's drive (square-wave DEA switching) with SUNDIALS IDA, or\n"
      "exactly (--method exact) for linear networks under piecewise-linear sources (any rise\n"
      "time)");
  add_common(tran_command, options);
  sets_fields(
      tran_command->add_option("--switching", tran_options->switching,
                               "switching frequency [Hz] (default: the scene's drive.frequency)"),
      {"switching_hz"});
  sets_fields(tran_command->add_option("--periods", tran_options->periods,
                                       "number of periods (default 10)"),
              {"periods"});
  sets_fields(tran_command->add_option("--rtol", tran_options->rtol,
                                       "IDA relative tolerance (default 1e-6)"),
              {"rtol"});
  sets_fields(tran_command->add_option("--atol", tran_options->atol,
                                       "IDA absolute tolerance for every unknown (default: rtol "
                                       "times a scale per kind of unknown from the static state)"),
              {"atol"});
  sets_fields(tran_command->add_option("--max-step", tran_options->max_step,
                                       "IDA's largest step [s] (default 0: no limit)"),
              {"max_step"});
  sets_fields(tran_command->add_option("--method", tran_options->method, "ida or exact")
                  ->check(CLI::IsMember({"ida", "exact"})),
              {"method"});
  sets_fields(tran_command
                  ->add_option("--start", tran_options->start,
                               "rest (default) or static (the static state under the first "
                               "half-period's drive)")
                  ->check(CLI::IsMember({"rest", "static"})),
              {"start"});
  sets_fields(tran_command->add_option("--points-per-period", tran_options->points_per_period,
                                       "output points per period (default 100)"),
              {"points_per_period"});
  add_plot_options(tran_command, tran_options->plot, tran_options->plot_script,
                   "the response over time (the deflections, or the --probe outputs, one panel "
                   "per unit) over a panel of the drive: the DEA voltages and the source "
                   "voltages [V]");
  add_shape_options(tran_command, tran_options->shape,
                    "over the last period, at output times (--shape-instants at most "
                    "--points-per-period)");

  return {tran_command,
          [tran_options, &options] { return run_tran_command(options, *tran_options); }};
}

}  // namespace emnet_cli
