#include "cli/common.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli/option_names.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/analysis/operating_point.hpp"
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
#include "emnet/studies/prepared_model.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "emnet/studies/sensitivity.hpp"
#include "emnet/verification/crosscheck.hpp"

namespace emnet_cli {

// --probe or --csv given to a command that has no use for it: refused, never ignored.
void refuse_option(bool given, const std::string& option, const std::string& why) {
  if (given) throw InputError(option, option, why);
}

emnet::Progress* progress_of(const CommonOptions& options) {
  return options.reporter;
}

// A step of a command without counts, shown on the progress line.
void show_phase(const CommonOptions& options, const std::string& what) {
  if (options.reporter) options.reporter->phase(what);
}

// The progress line ends before the result (or a warning) is printed.
void end_progress(const CommonOptions& options) {
  if (options.reporter) options.reporter->finish();
}

void stop_if_interrupted() {
  if (InterruptHandler::interrupted()) throw Interrupted("interrupted");
}

// Text from outside (scene, override, tool output) as shown on the terminal.
std::string shown(const std::string& text) {
  return emnet::terminal_text(text);
}

std::string format(const char* pattern, double value) {
  return emnet::format_number(pattern, value);
}

std::string si(double value, const std::string& unit) {
  return emnet::format_with_unit(value, unit);
}

std::string milliseconds(double seconds) {
  return emnet::format_duration(seconds);
}

// Upper bound of the values a command stores and prints or writes (time steps × outputs, AC
// points × probes, ...): 20 million doubles, 160 MB, which --json prints as several hundred MB
// of text. Checked before computing, with the estimate and what to change.

// A size in bytes as it is read: "168 MB", "4 GB".
std::string bytes_text(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, bytes < 1e9 ? "%.3g MB" : "%.3g GB",
                bytes < 1e9 ? bytes / 1e6 : bytes / 1e9);
  return text;
}

void check_stored_values(double values, const std::string& what, const std::string& option,
                         const std::string& remedy) {
  if (values <= kMaximumStoredValues) return;
  char counts[96];
  std::snprintf(counts, sizeof counts, " would store %.3g values (", values);
  throw InputError(option, option,
                   what + counts + bytes_text(8.0 * values) + " of doubles); at most " +
                       format("%.0f", kMaximumStoredValues) + " values (" +
                       bytes_text(8.0 * kMaximumStoredValues) +
                       ") are stored (inclusive): " + remedy);
}

// Every printed result must be finite: a NaN is a numerical failure, never an output.
double finite(double value, const std::string& what) {
  if (!std::isfinite(value)) throw NumericalFailure("non-finite result for " + what);
  return value;
}

// --set overrides with --segments appended.
std::vector<std::string> overrides_with_segments(const CommonOptions& options) {
  std::vector<std::string> overrides = options.overrides;
  if (options.segments) {
    if (*options.segments < 1)
      throw InputError(
          "--segments", "--segments",
          "must be >= 1 (a number of beam segments), got " + std::to_string(*options.segments));
    overrides.push_back("beam.segments=" + std::to_string(*options.segments));
  }
  return overrides;
}

emnet::Scene load_scene(const CommonOptions& options) {
  const std::vector<std::string> overrides = overrides_with_segments(options);
  const emnet::Scene scene = emnet::read_scene(options.scene_path, overrides);
  // beam.segments = "auto": chosen once here, so that every model a command builds from the
  // scene has the same N (emnet/studies/resolve.hpp).
  return emnet::resolve_segments(scene);
}

// A --probe asking for an electrical quantity (drive.electrical_dynamics = "auto" keeps the
// RC dynamics for it).
bool electrical_probe_requested(const CommonOptions& options) {
  return emnet::asks_for_dea_electrics(options.probes);
}

// The model of `scene` with its remaining "auto" keys resolved for the command's probes and
// its use of large kinematics.
emnet::Model resolved_model(const emnet::Scene& scene, const CommonOptions& options,
                            emnet::LargeKinematicsUse use) {
  emnet::PrepareOptions prepare = emnet::prepare_options_for_probes(options.probes);
  prepare.large_kinematics = use;
  return emnet::prepare_model(scene, prepare);
}

std::vector<emnet::Probe> selected_probes(const emnet::Model& model, const CommonOptions& options) {
  if (options.probes.empty()) return model.probes;
  std::vector<emnet::Probe> probes;
  for (const auto& text : options.probes) probes.push_back(model.parse_probe(text));
  return probes;
}

std::string validity_warning(const emnet::ValidityViolation& violation) {
  return "WARNING: outside the model's validity: " + violation.message;
}

void print_validity(const emnet::Validity& validity) {
  std::cout << "validity: " << validity.summary << "\n";
  for (const auto& v : validity.violations) std::cout << validity_warning(v) << "\n";
}

// The exit status of a computed result: 0, or 5 with the warnings on standard error.
int validity_exit(const emnet::Validity& validity) {
  for (const auto& v : validity.violations) std::cerr << "emnet: " << validity_warning(v) << "\n";
  return validity.within() ? 0 : emnet::kExitOutsideValidity;
}

void print_header(const emnet::Model& model, const emnet::System& system) {
  const auto& scene = model.scene;
  const auto& beam = scene.beam;
  std::cout << "scene " << shown(scene.name) << " (" << shown(scene.file)
            << "): " << model.beam.x.size() - 1 << " segments, L = " << si(beam.length, "m");
  if (beam.sections.empty())
    std::cout << ", EI = " << si(beam.bending_stiffness, "N*m^2")
              << ", rhoA = " << si(beam.mass_per_length, "kg/m");
  else
    std::cout << " in " << beam.sections.size() << " sections";
  if (!beam.masses.empty()) std::cout << ", " << beam.masses.size() << " point mass(es)";
  if (!beam.springs.empty()) std::cout << ", " << beam.springs.size() << " spring(s)";
  if (beam.theory == emnet::BeamTheory::timoshenko) std::cout << ", Timoshenko";
  std::cout << ", " << scene.deas.size() << " DEA(s), " << drive_summary(scene) << "\n"
            << "network: " << model.network.nodes().size() << " nodes, "
            << model.network.elements().size() << " elements, " << system.size() << " unknowns\n";
  for (const auto& note : model.notes) std::cout << "note: " << shown(note) << "\n";
}

void check_csv(const emnet::Status& status, const std::string& option) {
  if (!status.ok()) throw FileError(option + ": " + status.message);
}

void write_csv(const std::string& path, const std::vector<std::string>& header,
               const std::vector<std::vector<double>>& rows) {
  stop_if_interrupted();
  check_csv(emnet::write_csv(path, header, rows));
}

// A plot's Status as a FileError (gnuplot missing or failing is no numerical failure).
void check_plot(const emnet::Status& status) {
  if (status.ok()) return;
  if (status.cancelled()) throw Interrupted("interrupted");
  throw FileError("--plot: " + status.message);
}

emnet::PlotOutput plot_output(const CommonOptions& options, bool plot_script) {
  emnet::PlotOutput output;
  output.data_and_script = plot_script;
  output.progress = options.reporter;  // only asked whether Ctrl-C came
  return output;
}

void add_plot_options(CLI::App* command, std::string& plot, bool& plot_script,
                      const std::string& what) {
  command->add_option("--plot", plot,
                      "write a plot (PNG or SVG, by the extension) of " + what +
                          "; only the image, unless --plot-script");
  command->add_flag("--plot-script", plot_script,
                    "with --plot PATH: also write the plotted numbers (PATH.dat) and the gnuplot "
                    "script that draws them (PATH.gp; edit it and run `gnuplot PATH.gp` in its "
                    "directory to re-draw the image)");
}

PlotUnit plot_unit(const std::string& si_unit) {
  if (si_unit == "m") return {"mm", 1e3};
  return {si_unit, 1.0};
}

std::vector<emnet::ReferenceLine> deflection_limit_lines(const emnet::Validity& validity) {
  const PlotUnit shown = plot_unit("m");
  const std::string& unit = shown.unit;
  const double scale = shown.scale;
  std::vector<emnet::ReferenceLine> lines;
  for (const emnet::ValidityViolation& violation : validity.violations)
    if (violation.check == emnet::ValidityCheck::deflection) {
      const std::string label = "deflection limit +/-" + format("%.4g", violation.limit * scale) +
                                " " + unit + " (" + violation.key + ")";
      lines.push_back({unit, violation.limit * scale, label});
      lines.push_back({unit, -violation.limit * scale, ""});
      break;  // one limit for every output
    }
  return lines;
}

std::map<std::string, std::string> axis_labels(const std::string& prefix) {
  const std::map<std::string, std::string> quantities = {{"m", "deflection"},
                                                         {"mm", "deflection"},
                                                         {"m/s", "velocity"},
                                                         {"rad", "rotation"},
                                                         {"rad/s", "angular velocity"},
                                                         {"V", "voltage"},
                                                         {"A", "current"},
                                                         {"N", "force"},
                                                         {"N*m", "moment"}};
  std::map<std::string, std::string> labels;
  for (const auto& [unit, quantity] : quantities)
    labels[unit] = prefix + quantity + " [" + unit + "]";
  labels[""] = prefix + "strain [-]";  // the one quantity without a unit (it read "value")
  return labels;
}

void check_plot_options(const std::string& plot, bool plot_script) {
  if (plot_script && plot.empty())
    throw emnet::InputError("--plot-script", "--plot",
                            "--plot-script writes the files of a plot: give --plot PATH too");
}

// Builds the model and its operating point. A linear network without a static state (a free
// body) can still be analysed dynamically: its operating point is then zero, as said in a note;
// `static` itself requires the static state.
Prepared prepare(const CommonOptions& options, bool require_static,
                 std::optional<emnet::Scene> scene) {
  if (!scene) scene = load_scene(options);
  show_phase(options, "building the network");
  emnet::OperatingPointOptions point_options;
  point_options.static_options.progress = progress_of(options);
  point_options.require_static = require_static;
  emnet::PrepareOptions prepare;
  prepare.electrical_probe_requested = electrical_probe_requested(options);
  // `static` requires the static state (and takes an inextensible beam with large kinematics);
  // `ac`, the other command here, linearises about it.
  prepare.large_kinematics = require_static ? emnet::LargeKinematicsUse::static_state
                                            : emnet::LargeKinematicsUse::dynamics;
  emnet::PreparedModel prepared = emnet::prepare_at_rest(*scene, prepare, point_options);
  stop_if_interrupted();
  if (!prepared.status.ok()) throw NumericalFailure(prepared.status.message);
  return {std::move(prepared.model), std::move(prepared.system), std::move(prepared.rest)};
}

void add_common(CLI::App* command, CommonOptions& options) {
  command->add_option("scene", options.scene_path, "scene file (TOML), e.g. netlists/fishfin.toml")
      ->required();
  // Fields of the library's calls these set: the mesh, the scene's overrides, the probe texts.
  sets_fields(command->add_option("--segments", options.segments,
                                  "number of beam segments, >= 1 (same as --set beam.segments=N)"),
              {"segments"});
  sets_fields(command
                  ->add_option("--set", options.overrides,
                               "override a scene key: --set beam.length=0.2 or --set "
                               "\"drive.voltage=3 kV\"")
                  ->allow_extra_args(false),
              {"overrides"});
  sets_fields(command
                  ->add_option("--probe", options.probes,
                               "output: a probe name of the scene, QUANTITY@POSITION "
                               "(deflection, velocity, rotation, angular_velocity; e.g. "
                               "deflection@70mm) or dea_voltage:NAME / dea_current:NAME")
                  ->allow_extra_args(false),
              {"probe", "outputs"});
  command->add_flag("--json", options.json, "print machine-readable JSON instead of tables");
  command->add_option("--csv", options.csv, "also write the result table to this CSV file");
  auto* progress = command->add_flag(
      "--progress", options.progress,
      "show progress on standard error also when it is not a terminal (a line per step "
      "and per second)");
  command
      ->add_flag("--quiet", options.quiet,
                 "no progress line (by default shown on a terminal for runs over a second)")
      ->excludes(progress);
}

}  // namespace emnet_cli
