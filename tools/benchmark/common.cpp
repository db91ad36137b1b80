// The benchmark's shared pieces (declared in bench.hpp): formats, timing, processes, peaks,
// Pareto plots, method tables and their headline, ngspice helpers.
#include <filesystem>

#include "bench.hpp"

namespace emnet_bench {

std::string Settings::figure(const std::string& name) const {
  return figures + "/bench-" + name + ".png";
}

std::string Settings::figure_link(const std::string& name) const {
  namespace fs = std::filesystem;
  const fs::path from = fs::absolute(fs::path(report)).lexically_normal().parent_path();
  const fs::path to = fs::absolute(fs::path(figure(name))).lexically_normal();
  return to.lexically_relative(from).generic_string();
}

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
// Runs argv[0] (searched in PATH) through emnet's process helper, standard input and error
// /dev/null, standard output /dev/null or, with `capture`, kept (at most 1 MiB). `seconds` is
// the program's run as its supervisor sees it, from just before it is started until it is
// reaped (emnet/core/process.hpp): the program's own start, work and exit, without the
// supervisor's start or the clean-up after the program.
ProcessRun run_process(const std::vector<std::string>& arguments, bool capture,
                       double timeout_seconds) {
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
  run.succeeded = end.exited_with(0) || (emnet_run && end.exited_with(emnet::kExitOutsideValidity));
  run.output = end.standard_output;
  return run;
}

Timing measure_process(const std::vector<std::string>& arguments, int repetitions,
                       double budget_seconds, bool& ok) {
  ok = true;
  return measure(
      [&] {
        const ProcessRun run = run_process(arguments);
        if (!run.succeeded) ok = false;
        return run.seconds;
      },
      repetitions, budget_seconds);
}
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

double fishfin_ac_from_scene_seconds(const Settings& settings, const std::vector<double>& grid) {
  const auto start = Clock::now();
  const emnet::Model m = build(settings.fishfin(), ideal_drive);
  const emnet::System s = m.network.assemble();
  const emnet::StaticResult r = emnet::solve_static(s);
  emnet::run_ac(s, r.operating_point, grid, deflection_probes(m));
  return seconds_since(start);
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

// One gnuplot script and one data block per series (error floored at 1e-16 for the log axis):
// out/bench-<name>.gp and .dat, plotting to settings.figure(name).
void write_pareto_plot(const Settings& settings, const std::string& name, const std::string& title,
                       const std::vector<ParetoPoint>& points) {
  std::vector<std::string> series;
  for (const auto& point : points)
    if (std::find(series.begin(), series.end(), point.series) == series.end())
      series.push_back(point.series);
  const std::string data_path = settings.out + "/bench-" + name + ".dat";
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
  std::ofstream script(settings.out + "/bench-" + name + ".gp");
  script << plot_preamble(settings.figure(name), title)
         << "set logscale xy\nset format x '%.0e'\nset format y '%.0e'\n"
         << "set xlabel 'wall time [s] (median)'\nset ylabel 'error relative to peak (exact "
            "results at 1e-16)'\n"
         << "set key below maxrows 3\n"
         << "plot ";
  // Labels of neighbouring points on alternate sides (right and above, left and below), so
  // that close points' labels do not overlap.
  for (size_t k = 0; k < series.size(); ++k) {
    script << (k ? ", \\\n     " : "") << "'" << data_path << "' index " << k
           << " using 1:2 with linespoints ls " << k + 1 << " title '" << series[k]
           << "', '' index " << k
           << " every 2 using 1:2:3 with labels offset 0.8,0.6 left font ',8' tc ls " << k + 1
           << " notitle";
    if (std::count_if(points.begin(), points.end(),
                      [&](const ParetoPoint& p) { return p.series == series[k]; }) > 1)
      script << ", '' index " << k
             << " every 2::1 using 1:2:3 with labels offset -0.8,-0.6 right font ',8' tc ls "
             << k + 1 << " notitle";
  }
  script << "\n";
}

// The terminal, output, title and line styles every plot shares: dark colours that read on
// white (no yellow), a different point type for each.
std::string plot_preamble(const std::string& png, const std::string& title) {
  static const char* const colours[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                        "#000000", "#56b4e9", "#8c564b", "#7f7f7f"};
  std::ostringstream out;
  out << "set terminal pngcairo size 960,680 noenhanced font ',10'\n"
      << "set output '" << png << "'\n"
      << "set title '" << title << "'\n"
      << "set grid\n";
  for (int k = 0; k < 8; ++k)
    out << "set style line " << k + 1 << " lc rgb '" << colours[k] << "' lw 1.5 pt " << k + 4
        << " ps 1.2\n";
  return out.str();
}

// Largest |a − b| over outputs and kept times, relative to each output's peak |b|.
Timing measure_ida(const emnet::System& system, const std::vector<emnet::Probe>& probes,
                   const emnet::TransientOptions& options, emnet::TransientResult& last,
                   int repetitions, double budget_seconds) {
  return measure(
      [&] {
        last = emnet::run_transient_ida(system, probes, options);
        return last.seconds;
      },
      repetitions, budget_seconds);
}

double run_error(const std::vector<std::vector<double>>& values,
                 const std::vector<std::vector<double>>& reference, const std::vector<bool>& keep) {
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

namespace {

// "ngspice default (7.0e-03, 90.9 ms) against emnet exact (rounding, 12.2 ms)": the pair of a
// headline, whole-process times.
std::string pair_text(const MethodRow& spice, const MethodRow& own) {
  auto error = [](double e) { return e > 0.0 ? error_text(e) : std::string("rounding"); };
  auto setting = [](const MethodRow& row) {
    return row.setting == "–" || row.setting.empty() ? std::string() : " " + row.setting;
  };
  return "ngspice" + setting(spice) + " (" + error(spice.error) + ") against emnet " + own.method +
         setting(own) + " (" + error(own.error) + ")";
}

}  // namespace

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
        if (whole) {
          h.whole_process_spice = spice_time.median;
          h.whole_process_own = best->whole_process.median;
        }
        (whole ? h.whole_process_pair : h.in_process_pair) = pair_text(spice, *best);
      }
    }
  }
  // Against ngspice's most accurate run, whole process.
  const MethodRow* accurate = nullptr;
  for (const auto& spice : rows)
    if (spice.tool == "ngspice" && std::isfinite(spice.error) &&
        spice.whole_process.repetitions > 0 && (!accurate || spice.error < accurate->error))
      accurate = &spice;
  if (accurate) {
    const MethodRow* best = nullptr;
    for (const auto& own : rows)
      if (own.tool == "emnet" && own.error <= accurate->error &&
          own.whole_process.repetitions > 0 &&
          (!best || own.whole_process.median < best->whole_process.median))
        best = &own;
    if (best) {
      h.accurate = accurate->whole_process.median / best->whole_process.median;
      h.accurate_pair = pair_text(*accurate, *best);
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

SpicePoints spice_points_away_from_edges(const emnet::NgspiceResult& result,
                                         const emnet::SpiceDeck& deck, size_t outputs,
                                         double period, double edge_width, double end_time) {
  SpicePoints points;
  points.values.assign(outputs, {});
  if (!result.scale()) return points;
  const std::vector<double>& times = result.scale()->real_values;
  const double half = 0.5 * period;
  std::vector<bool> keep(times.size());
  for (size_t k = 0; k < times.size(); ++k) {
    keep[k] = std::abs(times[k] - half * std::round(times[k] / half)) > 10.0 * edge_width &&
              times[k] <= end_time;
    if (keep[k]) points.kept.push_back(times[k]);
  }
  for (size_t p = 0; p < outputs; ++p) {
    const emnet::NgspiceVector* vector = result.find(deck.outputs[p].vector);
    if (!vector) continue;
    for (size_t k = 0; k < times.size(); ++k)
      if (keep[k]) points.values[p].push_back(vector->real_values[k]);
  }
  return points;
}

std::string remove_options_line(const std::string& deck) {
  std::istringstream in(deck);
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(".options", 0) != 0) out << line << "\n";
  return out.str();
}

}  // namespace emnet_bench
