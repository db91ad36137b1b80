// The ac command: its options, the checks of them, and the call of emnet::run_ac_study; the
// report is in ac_report.cpp.
#include "cli/ac.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <memory>
#include <optional>
#include <string>

#include "cli/common.hpp"
#include "cli/option_names.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/studies/ac_study.hpp"

namespace emnet_cli {

using emnet::InputError;

struct AcOptions {
  std::string from, to;  // as given; parsed by checked_ac_spec
  std::optional<int> points;
  std::string scale;
  std::string plot;
  bool plot_script = false;
  bool reduce = false;
  std::string method;           // --method: auto, full or reduced (--reduce: reduced)
  std::string tolerance, band;  // as given, parsed and checked by reduction_options
};

// --method and --reduce as the study's method.
emnet::AcSweepMethod sweep_method(const AcOptions& ac_options) {
  if (ac_options.reduce && !ac_options.method.empty() && ac_options.method != "reduced")
    throw InputError("--reduce", "--method",
                     "--reduce is --method reduced; it contradicts --method " + ac_options.method);
  if (ac_options.reduce || ac_options.method == "reduced") return emnet::AcSweepMethod::reduced;
  if (ac_options.method == "full") return emnet::AcSweepMethod::full;
  return emnet::AcSweepMethod::automatic;
}

int run_ac_command(const CommonOptions& options, const AcOptions& ac_options) {
  const emnet::Stopwatch stopwatch;
  const emnet::AcSweepMethod method = sweep_method(ac_options);
  if (method == emnet::AcSweepMethod::full &&
      (!ac_options.tolerance.empty() || !ac_options.band.empty()))
    throw InputError("--tolerance/--band", "--method",
                     "--tolerance and --band set the modal reduction, which --method full "
                     "does not use");
  check_plot_options(ac_options.plot, ac_options.plot_script);
  emnet::Scene scene = load_scene(options);
  const emnet::AcSpec spec = checked_ac_spec(scene.ac, ac_options.from, ac_options.to,
                                             ac_options.points, ac_options.scale);
  // The scene's probes, or a tip probe when it has none, unless --probe names them.
  const size_t probe_count =
      options.probes.empty() ? std::max<size_t>(1, scene.probes.size()) : options.probes.size();
  check_stored_values(static_cast<double>(spec.points) * (2.0 * probe_count + 1.0),
                      "the AC sweep of " + std::to_string(spec.points) + " frequencies x " +
                          std::to_string(probe_count) + " complex probes",
                      "--points", "lower --points or give fewer --probe");
  const Prepared p = prepare(options, false, std::move(scene));
  const auto probes = selected_probes(p.model, options);
  emnet::require_ac_input(p.model, p.system);
  emnet::AcStudyOptions study_options;
  study_options.sweep = spec;
  study_options.probes = probes;
  study_options.progress = progress_of(options);
  study_options.method = method;
  if (method == emnet::AcSweepMethod::reduced || !ac_options.tolerance.empty() ||
      !ac_options.band.empty())
    study_options.reduction = reduction_options(ac_options.tolerance, ac_options.band, spec.to,
                                                p.model.scene.model.tolerance);
  const emnet::AcStudyResult result =
      emnet::run_ac_study(p.model, p.system, p.rest.operating_point, study_options);
  if (!result.status.ok())
    throw NumericalFailure((result.failed_stage == emnet::AcStudyStage::reduction
                                ? "ac (modal reduction): "
                                : "ac: ") +
                           result.status.message);
  end_progress(options);
  return report_ac({options, p, spec, probes, result, ac_options.plot, ac_options.plot_script,
                    stopwatch.seconds()});
}

Command add_ac_command(CLI::App& app, CommonOptions& options) {
  auto ac_options = std::make_shared<AcOptions>();
  auto* ac_command = app.add_subcommand(
      "ac",
      "small-signal frequency response of the probes: magnitude and phase.\n"
      "The AC input depends on the scene's drive: antagonistic = the alternating part of the\n"
      "DEA forces (k_F*V^2/2 per DEA, in antiphase; x 4/pi for the square wave's fundamental);\n"
      "switched = the same force level on its one DEA (the 0/k_F*V^2 square wave's +/- part);\n"
      "bias_differential = +v / -v about V0 on the two DEAs (linearised at V0);\n"
      "single = v about V0 on one DEA; none = the scene's loads with their values as amplitudes.");
  add_common(ac_command, options);
  ac_command->add_option("--from", ac_options->from,
                         "start frequency [Hz] (default: scene ac.from)");
  ac_command->add_option("--to", ac_options->to,
                         "stop frequency [Hz] (default: scene ac.to; with --points 1: --from)");
  ac_command->add_option("--points", ac_options->points,
                         "number of frequencies, 1 to 1000000 (default: scene ac.points)");
  ac_command->add_option("--scale", ac_options->scale, "lin or log")
      ->check(CLI::IsMember({"lin", "log"}));
  add_plot_options(
      ac_command, ac_options->plot, ac_options->plot_script,
      "the response: a magnitude panel per unit over the phase, the resonances "
      "that show as a peak (damping ratio below 1/sqrt(2)) marked; the title names the "
      "AC input");
  sets_fields(ac_command
                  ->add_option("--method", ac_options->method,
                               "auto (default: the modal reduction above " +
                                   std::to_string(emnet::kAcReductionUnknowns) + " unknowns for " +
                                   std::to_string(emnet::kAcReductionPoints) +
                                   " frequencies or more, kept only when its check meets "
                                   "the tolerance; the full model otherwise), full (every "
                                   "frequency on the full model) or reduced")
                  ->check(CLI::IsMember({"auto", "full", "reduced"})),
              {"method"});
  sets_fields(ac_command->add_flag("--reduce", ac_options->reduce,
                                   "same as --method reduced: evaluate the sweep by modal "
                                   "reduction (modes below band/sqrt(tolerance), static "
                                   "correction for the rest), checked against the full model"),
              {"reduce"});
  add_reduction_tolerance_and_band(ac_command, ac_options->tolerance, ac_options->band);

  return {ac_command, [ac_options, &options] { return run_ac_command(options, *ac_options); }};
}

}  // namespace emnet_cli
