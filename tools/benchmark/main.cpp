// emnet_bench: speed against error, side by side with ngspice. tools/bench runs it and plots;
// a full run is the project's docs/benchmarks.md and docs/figures/bench-*.png.
//
// Every measurement is taken in this one run on this one machine, and the report says what each
// section measures, against which reference and how: each section's function (below) writes an
// introduction above its tables, and computes the conclusions (goals met or missed, ratios,
// where the time goes) from the numbers it measured. The method common to all (timing, in-process
// and whole process, errors) is the report's "How it is measured", written here.
//
//   emnet_bench [--root DIR] [--out DIR] [--emnet PROGRAM] [--report FILE] [--figures DIR]
//               [--quick] [--only 0|4|5a|5b|6|7|8]
//
// --out: the scratch directory (data *.dat and gnuplot scripts *.gp of the plots, decks/*.cir);
// --report: the report (default out/report.md, or out/report-<section>.md with --only);
// --figures: where the plots' scripts put their images, bench-<name>.png (default out), linked
// from the report relative to its directory. --quick: reduced sizes, a smoke run, not a
// measurement. --only: that section alone (0 limits, 4 scale, 5a simplifications, 5b modal
// reduction, 6 design studies, 7 large deflection), without plots.
//
// The sections are in tools/benchmark/: limits.cpp (0), discretisation.cpp (1, 4b), ac.cpp and
// transient.cpp (2, 3), sweep.cpp (the switching sweep), scale.cpp (4), simplifications.cpp (5a,
// 5b), study.cpp (6), crosscheck.cpp (the cross-check), large_deflection.cpp (7), real_devices.cpp
// (8); the pieces they share in common.cpp (bench.hpp); the report and the command line here.
#include <filesystem>

#include "bench.hpp"

namespace emnet_bench {

// ---- the report ------------------------------------------------------------------------------

namespace {

// "Measured 2026-12-03 11:52 UTC on 2 cores (nproc), AMD EPYC 7B13": the one date of the report.
std::string machine_text(std::time_t started) {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  const long cores = sysconf(_SC_NPROCESSORS_ONLN);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&started));
  return std::string("Measured ") + date + " on " + std::to_string(cores) + " cores (`nproc`), " +
         model;
}

std::string exponent_text(double exponent) {
  return std::isfinite(exponent) ? format("%.2f", exponent)
                                 : std::string("– (too few points within the budget)");
}

// GitHub's anchor of a heading: lower case, punctuation dropped, spaces as hyphens (the
// headings are ASCII).
std::string anchor(const std::string& heading) {
  std::string out;
  for (const unsigned char c : heading) {
    if (std::isalnum(c) || c == '_' || c == '-')
      out += static_cast<char>(std::tolower(c));
    else if (c == ' ')
      out += '-';
  }
  return out;
}

std::string figure(const Settings& settings, const std::string& name, const std::string& caption) {
  return "![" + name + "](" + settings.figure_link(name) + ")\n\n*" + caption + "*\n\n";
}

const char* const kParetoCaption =
    "Error (relative to each output's peak; exact results plotted at 1e-16) against wall time, "
    "every method and tool of the table above, in-process and whole process; points labelled by "
    "their setting. Down and to the left is better.";

std::string method_text(const Settings& settings) {
  std::ostringstream md;
  md << "- **Timing.** Each item runs once as a warm-up (caches, lazy loading of libraries), then "
        "again until a count of repetitions or a time budget per item is used up; the tables "
        "give the median, with the spread (min–max) and the number of runs. An item whose "
        "warm-up alone takes more than half its budget is timed by that one run and says "
        "\"1 run\".\n"
     << "- **In-process** is a function call in the benchmark's own process: emnet from the "
        "scene file (or from the assembled network, where the row says \"alone\") to the "
        "result; ngspice through libngspice loaded into the same process, deck to vectors.\n"
     << "- **Whole process** is a program started and waited for, output to /dev/null: "
        "`emnet ac|tran|sweep-switching …`, or `ngspice -b -r RAWFILE DECK` (without a rawfile "
        "or a .control block, `ngspice -b` writes nothing). It is timed from just before the "
        "program starts until it is reaped, so it includes the program's start, reading the "
        "scene or deck and writing the results.\n"
     << "- **The network** is the fish fin (`netlists/fishfin.toml`, N = 7 segments) unless a "
        "section says otherwise, mostly with the ideal drive "
        "(`drive.electrical_dynamics = false`, a linear network), so that emnet's exact method "
        "is the reference for every tool; the scene as it is, with each DEA's RC loop (a "
        "nonlinear network), where a section says so.\n"
     << "- **Errors** are relative to each output's peak, the largest over the outputs and over "
        "the run, the sweep or the frequencies, against the reference each section names. "
        "ngspice is compared at its own time points and frequencies, its transients away from "
        "the switching edges (the exported deck switches with short linear edges).\n"
     << "- **ngspice** runs the decks emnet's SPICE writer exports from the same model (kept "
        "in the scratch directory's `decks/`).\n"
     << "- **Goals** are the project's targets for speed, scale and overhead; each is marked "
        "met or **not met** from this run's numbers.\n"
     << "- **Variation.** The machine is shared with other work: the times of the same item "
        "move by about ±30 % from run to run (other processes compete for the "
     << sysconf(_SC_NPROCESSORS_ONLN)
     << " cores and their caches), the errors not at all. Compare ratios taken within one "
        "report rather than times across reports.\n";
  (void)settings;
  return md.str();
}

struct Goal {
  std::string task;
  double goal;
  const Section* section;
};

// The headline: each task's least favourable pair against its goal, and what meeting a missed
// goal would take.
std::string headline_text(const std::vector<Goal>& goals, const Timing& start_up,
                          const std::string& sweep_goal,
                          const std::map<std::string, double>& exponents) {
  std::ostringstream md;
  md << "How much faster emnet answers the same question than ngspice, for the three tasks both "
        "can do on the fish fin (ideal drive). For every ngspice run, the fastest emnet run "
        "whose error is equal or smaller; the ratio of their median times. The table gives the "
        "least favourable such pair per task (usually ngspice's cheapest, least accurate run); "
        "the goals are whole-process ratios, a user's command against ngspice's. The tables of "
        "[Against ngspice](#"
     << anchor("Against ngspice: AC, transient and switching sweep") << ") have every run.\n\n"
     << "| task | goal | whole process | | in-process | pair |\n|---|---|---|---|---|---|\n";
  for (const Goal& g : goals) {
    const Headline& h = g.section->headline;
    md << "| " << g.task << " | ≥ " << ratio_text(g.goal) << " | " << ratio_text(h.whole_process)
       << " | "
       << (std::isfinite(h.whole_process) && h.whole_process >= g.goal ? "met" : "**not met**")
       << " | " << ratio_text(h.in_process) << " | " << h.whole_process_pair << " |\n";
  }
  md << "\n";
  for (const Goal& g : goals) {
    const Headline& h = g.section->headline;
    if (!std::isfinite(h.whole_process) || h.whole_process >= g.goal ||
        !std::isfinite(h.whole_process_spice))
      continue;
    const double needed = h.whole_process_spice / g.goal;
    md << "- " << g.task << ": " << ratio_text(g.goal) << " would need emnet's whole process "
       << "under " << time_text(needed) << " (ngspice's " << time_text(h.whole_process_spice)
       << " / " << ratio_text(g.goal) << "); it took " << time_text(h.whole_process_own)
       << ", and starting the program (`emnet --help`) alone takes at least "
       << time_text(start_up.minimum) << " (the fastest of " << start_up.repetitions << " runs)"
       << (needed < start_up.minimum
               ? ": the goal is below the program's start, out of reach of any faster analysis"
               : "")
       << ".\n";
  }
  md << "\nAgainst ngspice's most accurate run (its smallest error), whole process:";
  for (const Goal& g : goals) {
    const Headline& h = g.section->headline;
    md << " " << g.task << " "
       << (std::isfinite(h.accurate) ? ratio_text(h.accurate) + " (" + h.accurate_pair + ")"
                                     : std::string("– (no emnet run as accurate)"))
       << (&g == &goals.back() ? "." : ";");
  }
  md << "\n\nOther goals: the fish fin's 61-frequency sweep under 10 ms in-process: " << sweep_goal
     << ". Growth of cost with N ([Scale](#" << anchor("Scale: cost against the number of segments")
     << "), fitted exponent from N = 300; goal ≤ 1.2): static "
     << exponent_text(exponents.at("static")) << ", modes " << exponent_text(exponents.at("modes"))
     << ", ac " << exponent_text(exponents.at("ac")) << ", tran "
     << exponent_text(exponents.at("tran")) << ", sweep " << exponent_text(exponents.at("sweep"))
     << ".\n";
  return md.str();
}

// The title and the one date line: when the run started, where, and how long it took.
std::string header_text(const Settings& settings, std::time_t started, double seconds) {
#ifdef NDEBUG
  const char* const build_kind = "Release build";
#else
  const char* const build_kind = "**build with assertions (not Release): not a measurement**";
#endif
  std::ostringstream md;
  md << "# Benchmarks: speed and accuracy\n\n"
     << machine_text(started) << "; " << build_kind << "; the run took " << time_text(seconds)
     << "."
     << (settings.quick ? " **--quick: reduced sizes, a smoke run, not a measurement.**" : "")
     << "\n\n"
     << "*Generated by `tools/bench` (`tools/benchmark/`); do not edit by hand: run `tools/bench` "
        "again.*\n\n";
  return md.str();
}

void write_report(const Settings& settings, const std::string& text) {
  const std::string temporary = settings.report + ".partial";
  {
    std::ofstream out(temporary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + temporary);
  }
  std::filesystem::rename(temporary, settings.report);
}

}  // namespace

int run(const Settings& settings) {
  const auto start = Clock::now();
  const std::time_t started = std::time(nullptr);
  mkdir(settings.out.c_str(), 0755);
  using Part = std::pair<std::string, std::string>;  // heading, text
  if (!settings.only.empty()) {
    std::map<std::string, double> only_exponents;
    const Part part =
        settings.only == "5a"
            ? Part{"Simplifications: what each costs and saves", simplification_section(settings)}
        : settings.only == "6" ? Part{"Design studies", study_section(settings)}
        : settings.only == "7" ? Part{"Large deflection: cost against small kinematics",
                                      large_deflection_section(settings)}
        : settings.only == "8"
            ? Part{"Real devices: the tweezer jaw's periodic state", real_device_section(settings)}
        : settings.only == "0"
            ? Part{"Limits: each analysis against its arithmetic", limits_section(settings)}
        : settings.only == "4"
            ? Part{"Scale: cost against the number of segments",
                   scale_section(settings, only_exponents)}
            : Part{"Modal reduction: speed gained and error", reduction_section(settings)};
    write_report(settings, header_text(settings, started, seconds_since(start)) + "## " +
                               part.first + "\n\n" + part.second);
    std::cerr << "emnet_bench: " << settings.report << " (" << time_text(seconds_since(start))
              << ")\n";
    return 0;
  }
  // The program's start, for the headline: measured first, before the sections load the machine.
  bool help_ok = true;
  const Timing start_up = measure_process({settings.emnet, "--help"}, 20, 2.0, help_ok);
  std::cerr << "emnet_bench: limits\n";
  const std::string limits = limits_section(settings);
  std::vector<ParetoPoint> discretisation_points, ac_points, tran_points, sweep_points;
  std::cerr << "emnet_bench: discretisation\n";
  const std::string discretisation = discretisation_section(settings, discretisation_points);
  std::cerr << "emnet_bench: ac\n";
  const Section ac = ac_section(settings, ac_points);
  std::cerr << "emnet_bench: transient\n";
  const Section tran = tran_section(settings, tran_points);
  std::cerr << "emnet_bench: switching sweep\n";
  std::string sweep_goal;
  const Section sweep = sweep_section(settings, sweep_points, sweep_goal);
  std::cerr << "emnet_bench: scale\n";
  std::map<std::string, double> exponents;
  const std::string scale = scale_section(settings, exponents);
  std::cerr << "emnet_bench: modes, dense against Arnoldi\n";
  const std::string modes = modes_section(settings);
  std::cerr << "emnet_bench: simplifications\n";
  const std::string simplifications = simplification_section(settings);
  std::cerr << "emnet_bench: modal reduction\n";
  const std::string reduction = reduction_section(settings);
  std::cerr << "emnet_bench: design studies\n";
  const std::string study = study_section(settings);
  std::cerr << "emnet_bench: cross-check\n";
  const std::string crosscheck = crosscheck_section(settings);
  std::cerr << "emnet_bench: large deflection\n";
  const std::string large_deflection = large_deflection_section(settings);
  std::cerr << "emnet_bench: real devices\n";
  const std::string real_devices = real_device_section(settings);
  write_pareto_plot(settings, "discretisation", "cantilever: discretisation error against cost",
                    discretisation_points);
  write_pareto_plot(settings, "ac", "fish fin AC, 1000 points: error against time", ac_points);
  write_pareto_plot(settings, "tran", "fish fin transient, 50 periods: error against time",
                    tran_points);
  write_pareto_plot(settings, "sweep", "fish fin switching sweep, 61 frequencies", sweep_points);

  const std::vector<Goal> goals = {{"AC, 1000 points", 10.0, &ac},
                                   {"transient, 50 periods", 100.0, &tran},
                                   {"switching sweep, 61 frequencies", 100.0, &sweep}};
  const std::vector<Part> parts = {
      {"How it is measured", method_text(settings)},
      {"Headline: emnet against ngspice at equal or smaller error",
       headline_text(goals, start_up, sweep_goal, exponents)},
      {"Limits: each analysis against its arithmetic", limits},
      {"Discretisation: error against the number of segments",
       discretisation +
           figure(settings, "discretisation",
                  "The cantilever's f1..f3 error against the cost of run_modes and of a "
                  "1000-point ac sweep, one point per N of the table; exact results plotted at "
                  "1e-16.")},
      {"Against ngspice: AC, transient and switching sweep",
       "emnet's methods and ngspice side by side on the same network, each at several settings, "
       "with the error of each against the section's reference; the "
       "[headline](#" +
           anchor("Headline: emnet against ngspice at equal or smaller error") +
           ") pairs them.\n\n" + ac.markdown + "\n" + figure(settings, "ac", kParetoCaption) +
           tran.markdown + "\n" + figure(settings, "tran", kParetoCaption) + sweep.markdown + "\n" +
           figure(settings, "sweep", kParetoCaption)},
      {"Scale: cost against the number of segments",
       scale + "\n" +
           figure(settings, "scale",
                  "Time of each analysis alone against the number of segments N, one fresh "
                  "process per point; log–log, so a slope of 1 is linear growth.")},
      {"Modes: dense against Arnoldi", modes},
      {"Simplifications: what each costs and saves", simplifications},
      {"Modal reduction: speed gained and error", reduction},
      {"Design studies", study},
      {"Cross-check against ngspice: differences and wall times", crosscheck},
      {"Large deflection: cost against small kinematics", large_deflection},
      {"Real devices: the tweezer jaw's periodic state", real_devices}};

  std::ostringstream md;
  md << "What emnet costs and how accurate it is, measured in one run on one machine: each "
        "analysis against the arithmetic it needs, against ngspice on the same network, "
        "against closed forms and converged answers; how the cost grows with the size of the "
        "beam; what the automatic simplifications and the modal reduction cost and save; design "
        "studies of many variants; and the differences of the cross-check with ngspice. Every "
        "number below comes from this run; the conclusions that depend on numbers are computed "
        "from them.\n\n";
  for (const Part& part : parts) md << "- [" << part.first << "](#" << anchor(part.first) << ")\n";
  md << "\n";
  for (const Part& part : parts) md << "## " << part.first << "\n\n" << part.second << "\n";
  std::string text = md.str();
  // No blank lines beyond one between blocks.
  for (size_t at; (at = text.find("\n\n\n")) != std::string::npos;) text.erase(at, 1);
  write_report(settings, header_text(settings, started, seconds_since(start)) + text);
  std::cerr << "emnet_bench: report written to " << settings.report << " ("
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
    } else if (argument == "--report") {
      settings.report = value();
    } else if (argument == "--figures") {
      settings.figures = value();
    } else if (argument == "--quick") {
      settings.quick = true;
    } else if (argument == "--only") {
      settings.only = value();
      if (settings.only != "0" && settings.only != "4" && settings.only != "5a" &&
          settings.only != "5b" && settings.only != "6" && settings.only != "7" &&
          settings.only != "8") {
        std::cerr << "emnet_bench: --only takes 0 (limits), 4 (scale), 5a (simplifications), 5b "
                     "(modal reduction), 6 (design studies) or 7 (large deflection)\n";
        return 2;
      }
    } else if (argument == "--scale-point") {
      scale_analysis = value();
      scale_segments = std::stoi(value());
    } else {
      std::cerr << "usage: emnet_bench [--root DIR] [--out DIR] [--emnet PROGRAM] [--report FILE] "
                   "[--figures DIR] [--quick] [--only 0|4|5a|5b|6|7|8]\n";
      return 2;
    }
  }
  if (settings.report.empty())
    settings.report =
        settings.out + (settings.only.empty() ? "/report.md" : "/report-" + settings.only + ".md");
  if (settings.figures.empty()) settings.figures = settings.out;
  try {
    if (!scale_analysis.empty()) return scale_point(settings, scale_analysis, scale_segments);
    return run(settings);
  } catch (const std::exception& error) {
    std::cerr << "emnet_bench: " << error.what() << "\n";
    return 1;
  }
}
