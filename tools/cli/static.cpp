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
#include "emnet/report/json.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/scene/parameter_listing.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "emnet/studies/sensitivity.hpp"
#include "emnet/studies/static_study.hpp"
#include "emnet/verification/crosscheck.hpp"

namespace emnet_cli {

using emnet::InputError;
using Json = nlohmann::ordered_json;

// ---- static ---------------------------------------------------------------------------

// Every value printed is finite: solve_static fails (Status, exit 3) on a non-finite unknown
// or residual, and a probe is a short sum of those unknowns times finite coefficients.
int run_static(const CommonOptions& options) {
  const emnet::Stopwatch stopwatch;
  Prepared p = prepare(options, true);
  const auto probes = selected_probes(p.model, options);
  const emnet::StaticStudyValues values =
      emnet::static_study_values(p.model, p.system, p.rest, probes);
  const auto& rows = values.nodes;
  const auto& probe_values = values.probe_values;
  const emnet::Validity& validity = values.validity;
  const double total = stopwatch.seconds();
  end_progress(options);
  auto write_files = [&] {
    if (!options.csv.empty()) write_csv(options.csv, emnet::static_node_columns(p.model), rows);
  };
  if (options.json) {
    std::cout << json_text(
                     emnet::to_json(p.model, p.rest, rows, probes, probe_values, validity, total))
              << "\n";
    write_files();
    return validity_exit(validity);
  }
  print_header(p.model, p.system);
  std::cout << "static state at rest (" << drive_summary(p.model.scene) << ", first half-period)\n"
            << "accuracy: Newton " << p.rest.newton_iterations << " iteration(s)"
            << (p.rest.load_steps > 1 ? " in " + std::to_string(p.rest.load_steps) + " load steps"
                                      : std::string())
            << ", relative residual " << format("%.2g", p.rest.relative_residual) << "; "
            << emnet::static_discretisation(p.model) << "\n"
            << "cost: solve " << milliseconds(p.rest.seconds) << ", total " << milliseconds(total)
            << "\n\n";
  const bool axial = emnet::static_node_columns(p.model).size() > 3;  // large kinematics
  std::printf("%8s %12s %16s %16s%s\n", "node", "x [mm]", "deflection [m]", "rotation [rad]",
              axial ? "      x displ. [m]" : "");
  for (size_t k = 0; k < rows.size(); ++k) {
    std::printf("%8zu %12.6g %16.6e %16.6e", k, rows[k][0] * 1e3, rows[k][1], rows[k][2]);
    if (axial) std::printf(" %17.6e", rows[k][3]);
    std::printf("\n");
  }
  if (!probes.empty()) std::cout << "\nprobes:\n";
  for (size_t k = 0; k < probes.size(); ++k)
    std::printf("  %-10s %-40s %14.6e %s\n", shown(probes[k].name).c_str(),
                shown(probes[k].description).c_str(), probe_values[k],
                shown(probes[k].unit).c_str());
  print_validity(validity);
  write_files();
  return validity_exit(validity);
}

Command add_static_command(CLI::App& app, CommonOptions& options) {
  auto* static_command = app.add_subcommand(
      "static", "deflection and rotation at every node at rest, and at the probes");
  add_common(static_command, options);

  return {static_command, [&options] { return run_static(options); }};
}

}  // namespace emnet_cli
