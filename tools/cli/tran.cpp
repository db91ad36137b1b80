// The tran command (tran.hpp): its options, their checks and the call of the transient
// analysis; tran_report.cpp prints the result. Also the outputs of a transient, shared with
// sweep-switching (common.hpp: transient_probes, transient_outputs, plotted_outputs).
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

namespace emnet_cli {

using emnet::InputError;

// Outputs of a transient: the scene's probes with P_k replaced by dx_k = P_k − P1 when a probe
// P1 exists (paper Eqs. 20–22), and each DEA's capacitor voltage and current when it has an
// electrical model (emnet/model/outputs.hpp, transient_output_list).
std::vector<emnet::Probe> transient_probes(const emnet::Model& model) {
  return emnet::probes_of(emnet::transient_output_list(model));
}

// The outputs of tran and sweep-switching: with --probe those, each an output name of
// transient_probes (dx4, u_A, ...) or any probe of parse_probe; else transient_probes.
std::vector<emnet::Probe> transient_outputs(const emnet::Model& model,
                                            const CommonOptions& options) {
  std::vector<emnet::Probe> outputs = transient_probes(model);
  if (options.probes.empty()) return outputs;
  std::vector<emnet::Probe> probes;
  for (const auto& text : options.probes) {
    const auto named = std::find_if(outputs.begin(), outputs.end(),
                                    [&](const emnet::Probe& probe) { return probe.name == text; });
    probes.push_back(named != outputs.end() ? *named : model.parse_probe(text));
  }
  return probes;
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
  if (!(tran.periods > 0.0) || tran.periods > 1e6)
    throw InputError("--periods", "--periods", "must be > 0 and at most 1e6 (inclusive)");
  if (!(tran.rtol >= 1e-13 && tran.rtol < 1.0))
    throw InputError("--rtol", "--rtol",
                     "must be >= 1e-13 (below that, double-precision rounding of the "
                     "residual exceeds the tolerance) and < 1");
  if (!(tran.atol >= 0.0) || !std::isfinite(tran.atol))
    throw InputError("--atol", "--atol", "must be >= 0");
  if (!(tran.max_step >= 0.0) || !std::isfinite(tran.max_step))
    throw InputError("--max-step", "--max-step", "must be >= 0 (0: no limit)");
  if (tran.points_per_period < 2 || tran.points_per_period > 100000)
    throw InputError("--points-per-period", "--points-per-period",
                     "must be from 2 to 100000 (inclusive)");
  show_phase(options, "building the network");
  const emnet::Model model = resolved_model(load_scene(options), options);
  const emnet::System system = model.network.assemble();
  const double frequency = model.scene.drive.frequency;
  if (!(frequency > 0.0))
    throw InputError(model.scene.file, "drive.frequency",
                     "a transient needs a drive with a frequency > 0 (or --switching)");
  if (tran.method == "exact" && system.is_nonlinear())
    throw InputError("--method", "--method",
                     "the exact method needs a linear network, and this scene's DEAs have their "
                     "electrical model (nonlinear); add --set drive.electrical_dynamics=false for "
                     "ideal voltage-driven DEAs, or use --method ida");
  const auto probes = transient_outputs(model, options);
  const PlottedOutputs plotted =
      tran.plot.empty() ? PlottedOutputs{} : plotted_outputs(probes, options, "");
  const double count = std::round(tran.periods * tran.points_per_period);
  if (count < 1.0)
    throw InputError("--periods", "--periods",
                     "--periods x --points-per-period must be >= 0.5, for at least one output "
                     "step after t = 0");
  check_stored_values((count + 1.0) * (probes.size() + 1.0),
                      format("%.0f", count + 1.0) + " output times x (" +
                          std::to_string(probes.size()) + " outputs + the time)",
                      "--periods", "lower --periods or --points-per-period, or give fewer --probe");
  const double period = 1.0 / frequency;
  emnet::TransientOptions transient;
  transient.end_time = tran.periods * period;
  transient.relative_tolerance = tran.rtol;
  transient.absolute_tolerance = tran.atol;
  transient.max_step = tran.max_step;
  transient.start = tran.start == "static" ? emnet::StartState::static_ : emnet::StartState::rest;
  transient.progress = progress_of(options);
  const long outputs = static_cast<long>(count);
  transient.output_times.reserve(static_cast<size_t>(outputs) + 1);
  for (long k = 0; k <= outputs; ++k)
    transient.output_times.push_back(transient.end_time * static_cast<double>(k) / outputs);
  const emnet::TransientResult result = tran.method == "exact"
                                            ? emnet::run_transient_exact(system, probes, transient)
                                            : emnet::run_transient_ida(system, probes, transient);
  if (!result.status.ok) throw NumericalFailure("tran: " + result.status.message);
  std::vector<emnet::DeflectionPeak> peaks;
  for (size_t k = 0; k < probes.size(); ++k)
    if (probes[k].quantity == emnet::ProbeQuantity::deflection) {
      peaks.push_back({probes[k].name, 0.0});
      for (double v : result.values[k])
        peaks.back().peak = std::max(peaks.back().peak, std::abs(v));
    }
  const emnet::Validity validity =
      emnet::check_validity(model.scene, peaks, emnet::drive_peak_voltages(model.scene));
  const double total = stopwatch.seconds();
  end_progress(options);
  const std::string start_text =
      tran.start == "static"
          ? "the static state under the drive's first half-period"
          : "at rest (every unknown zero before t = 0; the drive switches on at t = 0)";
  return report_tran({options, tran, model, system, probes, plotted, result, validity, start_text,
                      transient.end_time, total});
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
