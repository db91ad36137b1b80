// Benchmark sections 5b (modal reduction: run_ac_reduced and ReducedPeriodicSolver against the
// full analyses) and 5a (simplifications: the automatic segment count, the ideal drive against
// the RC drive).
#include "bench.hpp"
#include "emnet/core/constants.hpp"

namespace emnet_bench {

// ---- 5b. modal reduction ----------------------------------------------------------------------

// 5b. Modal reduction (modal_reduction.hpp) against the full model, side by side in this run.
// AC: the fish fin's 1000-point sweep (0–10 Hz, band 10 Hz) by run_ac and by run_ac_reduced
// (time: reduction + evaluation, without its own check); error: the largest |difference| over
// all 1000 points, relative to each probe's largest |response|. Periodic: the 61-frequency
// switching sweep (1–7 Hz, ideal drive, band 7 Hz, 256 samples) by PeriodicSolver and by
// ReducedPeriodicSolver, each with its one-off decomposition or reduction; error: the largest
// periodic_difference (every sample, relative to each probe's largest |deflection|).
namespace {

// Per N: the full time and the range of speed-ups over the tolerances, for the summary.
struct SpeedUpSummary {
  int n = 0;
  double full = 0.0, slowest = INFINITY, fastest = 0.0;
  void add(double speed_up) {
    slowest = std::min(slowest, speed_up);
    fastest = std::max(fastest, speed_up);
  }
};

// A line per N: faster or slower, by how much, and why when slower.
std::string speed_up_summary_text(const std::vector<SpeedUpSummary>& rows,
                                  const std::string& one_off) {
  std::ostringstream text;
  for (const SpeedUpSummary& r : rows) {
    text << "- N = " << r.n << " (full " << time_text(r.full) << "): the reduced "
         << (r.slowest >= 1.0  ? "is faster, "
             : r.fastest < 1.0 ? "is slower, "
                               : "is faster at some tolerances and slower at others, ")
         << (ratio_text(r.slowest) == ratio_text(r.fastest)
                 ? ratio_text(r.slowest)
                 : ratio_text(r.slowest) + " to " + ratio_text(r.fastest))
         << " the full speed"
         << (r.fastest < 1.0 ? ": at this size " + one_off + " outweighs what it saves" : "")
         << ".\n";
  }
  return text.str();
}

// The last column of a reduction row: failed (why), met, or not met.
std::string tolerance_verdict(const std::string& failure, double error, double tolerance) {
  return !failure.empty() ? "failed: " + failure : error <= tolerance ? "met" : "**not met**";
}

// The AC table's rows for the fish fin at N segments, one per tolerance.
std::string ac_reduction_rows(const Settings& settings, int n,
                              const std::vector<double>& tolerances, SpeedUpSummary& summary) {
  std::ostringstream md;
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
  summary = {n, full_time.median};
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
    if (reduced.status.ok() && full.status.ok()) {
      const std::vector<double> errors =
          emnet::errors_relative_to_peak(reduced.ac.values, full.values);
      error = *std::max_element(errors.begin(), errors.end());
    }
    summary.add(full_time.median / reduced_time.median);
    md << "| " << n << " | " << system.size() << " | " << format("%.0e", tolerance) << " | "
       << format("%.4g Hz", reduced.model.cutoff_hz) << " | " << reduced.model.kept_modes << " ("
       << emnet::method_name(reduced.model.modal_method)
       << (reduced.model.correction_order > 0
               ? ", s^" + std::to_string(reduced.model.correction_order)
               : std::string())
       << ") | " << full_time.text() << " | " << reduced_time.text() << " | "
       << ratio_text(full_time.median / reduced_time.median) << " | " << error_text(error) << " | "
       << tolerance_verdict(reduced.status.ok() ? "" : reduced.status.message, error, tolerance)
       << " |\n";
  }
  return md.str();
}

// The fish fin at N segments, assembled at each switching frequency of the periodic sweep.
std::vector<emnet::System> periodic_sweep_systems(const Settings& settings,
                                                  const emnet::Scene& scene) {
  std::vector<emnet::System> systems;
  const int count = settings.quick ? 7 : 61;
  for (int k = 0; k < count; ++k) {
    emnet::Scene at = scene;
    at.drive.frequency = 1.0 + (settings.quick ? 1.0 : 0.1) * k;
    systems.push_back(emnet::prepare_model(at).network.assemble());
  }
  return systems;
}

// The periodic table's rows for the fish fin at N segments, one per tolerance.
std::string periodic_reduction_rows(const Settings& settings, int n,
                                    const std::vector<double>& tolerances,
                                    SpeedUpSummary& summary) {
  std::ostringstream md;
  std::vector<std::string> overrides = ideal_drive;
  overrides.push_back("beam.segments=" + std::to_string(n));
  const emnet::Scene scene = emnet::read_scene(settings.fishfin(), overrides);
  const std::vector<emnet::Probe> probes = deflection_probes(emnet::prepare_model(scene));
  const std::vector<emnet::System> systems = periodic_sweep_systems(settings, scene);
  const auto period = [&](size_t k) { return 1.0 / (1.0 + (settings.quick ? 1.0 : 0.1) * k); };
  std::vector<emnet::PeriodicResult> full(systems.size());
  const Timing full_time = measure(
      [&] {
        const emnet::PeriodicSolver solver(systems[0]);
        for (size_t k = 0; k < systems.size(); ++k)
          full[k] = solver.solve(systems[k], probes, period(k));
        return -1.0;
      },
      5, 5.0);
  summary = {n, full_time.median};
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
            reduced[k] = solver.solve(systems[k], probes, period(k));
          return -1.0;
        },
        5, 5.0);
    double error = 0.0;
    for (size_t k = 0; k < systems.size(); ++k) {
      if (!reduced[k].status.ok() || !full[k].status.ok()) {
        failure = (reduced[k].status.ok() ? full[k] : reduced[k]).status.message;
        error = NAN;
        break;
      }
      error = std::max(error, emnet::periodic_difference(reduced[k], full[k]));
    }
    const double speed_up = full_time.median / reduced_time.median;
    summary.add(speed_up);
    md << "| " << n << " | " << format("%.0e", tolerance) << " | " << kept << " | "
       << full_time.text() << " | " << reduced_time.text() << " | " << ratio_text(speed_up)
       << (speed_up < 1.0 ? " (slower)" : "") << " | " << error_text(error) << " | "
       << tolerance_verdict(failure, error, tolerance) << " |\n";
  }
  return md.str();
}

}  // namespace

std::string reduction_section(const Settings& settings) {
  std::ostringstream md;
  const std::vector<int> sizes =
      settings.quick ? std::vector<int>{7, 100} : std::vector<int>{7, 100, 500};
  const std::vector<double> tolerances =
      settings.quick ? std::vector<double>{1e-2, 1e-3} : std::vector<double>{1e-2, 1e-3, 1e-4};
  md << "What the modal reduction saves and what it costs in accuracy: "
     << "modes below f_c = band/√tol kept, the rest as a static correction (AC: a Taylor series "
        "in s when Arnoldi stops below f_c) (`emnet ac --reduce`, `emnet sweep-switching "
        "--reduce`; "
        "[commands.md](commands.md#modal-reduction-ac---reduce-sweep-switching---reduce)). "
        "Full and reduced timed side by side in this run; the error is measured against the "
        "full model at every point.\n\n"
     << "AC, fish fin, 1000 points 0–10 Hz, band 10 Hz (reduced time: poles, left vectors, "
        "static solve(s) and evaluation; s^m: the correction's series order):\n\n"
     << "| N | unknowns | tol | f_c | kept modes (method) | full run_ac | reduced | speed-up | "
        "max error | |\n|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<SpeedUpSummary> ac_summary(sizes.size());
  for (size_t i = 0; i < sizes.size(); ++i)
    md << ac_reduction_rows(settings, sizes[i], tolerances, ac_summary[i]);
  md << "\n"
     << speed_up_summary_text(ac_summary,
                              "the reduction's one-off work (poles, left vectors, static solves)");
  md << "\nPeriodic steady state, fish fin (ideal drive), 61 switching frequencies 1–7 Hz, "
        "band 7 Hz, 256 samples (times include the one-off decomposition or reduction):\n\n"
     << "| N | tol | kept modes | full (PeriodicSolver) | reduced | speed-up | max error | |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  const std::vector<int> periodic_sizes =
      settings.quick ? std::vector<int>{7} : std::vector<int>{7, 100};
  std::vector<SpeedUpSummary> periodic_summary(periodic_sizes.size());
  for (size_t i = 0; i < periodic_sizes.size(); ++i)
    md << periodic_reduction_rows(settings, periodic_sizes[i], tolerances, periodic_summary[i]);
  md << "\n"
     << speed_up_summary_text(periodic_summary,
                              "the reduction's one-off work (its modes and static correction)")
     << "\nA tolerance is met when the largest error is at most the tolerance.\n";
  return md.str();
}

// ---- 5a. simplifications ---------------------------------------------------------------------

namespace {

// How many times and how long each item of section 5a is measured.
struct Repeats {
  int repetitions;
  double budget;  // s
};

// The bare fin beam's frequencies up to band_top [Hz], converged by Richardson from N = n and 2n.
std::vector<double> converged_beam_frequencies(const emnet::BeamSpec& beam, int n,
                                               double band_top) {
  const std::vector<double> coarse = emnet::beam_frequencies(beam, n, 5);
  const std::vector<double> fine = emnet::beam_frequencies(beam, 2 * n, 5);
  std::vector<double> converged;
  for (size_t k = 0; k < coarse.size() && k < fine.size(); ++k)
    if (emnet::richardson_extrapolate(coarse[k], fine[k]) <= band_top)
      converged.push_back(emnet::richardson_extrapolate(coarse[k], fine[k]));
  return converged;
}

// The worst relative error of the beam's modes at `segments` against the converged ones.
double beam_error(const emnet::BeamSpec& beam, int segments, const std::vector<double>& converged) {
  const std::vector<double> f = emnet::beam_frequencies(beam, segments, 5);
  double worst = 0.0;
  for (size_t k = 0; k < converged.size() && k < f.size(); ++k)
    worst = std::max(worst, std::abs(f[k] - converged[k]) / converged[k]);
  return worst;
}

// The analyses the segment choice serves, on the full fin model (damped, RC DEAs) at `segments`:
// run_modes (5 lowest modes) and an AC sweep over `grid` (P2-P4, tip).
std::pair<Timing, Timing> modes_and_ac_times(const Settings& settings, int segments,
                                             const std::vector<double>& grid,
                                             const Repeats& repeats) {
  const emnet::Model m = build(settings.fishfin(), {"beam.segments=" + std::to_string(segments)});
  const emnet::System system = m.network.assemble();
  const Eigen::VectorXd rest = emnet::solve_static(system).operating_point;
  emnet::ModalOptions options;
  options.count = 5;
  options.keep_vectors = false;
  const std::vector<emnet::Probe> probes = deflection_probes(m);
  return std::make_pair(measure([&] { return emnet::run_modes(system, rest, options).seconds; },
                                repeats.repetitions, repeats.budget),
                        measure([&] { return emnet::run_ac(system, rest, grid, probes).seconds; },
                                repeats.repetitions, repeats.budget));
}

// "a, b and c".
std::string listed(const std::vector<std::string>& items) {
  std::string text;
  for (size_t k = 0; k < items.size(); ++k)
    text += (k == 0 ? "" : k + 1 == items.size() ? " and " : ", ") + items[k];
  return text;
}

// ### Beam segments: the automatic count at three tolerances against a fixed N = 200.
std::string segment_choice_subsection(const Settings& settings, const Repeats& repeats) {
  std::ostringstream md;
  const double band_top = 130.0;
  const std::string band = "model.band=\"" + format("%g", band_top) + " Hz\"";
  // Converged reference: N = 1000 and 2000 (N = 200 and 400 with --quick).
  const emnet::BeamSpec beam = emnet::read_scene(settings.fishfin()).beam;
  const int reference_n = settings.quick ? 200 : 1000;
  const std::vector<double> converged = converged_beam_frequencies(beam, reference_n, band_top);
  const std::vector<double> grid = emnet::frequency_grid(0.0, band_top, 1000, false);
  const int fixed_n = 200;
  const auto [fixed_modes, fixed_ac] = modes_and_ac_times(settings, fixed_n, grid, repeats);
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
  std::vector<std::string> pays, does_not_pay;
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
        repeats.repetitions, repeats.budget);
    const auto [modes, ac] = modes_and_ac_times(settings, chosen, grid, repeats);
    md << "| " << format("%g", tolerance) << " | " << chosen << " | " << error_text(estimate)
       << " | " << error_text(beam_error(beam, chosen, converged)) << " | " << choose.text()
       << " | " << time_text(modes.median) << " (" << ratio_text(fixed_modes.median / modes.median)
       << ") | " << time_text(ac.median) << " (" << ratio_text(fixed_ac.median / ac.median)
       << ") | "
       << ratio_text((fixed_modes.median + fixed_ac.median) /
                     (modes.median + ac.median + choose.median))
       << " |\n";
    (fixed_modes.median + fixed_ac.median > modes.median + ac.median + choose.median ? pays
                                                                                     : does_not_pay)
        .push_back(format("%g", tolerance));
  }
  md << "| (fixed) | " << fixed_n << " | – | " << error_text(beam_error(beam, fixed_n, converged))
     << " | – | " << fixed_modes.text() << " | " << fixed_ac.text() << " | 1× |\n\n"
     << "Choosing costs a few modal solves of the bare beam (Arnoldi for chains over "
     << emnet::ModalOptions().dense_limit << " unknowns). "
     << (pays.empty() ? std::string("At no tolerance here does it pay for itself")
                      : "Including that time, it pays for itself on one modes and one ac at "
                        "tolerance " +
                            listed(pays))
     << (does_not_pay.empty()
             ? std::string(".")
             : "; at " + listed(does_not_pay) +
                   " only over analyses that run many times at one N (sweeps, studies), since "
                   "the choice is made once.")
     << "\n\n";
  return md.str();
}

// The fin with RC DEAs and with the ideal drive: each analysis's time and result.
struct DriveComparison {
  Timing rc_periodic_time, ideal_periodic_time, rc_transient_time, ideal_transient_time;
  emnet::PeriodicResult rc_periodic, ideal_periodic;
  emnet::TransientResult rc_transient, ideal_transient;
  int periods = 0;  // of the transients, from rest
};

DriveComparison compare_drives(const Settings& settings, const emnet::Model& rc,
                               const Repeats& repeats) {
  DriveComparison out;
  const emnet::Model ideal = build(settings.fishfin(), ideal_drive);
  const emnet::System rc_system = rc.network.assemble();
  const emnet::System ideal_system = ideal.network.assemble();
  const std::vector<emnet::Probe> rc_probes = deflection_probes(rc);
  const std::vector<emnet::Probe> ideal_probes = deflection_probes(ideal);
  const double period = 1.0 / rc.scene.drive.frequency;
  out.rc_periodic_time = measure(
      [&] {
        out.rc_periodic = emnet::run_periodic_shooting(rc_system, rc_probes, period, 1e-9);
        return out.rc_periodic.seconds;
      },
      repeats.repetitions, repeats.budget);
  out.ideal_periodic_time = measure(
      [&] {
        const auto start = Clock::now();
        emnet::PeriodicSolver solver(ideal_system);
        out.ideal_periodic = solver.solve(ideal_system, ideal_probes, period);
        return seconds_since(start);
      },
      repeats.repetitions, repeats.budget);
  out.periods = settings.quick ? 5 : 50;
  emnet::TransientOptions options;
  options.end_time = out.periods * period;
  for (int k = 0; k <= 100 * out.periods; ++k) options.output_times.push_back(k * period / 100);
  emnet::TransientOptions rc_options = options;
  rc_options.relative_tolerance = 1e-8;
  out.rc_transient_time = measure(
      [&] {
        out.rc_transient = emnet::run_transient_ida(rc_system, rc_probes, rc_options);
        return out.rc_transient.seconds;
      },
      repeats.repetitions, repeats.budget);
  out.ideal_transient_time = measure(
      [&] {
        out.ideal_transient = emnet::run_transient_exact(ideal_system, ideal_probes, options);
        return out.ideal_transient.seconds;
      },
      repeats.repetitions, repeats.budget);
  return out;
}

// Worst peak difference over the deflection outputs, relative to the RC model's peak: of the
// periodic extremes (first) and of the transients' largest |value| (second).
std::pair<double, double> peak_differences(const DriveComparison& c) {
  double periodic_difference = 0.0, transient_difference = 0.0;
  for (size_t p = 0; p < c.rc_periodic.maximum.size(); ++p) {
    const double peak =
        std::max(std::abs(c.rc_periodic.maximum[p]), std::abs(c.rc_periodic.minimum[p]));
    if (peak <= 0.0) continue;
    periodic_difference =
        std::max({periodic_difference,
                  std::abs(c.ideal_periodic.maximum[p] - c.rc_periodic.maximum[p]) / peak,
                  std::abs(c.ideal_periodic.minimum[p] - c.rc_periodic.minimum[p]) / peak});
    double rc_peak = 0.0, ideal_peak = 0.0;
    for (double v : c.rc_transient.values[p]) rc_peak = std::max(rc_peak, std::abs(v));
    for (double v : c.ideal_transient.values[p]) ideal_peak = std::max(ideal_peak, std::abs(v));
    if (rc_peak > 0.0)
      transient_difference =
          std::max(transient_difference, std::abs(ideal_peak - rc_peak) / rc_peak);
  }
  return {periodic_difference, transient_difference};
}

// ### DEA drive: ideal against RC, at the scene's N = 7 and 5 Hz switching.
std::string drive_dynamics_subsection(const Settings& settings, const Repeats& repeats) {
  std::ostringstream md;
  const emnet::Model rc = build(settings.fishfin(), {});
  const DriveComparison c = compare_drives(settings, rc, repeats);
  const auto [periodic_difference, transient_difference] = peak_differences(c);
  double tau = 0.0;
  for (const auto& dea : rc.deas) tau = std::max(tau, dea.electrode_resistance * dea.capacitance);
  const double drive_estimate = std::pow(emnet::kTwoPi * rc.scene.drive.frequency * tau, 2) / 2;
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
     << c.periods
     << " periods from rest, 100 outputs per period; RC by IDA (rtol 1e-8), ideal "
        "by the exact method.\n\n"
     << "| analysis | RC model | ideal drive | cost ratio RC/ideal | peak difference |\n"
     << "|---|---|---|---|---|\n"
     << "| periodic steady state | " << c.rc_periodic_time.text() << " | "
     << c.ideal_periodic_time.text() << " | "
     << ratio_text(c.rc_periodic_time.median / c.ideal_periodic_time.median) << " | "
     << error_text(periodic_difference) << " |\n"
     << "| transient | " << c.rc_transient_time.text() << " | " << c.ideal_transient_time.text()
     << " | " << ratio_text(c.rc_transient_time.median / c.ideal_transient_time.median) << " | "
     << error_text(transient_difference) << " |\n\n"
     << "The periodic peaks differ by " << ratio_text(periodic_difference / drive_estimate)
     << " the criterion's estimate"
     << (periodic_difference <= 10.0 * drive_estimate
             ? " (within a factor of 10: the estimate is a fair guide to the error of the ideal "
               "drive)"
             : " (more than 10 times: the estimate understates the error here)")
     << "; the transient's difference includes the start from rest.\n\n";
  return md.str();
}

}  // namespace

// 5a. What each automatic simplification (emnet/studies/segment_selection.hpp,
// drive.electrical_dynamics = "auto") costs in accuracy and saves in time, measured side by side.
std::string simplification_section(const Settings& settings) {
  const Repeats repeats{settings.quick ? 2 : 10, settings.quick ? 0.5 : 3.0};
  return "What each automatic simplification costs in accuracy and saves in time, measured side "
         "by side: the segment count chosen for a tolerance (`beam.segments = \"auto\"`) and the "
         "ideal drive in place of the DEAs' RC dynamics (`drive.electrical_dynamics`).\n\n" +
         segment_choice_subsection(settings, repeats) +
         drive_dynamics_subsection(settings, repeats);
}

}  // namespace emnet_bench
