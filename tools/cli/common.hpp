// What every command of the emnet program shares: the common options (scene, --set, --probe,
// --json, --csv, progress), loading and preparing a scene, number formats, the CSV writer, the
// failures that become exit statuses, and the lines every result prints (header, validity).
//
// Exit status of the program (tools/cli/main.cpp): 0 success; 2 bad input (InputError,
// FileError); 3 numerical failure (NumericalFailure); 4 crosscheck: a difference exceeds its
// tolerance; 5 computed but outside the model's validity; 130 interrupted (Interrupted).
#pragma once

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/output_file.hpp"
#include "emnet/model/drive.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/report/csv.hpp"
#include "emnet/report/describe.hpp"
#include "emnet/report/json.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/studies/resolve.hpp"
#include "terminal_progress.hpp"

namespace emnet_cli {

using emnet::InputError;
using Json = nlohmann::ordered_json;
constexpr double pi = 3.14159265358979323846;

// Raised for numerical failure: exit status 3.
struct NumericalFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An output file (--csv, --plot, -o) that could not be written: exit status 2, reported after
// the result.
struct FileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Ctrl-C: exit status 130, no output file written.
struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CommonOptions {
  std::string scene_path;
  std::optional<int> segments;
  std::vector<std::string> overrides;
  std::vector<std::string> probes;
  bool json = false;
  std::string csv;
  bool progress = false, quiet = false;  // --progress, --quiet
  TerminalProgress* reporter = nullptr;  // set by main: the progress line, Ctrl-C
};

// A command of the program: its CLI11 subcommand and what runs it once the options are parsed.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

// The scene argument and the options every scene command takes.
void add_common(CLI::App* command, CommonOptions& options);

// --probe or --csv given to a command that has no use for it: refused, never ignored.
void refuse_option(bool given, const std::string& option, const std::string& why);

emnet::Progress* progress_of(const CommonOptions& options);
// A step of a command without counts, shown on the progress line.
void show_phase(const CommonOptions& options, const std::string& what);
// The progress line ends before the result (or a warning) is printed.
void end_progress(const CommonOptions& options);
void stop_if_interrupted();

// Text from outside (scene, override, tool output) as shown on the terminal.
std::string shown(const std::string& text);
// --json output: strings with invalid UTF-8 (a name given by --set) are shown with U+FFFD
// instead of ending the program (emnet/report/json.hpp).
using emnet::json_text;

std::string format(const char* pattern, double value);
std::string si(double value, const std::string& unit);
std::string milliseconds(double seconds);

// Upper bound of the values a command stores and prints or writes (time steps × outputs, AC
// points × probes, ...): 20 million doubles, 160 MB, which --json prints as several hundred MB
// of text. Checked before computing, with the estimate and what to change.
constexpr double kMaximumStoredValues = 2e7;
// A size in bytes as it is read: "168 MB", "4 GB".
std::string bytes_text(double bytes);
void check_stored_values(double values, const std::string& what, const std::string& option,
                         const std::string& remedy);

// Every printed result must be finite: a NaN is a numerical failure, never an output.
double finite(double value, const std::string& what);

// --set overrides with --segments appended.
std::vector<std::string> overrides_with_segments(const CommonOptions& options);
// The scene of the command line, with beam.segments = "auto" chosen once.
emnet::Scene load_scene(const CommonOptions& options);
// A --probe asking for an electrical quantity (drive.electrical_dynamics = "auto" keeps the
// RC dynamics for it).
bool electrical_probe_requested(const CommonOptions& options);
// The model of `scene` with its remaining "auto" keys resolved for the command's probes.
emnet::Model resolved_model(const emnet::Scene& scene, const CommonOptions& options,
                            emnet::LargeKinematicsUse use);
std::vector<emnet::Probe> selected_probes(const emnet::Model& model, const CommonOptions& options);

// The drive in words (header line), what the AC input is (every AC result):
// emnet/report/describe.hpp.
using emnet::ac_input_description;
using emnet::drive_summary;

// The validity checks of a result (emnet/model/validity.hpp) in text: a line with the largest
// values against their limits and a WARNING line per violation ("validity" of --json:
// emnet/report/json.hpp).
std::string validity_warning(const emnet::ValidityViolation& violation);
void print_validity(const emnet::Validity& validity);
// The exit status of a computed result: 0, or 5 with the warnings on standard error.
int validity_exit(const emnet::Validity& validity);

void print_header(const emnet::Model& model, const emnet::System& system);

// The Status of writing the --csv file as a FileError ("--csv: <why>").
void check_csv(const emnet::Status& status, const std::string& option = "--csv");

// A plotted quantity's unit and the factor from SI to it: lengths in mm in every plot (the
// tables' unit of a deflection), every other unit as it is.
struct PlotUnit {
  std::string unit;
  double scale = 1.0;
};
PlotUnit plot_unit(const std::string& si_unit);

// Outside the deflection limit, the limit's lines at ±limit in the deflections' panel, in its
// plot unit (plot_unit): the plot shows where the result left the model's validity; none when it
// is inside.
std::vector<emnet::ReferenceLine> deflection_limit_lines(const emnet::Validity& validity);

// A CSV file of `count` rows, row i filled by fill_row(i, row), written completely or not at
// all (emnet/report/csv.hpp); FileError when it cannot be. The rows are formatted as they are
// written, not stored.
template <class FillRow>
void write_csv_rows(const std::string& path, const std::vector<std::string>& header, size_t count,
                    const FillRow& fill_row) {
  stop_if_interrupted();
  check_csv(emnet::write_csv_rows(path, header, count,
                                  [&](size_t i, std::vector<double>& row) { fill_row(i, row); }));
}

void write_csv(const std::string& path, const std::vector<std::string>& header,
               const std::vector<std::vector<double>>& rows);

// A plot's Status as a FileError (gnuplot missing or failing is no numerical failure).
void check_plot(const emnet::Status& status);
// What a plot writes besides its image (--plot-script), cancelled by Ctrl-C through the
// command's progress reporter: gnuplot is stopped and no file written.
emnet::PlotOutput plot_output(const CommonOptions& options, bool plot_script);

struct Prepared {
  emnet::Model model;
  emnet::System system;
  emnet::StaticResult rest;
};

// Builds the model and its operating point. A linear network without a static state (a free
// body) can still be analysed dynamically: its operating point is then zero, as said in a note;
// `static` itself requires the static state.
Prepared prepare(const CommonOptions& options, bool require_static = false,
                 std::optional<emnet::Scene> scene = std::nullopt);

// ---- Shared by several commands, defined in the file named -------------------------------------

// ac_options.cpp: a frequency option ("6.4", "6.4 Hz"); the AC sweep of the scene's [ac] table with
// --from, --to, --points and --scale applied (ac, netlist --analysis ac); --tolerance and --band
// of a modal reduction (ac, sweep-switching); the warning when its tolerance is not met.
double parse_frequency(const std::string& text, const std::string& option);
emnet::AcSpec checked_ac_spec(emnet::AcSpec spec, const std::string& from_text,
                              const std::string& to_text, std::optional<int> points,
                              const std::string& scale);
emnet::ReductionOptions reduction_options(const std::string& tolerance, const std::string& band,
                                          double default_band, double default_tolerance);
std::string tolerance_warning(double measured, double tolerance);
// The --tolerance and --band options of --reduce (ac, sweep-switching), as text for
// reduction_options.
void add_reduction_tolerance_and_band(CLI::App* command, std::string& tolerance, std::string& band);

// tran.cpp: the outputs of a transient (dx_k = P_k - P1, DEA voltages and currents); with
// --probe those (tran, sweep-switching); the outputs a --plot draws: with --probe every probe,
// else the deflections and the DEA voltages. A plot gives each unit its own panel.
std::vector<emnet::Probe> transient_outputs(const emnet::Model& model,
                                            const CommonOptions& options);
struct PlottedOutputs {
  std::vector<size_t> indices;
};
PlottedOutputs plotted_outputs(const std::vector<emnet::Probe>& probes,
                               const CommonOptions& options);

// --plot PATH and --plot-script (the plot's data and gnuplot script beside the image) of the
// commands that plot (ac, tran, sweep-switching); `what` says what the plot shows.
void add_plot_options(CLI::App* command, std::string& plot, bool& plot_script,
                      const std::string& what);
// Each unit's y-axis label in a plot: prefix + quantity + unit ("peak deflection [mm]",
// "voltage [V]"); a unit not named gets the plot's own "value [unit]".
std::map<std::string, std::string> axis_labels(const std::string& prefix);
// --plot-script without --plot: refused.
void check_plot_options(const std::string& plot, bool plot_script);

// The program's commands, one file each (tools/cli/<command>.cpp).
Command add_static_command(CLI::App& app, CommonOptions& options);
Command add_modes_command(CLI::App& app, CommonOptions& options);
Command add_ac_command(CLI::App& app, CommonOptions& options);
Command add_tran_command(CLI::App& app, CommonOptions& options);
Command add_sweep_switching_command(CLI::App& app, CommonOptions& options);
Command add_identify_command(CLI::App& app, CommonOptions& options);
Command add_sensitivity_command(CLI::App& app, CommonOptions& options);
Command add_mismatch_command(CLI::App& app, CommonOptions& options);
Command add_netlist_command(CLI::App& app, CommonOptions& options);
Command add_crosscheck_command(CLI::App& app, CommonOptions& options);
Command add_study_command(CLI::App& app, CommonOptions& options);
Command add_schema_command(CLI::App& app);

}  // namespace emnet_cli
