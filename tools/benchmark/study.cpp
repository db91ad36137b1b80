// Benchmark section 6, design studies: the fish fin's tolerance study (modes + static + the
// 61-frequency switching sweep per variant) by run_design_study on 1 and 2 threads, its cost per
// variant by stage, beside the same variants as users script them today: one emnet process per
// analysis and variant, and one ngspice process per variant on an AC deck. The Python module's
// overhead and the study on 1 and 2 Dask workers come from tools/benchmark/python_study.py, run
// from here.
#include "bench.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/studies/design_study.hpp"

namespace emnet_bench {

namespace {

// The tolerance study of examples/tolerance_study.py: ±5 % on EI, each DEA's film (dielectric
// and force thickness together), electrode width and lever arm.
std::vector<std::string> tolerance_variations() {
  std::vector<std::string> vary{"beam.bending_stiffness=uniform(95%,105%)"};
  for (const char* dea : {"A", "B"}) {
    const std::string d = dea;
    vary.push_back("dea." + d + ".dielectric_thickness+dea." + d +
                   ".force_thickness=uniform(95%,105%)");
    vary.push_back("dea." + d + ".electrode_width=uniform(95%,105%)");
    vary.push_back("dea." + d + ".lever_arm=uniform(95%,105%)");
  }
  return vary;
}

std::string ms(double seconds) {
  return format("%.3g", seconds * 1e3) + " ms";
}

}  // namespace

std::string study_section(const Settings& settings) {
  std::ostringstream out;
  const emnet::Scene scene = emnet::read_scene(settings.fishfin());
  std::vector<emnet::Variation> variations;
  for (const auto& text : tolerance_variations())
    variations.push_back(emnet::parse_variation(scene, text));
  const std::size_t count = settings.quick ? 40 : 1000;
  const emnet::VariantTable table = emnet::make_variants(variations, count, 1);
  emnet::DesignStudyOptions options;
  options.analyses = {emnet::StudyAnalysis::modes, emnet::StudyAnalysis::static_state,
                      emnet::StudyAnalysis::switching_sweep};
  options.report_frequencies = {5.0};
  // Warm-up (page faults, caches), then 1 and 2 threads, each run twice: the faster is kept.
  {
    emnet::VariantTable few = table;
    few.rows.resize(std::min<std::size_t>(few.rows.size(), 20));
    options.threads = 1;
    emnet::run_design_study(scene, few, options);
  }
  std::vector<emnet::DesignStudyResult> runs;
  for (int threads : {1, 2}) {
    options.threads = threads;
    emnet::DesignStudyResult best;
    for (int repetition = 0; repetition < 2; ++repetition) {
      emnet::DesignStudyResult run = emnet::run_design_study(scene, table, options);
      if (repetition == 0 || run.seconds < best.seconds) best = std::move(run);
    }
    runs.push_back(std::move(best));
  }
  const bool same = runs[0].rows.size() == runs[1].rows.size() &&
                    std::equal(runs[0].rows.begin(), runs[0].rows.end(), runs[1].rows.begin(),
                               [](const auto& a, const auto& b) { return a.values == b.values; });
  const double n = static_cast<double>(count);
  const emnet::VariantCost& cost = runs[0].cost;
  out << "Many variants of one scene, as a tolerance or design study runs them: in one process "
         "on a pool of threads (run_design_study, what `emnet study` and `emnet.study` call), "
         "against one process per variant as a script would start them, and through the Python "
         "module, locally and on Dask workers. The goal: 1000 variants in under 2 s on 2 "
         "cores.\n\n"
      << "The fish fin's tolerance study (`examples/tolerance_study.py`): " << count
      << " variants, ±5 % uniform on EI, each DEA's film thickness (dielectric and force "
         "thickness together), electrode width and lever arm (7 numbers per variant); per "
         "variant `modes` (f1 with its rounding bound), `static` (5 probes) and the 61-frequency "
         "switching sweep (1 to 7 Hz, the sweep peak, and every output's extremes at 5 Hz). "
      << runs[0].failed << " variants failed. " << runs[0].unknowns << " unknowns.\n\n"
      << "| threads | wall | per variant (wall) | work per variant | goal "
         "|\n|---|---|---|---|---|\n";
  for (const auto& run : runs)
    out << "| " << run.threads << " | " << time_text(run.seconds) << " | " << ms(run.seconds / n)
        << " | " << ms(run.cost.total() / n) << " | "
        << (run.threads == 2 ? std::string(run.seconds < 2.0 * n / 1000.0 ? "met" : "**not met**") +
                                   " (1000 variants in 2 s: 2 ms per variant and core)"
                             : "")
        << " |\n";
  out << "\nThe rows on 1 and 2 threads are "
      << (same ? "identical (bit for bit)" : "**NOT identical**")
      << ". Work per variant by stage (1 thread): build " << ms(cost.build / n)
      << " (set the keys, resolve, build, assemble), operating point "
      << ms(cost.operating_point / n) << ", modes " << ms(cost.modes / n)
      << " (dense, with the poles' error bounds), static " << ms(cost.static_state / n)
      << ", switching sweep " << ms(cost.sweep / n)
      << " (the ideal-drive model, one eigen-decomposition, 61 periodic solves of the last output "
         "and one of every output at 5 Hz).\n\n";

  // The same variants as users script them: processes per variant.
  const std::size_t scripted = settings.quick ? 2 : 10;
  double emnet_processes = 0.0, ngspice_processes = 0.0;
  bool emnet_ok = true, ngspice_ok = true;
  for (std::size_t i = 0; i < scripted; ++i) {
    std::vector<std::string> sets;
    for (std::size_t k = 0; k < table.keys.size(); ++k)
      sets.insert(sets.end(), {"--set", table.keys[k] + "=" + format("%.17g", table.rows[i][k])});
    for (const std::string command : {"modes", "static", "sweep-switching"}) {
      std::vector<std::string> arguments{settings.emnet, command, settings.fishfin()};
      arguments.insert(arguments.end(), sets.begin(), sets.end());
      arguments.insert(arguments.end(), {"--json", "--quiet"});
      const ProcessRun run = run_process(arguments);
      emnet_processes += run.seconds;
      emnet_ok = emnet_ok && run.succeeded;
    }
    emnet::Scene variant = scene;
    for (std::size_t k = 0; k < table.keys.size(); ++k)
      emnet::set_parameter(variant, table.keys[k], table.rows[i][k]);
    const auto started = Clock::now();
    emnet::SpiceDeckOptions deck_options;
    deck_options.analysis = emnet::SpiceAnalysis::ac;
    const emnet::SpiceDeck deck =
        emnet::write_spice_deck(emnet::prepare_model(variant), deck_options);
    const std::string path = write_deck(settings, "study-variant", deck.text);
    const double writing = seconds_since(started);
    bool ok = true;
    const Timing spice = ngspice_process(settings, path, 1, 60.0, ok);
    ngspice_ok = ngspice_ok && ok;
    ngspice_processes += writing + spice.median;
  }
  const double per_emnet_process = emnet_processes / static_cast<double>(scripted);
  const double per_ngspice = ngspice_processes / static_cast<double>(scripted);
  const double per_study = runs[0].cost.total() / n;
  out << "Scripted one process per variant (the first " << scripted
      << " variants, wall per variant):\n\n"
      << "| way | per variant | study's work per variant × |\n|---|---|---|\n"
      << "| `emnet modes`, `static`, `sweep-switching` processes (--json) | "
      << (emnet_ok ? ms(per_emnet_process) : std::string("failed")) << " | "
      << ratio_text(per_emnet_process / per_study) << " |\n"
      << "| ngspice: the variant's AC deck (1000 points) written, `ngspice -b` | "
      << (ngspice_ok ? ms(per_ngspice) : std::string("failed")) << " | "
      << ratio_text(per_ngspice / per_study)
      << " |\n\nThe ngspice way gives one AC sweep per variant (a resonance to read off a "
         "curve), not the modes with their error bounds, the static state and the periodic "
         "sweep of the study.\n\n";

  // The Python module and Dask (tools/benchmark/python_study.py prints its own section).
  const std::string python_dir = settings.emnet.substr(0, settings.emnet.rfind('/')) + "/python";
  const ProcessRun python =
      run_process({"/usr/bin/env", "PYTHONPATH=" + python_dir, "/usr/bin/python3",
                   settings.root + "/tools/benchmark/python_study.py", "--scene",
                   settings.fishfin(), "--variants", std::to_string(settings.quick ? 40 : 1000)},
                  true, 1200.0);
  out << (python.succeeded ? python.output
                           : std::string("The Python measurement (tools/benchmark/python_study.py) "
                                         "failed; run it alone to see why.\n"))
      << "\n";
  return out.str();
}

}  // namespace emnet_bench
