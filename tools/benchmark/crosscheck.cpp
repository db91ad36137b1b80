// The cross-check against ngspice: `emnet crosscheck SCENE --json` on every shipped scene
// (netlists/*.toml; --quick: the fish fin alone): the largest difference of each analysis
// against its tolerance per scene, and for the fish fin and the cantilever every quantity and
// the wall time of each analysis in emnet and in ngspice, as the command reports them.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "bench.hpp"

namespace emnet_bench {

namespace {

struct Checked {
  std::string scene;
  bool ran = false;
  std::string failure;
  nlohmann::json report;
  double seconds = 0.0;  // the whole command
};

Checked run_crosscheck_command(const Settings& settings, const std::string& name,
                               const std::string& path) {
  Checked checked;
  checked.scene = name;
  const ProcessRun run =
      run_process({settings.emnet, "crosscheck", path, "--json", "--quiet"}, true, 600.0);
  checked.seconds = run.seconds;
  try {
    checked.report = nlohmann::json::parse(run.output);
    checked.ran = checked.report.contains("rows");
    if (!checked.ran) checked.failure = "no rows in the command's output";
  } catch (const std::exception&) {
    checked.failure = "the command gave no JSON (exit status not 0: ngspice missing or failing?)";
  }
  return checked;
}

// A table cell's text: a '|' escaped.
std::string cell_text(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string crosscheck_section(const Settings& settings) {
  std::vector<std::string> paths = {settings.fishfin()};
  if (!settings.quick) {
    paths.clear();
    for (const auto& entry : std::filesystem::directory_iterator(settings.root + "/netlists"))
      if (entry.path().extension() == ".toml") paths.push_back(entry.path().string());
    std::sort(paths.begin(), paths.end());
  }
  std::vector<Checked> every;
  for (const std::string& path : paths)
    every.push_back(
        run_crosscheck_command(settings, std::filesystem::path(path).filename().string(), path));
  // In detail: the fish fin and the cantilever.
  std::vector<Checked> scenes;
  for (const char* name : {"fishfin.toml", "cantilever.toml"})
    for (const Checked& c : every)
      if (c.scene == name) scenes.push_back(c);
  for (Checked& c : scenes) c.scene = c.scene == "fishfin.toml" ? "fish fin" : "cantilever";
  std::ostringstream md;
  md << "`emnet crosscheck` exports a scene's decks, runs them in ngspice (libngspice, in its "
        "worker process) and compares: op at every node, ac in magnitude and phase at every "
        "frequency, the modes against the peaks of ngspice's fine AC sweeps, and the transient "
        "(emnet's exact method on the ideal drive against ngspice at reltol 1e-6). Below, the "
        "largest difference of each quantity on the shipped scenes, relative as its basis says "
        "(the command's documentation, [commands.md](commands.md#cross-check-emnet-crosscheck)), "
        "against the tolerance the command "
        "applies; a difference over its tolerance fails the command (exit status 4).\n\n"
     << "Every shipped scene (`netlists/*.toml`): the largest difference of each analysis as a "
        "fraction of its tolerance (under 1: within it), and the whole command's wall time:\n\n"
     << "| scene | op | ac | modal | tran | within every tolerance | command |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const Checked& c : every) {
    md << "| `" << c.scene << "` |";
    for (const char* analysis : {"op", "ac", "modal", "tran"}) {
      double worst = -1.0;
      if (c.ran)
        for (const auto& row : c.report["rows"])
          if (row.value("analysis", "") == analysis && row.value("tolerance", 0.0) > 0.0)
            worst =
                std::max(worst, row.value("largest_difference", 0.0) / row.value("tolerance", 1.0));
      md << " " << (worst < 0.0 ? std::string("–") : format("%.1e", worst)) << " |";
    }
    md << " "
       << (!c.ran                          ? "not run: " + c.failure
           : c.report.value("pass", false) ? std::string("yes")
                                           : std::string("**no**"))
       << " | " << time_text(c.seconds) << " |\n";
  }
  md << "\nThe modal rows compare ngspice's peak of a mode with emnet's mode; their tolerance "
        "is emnet's own offset between that mode and the peak of its AC response (plus 1e-6), "
        "so for a damped mode the fraction sits near 1 by construction: the row checks that "
        "ngspice's peak lies where emnet's own response puts it.\n\n"
     << "The fish fin and the cantilever in detail, every quantity compared:\n\n";
  for (const Checked& c : scenes)
    if (!c.ran) md << "- " << c.scene << ": not measured: " << c.failure << ".\n";
  // One row per (analysis, quantity), in the order the scenes give them.
  std::vector<std::pair<std::string, std::string>> keys;
  for (const Checked& c : scenes) {
    if (!c.ran) continue;
    for (const auto& row : c.report["rows"]) {
      const std::pair<std::string, std::string> key{row.value("analysis", ""),
                                                    row.value("quantity", "")};
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
  }
  md << "| analysis | quantity |";
  for (const Checked& c : scenes) md << " " << c.scene << " (tolerance) |";
  md << "\n|---|---|";
  for (size_t k = 0; k < scenes.size(); ++k) md << "---|";
  md << "\n";
  int failed = 0;
  for (const auto& [analysis, quantity] : keys) {
    md << "| " << analysis << " | " << cell_text(quantity) << " |";
    for (const Checked& c : scenes) {
      std::string cell = "–";
      if (c.ran)
        for (const auto& row : c.report["rows"])
          if (row.value("analysis", "") == analysis && row.value("quantity", "") == quantity) {
            const bool pass = row.value("pass", false);
            failed += pass ? 0 : 1;
            cell = error_text(row.value("largest_difference", NAN)) + " (" +
                   format("%.1e", row.value("tolerance", NAN)) + ")" + (pass ? "" : " **over**");
          }
      md << " " << cell << " |";
    }
    md << "\n";
  }
  md << "\n"
     << (failed == 0 ? std::string("Every difference is within its tolerance.")
                     : "**" + std::to_string(failed) + " difference(s) over their tolerance.**")
     << "\n\n";
  md << "Wall time of the same question (ngspice: loading and running the deck and reading the "
        "vectors back, without starting the worker; emnet: its analysis, in-process), as the "
        "command measured it:\n\n"
     << "| scene | analysis | ngspice | emnet | ngspice / emnet | emnet ran |\n"
     << "|---|---|---|---|---|---|\n";
  for (const Checked& c : scenes) {
    if (!c.ran || !c.report.contains("timings")) continue;
    for (const auto& t : c.report["timings"]) {
      const double spice = t.value("ngspice_seconds", NAN), own = t.value("emnet_seconds", NAN);
      md << "| " << c.scene << " | " << t.value("analysis", "") << " | " << time_text(spice)
         << " | " << time_text(own) << " | " << ratio_text(spice / own) << " | "
         << cell_text(t.value("emnet_what", "")) << " |\n";
    }
  }
  md << "\nThe whole command:";
  for (const Checked& c : scenes)
    md << " " << c.scene << " " << time_text(c.seconds) << (&c == &scenes.back() ? "." : ",");
  md << " Its notes for the fish fin:\n\n";
  if (scenes[0].ran && scenes[0].report.contains("notes"))
    for (const auto& note : scenes[0].report["notes"])
      md << "- " << note.get<std::string>() << "\n";
  md << "\n";
  return md.str();
}

}  // namespace emnet_bench
