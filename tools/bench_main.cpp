// emnet_bench: speed against error, side by side with ngspice (tools/bench runs it and plots).
//
// Every measurement is taken in this one run on this one machine. What each section measures
// and how:
//
//  Timing. A measured item runs once as a warm-up (caches, lazy library loading), then is
//  repeated until `repetitions` runs or a per-item time budget is used up; the report gives
//  the median, and the spread as min..max, with the number of repetitions. An item whose
//  warm-up alone takes more than half its budget is timed by that one run (repetitions 1).
//  "In-process" times a function call in this process; "whole process" times a program
//  started through emnet's process helper (emnet/core/process.hpp), from just before it is
//  started until it is reaped, as its supervisor sees it (wall clock, output to /dev/null), so
//  it includes program start, reading the scene or deck, and printing or writing results, but
//  not the start of the supervisor or the clean-up after the program.
//
//  1. Discretisation error against cost. Cantilever (netlists/cantilever.toml: L = 0.5 m,
//     EI = 2 N·m², ρA = 0.3 kg/m, 1 N at the tip) with N segments: f1..f3 of run_modes against
//     the continuum f = (βL)²/(2πL²)·√(EI/ρA), βL = 1.875104, 4.694091, 7.854757, and the
//     static tip deflection against F·L³/(3EI); cost = time of run_modes (3 lowest modes) and
//     of a 1000-point log AC sweep (0.5–200 Hz). Fish fin at N = 7 against its converged
//     answer: modes at N = 1000 and 2000, Richardson extrapolated for O(N⁻²) convergence.
//  2. Integrator error against cost. Fish fin with the ideal drive
//     (drive.electrical_dynamics = false: a linear network), 50 periods at 5 Hz from rest,
//     100 outputs per period: IDA at rtol 1e-3…1e-10 and the exact method. Error: the largest
//     |difference| over the run and over the deflection outputs, each relative to that output's
//     peak |value|, against run_transient_exact. Periodic steady state over 61 switching
//     frequencies (1–7 Hz, step 0.1): PeriodicSolver (direct) against run-until-settled (the
//     exact transient from rest for K periods, K doubled from 8 until the peaks of two
//     consecutive periods differ by less than a threshold; peaks refined by a parabola through
//     the largest sample and its neighbours). Error: the left and right peaks of every
//     deflection output, relative to that output's largest peak over the sweep, against the
//     direct method with 1024 samples per period.
//  3. ngspice side by side. The decks are written by write_spice_deck from the same model and
//     run by run_ngspice (in-process: libngspice in this process; whole process: the ngspice
//     program, `ngspice -b -r RAWFILE DECK`). AC: the scene's 1000-point sweep (0–10 Hz);
//     reference: a dense complex LU of (G + J_g + jωC)·Y = B_ac at ngspice's own frequencies
//     (f > 0). Transient: emnet's exact solution at ngspice's own time points, excluding ±10ε
//     around every switching edge (the deck switches with linear edges of width ε). Sweep: one
//     deck per frequency, run for as many periods as the exact transient needed to settle to
//     1e-4 per period, peaks of its last period (refined like emnet's run-until-settled).
//  4. Scale. Fish fin at N = 10 … 10 000: each point is a fresh process (this program with
//     --scale-point), which reports its own peak resident memory (VmHWM) and the time of the
//     analysis alone, after reading and building. Growth exponent: least squares of log(time)
//     on log(N) over the points with N ≥ 300. A point is skipped when the previous point's
//     time extrapolated with the fitted exponent (at least
//     1) exceeds the point budget.
//  5a. Simplifications: what each costs and saves. Fish fin, band 0–130 Hz, beam.segments =
//     "auto" at model.tolerance 1e-2, 1e-3, 1e-4: the chosen N, the selection's estimate and
//     its time, the band modes' error against the bare beam converged by Richardson from
//     N = 1000 and 2000, and the analyses N serves on the full model, run_modes (5 modes)
//     and a 1000-point AC sweep over the band, at N against a fixed N = 200 (ratios of
//     medians, without and with the time to choose). Ideal against RC drive at
//     the scene's N = 7 and 5 Hz: periodic steady state (exact PeriodicSolver against IDA
//     shooting) and 50 periods of transient (exact against IDA), cost ratio RC/ideal and
//     the largest peak-deflection difference relative to the RC peak.
//  5b. Modal reduction. Fish fin (ideal drive) at N = 7, 100, 500 (--quick: 7, 100): the
//     1000-point AC sweep (0–10 Hz) by run_ac and by run_ac_reduced (band 10 Hz, tol 1e-2,
//     1e-3, 1e-4), and the 61-frequency periodic sweep (1–7 Hz) by PeriodicSolver and by
//     ReducedPeriodicSolver (band 7 Hz) at N = 7 and 100, each timed side by side in this run;
//     error: the largest difference at every point (every sample of every period), relative
//     to each probe's largest |value|.
//
// --only 5a or --only 5b runs that section alone and writes report-5a.md or report-5b.md.
//
// Outputs (in --out): report.md, data files *.dat and gnuplot scripts *.gp for the Pareto
// plots (tools/bench runs gnuplot), decks/*.cir.
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
#include "emnet/model/model.hpp"
#include "emnet/spice/ngspice_runner.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/core/process.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

// "1.23 ms", "4.5 s": a time in the unit that keeps it readable.
std::string time_text(double seconds) {
  if (!(seconds > 0.0)) return "–";
  if (seconds < 1e-3) return format("%.3g µs", seconds * 1e6);
  if (seconds < 1.0) return format("%.3g ms", seconds * 1e3);
  return format("%.3g s", seconds);
}

std::string error_text(double error) {
  if (!std::isfinite(error)) return "–";
  return format("%.1e", error);
}

std::string ratio_text(double ratio) {
  if (!std::isfinite(ratio) || ratio <= 0.0) return "–";
  if (ratio >= 100.0) return format("%.0f×", ratio);
  if (ratio >= 10.0) return format("%.1f×", ratio);
  return format("%.2f×", ratio);
}

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

Timing summarise(std::vector<double> times) {
  Timing timing;
  if (times.empty()) return timing;
  std::sort(times.begin(), times.end());
  const size_t n = times.size();
  timing.median = n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
  timing.minimum = times.front();
  timing.maximum = times.back();
  timing.repetitions = static_cast<int>(n);
  return timing;
}

// Warm-up, then repetitions until `repetitions` or `budget_seconds` (see the header comment).
// `run` returns the seconds it measured itself (so that it can leave set-up out), or a negative
// value to be timed from outside.
Timing measure(const std::function<double()>& run, int repetitions, double budget_seconds) {
  auto timed = [&] {
    const auto start = Clock::now();
    const double inner = run();
    return inner >= 0.0 ? inner : seconds_since(start);
  };
  const auto budget_start = Clock::now();
  const double warm_up = timed();
  if (warm_up > 0.5 * budget_seconds || repetitions <= 1) return summarise({warm_up});
  std::vector<double> times;
  while (static_cast<int>(times.size()) < repetitions &&
         (times.empty() || seconds_since(budget_start) < budget_seconds))
    times.push_back(timed());
  return summarise(times);
}

// ---- processes -----------------------------------------------------------------------------

struct ProcessRun {
  bool ok = false;
  double seconds = 0.0;
  std::string output;  // standard output, when captured
};

// Runs argv[0] (searched in PATH) through emnet's process helper, standard input and error
// /dev/null, standard output /dev/null or, with `capture`, kept (at most 1 MiB). `seconds` is
// the program's run as its supervisor sees it, from just before it is started until it is
// reaped (emnet/core/process.hpp): the program's own start, work and exit, without the
// supervisor's start or the clean-up after the program.
ProcessRun run_process(const std::vector<std::string>& arguments, bool capture = false,
                       double timeout_seconds = 300.0) {
  emnet::ProcessOptions options;
  options.arguments = arguments;
  if (capture) options.standard_output = emnet::ProcessOutput::captured(std::size_t{1} << 20);
  options.timeout_seconds = timeout_seconds;
  const emnet::ProcessResult end = emnet::run_process(options);
  ProcessRun run;
  run.seconds = end.seconds;
  // emnet's exit status 5: computed, but outside the model's validity (the fish fin's tip at
  // resonance swings past 10 % of its length); the result is there and is timed like any other.
  const bool emnet_run =
      arguments[0].size() >= 5 && arguments[0].compare(arguments[0].size() - 5, 5, "emnet") == 0;
  run.ok = end.exited_with(0) || (emnet_run && end.exited_with(emnet::kExitOutsideValidity));
  run.output = end.standard_output;
  return run;
}

Timing measure_process(const std::vector<std::string>& arguments, int repetitions,
                       double budget_seconds, bool& ok) {
  ok = true;
  return measure(
      [&] {
        const ProcessRun run = run_process(arguments);
        if (!run.ok) ok = false;
        return run.seconds;
      },
      repetitions, budget_seconds);
}

// ---- settings ------------------------------------------------------------------------------

struct Settings {
  std::string root = ".";             // repository root (netlists/)
  std::string out = "build/bench";    // report, data, decks
  std::string emnet = "build/emnet";  // the program, for whole-process times
  std::string self;                   // this program, for scale points
  bool quick = false;                 // smoke test: tiny sizes, few repetitions
  std::string only;                   // --only 5a|5b: that section alone (report-5a.md, …)
  std::string fishfin() const { return root + "/netlists/fishfin.toml"; }
  std::string cantilever() const { return root + "/netlists/cantilever.toml"; }
};

const std::vector<std::string> ideal_drive = {"drive.electrical_dynamics=false"};

emnet::Model build(const std::string& path, std::vector<std::string> overrides) {
  return emnet::prepare_model(emnet::read_scene(path, overrides));
}

// The deflection outputs compared everywhere: the scene's probes in metres (and dx_k) that
// are not identically zero (P1 sits at the clamp).
std::vector<emnet::Probe> deflection_probes(const emnet::Model& model) {
  std::vector<emnet::Probe> probes;
  for (const auto& probe : emnet::spice_output_probes(model))
    if (probe.unit == "m" && !probe.terms.empty()) probes.push_back(probe);
  return probes;
}

// ---- peaks ---------------------------------------------------------------------------------

// The extreme of samples (t_k, y_k), k in [begin, end), refined by the parabola through the
// extreme sample and its neighbours, which may lie outside the window (non-uniform spacing
// allowed). `sign` +1: maximum.
double refined_extreme(const std::vector<double>& t, const std::vector<double>& y, size_t begin,
                       size_t end, double sign) {
  size_t best = begin;
  for (size_t k = begin; k < end; ++k)
    if (sign * y[k] > sign * y[best]) best = k;
  // The neighbours may lie outside [begin, end) (a peak at a period's boundary).
  if (best == 0 || best + 1 >= y.size()) return y[best];
  const double t0 = t[best - 1], t1 = t[best], t2 = t[best + 1];
  const double y0 = y[best - 1], y1 = y[best], y2 = y[best + 1];
  if (!(t1 > t0 && t2 > t1)) return y1;
  const double d01 = (y1 - y0) / (t1 - t0), d12 = (y2 - y1) / (t2 - t1);
  const double a = (d12 - d01) / (t2 - t0);
  if (!(sign * a < 0.0)) return y1;
  const double b = d01 - a * (t0 + t1);
  const double tv = -b / (2.0 * a);
  if (tv < t0 || tv > t2) return y1;
  return y0 + d01 * (tv - t0) + a * (tv - t0) * (tv - t1);
}

struct Peaks {
  std::vector<double> minimum, maximum;  // per probe
};

// Error of peaks against reference peaks, over frequencies: |difference| relative to that
// probe's largest |peak| over the sweep; the largest over all.
double sweep_error(const std::vector<Peaks>& peaks, const std::vector<Peaks>& reference) {
  if (reference.empty()) return NAN;
  const size_t probes = reference[0].maximum.size();
  double worst = 0.0;
  for (size_t p = 0; p < probes; ++p) {
    double scale = 0.0;
    for (const auto& r : reference)
      scale = std::max({scale, std::abs(r.minimum[p]), std::abs(r.maximum[p])});
    if (!(scale > 0.0)) continue;
    for (size_t k = 0; k < reference.size() && k < peaks.size(); ++k)
      worst = std::max({worst, std::abs(peaks[k].minimum[p] - reference[k].minimum[p]) / scale,
                        std::abs(peaks[k].maximum[p] - reference[k].maximum[p]) / scale});
  }
  return worst;
}

// ---- report pieces ---------------------------------------------------------------------------

struct ParetoPoint {
  std::string series;  // legend: method and tool
  std::string label;   // point label (rtol, threshold)
  double seconds = 0.0;
  double error = 0.0;
};

// One gnuplot script and one data block per series (error floored at 1e-16 for the log axis).
void write_pareto_plot(const Settings& settings, const std::string& name, const std::string& title,
                       const std::vector<ParetoPoint>& points) {
  std::vector<std::string> series;
  for (const auto& point : points)
    if (std::find(series.begin(), series.end(), point.series) == series.end())
      series.push_back(point.series);
  const std::string data_path = settings.out + "/pareto-" + name + ".dat";
  std::ofstream data(data_path);
  data << std::setprecision(6);
  for (const auto& s : series) {
    data << "# " << s << "\n";
    for (const auto& point : points)
      if (point.series == s)
        data << point.seconds << " " << std::max(point.error, 1e-16) << " \"" << point.label
             << "\"\n";
    data << "\n\n";
  }
  std::ofstream script(settings.out + "/pareto-" + name + ".gp");
  script << "set terminal pngcairo size 900,620 noenhanced font ',10'\n"
         << "set output '" << settings.out << "/pareto-" << name << ".png'\n"
         << "set title '" << title << "'\n"
         << "set logscale xy\nset format x '%.0e'\nset format y '%.0e'\n"
         << "set xlabel 'wall time [s] (median)'\nset ylabel 'error relative to peak (0 plotted at "
            "1e-16)'\n"
         << "set grid\nset key outside right top\n"
         << "plot ";
  for (size_t k = 0; k < series.size(); ++k) {
    script << (k ? ", \\\n     " : "") << "'" << data_path << "' index " << k
           << " using 1:2 with linespoints pt " << (k % 9) + 4 << " ps 1.2 title '" << series[k]
           << "', '' index " << k
           << " using 1:2:3 with labels offset 0.6,0.6 left font ',7' notitle";
  }
  script << "\n";
}

// ---- 1. discretisation -------------------------------------------------------------------------

struct DiscretisationRow {
  int segments = 0;
  int unknowns = 0;
  double frequency_error[3] = {NAN, NAN, NAN};
  double static_error = NAN;
  Timing modes, ac;
  std::string modal_method;
};

std::string discretisation_section(const Settings& settings, std::vector<ParetoPoint>& pareto) {
  std::ostringstream md;
  const double length = 0.5, stiffness = 2.0, mass = 0.3, force = 1.0;
  const double beta_l[3] = {1.875104, 4.694091, 7.854757};
  double continuum[3];
  for (int k = 0; k < 3; ++k)
    continuum[k] =
        beta_l[k] * beta_l[k] / (2.0 * M_PI * length * length) * std::sqrt(stiffness / mass);
  const double tip_reference = force * length * length * length / (3.0 * stiffness);
  std::vector<int> sizes =
      settings.quick ? std::vector<int>{1, 2, 4, 8, 16}
                     : std::vector<int>{1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1000, 2000};
  const auto grid = emnet::frequency_grid(0.5, 200.0, 1000, true);
  std::vector<DiscretisationRow> rows;
  for (int n : sizes) {
    DiscretisationRow row;
    row.segments = n;
    const emnet::Model model = build(settings.cantilever(), {"beam.segments=" + std::to_string(n)});
    const emnet::System system = model.network.assemble();
    row.unknowns = system.size();
    const emnet::StaticResult rest = emnet::solve_static(system);
    const emnet::Probe tip = model.parse_probe("tip");
    row.static_error =
        std::abs(std::abs(emnet::static_probe_value(system, rest, tip)) - tip_reference) /
        tip_reference;
    emnet::ModalOptions modal;
    modal.count = 3;
    modal.keep_vectors = false;
    emnet::ModalResult modes;
    row.modes = measure(
        [&] {
          modes = emnet::run_modes(system, rest.operating_point, modal);
          return modes.seconds;
        },
        5, 2.0);
    row.modal_method = modes.method;
    for (int k = 0; k < 3 && k < static_cast<int>(modes.modes.size()); ++k)
      row.frequency_error[k] =
          std::abs(modes.modes[k].natural_frequency_hz - continuum[k]) / continuum[k];
    row.ac = measure(
        [&] { return emnet::run_ac(system, rest.operating_point, grid, {tip}).seconds; }, 5, 2.0);
    rows.push_back(row);
    const double worst =
        std::max({row.frequency_error[0],
                  std::isfinite(row.frequency_error[2]) ? row.frequency_error[2] : 0.0});
    pareto.push_back({"f1 error vs modes time", "N=" + std::to_string(n), row.modes.median,
                      row.frequency_error[0]});
    if (std::isfinite(row.frequency_error[2]))
      pareto.push_back({"f3 error vs modes time", "N=" + std::to_string(n), row.modes.median,
                        row.frequency_error[2]});
    pareto.push_back({"f1..f3 worst error vs 1000-point ac time", "N=" + std::to_string(n),
                      row.ac.median, worst});
  }
  md << "### 1. Discretisation error against cost (cantilever)\n\n"
     << "`netlists/cantilever.toml` (L = 0.5 m, EI = 2 N·m², ρA = 0.3 kg/m, 1 N at the tip) with "
        "N segments. f1..f3: `run_modes` (3 lowest; dense up to 600 unknowns, Arnoldi above) "
        "against the continuum (βL = 1.875104, 4.694091, 7.854757: "
     << format("%.4f", continuum[0]) << ", " << format("%.3f", continuum[1]) << ", "
     << format("%.2f", continuum[2])
     << " Hz). Static tip deflection against F·L³/(3EI) = 20.833 mm. ac: 1000 log points "
        "0.5–200 Hz, one probe. Times: median (min–max, runs).\n\n"
     << "| N | unknowns | f1 error | f2 error | f3 error | static tip error | modes (method) | "
        "ac 1000 points |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& row : rows)
    md << "| " << row.segments << " | " << row.unknowns << " | "
       << error_text(row.frequency_error[0]) << " | " << error_text(row.frequency_error[1]) << " | "
       << error_text(row.frequency_error[2]) << " | " << error_text(row.static_error) << " | "
       << row.modes.text() << " (" << row.modal_method << ") | " << row.ac.text() << " |\n";
  // Observed order from the last two rows with finite errors.
  md << "\nf1..f3 converge as O(N⁻²) (lumped mass); the static tip deflection is exact for "
        "every N (the segments have the Hermite element's flexibility): its error is "
        "rounding. N = 1 has one mass and so one mode; N = 2 two.\n\n";

  // Fish fin: N = 7 against its converged answer.
  const std::vector<int> fin_sizes =
      settings.quick ? std::vector<int>{7, 14, 28} : std::vector<int>{7, 1000, 2000};
  std::vector<std::vector<double>> fin_frequencies;
  std::vector<double> fin_static;
  std::vector<double> fin_seconds;
  for (int n : fin_sizes) {
    const emnet::Model model = build(settings.fishfin(), {"beam.segments=" + std::to_string(n)});
    const emnet::System system = model.network.assemble();
    const emnet::StaticResult rest = emnet::solve_static(system);
    emnet::ModalOptions modal;
    modal.count = 3;
    modal.keep_vectors = false;
    const emnet::ModalResult modes = emnet::run_modes(system, rest.operating_point, modal);
    std::vector<double> f;
    for (int k = 0; k < 3 && k < static_cast<int>(modes.modes.size()); ++k)
      f.push_back(modes.modes[k].frequency_hz);
    fin_frequencies.push_back(f);
    fin_static.push_back(emnet::static_probe_value(system, rest, model.parse_probe("tip")));
    fin_seconds.push_back(modes.seconds);
  }
  const int large = fin_sizes[1], larger = fin_sizes[2];
  md << "**Fish fin, N = 7 against the converged beam.** `netlists/fishfin.toml` (full model), "
        "f1..f3 (damped) at N = "
     << large << " and " << larger
     << ", Richardson for O(N⁻²): f∞ = (4·f(2N) − f(N))/3; the static tip deflection under "
        "DEA A at 4 kV (exact at every N: its change is rounding).\n\n"
     << "| quantity | N = 7 | N = " << larger
     << " | converged (Richardson) | N = 7 error | N = " << larger
     << " error |\n|---|---|---|---|---|---|\n";
  for (int k = 0; k < 3; ++k) {
    if (fin_frequencies[0].size() <= static_cast<size_t>(k) ||
        fin_frequencies[1].size() <= static_cast<size_t>(k) ||
        fin_frequencies[2].size() <= static_cast<size_t>(k))
      continue;
    const double converged = (4.0 * fin_frequencies[2][k] - fin_frequencies[1][k]) / 3.0;
    md << "| f" << k + 1 << " [Hz] | " << format("%.5f", fin_frequencies[0][k]) << " | "
       << format("%.7f", fin_frequencies[2][k]) << " | " << format("%.7f", converged) << " | "
       << error_text(std::abs(fin_frequencies[0][k] - converged) / converged) << " | "
       << error_text(std::abs(fin_frequencies[2][k] - converged) / converged) << " |\n";
  }
  md << "| static tip [mm] | " << format("%.6f", fin_static[0] * 1e3) << " | "
     << format("%.6f", fin_static[2] * 1e3) << " | – | "
     << error_text(std::abs(fin_static[0] - fin_static[2]) / std::abs(fin_static[2]))
     << " (vs N = " << larger << ") | – |\n\n"
     << "Modes took " << time_text(fin_seconds[0]) << " at N = 7 and " << time_text(fin_seconds[2])
     << " at N = " << larger << ".\n\n";
  return md.str();
}

// ---- 2 and 3: the fish fin's transient -----------------------------------------------------

struct TranContext {
  emnet::Model model;
  emnet::System system;
  std::vector<emnet::Probe> probes;
  double period = 0.2, end_time = 10.0;
  std::vector<double> outputs;  // emnet's 100 per period
};

// Largest |a − b| over outputs and kept times, relative to each output's peak |b|.
double run_error(const std::vector<std::vector<double>>& values,
                 const std::vector<std::vector<double>>& reference,
                 const std::vector<bool>& keep = {}) {
  double worst = 0.0;
  for (size_t p = 0; p < reference.size(); ++p) {
    double peak = 0.0;
    for (size_t k = 0; k < reference[p].size(); ++k)
      if (keep.empty() || keep[k]) peak = std::max(peak, std::abs(reference[p][k]));
    if (!(peak > 0.0)) continue;
    for (size_t k = 0; k < reference[p].size() && k < values[p].size(); ++k)
      if (keep.empty() || keep[k])
        worst = std::max(worst, std::abs(values[p][k] - reference[p][k]) / peak);
  }
  return worst;
}

struct MethodRow {
  std::string tool, method, setting;
  double error = NAN;
  Timing in_process, whole_process;
  std::string note;
};

std::string method_table(const std::vector<MethodRow>& rows) {
  std::ostringstream md;
  md << "| tool | method | setting | error / peak | in-process | whole process | note |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const auto& row : rows)
    md << "| " << row.tool << " | " << row.method << " | " << row.setting << " | "
       << error_text(row.error) << " | " << row.in_process.text() << " | "
       << row.whole_process.text() << " | " << row.note << " |\n";
  return md.str();
}

// For every ngspice row: the fastest emnet row with error ≤ its error; the ratio
// ngspice time / emnet time. The headline is the smallest such ratio (the least favourable).
struct Headline {
  double in_process = NAN, whole_process = NAN;
  std::string in_process_pair, whole_process_pair;
};

Headline headline(const std::vector<MethodRow>& rows) {
  Headline h;
  h.in_process = h.whole_process = std::numeric_limits<double>::infinity();
  for (const auto& spice : rows) {
    if (spice.tool != "ngspice" || !std::isfinite(spice.error)) continue;
    for (int whole = 0; whole < 2; ++whole) {
      const Timing& spice_time = whole ? spice.whole_process : spice.in_process;
      if (spice_time.repetitions == 0) continue;
      const MethodRow* best = nullptr;
      for (const auto& own : rows) {
        if (own.tool != "emnet" || !(own.error <= spice.error)) continue;
        const Timing& own_time = whole ? own.whole_process : own.in_process;
        if (own_time.repetitions == 0) continue;
        if (!best || own_time.median < (whole ? best->whole_process : best->in_process).median)
          best = &own;
      }
      if (!best) continue;
      const double ratio =
          spice_time.median / (whole ? best->whole_process : best->in_process).median;
      double& slot = whole ? h.whole_process : h.in_process;
      if (ratio < slot) {
        slot = ratio;
        (whole ? h.whole_process_pair : h.in_process_pair) =
            "ngspice " + spice.setting + " (" + error_text(spice.error) + ") vs emnet " +
            best->method + " " + best->setting + " (" + error_text(best->error) + ")";
      }
    }
  }
  if (!std::isfinite(h.in_process)) h.in_process = NAN;
  if (!std::isfinite(h.whole_process)) h.whole_process = NAN;
  return h;
}

std::vector<std::string> emnet_cli(const Settings& settings, const std::string& command,
                                   std::vector<std::string> extra) {
  std::vector<std::string> arguments = {settings.emnet, command, settings.fishfin(), "--set",
                                        "drive.electrical_dynamics=false"};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return arguments;
}

std::string write_deck(const Settings& settings, const std::string& name, const std::string& text) {
  mkdir((settings.out + "/decks").c_str(), 0755);
  const std::string path = settings.out + "/decks/" + name + ".cir";
  std::ofstream(path) << text;
  return path;
}

// ngspice's whole process on a deck: the program with a rawfile (without one, `ngspice -b`
// runs no analysis that writes nothing).
Timing ngspice_process(const Settings& settings, const std::string& deck_path, int repetitions,
                       double budget, bool& ok) {
  const std::string raw = settings.out + "/decks/run.raw";
  return measure_process({"ngspice", "-b", "-r", raw, deck_path}, repetitions, budget, ok);
}

emnet::NgspiceOptions in_process_ngspice() {
  emnet::NgspiceOptions options;
  options.backend = emnet::NgspiceBackend::library;
  options.library_in_this_process = true;
  options.timeout_seconds = 300.0;
  return options;
}

std::string remove_options_line(const std::string& deck) {
  std::istringstream in(deck);
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(".options", 0) != 0) out << line << "\n";
  return out.str();
}

struct Section {
  std::string markdown;
  Headline headline;
};

// AC: emnet's run_ac and ngspice's .ac over the scene's 1000 points, against a dense solve.
Section ac_section(const Settings& settings, std::vector<ParetoPoint>& pareto) {
  const emnet::Model model = build(settings.fishfin(), ideal_drive);
  const emnet::System system = model.network.assemble();
  const emnet::StaticResult rest = emnet::solve_static(system);
  const auto probes = deflection_probes(model);
  const auto& spec = model.scene.ac;
  const auto grid = emnet::frequency_grid(spec.from, spec.to, spec.points, spec.log);
  const Eigen::MatrixXd g = Eigen::MatrixXd(emnet::linearised_g(system, rest.operating_point));
  const Eigen::MatrixXd c = Eigen::MatrixXd(system.C);
  const Eigen::VectorXcd b = system.b_ac();
  // Dense reference: [probe][frequency]; frequencies ≤ 0 left out (NaN).
  auto reference_at = [&](const std::vector<double>& frequencies) {
    std::vector<std::vector<std::complex<double>>> values(
        probes.size(), std::vector<std::complex<double>>(frequencies.size(), NAN));
    for (size_t k = 0; k < frequencies.size(); ++k) {
      if (!(frequencies[k] > 0.0)) continue;
      const double omega = 2.0 * M_PI * frequencies[k];
      const Eigen::MatrixXcd a = g.cast<std::complex<double>>() +
                                 std::complex<double>(0.0, omega) * c.cast<std::complex<double>>();
      const Eigen::VectorXcd y = a.fullPivLu().solve(b);
      for (size_t p = 0; p < probes.size(); ++p)
        values[p][k] = emnet::probe_phasor(probes[p], y, omega);
    }
    return values;
  };
  auto ac_error = [&](const std::vector<std::vector<std::complex<double>>>& values,
                      const std::vector<std::vector<std::complex<double>>>& reference) {
    double worst = 0.0;
    for (size_t p = 0; p < reference.size(); ++p) {
      double peak = 0.0;
      for (const auto& v : reference[p])
        if (std::isfinite(v.real())) peak = std::max(peak, std::abs(v));
      if (!(peak > 0.0)) continue;
      for (size_t k = 0; k < reference[p].size(); ++k)
        if (std::isfinite(reference[p][k].real()))
          worst = std::max(worst, std::abs(values[p][k] - reference[p][k]) / peak);
    }
    return worst;
  };
  std::vector<MethodRow> rows;
  {
    MethodRow row{"emnet", "run_ac (KLU)", std::to_string(grid.size()) + " points"};
    const emnet::AcResult result = emnet::run_ac(system, rest.operating_point, grid, probes);
    row.error = ac_error(result.values, reference_at(grid));
    // In-process: from the scene file to the result, as `emnet ac` does it.
    row.in_process = measure(
        [&] {
          const auto start = Clock::now();
          const emnet::Model m = build(settings.fishfin(), ideal_drive);
          const emnet::System s = m.network.assemble();
          const emnet::StaticResult r = emnet::solve_static(s);
          const auto own = deflection_probes(m);
          emnet::run_ac(s, r.operating_point, grid, own);
          return seconds_since(start);
        },
        20, 2.0);
    const Timing analysis_only = measure(
        [&] { return emnet::run_ac(system, rest.operating_point, grid, probes).seconds; }, 20, 1.0);
    bool ok = true;
    row.whole_process = measure_process(emnet_cli(settings, "ac", {}), 10, 3.0, ok);
    // The floor of any whole-process time: starting the program and printing its help.
    bool help_ok = true;
    const Timing start_up = measure_process({settings.emnet, "--help"}, 10, 2.0, help_ok);
    row.note = "in-process from the scene file; run_ac alone " + time_text(analysis_only.median) +
               "; `emnet --help` as a whole process " + time_text(start_up.median) +
               (ok ? "" : "; the program failed");
    rows.push_back(row);
  }
  {
    emnet::SpiceDeckOptions options;
    options.analysis = emnet::SpiceAnalysis::ac;
    options.outputs = probes;
    const emnet::SpiceDeck deck = emnet::write_spice_deck(model, options);
    const std::string path = write_deck(settings, "fishfin-ac", deck.text);
    MethodRow row{"ngspice", ".ac", "default options"};
    emnet::NgspiceResult result;
    row.in_process = measure(
        [&] {
          const auto start = Clock::now();
          result = emnet::run_ngspice(deck.text, in_process_ngspice());
          return seconds_since(start);
        },
        10, 3.0);
    if (result.status.ok && result.scale()) {
      std::vector<double> frequencies;
      for (const auto& v : result.scale()->complex_values) frequencies.push_back(v.real());
      if (frequencies.empty()) frequencies = result.scale()->real_values;
      std::vector<std::vector<std::complex<double>>> values(probes.size());
      for (size_t p = 0; p < probes.size(); ++p) {
        const emnet::NgspiceVector* vector = result.find(deck.outputs[p].vector);
        if (vector) values[p] = vector->complex_values;
        values[p].resize(frequencies.size(), NAN);
      }
      row.error = ac_error(values, reference_at(frequencies));
    } else {
      row.note = "ngspice failed: " + result.status.message;
    }
    bool ok = true;
    row.whole_process = ngspice_process(settings, path, 10, 3.0, ok);
    if (!ok) row.note += " whole process failed";
    rows.push_back(row);
  }
  for (const auto& row : rows) {
    pareto.push_back(
        {row.tool + " " + row.method + " in-process", "", row.in_process.median, row.error});
    pareto.push_back(
        {row.tool + " " + row.method + " whole process", "", row.whole_process.median, row.error});
  }
  Section section;
  section.headline = headline(rows);
  std::ostringstream md;
  md << "### AC: 1000 points, fish fin (ideal drive)\n\n"
     << "The scene's sweep (" << spec.points << " points, " << spec.from << "–" << spec.to
     << " Hz, linear), every deflection output. Error: the largest |Y − Y_ref| over frequencies "
        "f > 0, relative to that output's peak |Y_ref|; Y_ref by a dense full-pivoting complex "
        "LU of (G + J_g + jωC)·Y = B_ac at the tool's own frequencies. ngspice's deck writes "
        "12 significant digits and integrates deflections with a 1 F ‖ 1 GΩ leak (1.6e-9 "
        "relative at 0.1 Hz, more towards 0 Hz).\n\n"
     << method_table(rows);
  section.markdown = md.str();
  return section;
}

TranContext tran_context(const Settings& settings) {
  TranContext context{build(settings.fishfin(), ideal_drive), {}, {}};
  context.system = context.model.network.assemble();
  context.probes = deflection_probes(context.model);
  context.period = 1.0 / context.model.scene.drive.frequency;
  const int periods = settings.quick ? 5 : 50;
  context.end_time = periods * context.period;
  for (int k = 0; k <= periods * 100; ++k) context.outputs.push_back(k * context.period / 100.0);
  return context;
}

Section tran_section(const Settings& settings, std::vector<ParetoPoint>& pareto) {
  TranContext context = tran_context(settings);
  const int periods = static_cast<int>(std::lround(context.end_time / context.period));
  emnet::TransientOptions options;
  options.end_time = context.end_time;
  options.output_times = context.outputs;
  const emnet::TransientResult exact =
      emnet::run_transient_exact(context.system, context.probes, options);
  std::vector<MethodRow> rows;
  std::string exact_breakdown;
  const std::string periods_text = std::to_string(periods);
  {
    MethodRow row{"emnet", "exact", "–"};
    row.error = 0.0;
    row.in_process = measure(
        [&] {
          const auto start = Clock::now();
          const emnet::Model m = build(settings.fishfin(), ideal_drive);
          emnet::run_transient_exact(m.network.assemble(), deflection_probes(m), options);
          return seconds_since(start);
        },
        10, 3.0);
    bool ok = true;
    row.whole_process = measure_process(
        emnet_cli(settings, "tran", {"--method", "exact", "--periods", periods_text}), 10, 3.0, ok);
    // Where its time goes: the same run with outputs only at the period boundaries.
    emnet::TransientOptions sparse = options;
    sparse.output_times.clear();
    for (int k = 0; k <= periods; ++k) sparse.output_times.push_back(k * context.period);
    const Timing few_outputs = measure(
        [&] { return emnet::run_transient_exact(context.system, context.probes, sparse).seconds; },
        10, 2.0);
    const Timing all_outputs = measure(
        [&] { return emnet::run_transient_exact(context.system, context.probes, options).seconds; },
        10, 2.0);
    exact_breakdown =
        "run_transient_exact alone: " + time_text(all_outputs.median) + " with " +
        std::to_string(options.output_times.size()) + " outputs, " + time_text(few_outputs.median) +
        " with " + std::to_string(sparse.output_times.size()) +
        " (one per period): the outputs cost " +
        time_text((all_outputs.median - few_outputs.median) /
                  (options.output_times.size() - sparse.output_times.size())) +
        " each, " +
        format("%.0f", 100.0 * (all_outputs.median - few_outputs.median) / all_outputs.median) +
        " % of the run";
    row.note = "the reference (rounding only)";
    rows.push_back(row);
  }
  const std::vector<double> tolerances =
      settings.quick ? std::vector<double>{1e-3, 1e-6}
                     : std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  for (double rtol : tolerances) {
    MethodRow row{"emnet", "IDA", "rtol " + format("%.0e", rtol)};
    emnet::TransientOptions ida = options;
    ida.relative_tolerance = rtol;
    emnet::TransientResult result;
    row.in_process = measure(
        [&] {
          const auto start = Clock::now();
          const emnet::Model m = build(settings.fishfin(), ideal_drive);
          result = emnet::run_transient_ida(m.network.assemble(), deflection_probes(m), ida);
          return seconds_since(start);
        },
        3, 2.0);
    row.error = result.status.ok ? run_error(result.values, exact.values) : NAN;
    row.note = std::to_string(result.statistics.steps) + " steps";
    bool ok = true;
    row.whole_process = measure_process(
        emnet_cli(settings, "tran",
                  {"--method", "ida", "--rtol", format("%g", rtol), "--periods", periods_text}),
        3, 2.0, ok);
    if (!ok) row.note += "; the program failed";
    rows.push_back(row);
  }
  // ngspice: default options (the deck's .options line removed), then tightened.
  struct SpiceSetting {
    std::string name;
    double reltol;  // 0: ngspice's defaults
    double max_step_per_period;
  };
  std::vector<SpiceSetting> spice_settings =
      settings.quick
          ? std::vector<SpiceSetting>{{"default", 0.0, 0.0}}
          : std::vector<SpiceSetting>{
                {"default", 0.0, 0.0},      {"reltol 1e-4", 1e-4, 0.0},
                {"reltol 1e-5", 1e-5, 0.0}, {"reltol 1e-6", 1e-6, 0.0},
                {"reltol 1e-7", 1e-7, 0.0}, {"reltol 1e-6, max step T/1000", 1e-6, 1000.0}};
  double edge_width = 0.0;
  for (const auto& setting : spice_settings) {
    emnet::SpiceDeckOptions deck_options;
    deck_options.analysis = emnet::SpiceAnalysis::tran;
    deck_options.outputs = context.probes;
    deck_options.end_time = context.end_time;
    deck_options.output_step = context.period / 100.0;
    deck_options.relative_tolerance = setting.reltol > 0.0 ? setting.reltol : 1e-3;
    if (setting.max_step_per_period > 0.0)
      deck_options.max_step = context.period / setting.max_step_per_period;
    const emnet::SpiceDeck deck = emnet::write_spice_deck(context.model, deck_options);
    edge_width = deck_options.edge_fraction * 0.5 * context.period;
    const std::string text = setting.reltol > 0.0 ? deck.text : remove_options_line(deck.text);
    const std::string path =
        write_deck(settings, "fishfin-tran-" + std::to_string(&setting - &spice_settings[0]), text);
    MethodRow row{"ngspice", ".tran", setting.name};
    emnet::NgspiceResult result;
    row.in_process = measure(
        [&] {
          const auto start = Clock::now();
          result = emnet::run_ngspice(text, in_process_ngspice());
          return seconds_since(start);
        },
        3, 3.0);
    if (result.status.ok && result.scale()) {
      const std::vector<double> times = result.scale()->real_values;
      // Keep points outside ±10ε of every edge (edges at multiples of half a period).
      std::vector<bool> keep(times.size());
      std::vector<double> kept;
      for (size_t k = 0; k < times.size(); ++k) {
        const double half = 0.5 * context.period;
        const double distance = std::abs(times[k] - half * std::round(times[k] / half));
        keep[k] = distance > 10.0 * edge_width && times[k] <= context.end_time;
        if (keep[k]) kept.push_back(times[k]);
      }
      emnet::TransientOptions at = options;
      at.output_times = kept;
      const emnet::TransientResult reference =
          emnet::run_transient_exact(context.system, context.probes, at);
      std::vector<std::vector<double>> values(context.probes.size());
      for (size_t p = 0; p < context.probes.size(); ++p) {
        const emnet::NgspiceVector* vector = result.find(deck.outputs[p].vector);
        if (!vector) continue;
        for (size_t k = 0; k < times.size(); ++k)
          if (keep[k]) values[p].push_back(vector->real_values[k]);
      }
      row.error = run_error(values, reference.values);
      row.note = std::to_string(times.size()) + " time points";
    } else {
      row.note = "ngspice failed: " + result.status.message;
    }
    bool ok = true;
    row.whole_process = ngspice_process(settings, path, 3, 3.0, ok);
    if (!ok) row.note += "; whole process failed";
    rows.push_back(row);
  }
  for (const auto& row : rows) {
    const std::string series = row.tool + " " + row.method + (row.tool == "ngspice" ? "" : "");
    pareto.push_back({series + " in-process", row.setting == "–" ? "" : row.setting,
                      row.in_process.median, row.error});
    pareto.push_back({series + " whole process", "", row.whole_process.median, row.error});
  }
  Section section;
  section.headline = headline(rows);
  std::ostringstream md;
  md << "### Transient: " << periods << " periods at 5 Hz, fish fin (ideal drive), from rest\n\n"
     << "emnet: 100 outputs per period; in-process times run from the scene file to the result; "
        "whole process is `emnet tran … --method exact|ida`. Error: the largest |difference| "
        "over the run and over the deflection outputs (P2..P4, tip, dx2..dx4), relative to each "
        "output's peak, against the exact method. ngspice: the exported deck, output step T/100, "
        "max step = output step unless stated; \"default\" removes the deck's `.options` line "
        "(reltol 1e-3, ngspice's abstol and vntol); the tightened decks set vntol 1e-12, "
        "abstol 1e-15. ngspice is compared at its own time points, against the exact method "
        "evaluated there, excluding ±10ε = ±"
     << time_text(10.0 * edge_width)
     << " around every switching edge (the deck switches by linear edges of width ε centred "
        "on the instants).\n\n"
     << method_table(rows) << "\nWhere the exact method's time goes: " << exact_breakdown << ".\n";
  section.markdown = md.str();
  return section;
}

// ---- the switching sweep ---------------------------------------------------------------------

struct SweepContext {
  emnet::Scene scene;
  std::vector<double> frequencies;
  std::vector<emnet::Probe> probes;
};

SweepContext sweep_context(const Settings& settings) {
  SweepContext context;
  context.scene = emnet::read_scene(settings.fishfin(), ideal_drive);
  const emnet::Model model = emnet::prepare_model(context.scene);
  context.probes = deflection_probes(model);
  const int count = settings.quick ? 7 : 61;
  const double step = settings.quick ? 1.0 : 0.1;
  for (int k = 0; k < count; ++k) context.frequencies.push_back(1.0 + step * k);
  return context;
}

// The direct sweep as `emnet sweep-switching` runs it: one PeriodicSolver, one model assembled
// once, the drive's excitation made again per frequency. Fills the time spent in each part
// (`build`: the excitation per frequency; `assemble`: the model's build and assembly, and each
// frequency's excitation set into the system).
struct DirectSweepParts {
  double decomposition = 0, build = 0, assemble = 0, solve = 0, total = 0;
};

std::vector<Peaks> direct_sweep(const SweepContext& context, int samples,
                                DirectSweepParts* parts = nullptr) {
  const auto start = Clock::now();
  std::vector<Peaks> peaks;
  std::unique_ptr<emnet::PeriodicSolver> solver;
  DirectSweepParts local;
  auto t0 = Clock::now();
  const emnet::Model model = emnet::prepare_model(context.scene);
  emnet::System system = model.network.assemble();
  local.assemble += seconds_since(t0);
  for (double f : context.frequencies) {
    t0 = Clock::now();
    emnet::Excitation excitation = emnet::drive_excitation(model, system.excitation, f);
    local.build += seconds_since(t0);
    t0 = Clock::now();
    system.set_excitation(std::move(excitation));
    local.assemble += seconds_since(t0);
    if (!solver) {
      t0 = Clock::now();
      solver = std::make_unique<emnet::PeriodicSolver>(system);
      local.decomposition += seconds_since(t0);
    }
    t0 = Clock::now();
    const emnet::PeriodicResult result = solver->solve(system, context.probes, 1.0 / f, samples);
    local.solve += seconds_since(t0);
    peaks.push_back({result.minimum, result.maximum});
  }
  local.total = seconds_since(start);
  if (parts) *parts = local;
  return peaks;
}

// Run until settled with the exact transient (see the header comment). Returns the peaks per
// frequency and, in `settled_periods`, the period count at which each settled.
std::vector<Peaks> settled_sweep(const SweepContext& context, double threshold,
                                 int samples_per_period, std::vector<int>* settled_periods) {
  std::vector<Peaks> all;
  for (double f : context.frequencies) {
    emnet::Scene at = context.scene;
    at.drive.frequency = f;
    const emnet::Model model = emnet::prepare_model(at);
    const emnet::System system = model.network.assemble();
    const double period = 1.0 / f;
    Peaks found;
    int settled_at = -1;
    for (int periods = 8; periods <= 8192 && settled_at < 0; periods *= 2) {
      emnet::TransientOptions options;
      options.end_time = periods * period;
      for (int k = 0; k <= periods * samples_per_period; ++k)
        options.output_times.push_back(k * period / samples_per_period);
      const emnet::TransientResult run =
          emnet::run_transient_exact(system, context.probes, options);
      if (!run.status.ok) break;
      Peaks previous;
      for (int q = 0; q < periods; ++q) {
        const size_t begin = static_cast<size_t>(q) * samples_per_period;
        const size_t end = begin + samples_per_period + 1;
        Peaks current;
        double scale = 0.0, change = 0.0;
        for (size_t p = 0; p < context.probes.size(); ++p) {
          current.minimum.push_back(refined_extreme(run.times, run.values[p], begin, end, -1.0));
          current.maximum.push_back(refined_extreme(run.times, run.values[p], begin, end, 1.0));
          scale = std::max({scale, std::abs(current.minimum[p]), std::abs(current.maximum[p])});
          if (q > 0)
            change = std::max({change, std::abs(current.minimum[p] - previous.minimum[p]),
                               std::abs(current.maximum[p] - previous.maximum[p])});
        }
        if (q > 0 && change <= threshold * scale) {
          found = current;
          settled_at = q + 1;
          break;
        }
        previous = current;
      }
    }
    if (settled_periods) settled_periods->push_back(settled_at);
    all.push_back(found);
  }
  return all;
}

Section sweep_section(const Settings& settings, std::vector<ParetoPoint>& pareto,
                      std::string& goal_sweep_text) {
  const SweepContext context = sweep_context(settings);
  const std::vector<Peaks> reference = direct_sweep(context, 1024);
  std::vector<MethodRow> rows;
  DirectSweepParts parts;
  {
    // 64 samples per period: sweep-switching's default for the exact method.
    MethodRow row{"emnet", "direct (PeriodicSolver)", "64 samples"};
    const std::vector<Peaks> peaks = direct_sweep(context, 64);
    row.error = sweep_error(peaks, reference);
    row.in_process = measure([&] { return direct_sweep(context, 64, &parts), -1.0; }, 20, 3.0);
    bool ok = true;
    row.whole_process = measure_process(
        {settings.emnet, "sweep-switching", settings.fishfin(), "--from", "1", "--to",
         settings.quick ? "7" : "7", "--step", settings.quick ? "1" : "0.1"},
        10, 3.0, ok);
    row.note = "from the read scene; exact method of `emnet sweep-switching`";
    rows.push_back(row);
  }
  std::vector<int> spice_periods;
  const std::vector<double> thresholds =
      settings.quick ? std::vector<double>{1e-3} : std::vector<double>{1e-2, 1e-3, 1e-4, 1e-6};
  for (double threshold : thresholds) {
    MethodRow row{"emnet", "run until settled (exact transient)",
                  "change/period < " + format("%.0e", threshold)};
    std::vector<int> periods;
    std::vector<Peaks> peaks;
    row.in_process = measure(
        [&] {
          periods.clear();
          peaks = settled_sweep(context, threshold, 64, &periods);
          return -1.0;
        },
        1, 1.0);
    row.error = sweep_error(peaks, reference);
    int total = 0, unsettled = 0;
    for (int p : periods) (p > 0 ? total += p : ++unsettled);
    row.note = std::to_string(total) + " periods to settle in all" +
               (unsettled ? ", " + std::to_string(unsettled) + " not settled" : "") +
               "; 64 samples per period; 1 run";
    if (threshold == 1e-4 || settings.quick) spice_periods = periods;
    rows.push_back(row);
  }
  // ngspice: each frequency for the periods the exact transient needed at 1e-4, from rest.
  struct SpiceSetting {
    std::string name;
    double reltol;
    bool whole_process;
  };
  const std::vector<SpiceSetting> spice_settings =
      settings.quick
          ? std::vector<SpiceSetting>{{"default", 0.0, true}}
          : std::vector<SpiceSetting>{{"default", 0.0, true}, {"reltol 1e-5", 1e-5, false}};
  const emnet::Model base = emnet::prepare_model(context.scene);
  for (const auto& setting : spice_settings) {
    MethodRow row{"ngspice", ".tran until settled", setting.name};
    std::vector<std::string> decks;
    std::vector<std::vector<emnet::SpiceOutput>> outputs;
    std::vector<double> end_times;
    for (size_t k = 0; k < context.frequencies.size(); ++k) {
      emnet::Scene at = context.scene;
      at.drive.frequency = context.frequencies[k];
      const emnet::Model model = emnet::prepare_model(at);
      const double period = 1.0 / context.frequencies[k];
      const int periods = std::max(2, spice_periods.size() > k ? spice_periods[k] : 50);
      emnet::SpiceDeckOptions options;
      options.analysis = emnet::SpiceAnalysis::tran;
      options.outputs = context.probes;
      options.end_time = periods * period;
      options.output_step = period / 100.0;
      options.relative_tolerance = setting.reltol > 0.0 ? setting.reltol : 1e-3;
      const emnet::SpiceDeck deck = emnet::write_spice_deck(model, options);
      decks.push_back(setting.reltol > 0.0 ? deck.text : remove_options_line(deck.text));
      outputs.push_back(deck.outputs);
      end_times.push_back(options.end_time);
    }
    std::vector<Peaks> peaks(context.frequencies.size());
    bool failed = false;
    const auto start = Clock::now();
    for (size_t k = 0; k < decks.size(); ++k) {
      const emnet::NgspiceResult result = emnet::run_ngspice(decks[k], in_process_ngspice());
      if (!result.status.ok || !result.scale()) {
        failed = true;
        break;
      }
      const std::vector<double>& times = result.scale()->real_values;
      const double period = 1.0 / context.frequencies[k];
      size_t begin = 0;
      while (begin < times.size() && times[begin] < end_times[k] - period - 1e-12) ++begin;
      for (size_t p = 0; p < context.probes.size(); ++p) {
        const emnet::NgspiceVector* vector = result.find(outputs[k][p].vector);
        if (!vector) {
          failed = true;
          break;
        }
        peaks[k].minimum.push_back(
            refined_extreme(times, vector->real_values, begin, times.size(), -1.0));
        peaks[k].maximum.push_back(
            refined_extreme(times, vector->real_values, begin, times.size(), 1.0));
      }
    }
    row.in_process = summarise({seconds_since(start)});
    row.error = failed ? NAN : sweep_error(peaks, reference);
    if (setting.whole_process) {
      std::vector<std::string> paths;
      for (size_t k = 0; k < decks.size(); ++k)
        paths.push_back(write_deck(settings, "fishfin-sweep-" + std::to_string(k), decks[k]));
      const auto whole_start = Clock::now();
      bool ok = true;
      for (const auto& path : paths) {
        bool one = true;
        ngspice_process(settings, path, 1, 0.0, one);
        ok = ok && one;
      }
      row.whole_process = summarise({seconds_since(whole_start)});
      if (!ok) row.note += "whole process failed; ";
    }
    row.note += std::string("1 run") + (failed ? "; ngspice failed" : "");
    rows.push_back(row);
  }
  for (const auto& row : rows) {
    pareto.push_back({row.tool + " " + row.method + " in-process", row.setting,
                      row.in_process.median, row.error});
    if (row.whole_process.repetitions > 0)
      pareto.push_back({row.tool + " " + row.method + " whole process", "",
                        row.whole_process.median, row.error});
  }
  Section section;
  section.headline = headline(rows);
  std::ostringstream md;
  md << "### Switching sweep: periodic steady state at " << context.frequencies.size()
     << " frequencies (" << context.frequencies.front() << "–" << context.frequencies.back()
     << " Hz), fish fin (ideal drive)\n\n"
     << "Peaks to either side of every deflection output. Error: the largest |peak − "
        "reference| over frequencies, relative to that output's largest peak over the sweep; "
        "reference: the direct method with 1024 samples per period (extremes refined by "
        "Newton). emnet direct: the loop of `emnet sweep-switching` (one PeriodicSolver, a "
        "model per frequency) from the read scene; whole process: `emnet sweep-switching "
        "netlists/fishfin.toml --from 1 --to 7 --step 0.1`. Run until settled: the exact "
        "transient from rest, K = 8, 16, … periods until the peaks of two consecutive periods "
        "differ by less than the threshold times the peak; peaks by a parabola through the "
        "largest sample and its neighbours. ngspice: one deck per frequency, run from rest for "
        "the number of periods the exact transient needed to settle to 1e-4 (ngspice itself "
        "has no per-period test), peaks of the last period refined the same way; whole "
        "process: one `ngspice -b -r` per frequency.\n\n"
     << method_table(rows)
     << "\nWhere the direct sweep's time goes (one in-process run): decomposition of the state "
        "equation (once) "
     << time_text(parts.decomposition) << ", the drive's excitation per frequency "
     << time_text(parts.build) << ", building and assembling the model once and setting each "
     << "excitation " << time_text(parts.assemble) << ", the periodic solves "
     << time_text(parts.solve) << "; total " << time_text(parts.total) << ".\n";
  const double sweep_seconds = rows[0].in_process.median;
  goal_sweep_text =
      time_text(sweep_seconds) +
      (sweep_seconds < 10e-3
           ? " (met)"
           : " (**not met**, by " + format("%.0f", 100.0 * (sweep_seconds / 10e-3 - 1.0)) + " %)") +
      " in-process (solves " + time_text(parts.solve) + ", model and excitations " +
      time_text(parts.build + parts.assemble) + ", decomposition " +
      time_text(parts.decomposition) + ")";
  section.markdown = md.str();
  // Remember the in-process median for the goal line.
  section.headline.in_process_pair += "";
  return section;
}

// ---- 4. scale --------------------------------------------------------------------------------

// Child mode: one analysis at N segments; prints "seconds=<analysis seconds> unknowns=<n>".
int scale_point(const Settings& settings, const std::string& analysis, int segments) {
  // modes, ac and tran: the scene as it is (the DEAs' RC loops: IDA's case); the direct
  // sweep needs the ideal drive (a linear network).
  std::vector<std::string> overrides = {"beam.segments=" + std::to_string(segments)};
  if (analysis == "sweep") overrides.push_back("drive.electrical_dynamics=false");
  const emnet::Model model = build(settings.fishfin(), overrides);
  const emnet::System system = model.network.assemble();
  const auto probes = deflection_probes(model);
  const auto start = Clock::now();
  bool ok = true;
  if (analysis == "modes") {
    const emnet::StaticResult rest = emnet::solve_static(system);
    emnet::ModalOptions options;
    options.count = 3;
    options.keep_vectors = false;
    ok = emnet::run_modes(system, rest.operating_point, options).status.ok;
  } else if (analysis == "ac") {
    const emnet::StaticResult rest = emnet::solve_static(system);
    ok = emnet::run_ac(system, rest.operating_point, emnet::frequency_grid(0.1, 10.0, 100, false),
                       probes)
             .status.ok;
  } else if (analysis == "tran") {
    emnet::TransientOptions options;
    options.end_time = 2.0 / model.scene.drive.frequency;
    options.relative_tolerance = 1e-5;
    for (int k = 0; k <= 200; ++k) options.output_times.push_back(k * options.end_time / 200.0);
    ok = emnet::run_transient_ida(system, probes, options).status.ok;
  } else if (analysis == "sweep") {
    SweepContext context = sweep_context(settings);
    context.scene.beam.segments = segments;
    context.probes = probes;
    direct_sweep(context, 64);
  } else {
    return 2;
  }
  // Peak resident set of this process image: VmHWM. (ru_maxrss would also count the pages of
  // the process that started it, whose address space it shares until exec.)
  const double seconds = seconds_since(start);
  long peak_kib = 0;
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) peak_kib = std::stol(line.substr(6));
  std::cout << "seconds=" << seconds << " unknowns=" << system.size() << " peak_kib=" << peak_kib
            << " ok=" << ok << "\n";
  return ok ? 0 : 3;
}

struct ScalePoint {
  int segments = 0, unknowns = 0;
  double seconds = NAN;
  long max_rss_kib = 0;
  std::string skipped;
};

double fit_exponent(const std::vector<ScalePoint>& points, int from_segments) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const auto& p : points) {
    if (p.segments < from_segments || !(p.seconds > 0.0)) continue;
    const double x = std::log(p.segments), y = std::log(p.seconds);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
  }
  if (n < 2) return NAN;
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

std::string scale_section(const Settings& settings, std::map<std::string, double>& exponents) {
  const std::vector<int> sizes = settings.quick
                                     ? std::vector<int>{10, 30}
                                     : std::vector<int>{10, 30, 100, 300, 1000, 3000, 10000};
  const double point_budget = settings.quick ? 10.0 : 20.0;
  const std::vector<std::pair<std::string, std::string>> analyses = {
      {"modes", "run_modes, 3 lowest (dense up to 80 unknowns, Arnoldi above)"},
      {"ac", "run_ac, 100 points 0.1–10 Hz"},
      {"tran", "run_transient_ida, 2 periods at 5 Hz, rtol 1e-5, 201 outputs"},
      {"sweep", "direct periodic sweep, 61 frequencies (dense decomposition)"}};
  std::ostringstream md;
  md << "### 4. Scale: fish fin against N\n\n"
     << "Each point is a fresh process (`emnet_bench --scale-point`); time: the analysis alone "
        "(after reading the scene and building the network; modes and ac include the static "
        "operating point), one run; memory: the child's peak resident set (VmHWM of "
        "/proc/self/status at its end). A point is skipped when the previous time extrapolated "
        "with the fitted "
        "exponent (at least 1) exceeds "
     << time_text(point_budget)
     << ". modes, ac and tran run the scene as it is (with the DEAs' RC loops); the direct "
        "sweep the ideal drive. Exponent: least squares slope of log(time) on log(N) over "
        "N ≥ 300, where every analysis runs its large-N method (modes switch from the dense "
        "method to Arnoldi above 600 unknowns, N ≈ 100).\n\n";
  std::map<std::string, std::vector<ScalePoint>> results;
  for (const auto& [analysis, description] : analyses) {
    auto& points = results[analysis];
    bool skipping = false;
    for (int n : sizes) {
      ScalePoint point;
      point.segments = n;
      if (!points.empty() && !skipping) {
        const ScalePoint& last = points.back();
        double exponent = std::max(1.0, fit_exponent(points, 0));
        if (!std::isfinite(exponent)) exponent = 1.0;
        if (std::isfinite(last.seconds) &&
            last.seconds * std::pow(static_cast<double>(n) / last.segments, exponent) >
                point_budget)
          skipping = true;
      }
      if (skipping) {
        point.skipped = "skipped (over the point budget)";
        points.push_back(point);
        continue;
      }
      const ProcessRun run = run_process(
          {settings.self, "--scale-point", analysis, std::to_string(n), "--root", settings.root},
          true, 1.5 * point_budget);
      std::istringstream in(run.output);
      std::string field;
      while (in >> field) {
        if (field.rfind("seconds=", 0) == 0) point.seconds = std::stod(field.substr(8));
        if (field.rfind("unknowns=", 0) == 0) point.unknowns = std::stoi(field.substr(9));
        if (field.rfind("peak_kib=", 0) == 0) point.max_rss_kib = std::stol(field.substr(9));
      }
      if (!run.ok) {
        point.skipped = "failed or timed out after " + time_text(run.seconds);
        point.seconds = NAN;
        skipping = true;
      }
      points.push_back(point);
    }
    exponents[analysis] = fit_exponent(points, 300);
  }
  md << "| N | ";
  for (const auto& a : analyses) md << a.first << " time | " << a.first << " memory | ";
  md << "\n|---|";
  for (size_t k = 0; k < analyses.size(); ++k) md << "---|---|";
  md << "\n";
  for (size_t i = 0; i < sizes.size(); ++i) {
    md << "| " << sizes[i] << " | ";
    for (const auto& a : analyses) {
      const ScalePoint& p = results[a.first][i];
      if (!p.skipped.empty())
        md << p.skipped << " | – | ";
      else
        md << time_text(p.seconds) << " | " << format("%.0f MiB", p.max_rss_kib / 1024.0) << " | ";
    }
    md << "\n";
  }
  md << "| growth exponent (N ≥ 300) | ";
  for (const auto& a : analyses)
    md << (std::isfinite(exponents[a.first]) ? format("%.2f", exponents[a.first]) : "–") << " | | ";
  md << "\n\n";
  for (const auto& a : analyses) md << "- " << a.first << ": " << a.second << "\n";
  // Scale data for a plot.
  std::ofstream data(settings.out + "/scale.dat");
  for (const auto& a : analyses) {
    data << "# " << a.first << "\n";
    for (const auto& p : results[a.first])
      if (p.skipped.empty() && p.seconds > 0.0)
        data << p.segments << " " << p.seconds << " " << p.max_rss_kib / 1024.0 << "\n";
    data << "\n\n";
  }
  std::ofstream script(settings.out + "/scale.gp");
  script << "set terminal pngcairo size 900,620 noenhanced font ',10'\n"
         << "set output '" << settings.out << "/scale.png'\n"
         << "set title 'fish fin: analysis time against segments'\n"
         << "set logscale xy\nset xlabel 'segments N'\nset ylabel 'time [s]'\nset grid\n"
         << "set key left top\nplot ";
  for (size_t k = 0; k < analyses.size(); ++k)
    script << (k ? ", " : "") << "'" << settings.out << "/scale.dat' index " << k
           << " using 1:2 with linespoints title '" << analyses[k].first << "'";
  script << "\n";
  return md.str();
}

// ---- 4b. modes: dense against Arnoldi ----------------------------------------------------------

// The size up to which run_modes takes the dense method (ModalOptions::dense_limit) is set by
// this measurement: both methods on the fish fin at a few sizes, the default request (the 10
// lowest modes) and error bounds on, side by side.
std::string modes_section(const Settings& settings) {
  const std::vector<int> sizes =
      settings.quick ? std::vector<int>{5, 10} : std::vector<int>{5, 10, 15, 20, 30, 60, 100};
  std::ostringstream out;
  out << "run_modes on the fish fin (its DEAs' RC loops kept), the default request, both "
         "methods forced (dense_limit 10⁶ / 0); median of repeated runs. The default dense limit "
         "is where the ratio crosses 1.\n\n"
      << "| N | unknowns | dense | Arnoldi | dense / Arnoldi | modes (dense / Arnoldi) |\n"
      << "|---|---|---|---|---|---|\n";
  for (int segments : sizes) {
    const emnet::Model model =
        build(settings.fishfin(), {"beam.segments=" + std::to_string(segments)});
    const emnet::System system = model.network.assemble();
    const emnet::StaticResult rest = emnet::solve_static(system);
    Timing timing[2];
    size_t found[2] = {0, 0};
    for (int dense = 0; dense < 2; ++dense) {
      emnet::ModalOptions options;
      options.dense_limit = dense ? 1000000 : 0;
      timing[dense] = measure(
          [&] {
            const emnet::ModalResult modes =
                emnet::run_modes(system, rest.operating_point, options);
            found[dense] = modes.modes.size();
            return modes.seconds;
          },
          settings.quick ? 3 : 9, settings.quick ? 2.0 : 10.0);
    }
    out << "| " << segments << " | " << system.size() << " | " << timing[1].text() << " | "
        << timing[0].text() << " | " << format("%.2f", timing[1].median / timing[0].median) << " | "
        << found[1] << " / " << found[0] << " |\n";
  }
  out << "\nThe dense method finds every pole; Arnoldi the 10 lowest modes (fewer where it stops "
         "at the Kelvin–Voigt relaxation cluster near −1/τ).\n\n";
  return out.str();
}

// ---- 5b. modal reduction ----------------------------------------------------------------------

// 5b. Modal reduction (modal_reduction.hpp) against the full model, side by side in this run.
// AC: the fish fin's 1000-point sweep (0–10 Hz, band 10 Hz) by run_ac and by run_ac_reduced
// (time: reduction + evaluation, without its own check); error: the largest |difference| over
// all 1000 points, relative to each probe's largest |response|. Periodic: the 61-frequency
// switching sweep (1–7 Hz, ideal drive, band 7 Hz, 256 samples) by PeriodicSolver and by
// ReducedPeriodicSolver, each with its one-off decomposition or reduction; error: the largest
// periodic_difference (every sample, relative to each probe's largest |deflection|).
std::string reduction_section(const Settings& settings) {
  std::ostringstream md;
  const std::vector<int> sizes =
      settings.quick ? std::vector<int>{7, 100} : std::vector<int>{7, 100, 500};
  const std::vector<double> tolerances =
      settings.quick ? std::vector<double>{1e-2, 1e-3} : std::vector<double>{1e-2, 1e-3, 1e-4};
  md << "## 5b. Modal reduction: speed gained and error\n\n"
     << "Modes below f_c = band/√tol kept, the rest as a static correction (AC: a Taylor series "
        "in s when Arnoldi stops below f_c) (`emnet ac --reduce`, `emnet sweep-switching "
        "--reduce`; README, Modal reduction). "
        "Full and reduced timed side by side in this run; the error is measured against the "
        "full model at every point.\n\n"
     << "AC, fish fin, 1000 points 0–10 Hz, band 10 Hz (reduced time: poles, left vectors, "
        "static solve(s) and evaluation; s^m: the correction's series order):\n\n"
     << "| N | unknowns | tol | f_c | kept modes (method) | full run_ac | reduced | speed-up | "
        "max error | |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (int n : sizes) {
    std::vector<std::string> overrides = ideal_drive;
    overrides.push_back("beam.segments=" + std::to_string(n));
    const emnet::Model model = build(settings.fishfin(), overrides);
    const emnet::System system = model.network.assemble();
    const emnet::StaticResult rest = emnet::solve_static(system);
    const std::vector<emnet::Probe> probes = deflection_probes(model);
    const auto grid = emnet::frequency_grid(0.0, 10.0, 1000, false);
    emnet::AcResult full;
    const Timing full_time = measure(
        [&] { return full = emnet::run_ac(system, rest.operating_point, grid, probes), -1.0; }, 5,
        3.0);
    for (double tolerance : tolerances) {
      emnet::ReductionOptions options;
      options.band = 10.0;
      options.tolerance = tolerance;
      emnet::AcReductionResult reduced;
      const Timing reduced_time = measure(
          [&] {
            reduced = emnet::run_ac_reduced(system, rest.operating_point, grid, probes, options);
            return reduced.reduce_seconds + reduced.evaluate_seconds;
          },
          5, 3.0);
      double error = NAN;
      if (reduced.status.ok && full.status.ok) {
        const std::vector<double> errors =
            emnet::errors_relative_to_peak(reduced.ac.values, full.values);
        error = *std::max_element(errors.begin(), errors.end());
      }
      md << "| " << n << " | " << system.size() << " | " << format("%.0e", tolerance) << " | "
         << format("%.4g Hz", reduced.model.cutoff_hz) << " | " << reduced.model.kept_modes << " ("
         << reduced.model.modal_method
         << (reduced.model.correction_order > 0
                 ? ", s^" + std::to_string(reduced.model.correction_order)
                 : std::string())
         << ") | " << full_time.text() << " | " << reduced_time.text() << " | "
         << ratio_text(full_time.median / reduced_time.median) << " | " << error_text(error)
         << " | "
         << (!reduced.status.ok   ? "failed: " + reduced.status.message
             : error <= tolerance ? "met"
                                  : "**not met**")
         << " |\n";
    }
  }
  md << "\nPeriodic steady state, fish fin (ideal drive), 61 switching frequencies 1–7 Hz, "
        "band 7 Hz, 256 samples (times include the one-off decomposition or reduction):\n\n"
     << "| N | tol | kept modes | full (PeriodicSolver) | reduced | speed-up | max error | |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (int n : std::vector<int>{7, 100}) {
    std::vector<std::string> overrides = ideal_drive;
    overrides.push_back("beam.segments=" + std::to_string(n));
    const emnet::Scene scene = emnet::read_scene(settings.fishfin(), overrides);
    const emnet::Model model = emnet::prepare_model(scene);
    const std::vector<emnet::Probe> probes = deflection_probes(model);
    std::vector<emnet::System> systems;
    const int count = settings.quick ? 7 : 61;
    for (int k = 0; k < count; ++k) {
      emnet::Scene at = scene;
      at.drive.frequency = 1.0 + (settings.quick ? 1.0 : 0.1) * k;
      systems.push_back(emnet::prepare_model(at).network.assemble());
    }
    std::vector<emnet::PeriodicResult> full(systems.size());
    const Timing full_time = measure(
        [&] {
          const emnet::PeriodicSolver solver(systems[0]);
          for (size_t k = 0; k < systems.size(); ++k)
            full[k] =
                solver.solve(systems[k], probes, 1.0 / (1.0 + (settings.quick ? 1.0 : 0.1) * k));
          return -1.0;
        },
        5, 5.0);
    for (double tolerance : tolerances) {
      emnet::ReductionOptions options;
      options.band = 7.0;
      options.tolerance = tolerance;
      std::vector<emnet::PeriodicResult> reduced(systems.size());
      int kept = 0;
      std::string failure;
      const Timing reduced_time = measure(
          [&] {
            const emnet::ReducedPeriodicSolver solver(systems[0], options);
            kept = solver.reduction().kept_modes;
            for (size_t k = 0; k < systems.size(); ++k)
              reduced[k] =
                  solver.solve(systems[k], probes, 1.0 / (1.0 + (settings.quick ? 1.0 : 0.1) * k));
            return -1.0;
          },
          5, 5.0);
      double error = 0.0;
      for (size_t k = 0; k < systems.size(); ++k) {
        if (!reduced[k].status.ok || !full[k].status.ok) {
          failure = (reduced[k].status.ok ? full[k] : reduced[k]).status.message;
          error = NAN;
          break;
        }
        error = std::max(error, emnet::periodic_difference(reduced[k], full[k]));
      }
      const double speed_up = full_time.median / reduced_time.median;
      md << "| " << n << " | " << format("%.0e", tolerance) << " | " << kept << " | "
         << full_time.text() << " | " << reduced_time.text() << " | " << ratio_text(speed_up)
         << (speed_up < 1.0 ? " (slower)" : "") << " | " << error_text(error) << " | "
         << (!failure.empty()     ? "failed: " + failure
             : error <= tolerance ? "met"
                                  : "**not met**")
         << " |\n";
    }
  }
  md << "\n";
  return md.str();
}

// ---- 5a. simplifications ---------------------------------------------------------------------

// 5a. What each automatic simplification (emnet/studies/segment_selection.hpp,
// drive.electrical_dynamics = "auto") costs in accuracy and saves in time, measured side by side.
std::string simplification_section(const Settings& settings) {
  std::ostringstream md;
  const int repetitions = settings.quick ? 2 : 10;
  const double budget = settings.quick ? 0.5 : 3.0;
  const double band_top = 130.0;
  const std::string band = "model.band=\"" + format("%g", band_top) + " Hz\"";
  // Converged reference: the bare fin beam, Richardson from N = 1000 and 2000 (N = 200 and
  // 400 with --quick).
  const emnet::BeamSpec beam = emnet::read_scene(settings.fishfin()).beam;
  const int reference_n = settings.quick ? 200 : 1000;
  const std::vector<double> coarse = emnet::beam_frequencies(beam, reference_n, 5);
  const std::vector<double> fine = emnet::beam_frequencies(beam, 2 * reference_n, 5);
  std::vector<double> converged;
  for (size_t k = 0; k < coarse.size() && k < fine.size(); ++k)
    if (emnet::richardson_extrapolate(coarse[k], fine[k]) <= band_top)
      converged.push_back(emnet::richardson_extrapolate(coarse[k], fine[k]));
  auto true_error = [&](int segments) {
    const std::vector<double> f = emnet::beam_frequencies(beam, segments, 5);
    double worst = 0.0;
    for (size_t k = 0; k < converged.size() && k < f.size(); ++k)
      worst = std::max(worst, std::abs(f[k] - converged[k]) / converged[k]);
    return worst;
  };
  // The analyses the choice serves, on the full fin model (damped, RC DEAs): run_modes (5
  // lowest modes) and a 1000-point AC sweep over the band (P2-P4, tip).
  const std::vector<double> grid = emnet::frequency_grid(0.0, band_top, 1000, false);
  auto analysis_times = [&](int segments) {
    const emnet::Model m = build(settings.fishfin(), {"beam.segments=" + std::to_string(segments)});
    const emnet::System system = m.network.assemble();
    const Eigen::VectorXd rest = emnet::solve_static(system).operating_point;
    emnet::ModalOptions options;
    options.count = 5;
    options.keep_vectors = false;
    const std::vector<emnet::Probe> probes = deflection_probes(m);
    return std::make_pair(measure([&] { return emnet::run_modes(system, rest, options).seconds; },
                                  repetitions, budget),
                          measure([&] { return emnet::run_ac(system, rest, grid, probes).seconds; },
                                  repetitions, budget));
  };
  const int fixed_n = 200;
  const auto [fixed_modes, fixed_ac] = analysis_times(fixed_n);
  md << "### Beam segments: `beam.segments = \"auto\"` against a fixed N = " << fixed_n << "\n\n"
     << "Fish fin, band 0–" << format("%g", band_top) << " Hz (" << converged.size()
     << " modes), the modes' worst relative error against the bare beam converged by "
        "Richardson from N = "
     << reference_n << " and " << 2 * reference_n
     << ". Choosing: the selection's own time (median over runs of prepare_model). The analyses "
        "it serves, on the full model (damped, RC DEAs): run_modes (5 lowest) and a 1000-point "
        "AC sweep over the band; \"saved\" is the time at N = "
     << fixed_n << " over the time at the chosen N, without and with the time to choose.\n\n"
     << "| tolerance | chosen N | estimate | error vs converged | time to choose | modes at N "
        "(saved) | ac at N (saved) | saved incl. choosing, modes + ac |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const double tolerance : {1e-2, 1e-3, 1e-4}) {
    const std::vector<std::string> overrides = {"beam.segments=auto", band,
                                                "model.tolerance=" + format("%g", tolerance)};
    int chosen = 0;
    double estimate = 0.0;
    const Timing choose = measure(
        [&] {
          const emnet::Model m = build(settings.fishfin(), overrides);
          chosen = m.scene.beam.segments;
          estimate = m.automatic_choices.front().estimated_error;
          return m.automatic_choices.front().seconds;
        },
        repetitions, budget);
    const auto [modes, ac] = analysis_times(chosen);
    md << "| " << format("%g", tolerance) << " | " << chosen << " | " << error_text(estimate)
       << " | " << error_text(true_error(chosen)) << " | " << choose.text() << " | "
       << time_text(modes.median) << " (" << ratio_text(fixed_modes.median / modes.median) << ") | "
       << time_text(ac.median) << " (" << ratio_text(fixed_ac.median / ac.median) << ") | "
       << ratio_text((fixed_modes.median + fixed_ac.median) /
                     (modes.median + ac.median + choose.median))
       << " |\n";
  }
  md << "| (fixed) | " << fixed_n << " | – | " << error_text(true_error(fixed_n)) << " | – | "
     << fixed_modes.text() << " | " << fixed_ac.text() << " | 1× |\n\n";

  // Ideal against RC drive, at the scene's N = 7 and 5 Hz switching.
  const emnet::Model rc = build(settings.fishfin(), {});
  const emnet::Model ideal = build(settings.fishfin(), ideal_drive);
  const emnet::System rc_system = rc.network.assemble();
  const emnet::System ideal_system = ideal.network.assemble();
  const std::vector<emnet::Probe> rc_probes = deflection_probes(rc);
  const std::vector<emnet::Probe> ideal_probes = deflection_probes(ideal);
  const double period = 1.0 / rc.scene.drive.frequency;
  emnet::PeriodicResult rc_periodic, ideal_periodic;
  const Timing rc_periodic_time = measure(
      [&] {
        rc_periodic = emnet::run_periodic_shooting(rc_system, rc_probes, period, 1e-9);
        return rc_periodic.seconds;
      },
      repetitions, budget);
  const Timing ideal_periodic_time = measure(
      [&] {
        const auto start = Clock::now();
        emnet::PeriodicSolver solver(ideal_system);
        ideal_periodic = solver.solve(ideal_system, ideal_probes, period);
        return seconds_since(start);
      },
      repetitions, budget);
  const int periods = settings.quick ? 5 : 50;
  emnet::TransientOptions options;
  options.end_time = periods * period;
  for (int k = 0; k <= 100 * periods; ++k) options.output_times.push_back(k * period / 100);
  emnet::TransientOptions rc_options = options;
  rc_options.relative_tolerance = 1e-8;
  emnet::TransientResult rc_transient, ideal_transient;
  const Timing rc_transient_time = measure(
      [&] {
        rc_transient = emnet::run_transient_ida(rc_system, rc_probes, rc_options);
        return rc_transient.seconds;
      },
      repetitions, budget);
  const Timing ideal_transient_time = measure(
      [&] {
        ideal_transient = emnet::run_transient_exact(ideal_system, ideal_probes, options);
        return ideal_transient.seconds;
      },
      repetitions, budget);
  // Worst peak difference over the deflection outputs, relative to the RC model's peak.
  double periodic_difference = 0.0, transient_difference = 0.0;
  for (size_t p = 0; p < rc_probes.size(); ++p) {
    const double peak =
        std::max(std::abs(rc_periodic.maximum[p]), std::abs(rc_periodic.minimum[p]));
    if (peak <= 0.0) continue;
    periodic_difference = std::max(
        {periodic_difference, std::abs(ideal_periodic.maximum[p] - rc_periodic.maximum[p]) / peak,
         std::abs(ideal_periodic.minimum[p] - rc_periodic.minimum[p]) / peak});
    double rc_peak = 0.0, ideal_peak = 0.0;
    for (double v : rc_transient.values[p]) rc_peak = std::max(rc_peak, std::abs(v));
    for (double v : ideal_transient.values[p]) ideal_peak = std::max(ideal_peak, std::abs(v));
    if (rc_peak > 0.0)
      transient_difference =
          std::max(transient_difference, std::abs(ideal_peak - rc_peak) / rc_peak);
  }
  double tau = 0.0;
  for (const auto& dea : rc.deas) tau = std::max(tau, dea.electrode_resistance * dea.capacitance);
  const double drive_estimate =
      std::pow(2 * 3.14159265358979323846 * rc.scene.drive.frequency * tau, 2) / 2;
  md << "### DEA drive: ideal (`electrical_dynamics = false`) against RC\n\n"
     << "Fish fin as in the scene (N = " << rc.scene.beam.segments << ", 4 kV square wave at "
     << format("%g", rc.scene.drive.frequency)
     << " Hz), RC time constant tau = " << format("%.4g", tau * 1e3)
     << " ms. Difference: the largest |difference| of the peak "
        "deflections over the outputs (P2–P4, tip), relative to the RC model's peak. The "
        "criterion's estimate at the drive frequency, (2*pi*f*tau)^2/2 = "
     << error_text(drive_estimate)
     << ". Periodic: RC by Newton shooting (IDA, rtol 1e-9), "
        "ideal by the exact PeriodicSolver (set-up included). Transient: "
     << periods
     << " periods from rest, 100 outputs per period; RC by IDA (rtol 1e-8), ideal "
        "by the exact method.\n\n"
     << "| analysis | RC model | ideal drive | cost ratio RC/ideal | peak difference |\n"
     << "|---|---|---|---|---|\n"
     << "| periodic steady state | " << rc_periodic_time.text() << " | "
     << ideal_periodic_time.text() << " | "
     << ratio_text(rc_periodic_time.median / ideal_periodic_time.median) << " | "
     << error_text(periodic_difference) << " |\n"
     << "| transient | " << rc_transient_time.text() << " | " << ideal_transient_time.text()
     << " | " << ratio_text(rc_transient_time.median / ideal_transient_time.median) << " | "
     << error_text(transient_difference) << " |\n\n";
  return md.str();
}

// ---- the report ------------------------------------------------------------------------------

std::string machine_text() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  const long cores = sysconf(_SC_NPROCESSORS_ONLN);
  char date[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return std::to_string(cores) + " cores (nproc), " + model + "; " + date;
}

std::string exponent_text(double exponent) {
  return std::isfinite(exponent) ? format("%.2f", exponent)
                                 : std::string("– (too few points within the budget)");
}

std::string goal_line(const std::string& name, double measured, double goal,
                      const std::string& pair) {
  std::ostringstream out;
  out << "| " << name << " | " << ratio_text(goal) << " | " << ratio_text(measured) << " | "
      << (std::isfinite(measured) && measured >= goal ? "met" : "**not met**") << " | " << pair
      << " |\n";
  return out.str();
}

int run(const Settings& settings) {
  const auto start = Clock::now();
  mkdir(settings.out.c_str(), 0755);
  if (!settings.only.empty()) {
    const std::string file = settings.out + "/report-" + settings.only + ".md";
    std::ofstream(file) << "Machine: " << machine_text() << ".\n\n"
                        << (settings.only == "5a" ? "## 5a. Simplifications: what each costs and "
                                                    "saves\n\n" +
                                                        simplification_section(settings)
                                                  : reduction_section(settings));
    std::cerr << "emnet_bench: " << file << " (" << time_text(seconds_since(start)) << ")\n";
    return 0;
  }
  std::vector<ParetoPoint> discretisation_points, ac_points, tran_points, sweep_points;
  std::cerr << "emnet_bench: 1. discretisation\n";
  const std::string discretisation = discretisation_section(settings, discretisation_points);
  std::cerr << "emnet_bench: 3. ac\n";
  const Section ac = ac_section(settings, ac_points);
  std::cerr << "emnet_bench: 2/3. transient\n";
  const Section tran = tran_section(settings, tran_points);
  std::cerr << "emnet_bench: 2/3. switching sweep\n";
  std::string sweep_goal;
  const Section sweep = sweep_section(settings, sweep_points, sweep_goal);
  std::cerr << "emnet_bench: 4. scale\n";
  std::map<std::string, double> exponents;
  const std::string scale = scale_section(settings, exponents);
  std::cerr << "emnet_bench: 4b. modes, dense against Arnoldi\n";
  const std::string modes = modes_section(settings);
  std::cerr << "emnet_bench: 5a. simplifications\n";
  const std::string simplifications = simplification_section(settings);
  std::cerr << "emnet_bench: 5b. modal reduction\n";
  const std::string reduction = reduction_section(settings);
  write_pareto_plot(settings, "discretisation", "cantilever: discretisation error against cost",
                    discretisation_points);
  write_pareto_plot(settings, "ac", "fish fin AC, 1000 points: error against time", ac_points);
  write_pareto_plot(settings, "tran", "fish fin transient, 50 periods: error against time",
                    tran_points);
  write_pareto_plot(settings, "sweep", "fish fin switching sweep, 61 frequencies", sweep_points);

  std::ofstream md(settings.out + "/report.md");
  md << "# emnet: speed and accuracy\n\n"
     << "Machine: " << machine_text() << ". Release build; one run of `tools/bench`"
     << (settings.quick ? " (--quick: reduced sizes, not a measurement)" : "") << ".\n\n"
     << "## Headline: ngspice time / emnet time at equal or smaller error\n\n"
     << "For every ngspice run, the fastest emnet run whose error is equal or smaller; the "
        "ratio of their median times. The table gives the least favourable such pair per "
        "task (usually ngspice's cheapest run).\n\n"
     << "| task | goal | measured (whole process) | | pair |\n|---|---|---|---|---|\n"
     << goal_line("AC, 1000 points", ac.headline.whole_process, 10.0,
                  ac.headline.whole_process_pair)
     << goal_line("transient, 50 periods", tran.headline.whole_process, 100.0,
                  tran.headline.whole_process_pair)
     << goal_line("switching sweep, 61 frequencies", sweep.headline.whole_process, 100.0,
                  sweep.headline.whole_process_pair)
     << "\n| task | measured (in-process) | pair |\n|---|---|---|\n"
     << "| AC | " << ratio_text(ac.headline.in_process) << " | " << ac.headline.in_process_pair
     << " |\n| transient | " << ratio_text(tran.headline.in_process) << " | "
     << tran.headline.in_process_pair << " |\n| switching sweep | "
     << ratio_text(sweep.headline.in_process) << " | " << sweep.headline.in_process_pair << " |\n\n"
     << "Other goals: the fish fin's 61-frequency sweep under 10 ms in-process: " << sweep_goal
     << ". Growth of cost with N (fitted exponent, N ≥ 300; goal ≤ 1 for ac and modes): modes "
     << exponent_text(exponents["modes"]) << ", ac " << exponent_text(exponents["ac"]) << ", tran "
     << exponent_text(exponents["tran"]) << ", sweep " << exponent_text(exponents["sweep"])
     << ".\n\n"
     << "## Method\n\nTimes are medians of repeated runs after one warm-up run, with min–max "
        "and the number of runs; slow items (over half their budget) run once, and say "
        "\"1 run\". In-process: a function call in the benchmark process (libngspice loaded "
        "into it, no worker process). Whole process: a program started and waited for, output "
        "to /dev/null (emnet: `build/emnet …`; ngspice: `ngspice -b -r RAWFILE DECK`, since "
        "without a rawfile or a .control block ngspice -b writes nothing).\n\n"
     << "## 1. Discretisation\n\n"
     << discretisation << "![discretisation](pareto-discretisation.png)\n\n"
     << "## 2 and 3. Integrators and ngspice, side by side\n\n"
     << ac.markdown << "\n![ac](pareto-ac.png)\n\n"
     << tran.markdown << "\n![tran](pareto-tran.png)\n\n"
     << sweep.markdown << "\n![sweep](pareto-sweep.png)\n\n"
     << "## 4. Scale\n\n"
     << scale << "\n![scale](scale.png)\n\n"
     << "## 4b. modes: dense against Arnoldi\n\n"
     << modes << "## 5a. Simplifications: what each costs and saves\n\n"
     << simplifications << reduction << "Total benchmark time: " << time_text(seconds_since(start))
     << ".\n";
  std::cerr << "emnet_bench: report written to " << settings.out << "/report.md ("
            << time_text(seconds_since(start)) << ")\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  char self[4096];
  const ssize_t length = readlink("/proc/self/exe", self, sizeof self - 1);
  settings.self = length > 0 ? std::string(self, static_cast<size_t>(length)) : argv[0];
  std::string scale_analysis;
  int scale_segments = 0;
  for (int k = 1; k < argc; ++k) {
    const std::string argument = argv[k];
    auto value = [&]() -> std::string {
      if (k + 1 >= argc) {
        std::cerr << "emnet_bench: " << argument << " needs a value\n";
        std::exit(2);
      }
      return argv[++k];
    };
    if (argument == "--root") {
      settings.root = value();
    } else if (argument == "--out") {
      settings.out = value();
    } else if (argument == "--emnet") {
      settings.emnet = value();
    } else if (argument == "--quick") {
      settings.quick = true;
    } else if (argument == "--only") {
      settings.only = value();
      if (settings.only != "5a" && settings.only != "5b") {
        std::cerr << "emnet_bench: --only takes 5a (simplifications) or 5b (modal reduction)\n";
        return 2;
      }
    } else if (argument == "--scale-point") {
      scale_analysis = value();
      scale_segments = std::stoi(value());
    } else {
      std::cerr << "usage: emnet_bench [--root DIR] [--out DIR] [--emnet PROGRAM] [--quick] "
                   "[--only 5a|5b]\n";
      return 2;
    }
  }
  try {
    if (!scale_analysis.empty()) return scale_point(settings, scale_analysis, scale_segments);
    return run(settings);
  } catch (const std::exception& error) {
    std::cerr << "emnet_bench: " << error.what() << "\n";
    return 1;
  }
}
