// `emnet identify SCENE --resonance F [--mode K] [--peak NAME=VALUE[@VOLTAGE]]`: fits
// beam.bending_stiffness so that mode K sits at F, and with --peak damping.loss_factor to a
// measured periodic peak (the study: emnet/studies/identify.hpp). This file parses the options,
// calls the study and prints the fitted values, the scene lines and their provenance (or --json).
#include "emnet/studies/identify.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "cli/common.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"

namespace emnet_cli {

using emnet::InputError;
using Json = nlohmann::ordered_json;

namespace {

struct IdentifyCommandOptions {
  double target_hz = 0.0;
  int mode_number = 1;
  std::string peak_text;
};

// --peak NAME=VALUE[@VOLTAGE]: the periodic-state peak |deflection| of output NAME under the
// scene's drive (at VOLTAGE when given) at the switching frequency --resonance.
emnet::PeakTarget parse_peak_target(const std::string& text) {
  emnet::PeakTarget target;
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw InputError("--peak", "--peak", "expected NAME=VALUE[@VOLTAGE], e.g. P4=9.3mm@4kV");
  target.output = text.substr(0, equals);
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

int run_identify(const CommonOptions& options, const IdentifyCommandOptions& command_options) {
  const emnet::Stopwatch stopwatch;
  refuse_option(!options.probes.empty(), "--probe",
                "identify has no probe outputs: it fits to --resonance, and with --peak "
                "NAME=VALUE to the peak of output NAME");
  refuse_option(!options.csv.empty(), "--csv",
                "identify prints the fitted values (or --json), not a CSV table");
  const double target_hz = command_options.target_hz;
  const int mode_number = command_options.mode_number;
  if (!(target_hz > 0.0) || !std::isfinite(target_hz))
    throw InputError("--resonance", "--resonance", "must be a positive frequency in Hz (> 0)");
  if (mode_number < 1) throw InputError("--mode", "--mode", "must be >= 1");
  const emnet::Scene scene = load_scene(options);
  emnet::IdentifyOptions study;
  study.target_hz = target_hz;
  study.mode_number = mode_number;
  if (!command_options.peak_text.empty()) study.peak = parse_peak_target(command_options.peak_text);
  study.progress = progress_of(options);
  const emnet::IdentifyResult result = emnet::identify(scene, study);
  if (!result.status.ok) {
    if (result.status.message == emnet::kCancelledMessage) throw Interrupted("interrupted");
    throw NumericalFailure(result.status.message);
  }
  const bool peak = study.peak.has_value();
  const double total = stopwatch.seconds();
  end_progress(options);
  // The command that re-identifies the values, for the scene's [provenance].
  std::string command =
      "emnet identify " + options.scene_path + " --resonance " + format("%.6g", target_hz);
  if (mode_number != 1) command += " --mode " + std::to_string(mode_number);
  if (peak) command += " --peak " + command_options.peak_text;
  if (options.json) {
    Json out = {{"automatic_choices", automatic_choices_json(scene.automatic_choices)},
                {"parameter", "beam.bending_stiffness"},
                {"value", result.bending_stiffness},
                {"unit", "N*m^2"},
                {"mode", mode_number},
                {"target_hz", target_hz},
                {"achieved_hz", result.achieved_hz},
                {"iterations", result.stiffness_iterations},
                {"command", command},
                {"total_seconds", total}};
    if (peak) {
      out["loss_factor"] = result.loss_factor;
      out["peak_probe"] = study.peak->output;
      out["target_peak_m"] = study.peak->value;
      out["achieved_peak_m"] = result.achieved_peak;
      out["peak_rounds"] = result.peak_rounds;
      out["validity"] = validity_json(*result.validity);
    }
    if (!result.notes.empty()) out["notes"] = result.notes;
    std::cout << json_text(out) << "\n";
    return result.validity ? validity_exit(*result.validity) : 0;
  }
  std::printf(
      "identified beam.bending_stiffness = %.6e N*m^2: mode %d at %.10g Hz (target %.6g Hz), "
      "%d iteration(s), %s\n",
      result.bending_stiffness, mode_number, result.achieved_hz, target_hz,
      result.stiffness_iterations, milliseconds(total).c_str());
  if (peak)
    std::printf(
        "identified damping.loss_factor = %.6e: periodic peak of %s at %.6g Hz = %.6e m "
        "(target %.6g m; DEAs as ideal voltage-driven forces), %d round(s)\n",
        result.loss_factor, shown(study.peak->output).c_str(), target_hz, result.achieved_peak,
        study.peak->value, result.peak_rounds);
  std::printf("scene lines:\n  bending_stiffness = \"%.6e N*m^2\"\n", result.bending_stiffness);
  if (peak) std::printf("  loss_factor = %.6e\n", result.loss_factor);
  std::printf("provenance:\n  \"beam.bending_stiffness\" = \"identified: %s\"\n",
              shown(command).c_str());
  if (peak) std::printf("  \"damping.loss_factor\" = \"identified: %s\"\n", shown(command).c_str());
  for (const auto& choice : scene.automatic_choices)
    std::cout << "note: " << shown(choice.reason) << "\n";
  for (const auto& note : result.notes) std::cout << "note: " << shown(note) << "\n";
  if (result.validity) print_validity(*result.validity);
  return result.validity ? validity_exit(*result.validity) : 0;
}

}  // namespace

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

  return {identify_command,
          [identify_options, &options] { return run_identify(options, *identify_options); }};
}

}  // namespace emnet_cli
