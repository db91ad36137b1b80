#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>

#include "cli/common.hpp"
#include "cli/option_names.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/output_file.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/report/design_study.hpp"
#include "emnet/studies/design_study.hpp"

namespace emnet_cli {

using emnet::InputError;

// ---- study ------------------------------------------------------------------------------
//
// `emnet study SCENE --vary KEY=SPEC ... [--samples N] [--seed S] [--analysis modes,static,
// sweep-switching] [--threads T] -o FILE.csv|.json`: many variants of one scene in one process
// (include/emnet/studies/design_study.hpp), one row per variant, failed variants included.

struct StudyCommandOptions {
  std::vector<std::string> vary;
  std::string variants;
  std::string samples = "0";  // strict unsigned integers (CLI11 wrapped -1 into 2^64 − 1)
  std::string seed = "1";
  std::string analyses = "modes";
  int modes = 1;
  std::vector<double> at;
  std::string from, to;
  double step = 0.1;
  int threads = 0;
  std::string output;
};

// `text` as an unsigned integer from 0 to `largest` (digits only: no sign, exponent or
// fraction, no wrap-around), else an InputError naming `option`.
std::uint64_t parse_unsigned(const std::string& text, const std::string& option,
                             std::uint64_t largest) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || value > largest)
    throw InputError(option, option,
                     "must be a whole number from 0 to " + std::to_string(largest) + ", got '" +
                         shown(text.substr(0, 40)) + (text.size() > 40 ? "…" : "") + "'");
  return value;
}

namespace {

void refuse_a_study_without_one_source_of_variants(const CommonOptions& options,
                                                   const StudyCommandOptions& cmd) {
  refuse_option(!options.probes.empty(), "--probe",
                "a study reports the scene's probes (static) and the switching outputs (sweep)");
  if (cmd.vary.empty() && cmd.variants.empty())
    throw InputError("--vary", "--vary",
                     "nothing to vary: give --vary KEY=SPEC (e.g. "
                     "beam.bending_stiffness=normal(100%,5%)) or --variants FILE.csv");
  if (!cmd.vary.empty() && !cmd.variants.empty())
    throw InputError("--variants", "--variants", "give --vary or --variants, not both");
}

// From --variants FILE.csv, or drawn from the --vary specs (a grid, or --samples draws).
emnet::VariantTable variant_table(const emnet::Scene& scene, const StudyCommandOptions& cmd,
                                  std::uint64_t samples, std::uint64_t seed) {
  if (!cmd.variants.empty()) {
    if (samples != 0)
      throw InputError("--samples", "--samples", "--variants lists the variants; --samples draws");
    return emnet::read_variants_csv(scene, cmd.variants);
  }
  std::vector<emnet::Variation> variations;
  for (const auto& text : cmd.vary) variations.push_back(emnet::parse_variation(scene, text));
  return emnet::make_variants(variations, samples, seed);
}

emnet::DesignStudyOptions design_study_options(const CommonOptions& options,
                                               const StudyCommandOptions& cmd) {
  emnet::DesignStudyOptions study;
  study.analyses = emnet::parse_study_analyses(cmd.analyses);
  study.mode_count = cmd.modes;
  study.threads = cmd.threads;
  study.report_frequencies = cmd.at;
  if (!cmd.from.empty() || !cmd.to.empty()) {
    const double from = cmd.from.empty() ? 1.0 : parse_frequency(cmd.from, "--from");
    const double to = cmd.to.empty() ? 7.0 : parse_frequency(cmd.to, "--to");
    if (!(cmd.step > 0.0) || !(from > 0.0) || !(to >= from))
      throw InputError("--from/--to/--step", "--step", "needs 0 < from <= to and step > 0");
    const double count = std::floor((to - from) / cmd.step + 1e-9) + 1.0;
    if (count > 100000) throw InputError("--step", "--step", "more than 100000 frequencies");
    for (int k = 0; k < static_cast<int>(count); ++k)
      study.sweep_frequencies.push_back(from + k * cmd.step);
  }
  study.progress = progress_of(options);
  return study;
}

// The table's file (-o, else --csv; none: empty path), checked before the study runs.
struct StudyOutputFile {
  std::string path, option;
  bool json = false;
};

StudyOutputFile study_output_file(const CommonOptions& options, const StudyCommandOptions& cmd) {
  StudyOutputFile file;
  file.path = !cmd.output.empty() ? cmd.output : options.csv;
  file.option = !cmd.output.empty() ? "-o/--output" : "--csv";
  const std::string& output = file.path;
  file.json = output.size() > 5 && output.substr(output.size() - 5) == ".json";
  if (!output.empty() && !file.json &&
      !(output.size() > 4 && output.substr(output.size() - 4) == ".csv"))
    throw InputError("-o", "-o",
                     "the table is written as .csv or .json; got '" + shown(output) + "'");
  return file;
}

void print_what_the_study_did(const emnet::Scene& scene, const emnet::DesignStudyResult& result) {
  const std::size_t n = result.rows.size();
  std::cout << "study of " << shown(scene.name) << " (" << shown(scene.file) << "): " << n
            << " variant(s) of " << result.keys.size() << " key(s), " << result.failed
            << " failed, " << result.outside_validity << " outside the model's validity; "
            << result.segments << " segments, " << result.unknowns << " unknowns\n";
  for (const auto& note : result.notes) std::cout << "note: " << shown(note) << "\n";
  // Work per variant [ms], by stage.
  auto per_variant = [&](double seconds) {
    return format("%.3g", seconds / static_cast<double>(std::max<std::size_t>(n, 1)) * 1e3) + " ms";
  };
  std::cout << "cost: " << milliseconds(result.seconds) << " on " << result.threads
            << " thread(s); per variant " << per_variant(result.cost.total()) << " of work (build "
            << per_variant(result.cost.build) << ", operating point "
            << per_variant(result.cost.operating_point) << ", modes "
            << per_variant(result.cost.modes) << ", static "
            << per_variant(result.cost.static_state) << ", sweep " << per_variant(result.cost.sweep)
            << ")\n";
  std::cout << "accuracy: each variant as its analysis reports it (f_k_error_hz: the pole's "
               "rounding bound); a failed variant is a row with its reason\n\n";
}

// Per column, over the variants that did not fail: min, mean, max and standard deviation.
void print_the_statistics_of_each_column(const emnet::DesignStudyResult& result) {
  std::printf("%-40s %-6s %14s %14s %14s %14s\n", "column", "unit", "min", "mean", "max", "std");
  for (std::size_t k = 0; k < result.columns.size(); ++k) {
    double low = INFINITY, high = -INFINITY, sum = 0.0, squares = 0.0;
    std::size_t count = 0;
    for (const auto& row : result.rows)
      if (row.status.ok()) {
        const double v = row.values[k];
        low = std::min(low, v);
        high = std::max(high, v);
        sum += v;
        ++count;
      }
    if (count == 0) continue;
    const double mean = sum / static_cast<double>(count);
    for (const auto& row : result.rows)
      if (row.status.ok()) squares += (row.values[k] - mean) * (row.values[k] - mean);
    const double sd = count > 1 ? std::sqrt(squares / static_cast<double>(count - 1)) : 0.0;
    std::printf("%-40s %-6s %14.7g %14.7g %14.7g %14.3g\n", shown(result.columns[k]).c_str(),
                shown(result.units[k]).c_str(), low, mean, high, sd);
  }
}

// The first five failures, and a warning naming the first variant outside the validity.
void print_the_failures_and_the_validity(const emnet::DesignStudyResult& result) {
  std::size_t shown_failures = 0;
  for (std::size_t i = 0; i < result.rows.size() && shown_failures < 5; ++i)
    if (!result.rows[i].status.ok()) {
      std::cout << "variant " << i << " failed: " << shown(result.rows[i].status.message) << "\n";
      ++shown_failures;
    }
  if (result.failed > shown_failures)
    std::cout << "(" << result.failed - shown_failures << " more failed; see the table)\n";
  if (result.outside_validity > 0) {
    std::size_t first = 0;
    while (result.rows[first].validity.within() || !result.rows[first].status.ok()) ++first;
    const std::string warning = "WARNING: " + std::to_string(result.outside_validity) +
                                " variant(s) outside the model's validity (column validity), "
                                "the first, variant " +
                                std::to_string(first) + ": " +
                                emnet::validity_text(result.rows[first]);
    std::cout << shown(warning) << "\n";
    std::cerr << "emnet: " << shown(warning) << "\n";
  }
}

void write_the_study_file(const StudyOutputFile& output, const emnet::Json& json,
                          const emnet::DesignStudyResult& result) {
  if (output.path.empty()) return;
  if (output.json) {
    emnet::OutputFile file(output.path);
    file.write(json_text(json) + "\n");
    check_csv(file.commit(), output.option);
  } else {
    check_csv(emnet::write_design_study_csv(output.path, result), output.option);
  }
}

}  // namespace

int run_study_command(const CommonOptions& options, const StudyCommandOptions& cmd) {
  refuse_a_study_without_one_source_of_variants(options, cmd);
  const std::uint64_t samples = parse_unsigned(cmd.samples, "--samples", 1000000);
  const std::uint64_t seed =
      parse_unsigned(cmd.seed, "--seed", std::numeric_limits<std::uint64_t>::max());
  const emnet::Scene scene = load_scene(options);
  const emnet::VariantTable table = variant_table(scene, cmd, samples, seed);
  const emnet::DesignStudyOptions study = design_study_options(options, cmd);
  const StudyOutputFile output = study_output_file(options, cmd);
  const emnet::DesignStudyResult result = emnet::run_design_study(scene, table, study);
  end_progress(options);
  stop_if_interrupted();
  const emnet::Json json = emnet::to_json(result);
  if (options.json) {
    std::cout << json_text(json) << "\n";
  } else {
    print_what_the_study_did(scene, result);
    print_the_statistics_of_each_column(result);
    print_the_failures_and_the_validity(result);
  }
  write_the_study_file(output, json, result);
  return result.outside_validity > 0 ? emnet::kExitOutsideValidity : 0;
}

Command add_study_command(CLI::App& app, CommonOptions& options) {
  auto study = std::make_shared<StudyCommandOptions>();
  auto* command = app.add_subcommand(
      "study",
      "a design study: many variants of the scene's numeric keys (a grid, Monte Carlo or a CSV\n"
      "list), the analyses per variant on every core, one row per variant (failed ones with\n"
      "their reason).\n"
      "Example: emnet study netlists/fishfin.toml --vary "
      "\"beam.bending_stiffness=normal(100%,5%)\"\n"
      "  --vary \"dea.A.lever_arm=uniform(95%,105%)\" --samples 1000 --seed 1\n"
      "  --analysis modes,static,sweep-switching --at 5 -o study.csv\n"
      "Reads the scene's keys named by --vary, [beam], [[dea]], [drive] (the sweep) and [[probe]]\n"
      "(static).");
  add_common(command, options);
  sets_fields(command
                  ->add_option("--vary", study->vary,
                               "KEY=SPEC: values v1,v2,... or linspace(a,b,n), logspace(a,b,n) (a "
                               "grid); uniform(a,b), normal(mean,sd), lognormal(median,s) (Monte "
                               "Carlo, with --samples); values in SI, with a unit (\"60 mm\") or "
                               "a percentage of the scene's value (\"95%\")")
                  ->allow_extra_args(false),
              {"variations"});
  sets_fields(command->add_option("--variants", study->variants,
                                  "a CSV file: a header of keys, one variant per line (instead "
                                  "of --vary)"),
              {"variants"});
  sets_fields(
      command->add_option("--samples", study->samples, "Monte Carlo draws (per grid point)"),
      {"samples"});
  command->add_option("--seed", study->seed, "the random generator's seed (default 1)");
  sets_fields(
      command->add_option("--analysis", study->analyses,
                          "comma-separated: modes, static, sweep-switching (default modes)"),
      {"analyses"});
  sets_fields(command->add_option("--modes", study->modes,
                                  "modes: the lowest K modes reported (default 1)"),
              {"mode_count"});
  sets_fields(command
                  ->add_option("--at", study->at,
                               "sweep-switching: report each output's periodic min and max at "
                               "this switching frequency [Hz] (repeatable)")
                  ->allow_extra_args(false),
              {"report_frequencies"});
  sets_fields(
      command->add_option("--from", study->from, "sweep-switching: first frequency (default 1 Hz)"),
      {"from"});
  sets_fields(
      command->add_option("--to", study->to, "sweep-switching: last frequency (default 7 Hz)"),
      {"to"});
  sets_fields(command->add_option("--step", study->step,
                                  "sweep-switching: frequency step [Hz] (default 0.1)"),
              {"step", "sweep_frequencies", "frequencies"});
  sets_fields(
      command->add_option("--threads", study->threads, "worker threads (default 0: every core)"),
      {"threads"});
  command->add_option("-o,--output", study->output, "write the table: FILE.csv or FILE.json");

  return {command, [study, &options] { return run_study_command(options, *study); }};
}

}  // namespace emnet_cli
