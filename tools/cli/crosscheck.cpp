#include "emnet/verification/crosscheck.hpp"

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
#include "emnet/report/crosscheck_json.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/scene/parameter_listing.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "emnet/studies/sensitivity.hpp"

namespace emnet_cli {

using emnet::InputError;
using Json = nlohmann::ordered_json;

// ---- crosscheck: emnet against ngspice -------------------------------------------------
//
// `emnet crosscheck SCENE [--analysis op,ac,modal,tran]`: exports the decks, runs ngspice
// (include/emnet/spice/ngspice_runner.hpp) and compares with emnet's own analyses
// (include/emnet/verification/crosscheck.hpp says what is compared and why each tolerance). Exit
// status 0 when every difference is within its tolerance, 4 when one is not, 3 when ngspice is
// missing, fails or times out, or an emnet analysis fails.

struct CrosscheckCommandOptions {
  std::string analyses = "all";
  double timeout = 60.0;
  std::string backend = "auto";
  std::string keep_decks;
  std::string program;  // empty: "ngspice"
  double periods = 2.0;
  int points_per_period = 2000;
  double reltol = 1e-6;
};

int run_crosscheck_command(CommonOptions options, const CrosscheckCommandOptions& cross) {
  const emnet::Stopwatch stopwatch;
  if (!options.csv.empty())
    throw InputError("--csv", "--csv", "crosscheck prints a table (or --json), not a CSV file");
  if (!options.probes.empty())
    throw InputError("--probe", "--probe", "crosscheck compares every output of the decks");
  if (!(cross.timeout > 0.0) || cross.timeout > 86400.0)
    throw InputError("--timeout", "--timeout", "must be > 0 s and at most 86400 s (inclusive)");
  emnet::CrosscheckOptions check;
  check.analyses = emnet::parse_crosscheck_analyses(cross.analyses);
  check.ngspice.timeout_seconds = cross.timeout;
  check.ngspice.backend = cross.backend == "library"   ? emnet::NgspiceBackend::library
                          : cross.backend == "program" ? emnet::NgspiceBackend::program
                                                       : emnet::NgspiceBackend::automatic;
  if (!cross.program.empty()) check.ngspice.program = cross.program;
  check.keep_decks_directory = cross.keep_decks;
  check.tran_periods = cross.periods;
  check.tran_reltol = cross.reltol;
  check.tran_points_per_period = cross.points_per_period;
  check.overrides = overrides_with_segments(options);
  const bool static_only =
      check.analyses == std::vector<emnet::CrosscheckAnalysis>{emnet::CrosscheckAnalysis::op};
  const emnet::Model model = resolved_model(
      load_scene(options), options,
      static_only ? emnet::LargeKinematicsUse::static_state : emnet::LargeKinematicsUse::dynamics);
  show_phase(options, "ngspice and emnet analyses");
  const emnet::CrosscheckReport report = emnet::run_crosscheck(model, check);
  stop_if_interrupted();
  const double total = stopwatch.seconds();
  end_progress(options);
  const bool pass = report.all_pass();
  if (options.json) {
    std::cout << json_text(emnet::to_json(report, model, total)) << "\n";
  } else {
    const emnet::System system = model.network.assemble();
    print_header(model, system);
    std::cout << "ngspice backend: "
              << (report.backend.empty() ? "(none ran)" : shown(report.backend)) << "\n\n";
    std::printf("%-6s %-38s %11s %10s %-4s  %s\n", "", "quantity", "largest", "tolerance", "",
                "where");
    for (const auto& row : report.rows)
      std::printf("%-6s %-38s %11.3e %10.1e %-4s  %s\n",
                  emnet::crosscheck_analysis_name(row.analysis), shown(row.quantity).c_str(),
                  row.largest_difference, row.tolerance, row.pass ? "pass" : "FAIL",
                  shown(row.where).c_str());
    std::cout << "\ndifferences relative to:\n";
    for (const auto& row : report.rows)
      std::cout << "  " << emnet::crosscheck_analysis_name(row.analysis) << " "
                << shown(row.quantity) << ": " << shown(row.basis) << "\n";
    if (!report.timings.empty()) {
      std::cout << "\nwall time, same run:\n";
      std::printf("%-6s %12s %12s %12s  %s\n", "", "ngspice", "(+ start)", "emnet", "emnet did");
      for (const auto& t : report.timings)
        std::printf("%-6s %12s %12s %12s  %s\n", emnet::crosscheck_analysis_name(t.analysis),
                    milliseconds(t.ngspice_seconds).c_str(),
                    milliseconds(t.ngspice_total_seconds).c_str(),
                    milliseconds(t.emnet_seconds).c_str(), shown(t.emnet_what).c_str());
    }
    for (const auto& note : report.notes) std::cout << "note: " << shown(note) << "\n";
    std::cout << "total " << milliseconds(total) << "\n";
  }
  if (!report.status.ok()) {
    std::cerr << "emnet: crosscheck failed: " << emnet::terminal_lines(report.status.message)
              << "\n";
    return 3;
  }
  if (!pass) {
    std::cerr << "emnet: crosscheck: a difference exceeds its tolerance (exit 4)\n";
    return 4;
  }
  if (!options.json) std::cout << "crosscheck passed\n";
  return 0;
}

Command add_crosscheck_command(CLI::App& app, CommonOptions& options) {
  auto crosscheck_options = std::make_shared<CrosscheckCommandOptions>();
  CrosscheckCommandOptions& cross = *crosscheck_options;
  CLI::App* command = app.add_subcommand(
      "crosscheck",
      "export the scene's decks, run them in ngspice and compare with emnet: op (every node),\n"
      "ac (magnitude and phase at every frequency), modal (modes against ngspice's AC peaks),\n"
      "tran (emnet's exact solution against ngspice at reltol 1e-6).\n"
      "Exit status: 0 every difference within its tolerance; 4 one exceeds it; 3 ngspice\n"
      "missing, failing or timed out, or an emnet analysis failed; 2 bad input.");
  add_common(command, options);
  sets_fields(command->add_option("--analysis", cross.analyses,
                                  "comma-separated subset of op,ac,modal,tran (default: all)"),
              {"analyses"});
  command->add_option("--timeout", cross.timeout,
                      "wall-clock limit per ngspice run [s] (default 60)");
  command
      ->add_option("--backend", cross.backend,
                   "auto (libngspice, else the ngspice program), library or program")
      ->check(CLI::IsMember({"auto", "library", "program"}));
  command->add_option("--ngspice-program", cross.program,
                      "the ngspice program of the program backend (default: ngspice in PATH)");
  sets_fields(command->add_option("--keep-decks", cross.keep_decks,
                                  "also write the decks that were run into this directory"),
              {"keep_decks_directory"});
  sets_fields(command->add_option("--periods", cross.periods,
                                  "tran: periods of the drive (or of the first mode) to compare "
                                  "(default 2)"),
              {"tran_periods"});
  sets_fields(command->add_option("--points-per-period", cross.points_per_period,
                                  "tran: ngspice's max step = period / this (default 2000)"),
              {"tran_points_per_period"});
  sets_fields(
      command->add_option("--reltol", cross.reltol, "tran: ngspice's reltol (default 1e-6)"),
      {"tran_reltol"});
  return {command, [crosscheck_options, &options] {
            return run_crosscheck_command(options, *crosscheck_options);
          }};
}

}  // namespace emnet_cli
