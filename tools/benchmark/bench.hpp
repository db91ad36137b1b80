// What the benchmark's sections share (tools/benchmark/*.cpp): number and time formats, the
// timing loop (warm-up, repetitions within a budget, median and spread), processes started and
// timed through emnet's process helper, the settings, the peaks of a periodic run and their
// error, the Pareto plots' data, the rows and headline of a method table, ngspice helpers, and
// the sections themselves. What each section measures: main.cpp's header comment.
#pragma once

#include <sys/stat.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/process.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/spice/ngspice_runner.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "emnet/studies/switching_sweep.hpp"

namespace emnet_bench {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start);
std::string format(const char* pattern, double value);
// "1.23 ms", "4.5 s": a time in the unit that keeps it readable.
std::string time_text(double seconds);
std::string error_text(double error);
std::string ratio_text(double ratio);

// ---- timing --------------------------------------------------------------------------------

struct Timing {
  double median = 0.0, minimum = 0.0, maximum = 0.0;
  int repetitions = 0;
  std::string text() const {
    if (repetitions <= 0) return "–";
    if (repetitions == 1) return time_text(median) + " (1 run)";
    return time_text(median) + " (" + time_text(minimum) + "–" + time_text(maximum) + ", " +
           std::to_string(repetitions) + " runs)";
  }
};

Timing summarise(std::vector<double> times);
// Warm-up, then repetitions until `repetitions` or `budget_seconds` (see main.cpp's header
// comment). `run` returns the seconds it measured itself (so that it can leave set-up out), or
// a negative value to be timed from outside.
Timing measure(const std::function<double()>& run, int repetitions, double budget_seconds);

// ---- processes -----------------------------------------------------------------------------

struct ProcessRun {
  bool succeeded = false;
  double seconds = 0.0;
  std::string output;  // standard output, when captured
};

// Runs argv[0] (searched in PATH) through emnet's process helper, standard input and error
// /dev/null, standard output /dev/null or, with `capture`, kept (at most 1 MiB). `seconds` is
// the program's run as its supervisor sees it, from just before it is started until it is
// reaped (emnet/core/process.hpp): the program's own start, work and exit, without the
// supervisor's start or the clean-up after the program.
ProcessRun run_process(const std::vector<std::string>& arguments, bool capture = false,
                       double timeout_seconds = 300.0);
Timing measure_process(const std::vector<std::string>& arguments, int repetitions,
                       double budget_seconds, bool& ok);

// ---- settings ------------------------------------------------------------------------------

struct Settings {
  std::string root = ".";             // repository root (netlists/)
  std::string out = "build/bench";    // report, data, decks
  std::string emnet = "build/emnet";  // the program, for whole-process times
  std::string self;                   // this program, for scale points
  bool quick = false;                 // smoke test: tiny sizes, few repetitions
  std::string only;                   // --only 0|4|5a|5b|6: that section alone (report-5a.md, …)
  std::string report;                 // the report's path (default: out/report.md)
  std::string figures;                // where the plots go (default: out)
  std::string fishfin() const { return root + "/netlists/fishfin.toml"; }
  // A plot's file, figures/bench-<name>.png, and the link to it from the report's directory.
  std::string figure(const std::string& name) const;
  std::string figure_link(const std::string& name) const;
  std::string cantilever() const { return root + "/netlists/cantilever.toml"; }
};

inline const std::vector<std::string> ideal_drive = {"drive.electrical_dynamics=false"};

emnet::Model build(const std::string& path, std::vector<std::string> overrides);
// The deflection outputs compared everywhere: the scene's probes in metres (and dx_k) that
// are not identically zero (P1 sits at the clamp).
std::vector<emnet::Probe> deflection_probes(const emnet::Model& model);
// The seconds `emnet ac` takes in process on the ideal-drive fish fin: read the scene, build and
// assemble its model, solve the static state, run_ac over `grid` at its deflection probes.
double fishfin_ac_from_scene_seconds(const Settings& settings, const std::vector<double>& grid);

// ---- peaks ---------------------------------------------------------------------------------

// The extreme of samples (t_k, y_k), k in [begin, end), refined by the parabola through the
// extreme sample and its neighbours, which may lie outside the window (non-uniform spacing
// allowed). `sign` +1: maximum.
double refined_extreme(const std::vector<double>& t, const std::vector<double>& y, size_t begin,
                       size_t end, double sign);

struct Peaks {
  std::vector<double> minimum, maximum;  // per probe
};

// Error of peaks against reference peaks, over frequencies: |difference| relative to that
// probe's largest |peak| over the sweep; the largest over all.
double sweep_error(const std::vector<Peaks>& peaks, const std::vector<Peaks>& reference);

// ---- report pieces ---------------------------------------------------------------------------

struct ParetoPoint {
  std::string series;  // legend: method and tool
  std::string label;   // point label (rtol, threshold)
  double seconds = 0.0;
  double error = 0.0;
};

// One gnuplot script and one data block per series (error floored at 1e-16 for the log axis):
// out/bench-<name>.gp and .dat, plotting to settings.figure(name).
void write_pareto_plot(const Settings& settings, const std::string& name, const std::string& title,
                       const std::vector<ParetoPoint>& points);
// The start of every plot's gnuplot script: terminal, output `png`, title, grid, line styles
// 1..8 (colours that read on white).
std::string plot_preamble(const std::string& png, const std::string& title);

// run_transient_ida of `system` timed by `measure` (its own seconds); `last` keeps a run's result.
Timing measure_ida(const emnet::System& system, const std::vector<emnet::Probe>& probes,
                   const emnet::TransientOptions& options, emnet::TransientResult& last,
                   int repetitions, double budget_seconds);

// Largest |a − b| over outputs and kept times, relative to each output's peak |b|.
double run_error(const std::vector<std::vector<double>>& values,
                 const std::vector<std::vector<double>>& reference,
                 const std::vector<bool>& keep = {});

struct MethodRow {
  std::string tool, method, setting;
  double error = NAN;
  Timing in_process, whole_process;
  std::string note;
};

std::string method_table(const std::vector<MethodRow>& rows);

// For every ngspice row: the fastest emnet row with error ≤ its error; the ratio
// ngspice time / emnet time. The headline is the smallest such ratio (the least favourable).
struct Headline {
  double in_process = NAN, whole_process = NAN;
  std::string in_process_pair, whole_process_pair;
  // The least favourable whole-process pair's times.
  double whole_process_spice = NAN, whole_process_own = NAN;
  // Against ngspice's most accurate run (the smallest error), whole process.
  double accurate = NAN;
  std::string accurate_pair;
};

Headline headline(const std::vector<MethodRow>& rows);

std::vector<std::string> emnet_cli(const Settings& settings, const std::string& command,
                                   std::vector<std::string> extra);
std::string write_deck(const Settings& settings, const std::string& name, const std::string& text);
// ngspice's whole process on a deck: the program with a rawfile (without one, `ngspice -b`
// runs no analysis that writes nothing).
Timing ngspice_process(const Settings& settings, const std::string& deck_path, int repetitions,
                       double budget, bool& ok);
emnet::NgspiceOptions in_process_ngspice();
// A .tran result of ngspice at its own time points, away from the switching edges: the times
// outside ±10·edge_width of every multiple of half a period (the deck's edges), up to
// end_time, and each output's values there ([output][kept time]), to compare with a reference
// evaluated at `kept`. `outputs` of the deck's outputs in order (empty where one is missing).
struct SpicePoints {
  std::vector<double> kept;
  std::vector<std::vector<double>> values;
};
SpicePoints spice_points_away_from_edges(const emnet::NgspiceResult& result,
                                         const emnet::SpiceDeck& deck, size_t outputs,
                                         double period, double edge_width, double end_time);
std::string remove_options_line(const std::string& deck);

struct Section {
  std::string markdown;
  Headline headline;
};

// ---- the sections ----------------------------------------------------------------------------
//
// Each returns its part of the report below its heading (main.cpp writes the headings): an
// introduction saying what it measures, against which reference and how, then the tables and
// the conclusions computed from them.

// limits.cpp: 0. every analysis against its arithmetic limit, and IDA against ngspice on the
// RC-loop fin.
std::string limits_section(const Settings& settings);

// study.cpp: 6. design studies (and the Python module's measurements).
std::string study_section(const Settings& settings);

// discretisation.cpp: 1. the cantilever and the fish fin against N; 4b. dense against Arnoldi.
std::string discretisation_section(const Settings& settings, std::vector<ParetoPoint>& pareto);
std::string modes_section(const Settings& settings);
// The fish fin (ideal drive) of the AC measurements: its network at rest, the deflection
// outputs and the scene's grid (ac.cpp).
struct AcContext {
  emnet::Model model;
  emnet::System system;
  emnet::StaticResult rest;
  std::vector<emnet::Probe> probes;
  std::vector<double> grid;
};
AcContext ac_context(const Settings& settings);
// ac.cpp and transient.cpp: 2 and 3, emnet's methods and ngspice side by side.
Section ac_section(const Settings& settings, std::vector<ParetoPoint>& pareto);
Section tran_section(const Settings& settings, std::vector<ParetoPoint>& pareto);

// sweep.cpp: the switching sweep.
struct SweepContext {
  emnet::Scene scene;
  std::vector<double> frequencies;
  std::vector<emnet::Probe> probes;
};

SweepContext sweep_context(const Settings& settings);
// The time spent in each part of one direct sweep (see sweep.cpp).
struct DirectSweepParts {
  double decomposition = 0, build = 0, assemble = 0, solve = 0, total = 0;
};
// The direct sweep by emnet::run_switching_sweep (the exact method of `emnet sweep-switching`)
// from the context's scene, the model prepared inside the timed call.
std::vector<Peaks> direct_sweep(const SweepContext& context, int samples,
                                DirectSweepParts* parts = nullptr);
Section sweep_section(const Settings& settings, std::vector<ParetoPoint>& pareto,
                      std::string& goal_sweep_text);

// scale.cpp: 4. fresh processes at N = 10 … 10 000; the child mode of one point.
int scale_point(const Settings& settings, const std::string& analysis, int segments);
std::string scale_section(const Settings& settings, std::map<std::string, double>& exponents);

// simplifications.cpp: 5a and 5b.
std::string simplification_section(const Settings& settings);
std::string reduction_section(const Settings& settings);

// crosscheck.cpp: `emnet crosscheck` on the shipped scenes, its differences and wall times.
std::string crosscheck_section(const Settings& settings);
// large_deflection.cpp: 7, large kinematics against small (static, IDA).
std::string large_deflection_section(const Settings& settings);
// real_devices.cpp: 8, the tweezer jaw's periodic state over switching frequencies.
std::string real_device_section(const Settings& settings);

}  // namespace emnet_bench
