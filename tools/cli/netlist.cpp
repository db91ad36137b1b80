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
#include "emnet/core/terminal_text.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/report/spice_deck_json.hpp"
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

// ---- netlist: SPICE export ------------------------------------------------------------
//
// `emnet netlist SCENE --analysis op|ac|tran [-o FILE.cir]`: the scene's network as a SPICE3
// deck (src/spice/spice_netlist.cpp; include/emnet/spice/spice_netlist.hpp explains the mapping).
// The ac options are those of `emnet ac`, the tran options those of `emnet tran`, plus the deck's
// own max step and reltol.

struct NetlistOptions {
  std::string analysis;
  std::string output;  // empty: standard output
  bool control = false;
  // ac, as `emnet ac`
  std::string from_text, to_text;
  std::optional<int> points;
  std::string scale;
  // tran, as `emnet tran`
  std::optional<double> switching;  // default: the scene's drive.frequency
  double periods = 10.0;
  std::string start = "rest";
  int points_per_period = 100;
  double max_step = 0.0;  // s; 0: the output step
  double reltol = 1e-6;
};

int run_netlist_command(CommonOptions options, const NetlistOptions& netlist) {
  if (!options.csv.empty())
    throw InputError("--csv", "--csv", "netlist writes a deck (-o), not a CSV table");
  if (options.json && netlist.output.empty())
    throw InputError("--json", "--json",
                     "--json prints the deck's vector map; give the deck a file with -o");
  emnet::SpiceDeckOptions deck_options;
  deck_options.analysis = netlist.analysis == "ac"     ? emnet::SpiceAnalysis::ac
                          : netlist.analysis == "tran" ? emnet::SpiceAnalysis::tran
                                                       : emnet::SpiceAnalysis::op;
  deck_options.control = netlist.control;
  if (deck_options.analysis == emnet::SpiceAnalysis::tran) {
    if (netlist.switching) {
      if (!(*netlist.switching > 0.0) || !std::isfinite(*netlist.switching))
        throw InputError("--switching", "--switching", "must be a positive frequency in Hz (> 0)");
      options.overrides.push_back("drive.frequency=" + format("%.17g", *netlist.switching));
    }
    if (!(netlist.periods > 0.0) || netlist.periods > 1e6)
      throw InputError("--periods", "--periods", "must be > 0 and at most 1e6 (inclusive)");
    if (netlist.points_per_period < 2 || netlist.points_per_period > 100000)
      throw InputError("--points-per-period", "--points-per-period",
                       "must be from 2 to 100000 (inclusive)");
    if (!(netlist.reltol > 0.0 && netlist.reltol < 1.0))
      throw InputError("--reltol", "--reltol", "must be > 0 and < 1");
    if (!(netlist.max_step >= 0.0) || !std::isfinite(netlist.max_step))
      throw InputError("--max-step", "--max-step", "must be >= 0 s");
  }
  const std::vector<std::string> shown_overrides = overrides_with_segments(options);
  emnet::Scene scene = load_scene(options);
  if (deck_options.analysis == emnet::SpiceAnalysis::ac)
    deck_options.ac = checked_ac_spec(scene.ac, netlist.from_text, netlist.to_text, netlist.points,
                                      netlist.scale);
  // Large kinematics: the op deck takes what the static analysis takes, the others the dynamics'
  // EA (the writer refuses what it does not write, naming the key).
  const emnet::Model model = resolved_model(scene, options,
                                            deck_options.analysis == emnet::SpiceAnalysis::op
                                                ? emnet::LargeKinematicsUse::static_state
                                                : emnet::LargeKinematicsUse::dynamics);
  deck_options.overrides = shown_overrides;
  if (!options.probes.empty()) deck_options.outputs = selected_probes(model, options);
  if (deck_options.analysis == emnet::SpiceAnalysis::tran) {
    const double frequency = model.scene.drive.frequency;
    if (!(frequency > 0.0))
      throw InputError(model.scene.file, "drive.frequency",
                       "a transient needs a drive with a frequency (or --switching)");
    const double period = 1.0 / frequency;
    deck_options.end_time = netlist.periods * period;
    deck_options.output_step = period / netlist.points_per_period;
    deck_options.max_step = netlist.max_step;
    deck_options.relative_tolerance = netlist.reltol;
    deck_options.start =
        netlist.start == "static" ? emnet::StartState::static_ : emnet::StartState::rest;
    if (deck_options.start == emnet::StartState::static_)
      deck_options.static_state = emnet::solve_static(model.network.assemble());
  }
  const emnet::SpiceDeck deck = emnet::write_spice_deck(model, deck_options);
  // What the deck asks ngspice to store: every output at every output step (or frequency).
  const double deck_outputs = static_cast<double>(deck.outputs.size()) + 1.0;
  if (deck_options.analysis == emnet::SpiceAnalysis::tran)
    check_stored_values(
        (std::round(netlist.periods * netlist.points_per_period) + 1.0) * deck_outputs,
        "the deck's transient (" + format("%.6g", netlist.periods) + " periods x " +
            std::to_string(netlist.points_per_period) + " output steps, " +
            std::to_string(deck.outputs.size()) + " outputs) in ngspice",
        "--periods", "lower --periods or --points-per-period, or give fewer --probe");
  if (deck_options.analysis == emnet::SpiceAnalysis::ac)
    check_stored_values(deck_options.ac->points * 2.0 * deck_outputs,
                        "the deck's AC sweep (" + std::to_string(deck_options.ac->points) +
                            " frequencies, " + std::to_string(deck.outputs.size()) +
                            " complex outputs) in ngspice",
                        "--points", "lower --points or give fewer --probe");
  if (netlist.output.empty()) {
    std::cout << deck.text;
    return 0;
  }
  stop_if_interrupted();
  if (const emnet::Status status = emnet::write_output_file(netlist.output, deck.text);
      !status.ok())
    throw FileError("-o: " + status.message);
  if (options.json) {
    Json out = {{"deck", netlist.output}};
    out.update(emnet::to_json(deck, model));
    std::cout << json_text(out) << "\n";
    return 0;
  }
  std::cout << "SPICE deck (" << emnet::spice_analysis_name(deck.analysis) << ") written to "
            << shown(netlist.output) << ": " << deck.outputs.size() << " outputs\n";
  for (const auto& note : deck.notes) std::cout << "note: " << shown(note) << "\n";
  return 0;
}

Command add_netlist_command(CLI::App& app, CommonOptions& options) {
  auto netlist_options = std::make_shared<NetlistOptions>();
  NetlistOptions& netlist = *netlist_options;
  CLI::App* command = app.add_subcommand(
      "netlist",
      "write the scene's network as a SPICE3 deck (ngspice runs it unchanged; LTspice reads\n"
      "it): op = the static network in displacements, ac = the small-signal input of\n"
      "`emnet ac`, tran = the drive's time functions from the start state of `emnet tran`");
  add_common(command, options);
  command->add_option("--analysis", netlist.analysis, "op, ac or tran")
      ->required()
      ->check(CLI::IsMember({"op", "ac", "tran"}));
  command->add_option("-o,--output", netlist.output, "deck file (default: standard output)");
  command->add_flag("--control", netlist.control,
                    "append an ngspice-only .control block (run, wrdata of the outputs)");
  command->add_option("--from", netlist.from_text, "ac: start frequency [Hz] (scene ac.from)");
  command->add_option("--to", netlist.to_text, "ac: stop frequency [Hz] (scene ac.to)");
  command->add_option("--points", netlist.points, "ac: number of frequencies (scene ac.points)");
  command->add_option("--scale", netlist.scale, "ac: lin or log")
      ->check(CLI::IsMember({"lin", "log"}));
  command->add_option("--switching", netlist.switching,
                      "tran: switching frequency [Hz] (default: the scene's drive.frequency)");
  command->add_option("--periods", netlist.periods, "tran: number of periods (default 10)");
  sets_fields(command
                  ->add_option("--start", netlist.start,
                               "tran: rest (default) or static (the static state under the first "
                               "half-period's drive)")
                  ->check(CLI::IsMember({"rest", "static"})),
              {"start"});
  command->add_option("--points-per-period", netlist.points_per_period,
                      "tran: output step = period / this (default 100)");
  command->add_option("--max-step", netlist.max_step,
                      "tran: largest time step of the deck [s] (default: the output step)");
  command->add_option("--reltol", netlist.reltol, "tran: the deck's .options reltol (1e-6)");
  return {command,
          [netlist_options, &options] { return run_netlist_command(options, *netlist_options); }};
}

}  // namespace emnet_cli
