#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli/common.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/output_file.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/terminal_text.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/scene/parameter_listing.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "emnet/studies/sensitivity.hpp"
#include "emnet/verification/crosscheck.hpp"

namespace emnet_cli {

using emnet::InputError;
using Json = nlohmann::ordered_json;

// ---- identify -------------------------------------------------------------------------

// The identified bending stiffness: the fixed point of EI ← EI·(target/f)², from the
// scene's value. Every trial sets its values on the scene loaded once (set_parameter,
// emnet/scene/parameters.hpp), so beam.segments = "auto" is chosen once, at the start values: the
// fit is of one network, whose N the notes print.
struct IdentifyCommandOptions {
  double target_hz = 0.0;
  int mode_number = 1;
  std::string peak_text;
};

struct StiffnessFit {
  double stiffness = 0.0, frequency = 0.0;
  int iterations = 0;
};
StiffnessFit fit_stiffness(const CommonOptions& options, emnet::Scene scene, double target_hz,
                           int mode_number);

// --peak NAME=VALUE[@VOLTAGE]: the periodic-state peak |deflection| of probe NAME under the
// scene's drive (at VOLTAGE when given) at the switching frequency `frequency_hz`.
struct PeakTarget {
  std::string probe;
  double value = 0.0;    // [m]
  double voltage = 0.0;  // [V]; 0: the scene's drive.voltage
};

StiffnessFit fit_stiffness(const CommonOptions& options, emnet::Scene scene, double target_hz,
                           int mode_number) {
  CommonOptions trial = options;
  trial.reporter = nullptr;  // the iterations are the step shown, not each model they build
  double stiffness = emnet::get_parameter(scene, "beam.bending_stiffness");
  double frequency = 0.0;
  int iterations = 0;
  // Undamped frequencies scale as √EI exactly; damping and the electrical poles make the
  // update a fixed-point iteration, which converges in a few steps.
  for (iterations = 1; iterations <= 30; ++iterations) {
    if (!keep_going(progress_of(options), iterations - 1, 30,
                    "bending stiffness: fixed-point iterations (30 at most)"))
      throw Interrupted("interrupted");
    emnet::set_parameter(scene, "beam.bending_stiffness", stiffness);
    Prepared p = prepare(trial, false, scene);
    emnet::ModalOptions modal_options;
    modal_options.keep_vectors = false;
    if (p.system.size() > modal_options.dense_limit) modal_options.count = mode_number + 5;
    const auto modes = emnet::run_modes(p.system, p.rest.operating_point, modal_options);
    if (!modes.status.ok || static_cast<int>(modes.modes.size()) < mode_number)
      throw NumericalFailure("identify: mode " + std::to_string(mode_number) + " not found");
    frequency = modes.modes[static_cast<size_t>(mode_number - 1)].frequency_hz;
    if (std::abs(frequency - target_hz) <= 1e-10 * target_hz) break;
    stiffness *= (target_hz / frequency) * (target_hz / frequency);
  }
  return {stiffness, frequency, iterations};
}

PeakTarget parse_peak_target(const std::string& text) {
  PeakTarget target;
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw InputError("--peak", "--peak", "expected NAME=VALUE[@VOLTAGE], e.g. P4=9.3mm@4kV");
  target.probe = text.substr(0, equals);
  std::string rest = text.substr(equals + 1);
  const size_t at = rest.find('@');
  try {
    target.value = emnet::parse_quantity(rest.substr(0, at), emnet::dim::length);
    if (at != std::string::npos)
      target.voltage = emnet::parse_quantity(rest.substr(at + 1), emnet::dim::voltage);
  } catch (const std::invalid_argument& e) {
    throw InputError("--peak", "--peak", e.what());
  }
  if (!(target.value > 0.0)) throw InputError("--peak", "--peak", "the peak must be > 0");
  if (at != std::string::npos && !(target.voltage > 0.0))
    throw InputError("--peak", "--peak", "the voltage must be > 0");
  return target;
}

// The periodic extremes (minimum, maximum) of output `probe_name` of `scene` switched at
// `frequency_hz`, DEAs as ideal voltage-driven forces (the exact periodic method needs a linear
// network; the full DEA model moves the fish fin's peak at 5 Hz by 5e-4).
std::pair<double, double> periodic_extremes(emnet::Scene scene, const std::string& probe_name,
                                            double frequency_hz, const std::string& option) {
  emnet::check_overlap_fits(scene, frequency_hz, option);
  scene.drive.electrical_dynamics = false;
  scene.drive.electrical_dynamics_auto = false;
  scene.drive.frequency = frequency_hz;
  const emnet::Model model = emnet::prepare_model(scene);
  const emnet::System system = model.network.assemble();
  emnet::check_periodic_memory(system.size(), "--segments");
  std::vector<emnet::Probe> probes;
  for (const auto& probe : transient_probes(model))
    if (probe.name == probe_name) probes.push_back(probe);
  for (const auto& probe : model.probes)
    if (probes.empty() && probe.name == probe_name) probes.push_back(probe);
  if (probes.empty())
    throw InputError(option, option, "no deflection output named '" + probe_name + "'");
  const emnet::PeriodicSolver solver(system);
  const emnet::PeriodicResult r = solver.solve(system, probes, 1.0 / frequency_hz, 256);
  if (!r.status.ok) throw NumericalFailure("periodic state: " + r.status.message);
  finite(r.minimum[0], "a periodic minimum");
  finite(r.maximum[0], "a periodic maximum");
  return {r.minimum[0], r.maximum[0]};
}

// The periodic peak max(|min|, |max|) of `scene`.
double periodic_peak(const emnet::Scene& scene, const std::string& probe_name,
                     double frequency_hz) {
  const auto [minimum, maximum] = periodic_extremes(scene, probe_name, frequency_hz, "--peak");
  return std::max(std::abs(minimum), std::abs(maximum));
}

int run_identify(const CommonOptions& options, double target_hz, int mode_number,
                 const std::string& peak_text) {
  const emnet::Stopwatch stopwatch;
  refuse_option(!options.probes.empty(), "--probe",
                "identify has no probe outputs: it fits to --resonance, and with --peak "
                "NAME=VALUE to the peak of output NAME");
  refuse_option(!options.csv.empty(), "--csv",
                "identify prints the fitted values (or --json), not a CSV table");
  if (!(target_hz > 0.0) || !std::isfinite(target_hz))
    throw InputError("--resonance", "--resonance", "must be a positive frequency in Hz (> 0)");
  if (mode_number < 1) throw InputError("--mode", "--mode", "must be >= 1");
  // Only parameters the scene marks as identified or assumed are fitted: a value taken from the
  // paper or a data sheet is a given, not an unknown.
  std::vector<emnet::AutomaticChoice> automatic_choices;
  const emnet::Scene start_scene = load_scene(options);  // every trial sets its values on a copy
  {
    const emnet::Scene& scene = start_scene;
    automatic_choices = scene.automatic_choices;
    std::vector<std::string> fitted_keys{"beam.bending_stiffness"};
    if (!peak_text.empty()) fitted_keys.push_back("damping.loss_factor");
    for (const std::string& key : fitted_keys) {
      const auto entry = scene.provenance.find(key);
      if (entry == scene.provenance.end()) continue;
      const std::string& origin = entry->second;
      if (origin.rfind("paper", 0) == 0 || origin.rfind("data sheet", 0) == 0)
        throw InputError(scene.file, "provenance." + key,
                         "identify would fit " + key + ", which the scene takes as given (\"" +
                             origin.substr(0, origin.find(':')) +
                             "\"); only 'identified:' or 'assumed:' values are fitted");
    }
  }
  // 1. Bending stiffness to the resonance; 2. with --peak, the loss factor to the peak at the
  // resonance, then the stiffness again (the damping moves the damped frequency a little),
  // until both hold.
  emnet::Scene fitted = start_scene;  // with --peak's voltage
  StiffnessFit fit = fit_stiffness(options, start_scene, target_hz, mode_number);
  std::optional<PeakTarget> peak;
  double loss_factor = 0.0, achieved_peak = 0.0;
  int peak_rounds = 0;
  if (!peak_text.empty()) {
    peak = parse_peak_target(peak_text);
    if (!start_scene.damping.loss_factor)
      throw InputError(start_scene.file, "damping.loss_factor",
                       "--peak fits damping.loss_factor, which the scene does not set");
    loss_factor = *start_scene.damping.loss_factor;
    if (peak->voltage > 0.0) emnet::set_parameter(fitted, "drive.voltage", peak->voltage);
    auto with = [&](double eta, double stiffness) {
      emnet::Scene trial = fitted;
      emnet::set_parameter(trial, "damping.loss_factor", eta);
      emnet::set_parameter(trial, "beam.bending_stiffness", stiffness);
      return trial;
    };
    for (peak_rounds = 1; peak_rounds <= 10; ++peak_rounds) {
      // The peak falls monotonically with the loss factor: bisection in log η over [1e-5, 2].
      double low = 1e-5, high = 2.0;
      int bisection_step = 0;
      auto peak_at = [&](double eta) {
        if (!keep_going(progress_of(options), bisection_step++, 82,
                        "loss factor: round " + std::to_string(peak_rounds) +
                            " (10 at most), bisection steps (82 at most)"))
          throw Interrupted("interrupted");
        return periodic_peak(with(eta, fit.stiffness), peak->probe, target_hz);
      };
      if (peak_at(low) < peak->value || peak_at(high) > peak->value)
        throw NumericalFailure("identify --peak: no loss factor in [1e-5, 2] gives the peak " +
                               si(peak->value, "m") + " at " + si(target_hz, "Hz"));
      for (int k = 0; k < 80 && high / low > 1 + 1e-12; ++k) {
        const double middle = std::sqrt(low * high);
        (peak_at(middle) > peak->value ? low : high) = middle;
      }
      const double previous = loss_factor;
      loss_factor = std::sqrt(low * high);
      emnet::Scene trial = fitted;
      emnet::set_parameter(trial, "damping.loss_factor", loss_factor);
      const double previous_stiffness = fit.stiffness;
      fit = fit_stiffness(options, trial, target_hz, mode_number);
      achieved_peak = periodic_peak(with(loss_factor, fit.stiffness), peak->probe, target_hz);
      if (std::abs(loss_factor - previous) <= 1e-9 * loss_factor &&
          std::abs(fit.stiffness - previous_stiffness) <= 1e-9 * fit.stiffness)
        break;
    }
  }
  const double stiffness = fit.stiffness, frequency = fit.frequency;
  const int iterations = fit.iterations;
  // Validity of the periodic peak --peak prints, at the drive's levels (--peak's voltage).
  std::optional<emnet::Validity> validity;
  if (peak) {
    validity = emnet::check_validity(fitted, {{peak->probe, achieved_peak}},
                                     emnet::drive_peak_voltages(fitted));
  }
  const double total = stopwatch.seconds();
  end_progress(options);
  // The command that re-identifies the values, for the scene's [provenance].
  std::string command =
      "emnet identify " + options.scene_path + " --resonance " + format("%.6g", target_hz);
  if (mode_number != 1) command += " --mode " + std::to_string(mode_number);
  if (peak) command += " --peak " + peak_text;
  if (options.json) {
    Json out = {{"automatic_choices", automatic_choices_json(automatic_choices)},
                {"parameter", "beam.bending_stiffness"},
                {"value", stiffness},
                {"unit", "N*m^2"},
                {"mode", mode_number},
                {"target_hz", target_hz},
                {"achieved_hz", frequency},
                {"iterations", iterations},
                {"command", command},
                {"total_seconds", total}};
    if (peak) {
      out["loss_factor"] = loss_factor;
      out["peak_probe"] = peak->probe;
      out["target_peak_m"] = peak->value;
      out["achieved_peak_m"] = achieved_peak;
      out["peak_rounds"] = peak_rounds;
      out["validity"] = validity_json(*validity);
    }
    std::cout << json_text(out) << "\n";
    return validity ? validity_exit(*validity) : 0;
  }
  std::printf(
      "identified beam.bending_stiffness = %.6e N*m^2: mode %d at %.10g Hz (target %.6g Hz), "
      "%d iteration(s), %s\n",
      stiffness, mode_number, frequency, target_hz, iterations, milliseconds(total).c_str());
  if (peak)
    std::printf(
        "identified damping.loss_factor = %.6e: periodic peak of %s at %.6g Hz = %.6e m "
        "(target %.6g m; DEAs as ideal voltage-driven forces), %d round(s)\n",
        loss_factor, shown(peak->probe).c_str(), target_hz, achieved_peak, peak->value,
        peak_rounds);
  std::printf("scene lines:\n  bending_stiffness = \"%.6e N*m^2\"\n", stiffness);
  if (peak) std::printf("  loss_factor = %.6e\n", loss_factor);
  std::printf("provenance:\n  \"beam.bending_stiffness\" = \"identified: %s\"\n",
              shown(command).c_str());
  if (peak) std::printf("  \"damping.loss_factor\" = \"identified: %s\"\n", shown(command).c_str());
  for (const auto& choice : automatic_choices)
    std::cout << "note: " << shown(choice.reason) << "\n";
  if (validity) print_validity(*validity);
  return validity ? validity_exit(*validity) : 0;
}

Command add_identify_command(CLI::App& app, CommonOptions& options) {
  auto identify_options = std::make_shared<IdentifyCommandOptions>();
  auto* identify_command = app.add_subcommand(
      "identify",
      "fit beam.bending_stiffness so that a mode sits at a target frequency (and, with --peak, "
      "damping.loss_factor to a measured peak deflection)");
  add_common(identify_command, options);
  identify_command->add_option("--resonance", identify_options->target_hz, "target frequency [Hz]")
      ->required();
  identify_command->add_option("--mode", identify_options->mode_number,
                               "which oscillatory mode (default 1)");
  identify_command->add_option(
      "--peak", identify_options->peak_text,
      "also fit damping.loss_factor: NAME=VALUE[@VOLTAGE], the periodic peak |deflection| of "
      "output NAME (P4, dx4, tip, ...) under the scene's square-wave drive switched at the "
      "--resonance frequency, e.g. P4=9.3mm@4kV");

  return {identify_command, [identify_options, &options] {
            return run_identify(options, identify_options->target_hz, identify_options->mode_number,
                                identify_options->peak_text);
          }};
}

}  // namespace emnet_cli
