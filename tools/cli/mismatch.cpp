// `emnet mismatch SCENE [--frequency F] [--output NAME] [--change X]`: the left/right asymmetry
// of the periodic swing from a mismatched antagonistic pair (the study:
// emnet/studies/mismatch.hpp). This file parses the options, calls the study and prints its
// table (or --json).
#include "emnet/studies/mismatch.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli/common.hpp"
#include "cli/option_names.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/core/units.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/report/mismatch_json.hpp"
#include "emnet/studies/periodic_peak.hpp"

namespace emnet_cli {

namespace {

struct MismatchCommandOptions {
  std::optional<double> frequency;  // default: the scene's drive.frequency
  std::string output;               // "": the last deflection output (dx4 on the fish fin)
  double change = 0.05;
};

int run_mismatch_command(const CommonOptions& options, const MismatchCommandOptions& cmd) {
  const emnet::Stopwatch stopwatch;
  refuse_option(!options.probes.empty(), "--probe",
                "mismatch compares one deflection output: name it with --output");
  refuse_option(!options.csv.empty(), "--csv",
                "mismatch prints its table (or --json), not a CSV file");
  const emnet::Scene scene = load_scene(options);
  emnet::MismatchOptions study;
  study.frequency_hz = cmd.frequency;
  study.output = cmd.output;
  study.change = cmd.change;
  study.progress = progress_of(options);
  const emnet::MismatchResult result = emnet::run_mismatch(scene, study);
  if (!result.status.ok()) {
    if (result.status.cancelled()) throw Interrupted("interrupted");
    throw NumericalFailure(result.status.message);
  }
  const double total = stopwatch.seconds();
  end_progress(options);
  if (options.json) {
    std::cout << json_text(emnet::to_json(result, scene.automatic_choices, total)) << "\n";
    return validity_exit(result.validity);
  }
  std::printf(
      "scene %s: left/right asymmetry of %s switched at %s, DEAs as ideal voltage-driven "
      "forces\n",
      shown(scene.name).c_str(), shown(result.output).c_str(),
      si(result.frequency_hz, "Hz").c_str());
  std::printf("asymmetry = (|left| - right) / mean, > 0: larger to the left (negative) side\n");
  if (result.method == emnet::Method::shooting)
    std::cout << "accuracy: periodic states by shooting (large kinematics), IDA rtol "
              << emnet::short_number(emnet::kPeriodicPeakShootingRtol)
              << ", periodicity residual below "
              << emnet::short_number(
                     emnet::shooting_residual_limit(emnet::kPeriodicPeakShootingRtol))
              << "\n";
  else
    std::printf("accuracy: exact periodic states, extremes to 1e-11 of the peak\n");
  std::printf("cost: %d periodic solves, total %s\n", result.periodic_solves,
              milliseconds(total).c_str());
  for (const auto& choice : scene.automatic_choices)
    std::cout << "note: " << shown(choice.reason) << "\n";
  for (const auto& note : result.notes) std::cout << "note: " << shown(note) << "\n";
  std::printf("\n");
  std::printf("%-28s %8s %12s %12s %12s %16s\n", "mismatch", "change", "left [mm]", "right [mm]",
              "asymmetry", "per 1 % change");
  std::printf("%-28s %8s %12.6g %12.6g %11.4f%% %16s\n", "none", "", result.nominal_left * 1e3,
              result.nominal_right * 1e3, 100.0 * result.nominal_asymmetry, "");
  for (const emnet::MismatchRow& row : result.rows)  // [%] per 1 % of change = asymmetry / X
    std::printf("%-28s %+7.1f%% %12.6g %12.6g %11.4f%% %15.6g%%\n", shown(row.label).c_str(),
                100.0 * row.change, row.left * 1e3, row.right * 1e3, 100.0 * row.asymmetry,
                row.asymmetry_per_unit_change);
  print_validity(result.validity);
  return validity_exit(result.validity);
}

}  // namespace

Command add_mismatch_command(CLI::App& app, CommonOptions& options) {
  auto mismatch_options = std::make_shared<MismatchCommandOptions>();
  auto* mismatch_command = app.add_subcommand(
      "mismatch",
      "left/right asymmetry of the periodic swing from a mismatched antagonistic pair: DEA A's\n"
      "electrode area or film thickness changed by +/-X, or the switching overlapping by X*T/2");
  add_common(mismatch_command, options);
  sets_fields(mismatch_command->add_option(
                  "--frequency", mismatch_options->frequency,
                  "switching frequency [Hz] (default: the scene's drive.frequency)"),
              {"frequency_hz"});
  sets_fields(mismatch_command->add_option("--output", mismatch_options->output,
                                           "deflection output (default: the last, e.g. dx4)"),
              {"output"});
  sets_fields(mismatch_command->add_option("--change", mismatch_options->change,
                                           "relative change of each parameter (default 0.05)"),
              {"change"});

  return {mismatch_command, [mismatch_options, &options] {
            return run_mismatch_command(options, *mismatch_options);
          }};
}

}  // namespace emnet_cli
