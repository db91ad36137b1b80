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
//  4. Scale. Fish fin at N = 10 … 10 000, static, modes, a 1000-point AC, IDA over 2 periods and
//     the 61-frequency switching sweep through the modal reduction: each point is a fresh
//     process (this program with --scale-point), which reports its own peak resident memory
//     (VmHWM) and the time of the analysis alone, after reading and building. Growth exponent:
//     least squares of log(time) on log(N) over the points with N ≥ 300. A point is skipped when
//     the previous point's time extrapolated with the fitted exponent (at least 1) exceeds the
//     point budget.
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
//  6. Design studies. The fish fin's tolerance study (1000 variants, --quick 40: modes, static
//     and the 61-frequency switching sweep each) by run_design_study on 1 and 2 threads, the
//     cost per variant by stage; beside it the first 10 variants (--quick 2) as scripted one
//     process per variant: emnet's modes, static and sweep-switching commands, and ngspice on
//     the variant's AC deck. Then tools/benchmark/python_study.py: the Python module's overhead
//     on one `modes` call and the study through Python, locally and on 1 and 2 Dask workers.
//
//  0. Limits. Each analysis of the fish fin (N = 7) against the operation count of the method a
//     careful implementation would use at this machine's measured dense arithmetic rate, beside
//     ngspice; and IDA against ngspice at equal error on the RC-loop (nonlinear) fin
//     (limits.cpp's header comment has the counts).
//
// --only 0, 4, 5a, 5b or 6 runs that section alone and writes report-<section>.md.
//
// Outputs (in --out): report.md, data files *.dat and gnuplot scripts *.gp for the Pareto
// plots (tools/bench runs gnuplot), decks/*.cir.
//
// The sections are in tools/benchmark/: limits.cpp (0), discretisation.cpp (1, 4b), ac.cpp and
// transient.cpp (2, 3), sweep.cpp (the switching sweep), scale.cpp (4), simplifications.cpp (5a,
// 5b), study.cpp (6); the pieces they share in common.cpp (bench.hpp); the report and the command
// line here.
#include "bench.hpp"

namespace emnet_bench {

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
    std::map<std::string, double> only_exponents;
    const std::string file = settings.out + "/report-" + settings.only + ".md";
    std::ofstream(file) << "Machine: " << machine_text() << ".\n\n"
                        << (settings.only == "5a" ? "## 5a. Simplifications: what each costs and "
                                                    "saves\n\n" +
                                                        simplification_section(settings)
                            : settings.only == "6"
                                ? "## 6. Design studies\n\n" + study_section(settings)
                            : settings.only == "0"
                                ? "## 0. Limits: each analysis against its arithmetic\n\n" +
                                      limits_section(settings)
                            : settings.only == "4"
                                ? "## 4. Scale\n\n" + scale_section(settings, only_exponents)
                                : reduction_section(settings));
    std::cerr << "emnet_bench: " << file << " (" << time_text(seconds_since(start)) << ")\n";
    return 0;
  }
  std::cerr << "emnet_bench: 0. limits\n";
  const std::string limits = limits_section(settings);
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
  std::cerr << "emnet_bench: 6. design studies\n";
  const std::string study = study_section(settings);
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
     << ". Growth of cost with N (fitted exponent, N ≥ 300; goal ≤ 1.2): static "
     << exponent_text(exponents["static"]) << ", modes " << exponent_text(exponents["modes"])
     << ", ac " << exponent_text(exponents["ac"]) << ", tran " << exponent_text(exponents["tran"])
     << ", sweep " << exponent_text(exponents["sweep"]) << ".\n\n"
     << "## 0. Limits: each analysis against its arithmetic\n\n"
     << limits
     << "\n## Method\n\nTimes are medians of repeated runs after one warm-up run, with min–max "
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
     << simplifications << reduction << "## 6. Design studies\n\n"
     << study << "Total benchmark time: " << time_text(seconds_since(start)) << ".\n";
  std::cerr << "emnet_bench: report written to " << settings.out << "/report.md ("
            << time_text(seconds_since(start)) << ")\n";
  return 0;
}

}  // namespace emnet_bench

using namespace emnet_bench;

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
      if (settings.only != "0" && settings.only != "4" && settings.only != "5a" &&
          settings.only != "5b" && settings.only != "6") {
        std::cerr << "emnet_bench: --only takes 0 (limits), 4 (scale), 5a (simplifications), 5b "
                     "(modal reduction) or 6 (design studies)\n";
        return 2;
      }
    } else if (argument == "--scale-point") {
      scale_analysis = value();
      scale_segments = std::stoi(value());
    } else {
      std::cerr << "usage: emnet_bench [--root DIR] [--out DIR] [--emnet PROGRAM] [--quick] "
                   "[--only 0|4|5a|5b|6]\n";
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
