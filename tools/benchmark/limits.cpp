// Benchmark section 0, limits: each analysis of the fish fin against the arithmetic it needs,
// side by side with ngspice, all measured in this run.
//
// The limit of an analysis is the operation count of the method a careful implementation would
// use, divided by this machine's measured rate for dense double arithmetic (an Eigen matrix
// product, the best case of the arithmetic; so a ratio emnet/limit is, if anything, too
// pessimistic for emnet), and, for a whole process, the start of a program that does nothing
// (/bin/true) plus the bytes written at the measured copy bandwidth. The counts (n poles, P
// outputs, F frequencies, K output times, I intervals between switching edges):
//   eigen-decomposition of the n×n state matrix with vectors: 25·n³ (Hessenberg reduction,
//     the QR iteration and back-substitution: Golub and Van Loan's count);
//   AC, F frequencies: decomposition + F·(8·n + 16·n·P) (one complex reciprocal per pole, two
//     complex multiply-adds per pole and output);
//   exact transient: decomposition + I·16·n² (the interval's start in modal coordinates and
//     its end) + K·(12·n/2 + 8·n/2·P) (the addition theorem over one pole of each pair, a
//     complex dot product per output);
//   switching sweep, F frequencies, S samples per period: decomposition + F·(2·8·n + S·8·n/2·P)
//     (the periodic state in modal coordinates, every sample of every output);
//   IDA on the RC-loop fin: its own steps × (one residual, 4·nnz, and a solve with the factors,
//     4·nnz(L+U)) + its factorisations × 2·nnz(L+U)·(fill per column): the BDF method's own
//     arithmetic at the steps it needs; the count of steps is the method's, not a limit.
#include <Eigen/Dense>

#include "bench.hpp"

namespace emnet_bench {

namespace {

// Dense double arithmetic [flop/s]: a 192×192 Eigen product (2·n³ flops), the fastest of the
// repeats: the machine's rate when nothing else runs on its core (on this shared machine the
// median moved between 5.8 and 8.8 Gflop/s from run to run).
double arithmetic_rate() {
  const int n = 192;
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n), b = Eigen::MatrixXd::Random(n, n);
  Eigen::MatrixXd c(n, n);
  const Timing t = measure(
      [&] {
        c.noalias() = a * b;
        return -1.0;
      },
      50, 1.0);
  return 2.0 * n * n * n / t.minimum;
}

// Memory copy [byte/s]: 64 MiB read and written, the fastest of the repeats.
double copy_rate() {
  const size_t count = (size_t{64} << 20) / sizeof(double);
  std::vector<double> from(count, 1.0), to(count, 0.0);
  const Timing t = measure(
      [&] {
        std::copy(from.begin(), from.end(), to.begin());
        return -1.0;
      },
      10, 1.0);
  return 2.0 * count * sizeof(double) / t.minimum;
}

struct LimitRow {
  std::string analysis, method, limit_text;
  double limit = NAN, emnet = NAN, ngspice = NAN, goal = NAN;
  std::string note;
};

std::string limit_table(const std::vector<LimitRow>& rows) {
  std::ostringstream md;
  md << "| analysis | limit | emnet | emnet / limit | ngspice | ngspice / emnet | goal |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    md << "| " << r.analysis << " | " << time_text(r.limit) << " (" << r.limit_text << ") | "
       << time_text(r.emnet) << " (" << r.method << ") | " << ratio_text(r.emnet / r.limit) << " | "
       << (std::isfinite(r.ngspice) ? time_text(r.ngspice) : "–") << " | "
       << (std::isfinite(r.ngspice) ? ratio_text(r.ngspice / r.emnet) : "–") << " | "
       << (std::isfinite(r.goal)
               ? "≤ " + time_text(r.goal) +
                     (r.emnet <= r.goal ? ": met"
                                        : ": **missed by " + ratio_text(r.emnet / r.goal) + "**")
               : "–")
       << " |\n";
  }
  md << "\n";
  for (const auto& r : rows)
    if (!r.note.empty()) md << "- " << r.analysis << ": " << r.note << "\n";
  return md.str();
}

// ngspice's analysis in this process, median.
double ngspice_in_process(const std::string& deck, emnet::NgspiceResult* result = nullptr) {
  emnet::NgspiceResult last;
  const Timing t = measure(
      [&] {
        const auto start = Clock::now();
        last = emnet::run_ngspice(deck, in_process_ngspice());
        return seconds_since(start);
      },
      10, 3.0);
  if (result) *result = last;
  return last.status.ok() ? t.median : NAN;
}

// The fin's .tran deck as tools/bench runs ngspice by default: output step T/100, ngspice's own
// options (the deck's .options line removed).
std::string default_tran_deck(const emnet::Model& model, const std::vector<emnet::Probe>& probes,
                              double end_time, double period, emnet::SpiceDeck* deck = nullptr) {
  emnet::SpiceDeckOptions options;
  options.analysis = emnet::SpiceAnalysis::tran;
  options.outputs = probes;
  options.end_time = end_time;
  options.output_step = period / 100.0;
  options.relative_tolerance = 1e-3;
  const emnet::SpiceDeck written = emnet::write_spice_deck(model, options);
  if (deck) *deck = written;
  return remove_options_line(written.text);
}

// IDA on the RC-loop fin (the scene as it is: the exact method cannot serve), 50 periods from
// rest, 100 outputs per period, against ngspice's default .tran; both against IDA at rtol 1e-10
// (ngspice at its own time points, ±10ε around every edge left out as in ac.cpp and
// transient.cpp).
std::string ida_against_ngspice(const Settings& settings) {
  const emnet::Model model = build(settings.fishfin(), {});
  const emnet::System system = model.network.assemble();
  const auto probes = deflection_probes(model);
  const double period = 1.0 / model.scene.drive.frequency;
  emnet::TransientOptions options;
  options.end_time = (settings.quick ? 5 : 50) * period;
  const int count = static_cast<int>(std::lround(options.end_time / period * 100));
  for (int k = 0; k <= count; ++k) options.output_times.push_back(k * period / 100.0);
  emnet::TransientOptions tight = options;
  tight.relative_tolerance = 1e-10;
  const emnet::TransientResult reference = emnet::run_transient_ida(system, probes, tight);
  std::ostringstream md;
  md << "\n### IDA against ngspice on the RC-loop fin\n\n"
     << "Where the exact method cannot serve, IDA (variable-order BDF) is emnet's integrator: "
        "here against ngspice's transient on the same nonlinear network, "
     << std::lround(options.end_time / period)
     << " periods at 5 Hz from rest, 100 outputs per period; the goal: IDA at least 3× "
        "faster than ngspice at equal or smaller error. "
     << "The scene as it is (each DEA's electrode resistance and capacitance: the force is k_F·u² "
        "of the capacitor's voltage, so the exact method cannot serve). Error: the largest "
        "|difference| of the deflection outputs over the run, relative to each output's peak, "
        "against IDA at rtol 1e-10; ngspice at its own time points, ±10ε around every edge left "
        "out. Times: medians in this process.\n\n"
     << "| tool | setting | error | time | steps | residuals | Jacobians (factorisations) | "
        "Newton iterations |\n|---|---|---|---|---|---|---|---|\n";
  struct Run {
    double rtol, error, seconds;
  };
  std::vector<Run> runs;
  for (double rtol : {1e-2, 3e-3, 1e-3, 1e-4}) {
    emnet::TransientOptions at = options;
    at.relative_tolerance = rtol;
    emnet::TransientResult result;
    const Timing t = measure_ida(system, probes, at, result, 7, 3.0);
    const double error = result.status.ok() && reference.status.ok()
                             ? run_error(result.values, reference.values)
                             : NAN;
    runs.push_back({rtol, error, t.median});
    const auto& st = result.statistics;
    md << "| emnet IDA | rtol " << format("%.0e", rtol) << " | " << error_text(error) << " | "
       << t.text() << " | " << st.steps << " | " << st.residual_evaluations << " | "
       << st.jacobian_evaluations << " | " << st.newton_iterations << " |\n";
  }
  emnet::SpiceDeck deck;
  const std::string text = default_tran_deck(model, probes, options.end_time, period, &deck);
  emnet::NgspiceResult result;
  const double spice_seconds = ngspice_in_process(text, &result);
  double spice_error = NAN;
  if (result.status.ok() && result.scale()) {
    const SpicePoints points = spice_points_away_from_edges(
        result, deck, probes.size(), period, emnet::SpiceDeckOptions().edge_fraction * 0.5 * period,
        options.end_time);
    emnet::TransientOptions at = tight;
    at.output_times = points.kept;
    const emnet::TransientResult there = emnet::run_transient_ida(system, probes, at);
    const std::vector<std::vector<double>>& values = points.values;
    if (there.status.ok()) spice_error = run_error(values, there.values);
  }
  md << "| ngspice | default | " << error_text(spice_error) << " | " << time_text(spice_seconds)
     << " | | | | |\n\n";
  // Equal error: the fastest IDA run whose error is at most ngspice's.
  const Run* best = nullptr;
  for (const Run& r : runs)
    if (r.error <= spice_error && (!best || r.seconds < best->seconds)) best = &r;
  md << "At equal or smaller error: "
     << (best ? "IDA at rtol " + format("%.0e", best->rtol) + " (" + error_text(best->error) +
                    " in " + time_text(best->seconds) + ") against ngspice's " +
                    error_text(spice_error) + " in " + time_text(spice_seconds) + ": " +
                    ratio_text(spice_seconds / best->seconds) + " faster (goal ≥ 3×: " +
                    (spice_seconds / best->seconds >= 3.0 ? "met" : "**not met**") + ")"
              : std::string("no IDA run reached ngspice's error"))
     << ".\n\n";
  return md.str();
}

}  // namespace

namespace {

// What every row of the limits section measures against: the machine's rates and the fish fin's
// AC network (N = 7, ideal drive) with its poles.
struct LimitInputs {
  const Settings& settings;
  double rate = 0.0;       // dense arithmetic [flop/s]
  double bandwidth = 0.0;  // memory copy [B/s]
  Timing empty_process;    // /bin/true
  AcContext context;
  emnet::AcResult ac;
  double poles = 0.0, outputs = 0.0;
  double decomposition = 0.0;  // 25·n³ flop
  emnet::SpiceDeck ac_deck;    // the network's AC deck, for ngspice
};

LimitInputs limit_inputs(const Settings& settings) {
  LimitInputs in{settings};
  in.rate = arithmetic_rate();
  in.bandwidth = copy_rate();
  bool true_ok = true;
  in.empty_process = measure_process({"/bin/true"}, 20, 2.0, true_ok);
  in.context = ac_context(settings);
  in.ac = emnet::run_ac(in.context.system, in.context.rest.operating_point, in.context.grid,
                        in.context.probes);
  in.poles = static_cast<double>(in.ac.poles.size());
  in.outputs = static_cast<double>(in.context.probes.size());
  in.decomposition = 25.0 * in.poles * in.poles * in.poles;
  emnet::SpiceDeckOptions options;
  options.analysis = emnet::SpiceAnalysis::ac;
  options.outputs = in.context.probes;
  in.ac_deck = emnet::write_spice_deck(in.context.model, options);
  return in;
}

// The section's opening: how a limit is counted, and this machine's rates.
std::string limits_preamble(const LimitInputs& in) {
  std::ostringstream md;
  md << "How far each analysis of the fish fin (N = 7, ideal drive) is from the arithmetic it "
        "cannot avoid. The limit of an analysis is the operation count of the method a careful "
        "implementation would use, divided by this machine's rate for dense double arithmetic, "
        "measured as the fastest of repeated 192×192 matrix products: the most favourable rate, "
        "so the limit is a lower bound on the time and emnet / limit an upper bound on how far "
        "emnet is from it. For a whole process the limit adds the start of a program that does "
        "nothing (`/bin/true`) and the bytes written at the measured copy bandwidth. The counts "
        "(n poles, P outputs, F frequencies, K output times, I intervals between switching "
        "edges, S samples per period):\n\n"
        "- eigen-decomposition of the n×n state matrix with vectors: 25·n³ (Hessenberg "
        "reduction, QR iteration and back-substitution);\n"
        "- AC: the decomposition + F·(8·n + 16·n·P) (a complex reciprocal per pole, two complex "
        "multiply-adds per pole and output);\n"
        "- exact transient: the decomposition + I·16·n² (each interval's start and end in modal "
        "coordinates) + K·(6·n + 4·n·P) (the addition theorem over one pole of each conjugate "
        "pair, a complex dot product per output);\n"
        "- switching sweep: the decomposition + F·(16·n + S·4·n·P) (the periodic state in modal "
        "coordinates, every sample of every output).\n\n"
     << "Measured here: dense arithmetic " << format("%.1f", in.rate * 1e-9)
     << " Gflop/s (one core), memory copy " << format("%.1f", in.bandwidth * 1e-9)
     << " GB/s, an empty process (`/bin/true`) " << time_text(in.empty_process.median)
     << ". Times are medians in this process unless the row says whole process; each goal is "
        "an absolute time.\n\n";
  return md.str();
}

// AC: run_ac alone and from the scene file, ngspice's in-process time beside the first.
std::vector<LimitRow> ac_limit_rows(const LimitInputs& in) {
  const Settings& settings = in.settings;
  const AcContext& context = in.context;
  const auto& grid = context.grid;
  LimitRow row;
  row.analysis = "AC, " + std::to_string(grid.size()) + " points, N = 7";
  row.method = emnet::method_name(in.ac.method) + ", run_ac alone";
  const double flops =
      in.decomposition + grid.size() * (8.0 * in.poles + 16.0 * in.poles * in.outputs);
  row.limit = flops / in.rate;
  row.limit_text =
      format("%.2g flop", flops) + ", " + std::to_string(in.ac.poles.size()) + " poles";
  row.emnet =
      measure(
          [&] {
            return emnet::run_ac(context.system, context.rest.operating_point, grid, context.probes)
                .seconds;
          },
          50, 2.0)
          .median;
  row.ngspice = ngspice_in_process(in.ac_deck.text);
  row.goal = 1e-3;
  row.note = "pole-residue form checked at " + std::to_string(in.ac.check_points) +
             " frequencies, largest difference from the direct solve " +
             error_text(in.ac.check_deviation) +
             " of the peak (the error against a dense solve is under Against ngspice)";
  LimitRow scene = row;
  scene.analysis = "AC from the scene file";
  scene.method = emnet::method_name(in.ac.method) + ", read, build, static, run_ac";
  scene.emnet =
      measure([&] { return fishfin_ac_from_scene_seconds(settings, grid); }, 30, 2.0).median;
  scene.note.clear();
  return {row, scene};
}

// The scene's own RC-loop drive through `emnet ac`: its time and the method it took.
std::string rc_drive_ac_text(const LimitInputs& in) {
  const Settings& settings = in.settings;
  bool rc_ok = true;
  const Timing rc = measure_process({settings.emnet, "ac", settings.fishfin()}, 10, 3.0, rc_ok);
  const emnet::Model rc_model = build(settings.fishfin(), {});
  const emnet::System rc_system = rc_model.network.assemble();
  const emnet::AcResult rc_ac =
      emnet::run_ac(rc_system, emnet::solve_static(rc_system).operating_point, in.context.grid,
                    deflection_probes(rc_model));
  return time_text(rc.median) + " (" + emnet::method_name(rc_ac.method) +
         (rc_ac.note.empty() ? "" : ": " + rc_ac.note) + ")";
}

// Whole process: `emnet ac` against `ngspice -b` on the same deck; ac_limit is run_ac's limit.
LimitRow ac_process_limit_row(const LimitInputs& in, double ac_limit) {
  const Settings& settings = in.settings;
  LimitRow row;
  row.analysis = "AC, whole process";
  row.method = "`emnet ac` (ideal drive), 1000 rows written";
  const double bytes = 1000.0 * (15.0 + 29.0 * in.context.model.probes.size());
  row.limit = in.empty_process.median + ac_limit + bytes / in.bandwidth;
  row.limit_text = "empty process + AC limit + " + format("%.0f kB", bytes * 1e-3) + " written";
  bool ok = true;
  row.emnet = measure_process(emnet_cli(settings, "ac", {}), 20, 3.0, ok).median;
  bool help_ok = true;
  const Timing help = measure_process({settings.emnet, "--help"}, 20, 2.0, help_ok);
  bool ngspice_ok = true;
  const Timing ngspice = ngspice_process(
      settings, write_deck(settings, "limits-ac", in.ac_deck.text), 10, 3.0, ngspice_ok);
  row.ngspice = ngspice_ok ? ngspice.median : NAN;
  row.goal = 5e-3;
  row.note = "`emnet --help` alone " + time_text(help.median) + " (" +
             format("%.0f", 100.0 * help.median / row.emnet) +
             " % of the command; program start: the dynamic loader, static initialisers, the "
             "commands' options); the scene's own RC-loop drive (`emnet ac "
             "netlists/fishfin.toml`) " +
             rc_drive_ac_text(in);
  return row;
}

// Exact transient, 50 periods, 100 outputs per period, and with one output per period.
LimitRow exact_transient_limit_row(const LimitInputs& in) {
  const emnet::Model& model = in.context.model;
  const emnet::System& system = in.context.system;
  const auto& probes = in.context.probes;
  const double period = 1.0 / model.scene.drive.frequency;
  emnet::TransientOptions options;
  options.end_time = 50 * period;
  for (int k = 0; k <= 5000; ++k) options.output_times.push_back(k * period / 100.0);
  LimitRow row;
  row.analysis = "exact transient, 50 periods, 5001 outputs";
  row.method = "modal, run_transient_exact alone";
  const double intervals = 100.0, times = 5001.0;
  const double flops = in.decomposition + intervals * 16.0 * in.poles * in.poles +
                       times * (6.0 * in.poles + 4.0 * in.poles * in.outputs);
  row.limit = flops / in.rate;
  row.limit_text = format("%.2g flop", flops);
  row.emnet =
      measure([&] { return emnet::run_transient_exact(system, probes, options).seconds; }, 20, 2.0)
          .median;
  row.ngspice = ngspice_in_process(default_tran_deck(model, probes, options.end_time, period));
  row.goal = 1e-3;
  emnet::TransientOptions few = options;
  few.output_times.clear();
  for (int k = 0; k <= 50; ++k) few.output_times.push_back(k * period);
  const double sparse =
      measure([&] { return emnet::run_transient_exact(system, probes, few).seconds; }, 20, 2.0)
          .median;
  row.note = "with 51 outputs " + time_text(sparse) + ": the outputs cost " +
             time_text((row.emnet - sparse) / 4950.0) +
             " each; the fixed part is the state equation (equilibration and the QR of E, " +
             std::to_string(system.size()) + " unknowns) and its " +
             std::to_string(in.ac.poles.size()) + "-pole eigen-decomposition, then " +
             "per interval the modal start and end (ngspice: default options)";
  return row;
}

// Switching sweep, 61 frequencies, by the exact periodic solver with 64 samples.
LimitRow switching_sweep_limit_row(const LimitInputs& in) {
  SweepContext context = sweep_context(in.settings);
  LimitRow row;
  row.analysis = "switching sweep, " + std::to_string(context.frequencies.size()) + " frequencies";
  row.method = "exact PeriodicSolver, 64 samples";
  const double frequencies = static_cast<double>(context.frequencies.size());
  const double flops =
      in.decomposition + frequencies * (16.0 * in.poles + 64.0 * 4.0 * in.poles * in.outputs);
  row.limit = flops / in.rate;
  row.limit_text = format("%.2g flop", flops);
  DirectSweepParts parts;
  row.emnet = measure([&] { return direct_sweep(context, 64, &parts), -1.0; }, 20, 3.0).median;
  row.goal = 2e-3;
  row.note = "of which decomposition " + time_text(parts.decomposition) +
             ", the drives' excitations " + time_text(parts.build) + ", the model " +
             time_text(parts.assemble) + ", the 61 periodic solves with their global extremes " +
             time_text(parts.solve) +
             " (ngspice needs a transient per frequency until settled: see the switching "
             "sweep under Against ngspice)";
  return row;
}

}  // namespace

std::string limits_section(const Settings& settings) {
  const LimitInputs in = limit_inputs(settings);
  std::vector<LimitRow> rows = ac_limit_rows(in);
  rows.push_back(ac_process_limit_row(in, rows.front().limit));
  rows.push_back(exact_transient_limit_row(in));
  rows.push_back(switching_sweep_limit_row(in));
  std::ostringstream md;
  md << limits_preamble(in) << limit_table(rows)
     << "\nWhere a goal is missed, the notes split the time as this run measured it: a fixed "
        "part (the state equation and its eigen-decomposition, the program's start) against a "
        "part per frequency, output or interval. Below that split, a profile of the analysis "
        "in a loop (`perf record`) or of the program (`perf stat`: page faults, instructions) "
        "shows which function the time is in.\n";
  md << ida_against_ngspice(settings);
  return md.str();
}

}  // namespace emnet_bench
