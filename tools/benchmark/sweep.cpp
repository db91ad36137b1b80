// Benchmark section 2/3, the switching sweep: the periodic steady state at 61 frequencies by
// emnet::run_switching_sweep (the exact method of `emnet sweep-switching`), by running the exact
// transient until settled, and by ngspice's .tran until settled.
#include "bench.hpp"

namespace emnet_bench {

// ---- the switching sweep ---------------------------------------------------------------------

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

// The direct sweep by emnet::run_switching_sweep, as `emnet sweep-switching` runs it: one
// PeriodicSolver, one model prepared and assembled once, the drive's excitation made again per
// frequency (f1 not asked for: no modes). Fills the time spent in each part (`decomposition`:
// PeriodicSolver's; `build`: the drive's excitation made and set per frequency; `assemble`:
// preparing and assembling the model once; `solve`: the periodic solves; `total`: all of it,
// with the study's checks and the validity of its peaks).
std::vector<Peaks> direct_sweep(const SweepContext& context, int samples, DirectSweepParts* parts) {
  const auto start = Clock::now();
  const auto prepare_start = Clock::now();
  const emnet::Model model = emnet::prepare_model(context.scene);
  const double prepare_seconds = seconds_since(prepare_start);
  emnet::SwitchingSweepOptions options;
  options.frequencies = context.frequencies;
  options.samples = samples;
  options.outputs = context.probes;
  options.first_mode = false;
  const emnet::SwitchingSweepResult result =
      emnet::run_switching_sweep(model, context.scene, options);
  if (!result.status.ok()) throw std::runtime_error("switching sweep: " + result.status.message);
  std::vector<Peaks> peaks(result.frequencies.size());
  for (size_t k = 0; k < peaks.size(); ++k)
    for (const auto& output : result.outputs) {
      peaks[k].minimum.push_back(output.left[k]);
      peaks[k].maximum.push_back(output.right[k]);
    }
  if (parts) {
    parts->decomposition = result.decomposition_seconds;
    parts->build = result.excitation_seconds;
    parts->assemble = prepare_seconds + result.model_seconds;
    parts->solve = result.solve_seconds;
    parts->total = seconds_since(start);
  }
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
      if (!run.status.ok()) break;
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

namespace {

// emnet's direct sweep with 64 samples per period (sweep-switching's default for the exact
// method), in process and as the command; `parts` gets where one run's time went.
MethodRow direct_sweep_row(const Settings& settings, const SweepContext& context,
                           const std::vector<Peaks>& reference, DirectSweepParts& parts) {
  MethodRow row{"emnet", "direct (PeriodicSolver)", "64 samples"};
  const std::vector<Peaks> peaks = direct_sweep(context, 64);
  row.error = sweep_error(peaks, reference);
  row.in_process = measure([&] { return direct_sweep(context, 64, &parts), -1.0; }, 20, 3.0);
  bool ok = true;
  row.whole_process =
      measure_process({settings.emnet, "sweep-switching", settings.fishfin(), "--from", "1", "--to",
                       "7", "--step", settings.quick ? "1" : "0.1"},
                      10, 3.0, ok);
  row.note = "from the read scene; exact method of `emnet sweep-switching`";
  return row;
}

// The exact transient from rest until the peaks settle to `threshold`; `periods` gets each
// frequency's count (0: not settled).
MethodRow settled_sweep_row(const SweepContext& context, const std::vector<Peaks>& reference,
                            double threshold, std::vector<int>& periods) {
  MethodRow row{"emnet", "run until settled (exact transient)",
                "change/period < " + format("%.0e", threshold)};
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
  return row;
}

// One ngspice setting of the sweep: its name, RELTOL (0: ngspice's default) and whether the
// whole-process time is measured too.
struct SpiceSetting {
  std::string name;
  double reltol;
  bool whole_process;
};

// A transient deck per frequency, from rest for the periods the exact transient needed.
struct SpiceSweepDecks {
  std::vector<std::string> decks;
  std::vector<std::vector<emnet::SpiceOutput>> outputs;
  std::vector<double> end_times;
};

SpiceSweepDecks spice_sweep_decks(const SweepContext& context,
                                  const std::vector<int>& spice_periods,
                                  const SpiceSetting& setting) {
  SpiceSweepDecks out;
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
    out.decks.push_back(setting.reltol > 0.0 ? deck.text : remove_options_line(deck.text));
    out.outputs.push_back(deck.outputs);
    out.end_times.push_back(options.end_time);
  }
  return out;
}

// The peaks of each deck's last period, refined as emnet's; `failed` when ngspice failed or an
// output is missing.
std::vector<Peaks> ngspice_sweep_peaks(const SweepContext& context, const SpiceSweepDecks& decks,
                                       bool& failed) {
  std::vector<Peaks> peaks(context.frequencies.size());
  for (size_t k = 0; k < decks.decks.size(); ++k) {
    const emnet::NgspiceResult result = emnet::run_ngspice(decks.decks[k], in_process_ngspice());
    if (!result.status.ok() || !result.scale()) {
      failed = true;
      return peaks;
    }
    const std::vector<double>& times = result.scale()->real_values;
    const double period = 1.0 / context.frequencies[k];
    size_t begin = 0;
    while (begin < times.size() && times[begin] < decks.end_times[k] - period - 1e-12) ++begin;
    for (size_t p = 0; p < context.probes.size(); ++p) {
      const emnet::NgspiceVector* vector = result.find(decks.outputs[k][p].vector);
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
  return peaks;
}

// One `ngspice -b -r` per frequency, timed together; `ok` false when any failed.
Timing ngspice_sweep_processes(const Settings& settings, const SpiceSweepDecks& decks, bool& ok) {
  std::vector<std::string> paths;
  for (size_t k = 0; k < decks.decks.size(); ++k)
    paths.push_back(write_deck(settings, "fishfin-sweep-" + std::to_string(k), decks.decks[k]));
  const auto start = Clock::now();
  for (const auto& path : paths) {
    bool one = true;
    ngspice_process(settings, path, 1, 0.0, one);
    ok = ok && one;
  }
  return summarise({seconds_since(start)});
}

// ngspice with `setting`: each frequency for the periods the exact transient needed, from rest.
MethodRow ngspice_sweep_row(const Settings& settings, const SweepContext& context,
                            const std::vector<Peaks>& reference,
                            const std::vector<int>& spice_periods, const SpiceSetting& setting) {
  MethodRow row{"ngspice", ".tran until settled", setting.name};
  const SpiceSweepDecks decks = spice_sweep_decks(context, spice_periods, setting);
  bool failed = false;
  const auto start = Clock::now();
  const std::vector<Peaks> peaks = ngspice_sweep_peaks(context, decks, failed);
  row.in_process = summarise({seconds_since(start)});
  row.error = failed ? NAN : sweep_error(peaks, reference);
  if (setting.whole_process) {
    bool ok = true;
    row.whole_process = ngspice_sweep_processes(settings, decks, ok);
    if (!ok) row.note += "whole process failed; ";
  }
  row.note += std::string("1 run") + (failed ? "; ngspice failed" : "");
  return row;
}

// The subsection's text: what is compared, the table, and where the direct sweep's time goes.
std::string sweep_markdown(const SweepContext& context, const std::vector<MethodRow>& rows,
                           const DirectSweepParts& parts) {
  std::ostringstream md;
  md << "### Switching sweep: periodic steady state at " << context.frequencies.size()
     << " frequencies (" << context.frequencies.front() << "–" << context.frequencies.back()
     << " Hz), fish fin (ideal drive)\n\n"
     << "Peaks to either side of every deflection output. Error: the largest |peak − "
        "reference| over frequencies, relative to that output's largest peak over the sweep; "
        "reference: the direct method with 1024 samples per period (extremes refined by "
        "Newton). emnet direct: emnet::run_switching_sweep, the exact method of `emnet "
        "sweep-switching` (one PeriodicSolver, one model, its excitation per frequency) from "
        "the read scene; whole process: `emnet sweep-switching "
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
     << time_text(parts.decomposition) << ", the drive's excitation made and set per frequency "
     << time_text(parts.build) << ", building and assembling the model once "
     << time_text(parts.assemble) << ", the periodic solves " << time_text(parts.solve)
     << "; total " << time_text(parts.total) << ".\n";
  return md.str();
}

// The sweep's goal line: the direct sweep's in-process time against 10 ms, and its parts.
std::string goal_sweep_line(double sweep_seconds, const DirectSweepParts& parts) {
  return time_text(sweep_seconds) +
         (sweep_seconds < 10e-3
              ? " (met)"
              : " (**not met**, by " + format("%.0f", 100.0 * (sweep_seconds / 10e-3 - 1.0)) +
                    " %)") +
         " in-process (solves " + time_text(parts.solve) + ", model and excitations " +
         time_text(parts.build + parts.assemble) + ", decomposition " +
         time_text(parts.decomposition) + ")";
}

}  // namespace

Section sweep_section(const Settings& settings, std::vector<ParetoPoint>& pareto,
                      std::string& goal_sweep_text) {
  const SweepContext context = sweep_context(settings);
  const std::vector<Peaks> reference = direct_sweep(context, 1024);
  DirectSweepParts parts;
  std::vector<MethodRow> rows{direct_sweep_row(settings, context, reference, parts)};
  std::vector<int> spice_periods;
  const std::vector<double> thresholds =
      settings.quick ? std::vector<double>{1e-3} : std::vector<double>{1e-2, 1e-3, 1e-4, 1e-6};
  for (double threshold : thresholds) {
    std::vector<int> periods;
    rows.push_back(settled_sweep_row(context, reference, threshold, periods));
    if (threshold == 1e-4 || settings.quick) spice_periods = periods;
  }
  const std::vector<SpiceSetting> spice_settings =
      settings.quick
          ? std::vector<SpiceSetting>{{"default", 0.0, true}}
          : std::vector<SpiceSetting>{{"default", 0.0, true}, {"reltol 1e-5", 1e-5, false}};
  for (const auto& setting : spice_settings)
    rows.push_back(ngspice_sweep_row(settings, context, reference, spice_periods, setting));
  for (const auto& row : rows) {
    pareto.push_back({row.tool + " " + row.method + " in-process", row.setting,
                      row.in_process.median, row.error});
    if (row.whole_process.repetitions > 0)
      pareto.push_back({row.tool + " " + row.method + " whole process", "",
                        row.whole_process.median, row.error});
  }
  Section section;
  section.headline = headline(rows);
  section.markdown = sweep_markdown(context, rows, parts);
  goal_sweep_text = goal_sweep_line(rows[0].in_process.median, parts);
  return section;
}

}  // namespace emnet_bench
