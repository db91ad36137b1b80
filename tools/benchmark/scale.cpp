// Benchmark section 4, scale: the fish fin at N = 10 … 10 000, each point a fresh process (this
// program with --scale-point) reporting its peak resident memory and the analysis's time.
#include <functional>
#include <map>
#include <nlohmann/json.hpp>

#include "bench.hpp"

namespace emnet_bench {

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
  std::string extra;  // further fields of the report line
  if (analysis == "static") {
    ok = emnet::solve_static(system).status.ok();
  } else if (analysis == "modes") {
    const emnet::StaticResult rest = emnet::solve_static(system);
    emnet::ModalOptions options;
    options.count = 3;
    options.keep_vectors = false;
    ok = emnet::run_modes(system, rest.operating_point, options).status.ok();
  } else if (analysis == "ac") {
    const emnet::StaticResult rest = emnet::solve_static(system);
    ok = emnet::run_ac(system, rest.operating_point, emnet::frequency_grid(0.0, 10.0, 1000, false),
                       probes)
             .status.ok();
  } else if (analysis == "tran") {
    emnet::TransientOptions options;
    options.end_time = 2.0 / model.scene.drive.frequency;
    options.relative_tolerance = 1e-5;
    for (int k = 0; k <= 200; ++k) options.output_times.push_back(k * options.end_time / 200.0);
    ok = emnet::run_transient_ida(system, probes, options).status.ok();
  } else if (analysis == "sweep") {
    // Through the modal reduction (band 7 Hz, tolerance 1e-3; ReducedPeriodicSolver), one
    // reduction for the 61 switching frequencies; its a-priori truncation factor (the bound's
    // ρ at the band's edge, modal_reduction.hpp) is reported.
    emnet::ReductionOptions reduction;
    reduction.band = 7.0;
    reduction.tolerance = 1e-3;
    const emnet::ReducedPeriodicSolver solver(system, reduction);
    ok = solver.reduction().status.ok();
    extra = " truncation=" + format("%.3g", solver.reduction().truncation_factor) +
            " kept=" + std::to_string(solver.reduction().kept_modes);
    for (int k = 0; ok && k <= 60; ++k) {
      emnet::Scene at = model.scene;
      at.drive.frequency = 1.0 + 0.1 * k;
      const emnet::Model variant = emnet::build_model(at);
      const emnet::System driven = variant.network.assemble();
      ok = solver.solve(driven, probes, 1.0 / at.drive.frequency, 64).status.ok();
    }
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
            << " ok=" << ok << extra << "\n";
  return ok ? 0 : 3;
}

struct ScalePoint {
  int segments = 0, unknowns = 0;
  double seconds = NAN;
  long max_rss_kib = 0;
  std::string skipped, note;
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

// A command a user runs at the largest sizes (1000 up, or the two largest), side by side with
// the library's analysis: `emnet COMMAND netlists/fishfin.toml --segments N --quiet --json`, the
// whole process timed; `read` gives the method and the stated error from its JSON.
using MethodAndError = std::pair<std::string, std::string>;
std::string command_rows(const Settings& settings, const std::string& command,
                         const std::vector<ScalePoint>& library, const std::vector<int>& sizes,
                         double limit,
                         const std::function<MethodAndError(const nlohmann::json&)>& read) {
  std::ostringstream md;
  md << "| N | command | library | method | stated error | goal at N = 10000 |\n"
        "|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < sizes.size(); ++i) {
    if (sizes[i] < 1000 && i + 2 < sizes.size()) continue;  // the two largest, or from 1000
    const ProcessRun run = run_process({settings.emnet, command, settings.fishfin(), "--segments",
                                        std::to_string(sizes[i]), "--quiet", "--json"},
                                       true, 120.0);
    MethodAndError described{"failed", "–"};
    try {
      described = read(nlohmann::json::parse(run.output));
    } catch (const std::exception&) {
    }
    const ScalePoint& point = library[i];
    const bool ok = !run.output.empty();
    md << "| " << sizes[i] << " | " << (ok ? time_text(run.seconds) : "failed") << " | "
       << (point.skipped.empty() ? time_text(point.seconds) : point.skipped) << " | "
       << described.first << " | " << described.second << " | "
       << (sizes[i] != 10000 ? std::string("–")
                             : "≤ " + time_text(limit) + ": " +
                                   (ok && run.seconds <= limit ? "met" : "**not met**"))
       << " |\n";
  }
  return md.str();
}

// `emnet sweep-switching` with its automatic method (the reduction above 1000 unknowns, checked
// by a wider reduction and the edge estimate) and `emnet ac` with its automatic method (1000
// points: the modal reduction above 2000 unknowns with its error measured against the full
// model, else the direct solve's largest relative residual), against the library's sweep and
// AC (run_ac, the direct solve at every point).
std::string command_paragraph(const Settings& settings,
                              const std::map<std::string, std::vector<ScalePoint>>& results,
                              const std::vector<int>& sizes) {
  std::ostringstream md;
  md << "\nThe commands users run, `emnet sweep-switching` and `emnet ac` on "
        "`netlists/fishfin.toml --segments N --quiet --json` (the whole process, one run), "
        "against the library's analysis above. sweep-switching: 61 frequencies, the automatic "
        "method and its check:\n\n"
     << command_rows(
            settings, "sweep-switching", results.at("sweep"), sizes, 10.0,
            [](const nlohmann::json& json) {
              std::string error;
              if (json.contains("reduction"))
                error = format("%.2g", json["reduction"].value("measured_error", 0.0)) +
                        (json["reduction"].value("status", "") == "met" ? " (met)" : " (not met)");
              else
                error = format("%.2g", json["accuracy"].value("worst_periodicity_residual", 0.0)) +
                        " (periodicity residual)";
              return MethodAndError{json.value("method", "–"), error};
            })
     << "\nac: the scene's 1000 points with the resonance markers, the automatic method (the "
        "modal reduction above 2000 unknowns; the goal: 2 s at N = 10 000):"
        "\n\n"
     << command_rows(settings, "ac", results.at("ac"), sizes, 2.0, [](const nlohmann::json& json) {
          const nlohmann::json& accuracy = json["accuracy"];
          if (accuracy.contains("measured_error"))  // the automatic modal reduction
            return MethodAndError{accuracy.value("method", "–"),
                                  format("%.2g", accuracy.value("measured_error", 0.0)) +
                                      " (measured against the full model; tolerance " +
                                      format("%.2g", accuracy.value("tolerance", 0.0)) + ")"};
          return MethodAndError{accuracy.value("method", "–"),
                                format("%.2g", accuracy.value("max_relative_residual", 0.0)) +
                                    " (relative residual)"};
        });
  return md.str();
}

std::string scale_section(const Settings& settings, std::map<std::string, double>& exponents) {
  const std::vector<int> sizes = settings.quick
                                     ? std::vector<int>{10, 30}
                                     : std::vector<int>{10, 30, 100, 300, 1000, 3000, 10000};
  const double point_budget = settings.quick ? 10.0 : 20.0;
  const std::vector<std::pair<std::string, std::string>> analyses = {
      {"static", "solve_static (sparse LU, Newton)"},
      {"modes", "run_modes, 3 lowest (dense up to " +
                    std::to_string(emnet::ModalOptions().dense_limit) +
                    " unknowns, Arnoldi above)"},
      {"ac", "run_ac, 1000 points 0–10 Hz (pole-residue up to " +
                 std::to_string(emnet::kPoleResidueUnknowns) + " unknowns, direct above)"},
      {"tran", "run_transient_ida, 2 periods at 5 Hz, rtol 1e-5, 201 outputs"},
      {"sweep",
       "61 switching frequencies 1–7 Hz through the modal reduction "
       "(ReducedPeriodicSolver, band 7 Hz, tolerance 1e-3, 64 samples; the a-priori "
       "truncation factor ρ at the band's edge in brackets)"}};
  std::ostringstream md;
  md << "How the cost of each analysis grows with the number of beam segments N, and the "
        "memory it takes, from N = 10 to the largest N. The goals: at N = 10 000 every analysis "
        "under 10 s and 1 GiB, and growth no faster than N^1.2 from N = 300 on.\n\n"
     << "Each point is a fresh process (`emnet_bench --scale-point`); time: the analysis alone "
        "(after reading the scene and building the network; modes and ac include the static "
        "operating point), one run; memory: the child's peak resident set (VmHWM of "
        "/proc/self/status at its end). A point is skipped when the previous time extrapolated "
        "with the exponent "
        "fitted so far (kept between 1 and 2) exceeds "
     << time_text(point_budget)
     << ". static, modes, ac and tran run the scene as it is (with the DEAs' RC loops); the "
        "sweep the ideal drive. Exponent: least squares slope of log(time) on log(N) over "
        "N ≥ 300, where every analysis runs its large-N method (the list below the table says "
        "where each one switches). The sweep at large N runs through the modal reduction; the "
        "direct method's dense decomposition is for small N.\n\n";
  std::map<std::string, std::vector<ScalePoint>> results;
  for (const auto& [analysis, description] : analyses) {
    auto& points = results[analysis];
    bool skipping = false;
    for (int n : sizes) {
      ScalePoint point;
      point.segments = n;
      if (!points.empty() && !skipping) {
        const ScalePoint& last = points.back();
        // The slope over the small sizes, where some analyses still run their small-N
        // method, overstates the growth: kept between 1 and 2.
        double exponent = std::clamp(fit_exponent(points, 0), 1.0, 2.0);
        if (!std::isfinite(exponent)) exponent = 1.0;
        // The sweep's reduction changes method at 600 unknowns (dense poles below, Arnoldi
        // above, N ≈ 100): its small-N growth says nothing of its large-N cost, so it is
        // skipped only once a point itself exceeds the budget.
        const double predicted =
            analysis == "sweep"
                ? last.seconds
                : last.seconds * std::pow(static_cast<double>(n) / last.segments, exponent);
        if (std::isfinite(last.seconds) && predicted > point_budget) skipping = true;
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
        if (field.rfind("truncation=", 0) == 0) point.note = "ρ " + field.substr(11);
      }
      if (!run.succeeded) {
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
        md << time_text(p.seconds) << (p.note.empty() ? "" : " (" + p.note + ")") << " | "
           << format("%.0f MiB", p.max_rss_kib / 1024.0) << " | ";
    }
    md << "\n";
  }
  md << "| growth exponent (N ≥ 300) | ";
  for (const auto& a : analyses)
    md << (std::isfinite(exponents[a.first]) ? format("%.2f", exponents[a.first]) : "–") << " | | ";
  md << "\n\n";
  for (const auto& a : analyses) md << "- " << a.first << ": " << a.second << "\n";
  // The goals at the largest N: under 10 s and 1 GB, growth at most N^1.2 from N = 300.
  md << "\nGoals at N = " << sizes.back() << " (under 10 s and 1 GiB, growth exponent ≤ 1.2):";
  for (const auto& a : analyses) {
    const ScalePoint& p = results[a.first].back();
    const bool met = p.skipped.empty() && p.seconds < 10.0 && p.max_rss_kib < 1024 * 1024 &&
                     !(exponents[a.first] > 1.2);
    md << " " << a.first << " " << (met ? "met" : "**not met**")
       << (&a == &analyses.back() ? "." : ",");
  }
  md << "\n" << command_paragraph(settings, results, sizes);
  // Scale data for a plot.
  const std::string data_path = settings.out + "/bench-scale.dat";
  std::ofstream data(data_path);
  for (const auto& a : analyses) {
    data << "# " << a.first << "\n";
    for (const auto& p : results[a.first])
      if (p.skipped.empty() && p.seconds > 0.0)
        data << p.segments << " " << p.seconds << " " << p.max_rss_kib / 1024.0 << "\n";
    data << "\n\n";
  }
  std::ofstream script(settings.out + "/bench-scale.gp");
  script << plot_preamble(settings.figure("scale"), "fish fin: analysis time against segments")
         << "set logscale xy\nset xlabel 'segments N'\nset ylabel 'time of the analysis [s]'\n"
         << "set format y '%.0e'\nset key left top\nplot ";
  for (size_t k = 0; k < analyses.size(); ++k)
    script << (k ? ", " : "") << "'" << data_path << "' index " << k
           << " using 1:2 with linespoints ls " << k + 1 << " title '" << analyses[k].first << "'";
  script << "\n";
  return md.str();
}

}  // namespace emnet_bench
