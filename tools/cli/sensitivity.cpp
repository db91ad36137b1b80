#include "emnet/studies/sensitivity.hpp"

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
#include "cli/option_names.hpp"
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
#include "emnet/report/json.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/scene/parameter_listing.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "emnet/verification/crosscheck.hpp"

namespace emnet_cli {

using emnet::InputError;
using Json = nlohmann::ordered_json;

// ---- sensitivity ------------------------------------------------------------------------
//
// `emnet sensitivity SCENE [--modes K] [--parameter KEY ...] [--check]`: df/dp of the first K
// resonances for every scene parameter, from the eigenvectors
// (include/emnet/studies/sensitivity.hpp), and with --check the finite-difference reference.

struct SensitivityCommandOptions {
  int modes = 3;
  std::vector<std::string> parameters;
  bool check = false;
};

int run_sensitivity_command(const CommonOptions& options, const SensitivityCommandOptions& cmd) {
  const emnet::Stopwatch stopwatch;
  refuse_option(!options.probes.empty(), "--probe",
                "sensitivity differentiates resonance frequencies, not probe outputs");
  refuse_option(!options.csv.empty(), "--csv",
                "sensitivity prints its table (or --json), not a CSV file");
  if (cmd.modes < 1) throw InputError("--modes", "--modes", "must be >= 1");
  const emnet::Scene scene = load_scene(options);
  emnet::SensitivityOptions sensitivity_options;
  sensitivity_options.modes = cmd.modes;
  sensitivity_options.check = cmd.check;
  sensitivity_options.progress = progress_of(options);
  const emnet::SensitivityResult result =
      emnet::run_sensitivity(scene, cmd.parameters, sensitivity_options);
  if (!result.status.ok()) throw NumericalFailure("sensitivity: " + result.status.message);
  for (const auto& parameter : result.parameters)
    for (const auto& mode : parameter.modes) {
      finite(mode.frequency_derivative, "df/d" + parameter.parameter.key);
      finite(mode.normalised, "the normalised sensitivity to " + parameter.parameter.key);
    }
  const double total = stopwatch.seconds();
  end_progress(options);
  const auto& modes = result.modes;
  if (options.json) {
    std::cout << json_text(emnet::to_json(result, scene, cmd.check, total)) << "\n";
    return 0;
  }
  std::cout << "scene " << shown(scene.name) << " (" << shown(scene.file)
            << "): " << scene.beam.segments << " segments\n";
  for (const auto& choice : scene.automatic_choices)
    std::cout << "note: " << shown(choice.reason) << "\n";
  for (const auto& note : result.notes) std::cout << "note: " << shown(note) << "\n";
  std::cout << "modes:";
  for (size_t k = 0; k < modes.size(); ++k)
    std::printf(" f%zu = %.7g Hz (natural %.7g Hz)%s", k + 1, modes[k].frequency_hz,
                modes[k].natural_frequency_hz, k + 1 < modes.size() ? "," : "\n");
  std::cout << "method: first-order eigenvalue perturbation, ds/dp = -y^H (dG/dp + s dC/dp) x / "
               "(y^H C x), matrices differenced at p(1 +/- 1e-6); left-vector residual "
            << format("%.2g", result.left_vector_residual) << "\n"
            << "columns per mode: df/dp of the damped frequency [Hz per unit], S = (p/f) df/dp [-]"
            << (cmd.check ? ", and the check: |dS analytic - FD| (FD error estimate), FD of the "
                            "poles at p(1 +/- 1e-4)"
                          : "")
            << "\ncost: " << milliseconds(result.seconds - result.check_seconds)
            << (cmd.check ? ", check " + milliseconds(result.check_seconds) : "") << ", total "
            << milliseconds(total) << "\n\n";
  std::printf("%-32s %13s %-6s", "parameter", "value", "unit");
  for (size_t k = 0; k < modes.size(); ++k) {
    std::printf(" %13s %9s", ("df" + std::to_string(k + 1) + "/dp").c_str(),
                ("S" + std::to_string(k + 1)).c_str());
    if (cmd.check) std::printf(" %19s", "check");
  }
  std::printf("\n");
  for (const auto& parameter : result.parameters) {
    std::printf("%-32s %13.6g %-6s", shown(parameter.parameter.key).c_str(),
                parameter.parameter.value, shown(parameter.parameter.unit).c_str());
    for (const auto& s : parameter.modes) {
      // |S| below 1e-12 is rounding of an exact zero (a parameter the modes do not see).
      const bool zero = std::abs(s.normalised) < 1e-12;
      std::printf(" %13.5g %+9.6g", zero ? 0.0 : s.frequency_derivative, zero ? 0.0 : s.normalised);
      if (cmd.check) std::printf(" %8.1e (%8.1e)", s.check_difference, s.check_error_estimate);
    }
    std::printf("\n");
  }
  return 0;
}

Command add_sensitivity_command(CLI::App& app, CommonOptions& options) {
  auto sensitivity_options = std::make_shared<SensitivityCommandOptions>();
  auto* sensitivity_command = app.add_subcommand(
      "sensitivity",
      "derivative of each resonance frequency with respect to every scene parameter, from the\n"
      "eigenvectors (first-order eigenvalue perturbation); --check compares with finite\n"
      "differences of the poles");
  add_common(sensitivity_command, options);
  sets_fields(sensitivity_command->add_option("--modes", sensitivity_options->modes,
                                              "number of lowest oscillatory modes (default 3)"),
              {"modes"});
  sets_fields(sensitivity_command
                  ->add_option("--parameter", sensitivity_options->parameters,
                               "a scene key, e.g. beam.bending_stiffness or dea[A].lever_arm "
                               "(default: every non-zero parameter)")
                  ->allow_extra_args(false),
              {"parameters"});
  sensitivity_command->add_flag("--check", sensitivity_options->check,
                                "also difference the poles at p(1 +/- 1e-4) and report the "
                                "difference");

  return {sensitivity_command, [sensitivity_options, &options] {
            return run_sensitivity_command(options, *sensitivity_options);
          }};
}

}  // namespace emnet_cli
