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

// ---- mismatch ---------------------------------------------------------------------------
//
// `emnet mismatch SCENE [--frequency F] [--output NAME] [--change X]`: the left/right asymmetry
// of the periodic swing when the antagonistic pair is not identical — DEA A's electrode area
// (electrode width) or film thickness changed by ±X, or the switching overlapping (A on X·T/2
// longer, both on together) or leaving a dead time (−X·T/2). The paper (Sect. 3) explains its
// larger left-side deflection by such tolerances.
//
// Asymmetry = (|left| − right) / ((|left| + right)/2), left = the negative side: > 0 when the
// swing is larger to the left. In the linear network a mismatch adds a constant force to the
// symmetric square wave: a static offset that the resonance does not amplify.

struct MismatchOptions {
  std::optional<double> frequency;  // default: the scene's drive.frequency
  std::string output;               // "": the last deflection output (dx4 on the fish fin)
  double change = 0.05;
};

int run_mismatch_command(const CommonOptions& options, const MismatchOptions& cmd) {
  const emnet::Stopwatch stopwatch;
  refuse_option(!options.probes.empty(), "--probe",
                "mismatch compares one deflection output: name it with --output");
  refuse_option(!options.csv.empty(), "--csv",
                "mismatch prints its table (or --json), not a CSV file");
  const emnet::Scene scene = load_scene(options);
  if (scene.drive.kind != emnet::DriveKind::antagonistic || scene.drive.deas.size() != 2)
    throw InputError(scene.file, "drive.kind",
                     "mismatch needs the antagonistic drive of two DEAs (drive.kind = "
                     "\"antagonistic\", drive.deas = [A, B])");
  if (!(cmd.change > 0.0 && cmd.change < 0.5))
    throw InputError("--change", "--change", "must be > 0 and < 0.5 (a fraction)");
  const double frequency = cmd.frequency.value_or(scene.drive.frequency);
  if (!(frequency > 0.0) || !std::isfinite(frequency))
    throw InputError(cmd.frequency ? "--frequency" : scene.file,
                     cmd.frequency ? "--frequency" : "drive.frequency",
                     "must be a positive frequency in Hz (> 0)");
  std::string output = cmd.output;
  if (output.empty()) {
    const emnet::Model model = emnet::prepare_model(scene);
    // The last speckle-point difference dx_k (the paper measures dx4), else the last deflection.
    const std::vector<emnet::ModelOutput> outputs = emnet::transient_output_list(model);
    const emnet::ModelOutput* chosen = emnet::default_deflection_output(outputs);
    if (!chosen) throw InputError(scene.file, "probe", "the scene has no deflection output");
    output = chosen->probe.name;
  }
  const std::string& dea_name = scene.drive.deas[0];
  size_t dea = scene.deas.size();
  for (size_t k = 0; k < scene.deas.size(); ++k)
    if (scene.deas[k].name == dea_name) dea = k;
  if (dea == scene.deas.size())
    throw InputError(scene.file, "drive.deas", "no DEA named '" + dea_name + "'");

  struct Case {
    std::string label, key;
    std::function<void(emnet::Scene&, double)> apply;  // change by the fraction x
  };
  const double half_period = 0.5 / frequency;
  const std::vector<Case> cases = {
      {"electrode area of " + dea_name, "dea." + dea_name + ".electrode_width",
       [dea](emnet::Scene& s, double x) { s.deas[dea].electrode_width *= 1.0 + x; }},
      {"film thickness of " + dea_name, "dea." + dea_name + ".dielectric_thickness",
       [dea](emnet::Scene& s, double x) { s.deas[dea].dielectric_thickness *= 1.0 + x; }},
      {"switching overlap (of T/2)", "drive.overlap",
       [half_period](emnet::Scene& s, double x) { s.drive.overlap = x * half_period; }},
  };
  auto asymmetry = [](std::pair<double, double> extremes) {
    const double left = std::abs(extremes.first), right = extremes.second;
    return (left - right) / (0.5 * (left + right));
  };
  const long solves = 1 + 2 * static_cast<long>(cases.size());
  if (!keep_going(progress_of(options), 0, solves, "periodic solves"))
    throw Interrupted("interrupted");
  const auto nominal = periodic_extremes(scene, output, frequency, "--output");
  struct Row {
    std::string label, key;
    double change;
    std::pair<double, double> extremes;
    double asymmetry;
  };
  std::vector<Row> rows;
  for (const Case& c : cases)
    for (const double x : {-cmd.change, cmd.change}) {
      emnet::Scene changed = scene;
      c.apply(changed, x);
      if (!keep_going(progress_of(options), static_cast<long>(rows.size()) + 1, solves,
                      "periodic solves"))
        throw Interrupted("interrupted");
      const auto extremes = periodic_extremes(changed, output, frequency, "--output");
      rows.push_back({c.label, c.key, x, extremes, asymmetry(extremes)});
    }
  std::vector<emnet::DeflectionPeak> peaks{
      {output, std::max(std::abs(nominal.first), std::abs(nominal.second))}};
  for (const Row& row : rows)
    peaks.push_back({output + " (" + row.label + " " + format("%+.3g", 100.0 * row.change) + " %)",
                     std::max(std::abs(row.extremes.first), std::abs(row.extremes.second))});
  const emnet::Validity validity =
      emnet::check_validity(scene, peaks, emnet::drive_peak_voltages(scene));
  const double total = stopwatch.seconds();
  end_progress(options);
  if (options.json) {
    Json out = {{"automatic_choices", automatic_choices_json(scene.automatic_choices)},
                {"output", output},
                {"frequency_hz", frequency},
                {"nominal", {{"left_m", nominal.first}, {"right_m", nominal.second}}},
                {"cases", Json::array()},
                {"total_seconds", total}};
    for (size_t k = 0; k < rows.size(); ++k)
      out["cases"].push_back({{"key", rows[k].key},
                              {"change", rows[k].change},
                              {"left_m", rows[k].extremes.first},
                              {"right_m", rows[k].extremes.second},
                              {"asymmetry", rows[k].asymmetry},
                              {"asymmetry_per_unit_change", rows[k].asymmetry / cmd.change}});
    out["validity"] = validity_json(validity);
    std::cout << json_text(out) << "\n";
    return validity_exit(validity);
  }
  std::printf(
      "scene %s: left/right asymmetry of %s switched at %s, DEAs as ideal voltage-driven "
      "forces\n",
      shown(scene.name).c_str(), shown(output).c_str(), si(frequency, "Hz").c_str());
  std::printf("asymmetry = (|left| - right) / mean, > 0: larger to the left (negative) side\n");
  std::printf("accuracy: exact periodic states, extremes to 1e-11 of the peak\n");
  std::printf("cost: %d periodic solves, total %s\n", static_cast<int>(rows.size()) + 1,
              milliseconds(total).c_str());
  for (const auto& choice : scene.automatic_choices)
    std::cout << "note: " << shown(choice.reason) << "\n";
  std::printf("\n");
  std::printf("%-28s %8s %12s %12s %12s %16s\n", "mismatch", "change", "left [mm]", "right [mm]",
              "asymmetry", "per 1 % change");
  std::printf("%-28s %8s %12.6g %12.6g %11.4f%% %16s\n", "none", "", nominal.first * 1e3,
              nominal.second * 1e3, 100.0 * asymmetry(nominal), "");
  for (const Row& row : rows)  // asymmetry [%] per 1 % of change = asymmetry / |change|
    std::printf("%-28s %+7.1f%% %12.6g %12.6g %11.4f%% %15.6g%%\n", shown(row.label).c_str(),
                100.0 * row.change, row.extremes.first * 1e3, row.extremes.second * 1e3,
                100.0 * row.asymmetry, row.asymmetry / cmd.change);
  print_validity(validity);
  return validity_exit(validity);
}

Command add_mismatch_command(CLI::App& app, CommonOptions& options) {
  auto mismatch_options = std::make_shared<MismatchOptions>();
  auto* mismatch_command = app.add_subcommand(
      "mismatch",
      "left/right asymmetry of the periodic swing from a mismatched antagonistic pair: DEA A's\n"
      "electrode area or film thickness changed by +/-X, or the switching overlapping by X*T/2");
  add_common(mismatch_command, options);
  mismatch_command->add_option("--frequency", mismatch_options->frequency,
                               "switching frequency [Hz] (default: the scene's drive.frequency)");
  mismatch_command->add_option("--output", mismatch_options->output,
                               "deflection output (default: the last, e.g. dx4)");
  mismatch_command->add_option("--change", mismatch_options->change,
                               "relative change of each parameter (default 0.05)");

  return {mismatch_command, [mismatch_options, &options] {
            return run_mismatch_command(options, *mismatch_options);
          }};
}

}  // namespace emnet_cli
