// `emnet identify SCENE --resonance F [--mode K] [--fit KEY] [--peak NAME=VALUE[@VOLTAGE]]`:
// fits KEY (beam.bending_stiffness by default; any numeric scene key the scene uses, e.g.
// spring.clamp.stiffness) so that mode K sits at F, and with --peak damping.loss_factor to a
// measured periodic peak (the study: emnet/studies/identify.hpp). This file parses the options,
// calls the study and prints the fitted values, the scene lines and their provenance (or --json).
#include "emnet/studies/identify.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "cli/common.hpp"
#include "cli/option_names.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"
#include "emnet/report/identify_json.hpp"
#include "emnet/scene/parameters.hpp"

namespace emnet_cli {

using emnet::InputError;
using Json = nlohmann::ordered_json;

namespace {

struct IdentifyCommandOptions {
  double target_hz = 0.0;
  int mode_number = 1;
  std::string fit_key;  // empty: beam.bending_stiffness, and the command line does not name it
  std::string peak_text;
};

// "spring[clamp].stiffness" as --fit takes it without shell quoting: "spring.clamp.stiffness".
std::string dotted_key(std::string key) {
  for (char& c : key)
    if (c == '[') c = '.';
  key.erase(std::remove(key.begin(), key.end(), ']'), key.end());
  return key;
}

// Where the scene line goes, for a key outside [beam]: "the [[spring]] entry name = \"clamp\""
// ("the 1st [[mass]] entry" for one without a name), "[damping]"; "" for a [beam] key.
std::string scene_line_place(const emnet::Scene& scene, const std::string& key) {
  const emnet::SceneParameterAddress address =
      emnet::find_scene_parameter_address(scene, key, "--fit");
  const emnet::ParameterInfo& info = *address.info;
  if (!info.in_entries) return info.table == "beam" ? "" : "[" + info.table + "]";
  std::string name;
  if (info.table == "mass") name = scene.beam.masses[address.entry].name;
  if (info.table == "spring") name = scene.beam.springs[address.entry].name;
  if (info.table == "dea") name = scene.deas[address.entry].name;
  if (info.table == "probe") name = scene.probes[address.entry].name;
  if (!name.empty()) return "the [[" + info.table + "]] entry name = \"" + name + "\"";
  const std::size_t ordinal = address.entry + 1;
  const char* suffix = ordinal % 10 == 1 && ordinal % 100 != 11   ? "st"
                       : ordinal % 10 == 2 && ordinal % 100 != 12 ? "nd"
                       : ordinal % 10 == 3 && ordinal % 100 != 13 ? "rd"
                                                                  : "th";
  return "the " + std::to_string(ordinal) + suffix + " [[" + info.table + "]] entry";
}

// The value as a scene file writes it: "\"1.234560e+00 N*m/rad\"", or a bare number.
std::string scene_value(double value, const std::string& unit) {
  return unit.empty() ? format("%.6e", value) : "\"" + format("%.6e", value) + " " + unit + "\"";
}

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
  if (!command_options.fit_key.empty()) study.parameter = command_options.fit_key;
  if (!command_options.peak_text.empty()) study.peak = parse_peak_target(command_options.peak_text);
  study.progress = progress_of(options);
  const emnet::IdentifyResult result = emnet::identify(scene, study);
  if (!result.status.ok()) {
    if (result.status.cancelled()) throw Interrupted("interrupted");
    throw NumericalFailure(result.status.message);
  }
  const bool peak = study.peak.has_value();
  const double total = stopwatch.seconds();
  end_progress(options);
  // The command that re-identifies the values, for the scene's [provenance].
  std::string command =
      "emnet identify " + options.scene_path + " --resonance " + format("%.6g", target_hz);
  if (mode_number != 1) command += " --mode " + std::to_string(mode_number);
  const emnet::FittedValue& fitted = result.parameter;
  if (!command_options.fit_key.empty()) command += " --fit " + dotted_key(fitted.key);
  if (peak) command += " --peak " + command_options.peak_text;
  if (options.json) {
    const emnet::IdentifyReportContext context{scene.automatic_choices, command, total};
    std::cout << json_text(emnet::to_json(result, study, context)) << "\n";
    return result.validity ? validity_exit(*result.validity) : 0;
  }
  const std::string unit_text = fitted.unit.empty() ? "" : " " + fitted.unit;
  std::printf("identified %s = %.6e%s: mode %d at %.10g Hz (target %.6g Hz), %d iteration(s), %s\n",
              fitted.key.c_str(), fitted.value, unit_text.c_str(), mode_number, result.achieved_hz,
              target_hz, result.stiffness_iterations, milliseconds(total).c_str());
  if (peak)
    std::printf(
        "identified damping.loss_factor = %.6e: periodic peak of %s at %.6g Hz = %.6e m "
        "(target %.6g m; DEAs as ideal voltage-driven forces), %d round(s)\n",
        result.loss_factor, shown(study.peak->output).c_str(), target_hz, result.achieved_peak,
        study.peak->value, result.peak_rounds);
  const std::string place = scene_line_place(scene, fitted.key);
  const std::string name = fitted.key.substr(fitted.key.rfind('.') + 1);
  std::printf("scene lines%s:\n  %s = %s\n", place.empty() ? "" : (" (in " + place + ")").c_str(),
              name.c_str(), scene_value(fitted.value, fitted.unit).c_str());
  if (peak)
    std::printf("  loss_factor = %.6e%s\n", result.loss_factor,
                place.empty() ? "" : "  # in [damping]");
  std::printf("provenance:\n  \"%s\" = \"identified: %s\"\n", fitted.key.c_str(),
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
      "fit a scene parameter (beam.bending_stiffness unless --fit names another) so that a mode "
      "sits at a target frequency (and, with --peak, damping.loss_factor to a measured peak "
      "deflection); e.g. emnet identify netlists/fishfin.toml --resonance 6.385, or "
      "emnet identify SCENE --resonance 40 --fit spring.clamp.stiffness for an elastic clamp");
  add_common(identify_command, options);
  sets_fields(identify_command
                  ->add_option("--resonance", identify_options->target_hz, "target frequency [Hz]")
                  ->required(),
              {"target_hz"});
  sets_fields(identify_command->add_option("--mode", identify_options->mode_number,
                                           "which oscillatory mode (default 1)"),
              {"mode_number"});
  sets_fields(identify_command->add_option(
                  "--fit", identify_options->fit_key,
                  "the scene key fitted to the resonance (default beam.bending_stiffness): any "
                  "numeric key the scene uses, as --set names it, e.g. spring.clamp.stiffness, "
                  "section.1.bending_stiffness, mass.0.mass, dea.A.lever_arm"),
              {"parameter"});
  sets_fields(identify_command->add_option(
                  "--peak", identify_options->peak_text,
                  "also fit damping.loss_factor: NAME=VALUE[@VOLTAGE], the periodic peak "
                  "|deflection| of output NAME (P4, dx4, tip, ...) under the scene's square-wave "
                  "drive switched at the --resonance frequency, e.g. P4=9.3mm@4kV"),
              {"peak"});

  return {identify_command,
          [identify_options, &options] { return run_identify(options, *identify_options); }};
}

}  // namespace emnet_cli
