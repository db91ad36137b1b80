// Cross-check, tran: emnet's transient (exact, or IDA for a nonlinear network) against ngspice's
// (include/emnet/verification/crosscheck.hpp says why each tolerance).
#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <string>
#include <vector>

#include "crosscheck_session.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/stopwatch.hpp"

namespace emnet::crosscheck_detail {

namespace {

// The first oscillatory mode's period (0 without one): ngspice's max step must resolve it
// even where the drive's period is far longer (a slow switching cycle of a stiff device),
// since its trapezoidal rule's phase error grows as (ω·h)² per cycle of every mode the drive
// excites.
double first_mode_period(const System& sys) {
  const OperatingPoint operating = operating_point(sys);
  if (!operating.status.ok()) throw CrosscheckFailure("emnet " + operating.status.message);
  const ModalResult modes = run_modes(sys, operating.rest.operating_point);
  if (modes.status.ok() && !modes.modes.empty()) return 1.0 / modes.modes.front().frequency_hz;
  return 0.0;
}

// The period the run is counted in, and what it is; 0 when the scene has none to compare over.
double run_period(const Scene& scene, double mode_period, std::string& period_from) {
  if (scene.drive.frequency > 0.0 && scene.drive.kind != DriveKind::none) {
    period_from = "the drive's period";
    return 1.0 / scene.drive.frequency;
  }
  if (scene.drive.frequency > 0.0 && !scene.circuit.empty()) {
    // drive.frequency with drive kind none: the period of tran --periods, the circuit's own.
    period_from = "the period of drive.frequency (the circuit's)";
    return 1.0 / scene.drive.frequency;
  }
  period_from = "the first mode's period";
  return mode_period > 0.0 ? mode_period : 0.0;
}

// ngspice's run of the deck, retried once with a wider max step where it gave up on a tight
// one; throws unless it reached the end time.
NgspiceResult run_tran_deck(CrosscheckSession& session, const Model& m, double step_period,
                            SpiceDeckOptions& d, SpiceDeck& deck) {
  const CrosscheckOptions& options = session.options_;
  std::vector<std::string>& notes = session.report_.notes;
  deck = write_spice_deck(m, d);
  NgspiceResult ng = session.run_deck(CrosscheckAnalysis::tran, deck, "tran", true);
  auto stopped_at = [&](const NgspiceResult& r) {
    const NgspiceVector* sc = r.scale();
    return sc && sc->size() > 0 ? real_at(*sc, sc->size() - 1) : 0.0;
  };
  // A step load from rest near a massless node can make ngspice give up ("timestep too
  // small") when its max step is tight (the cantilever below about T/1000); one retry with a
  // max step of T/200, said in the notes — the tolerance stays the same.
  const bool gave_up = !ng.status.ok() || !(stopped_at(ng) >= d.end_time * (1.0 - 1e-9));
  if (gave_up && options.tran_points_per_period > 200 &&
      lower(ng.messages_text()).find("timestep too small") != std::string::npos) {
    notes.push_back("tran: ngspice gave up (" + CrosscheckSession::last_error_line(ng) +
                    ") with max step T/" + std::to_string(options.tran_points_per_period) +
                    "; retried with T/200");
    d.output_step = step_period / 200;
    deck = write_spice_deck(m, d);
    ng = session.run_deck(CrosscheckAnalysis::tran, deck, "tran");
  } else if (!ng.status.ok()) {
    ng = session.run_deck(CrosscheckAnalysis::tran, deck, "tran");  // reports the failure
  }
  return ng;
}

// The compared instants: ngspice's time points within [0, end], at most tran_compared_points
// of them, evenly strided (each costs emnet one matrix exponential).
struct ComparedTimes {
  std::vector<std::size_t> indices;  // into ngspice's time vector
  std::vector<double> times;         // at those indices, within [0, end]
  std::vector<double> unique_times;  // sorted, each once: emnet's output times
  std::vector<bool> compared;        // false within the exclusion window of a switching edge
};

ComparedTimes compared_times(const NgspiceVector& scale, double end_time,
                             const CrosscheckOptions& options, std::vector<std::string>& notes) {
  ComparedTimes at;
  const std::size_t stride =
      (scale.size() + options.tran_compared_points - 1) / options.tran_compared_points;
  for (std::size_t i = 0; i < scale.size(); i += std::max<std::size_t>(stride, 1))
    at.indices.push_back(i);
  if (at.indices.back() != scale.size() - 1) at.indices.push_back(scale.size() - 1);
  for (std::size_t i : at.indices) at.times.push_back(std::clamp(real_at(scale, i), 0.0, end_time));
  if (stride > 1)
    notes.push_back("tran: ngspice took " + std::to_string(scale.size()) + " time points; one in " +
                    std::to_string(stride) + " is compared (" + std::to_string(at.indices.size()) +
                    ")");
  at.unique_times = at.times;
  std::sort(at.unique_times.begin(), at.unique_times.end());
  at.unique_times.erase(std::unique(at.unique_times.begin(), at.unique_times.end()),
                        at.unique_times.end());
  at.compared.assign(at.times.size(), true);
  return at;
}

// emnet's transient at the compared times: exact for a linear network; IDA at rtol 1e-10 for a
// nonlinear one and, where rounding stops its corrector first (stiff networks whose unknowns
// span many decades), at 1e-9 or 1e-8: its error stays ~100x below the tolerance of
// 100 x reltol = 1e-4 either way.
TransientResult tran_reference(const System& sys, const std::vector<Probe>& probes,
                               TransientOptions& t, std::vector<std::string>& notes) {
  if (!sys.is_nonlinear()) return run_transient_exact(sys, probes, t);
  TransientResult reference;
  std::string failures;
  for (const double rtol : {1e-10, 1e-9, 1e-8}) {
    t.relative_tolerance = rtol;
    reference = run_transient_ida(sys, probes, t);
    if (reference.status.ok()) {
      notes.push_back("tran: the network is nonlinear; the reference is IDA at rtol " +
                      number("%.0e", rtol) + ", not the exact method" +
                      (failures.empty() ? std::string() : " (" + failures + ")"));
      break;
    }
    failures += (failures.empty() ? "" : "; ") + std::string("rtol ") + number("%.0e", rtol) +
                " failed: " + reference.status.message;
  }
  return reference;
}

// Switching edges: emnet's instants; ε = edge fraction × the shorter level time. The times
// within the exclusion window of an edge are not compared.
void exclude_edges(const System& sys, double end_time, const CrosscheckOptions& options,
                   ComparedTimes& at, std::vector<std::string>& notes) {
  const std::vector<double> edges = sys.breakpoints(0.0, end_time);
  double shortest = end_time, previous = 0.0;
  for (double e : edges) {
    if (e - previous > 0.0) shortest = std::min(shortest, e - previous);
    previous = e;
  }
  const double epsilon = options.tran_edge_fraction * shortest;
  const double window = options.tran_edge_exclusion * epsilon;
  std::size_t excluded = 0;
  for (std::size_t i = 0; i < at.times.size(); ++i)
    for (double e : edges)
      if (std::abs(at.times[i] - e) <= window) {
        at.compared[i] = false;
        ++excluded;
        break;
      }
  if (!edges.empty())
    notes.push_back("tran: " + std::to_string(edges.size()) + " switching edge(s) of width " +
                    number("%.3g s", epsilon) + " in the deck; " + std::to_string(excluded) +
                    " of " + std::to_string(at.times.size()) + " ngspice time points within +/-" +
                    number("%.3g s", window) + " of an edge are not compared");
}

// One row per output unit: each output's largest difference relative to its peak |value|.
void add_tran_rows(CrosscheckSession& session, const NgspiceResult& ng, const SpiceDeck& deck,
                   const std::vector<Probe>& probes, const ComparedTimes& at,
                   const TransientResult& reference) {
  const CrosscheckOptions& options = session.options_;
  const NgspiceVector& scale = *ng.scale();
  std::map<std::string, CrosscheckRow> rows;
  std::vector<std::string> order;
  for (std::size_t p = 0; p < probes.size(); ++p) {
    const auto& spice = session.vector(ng, deck.outputs[p].vector, "tran");
    if (spice.size() != scale.size())
      throw CrosscheckFailure("ngspice's tran vector " + deck.outputs[p].vector +
                              " has a different length than its time vector");
    std::vector<double> emnet_values(at.times.size());
    double peak = 0.0;
    for (std::size_t i = 0; i < at.times.size(); ++i) {
      const std::size_t u = static_cast<std::size_t>(
          std::lower_bound(at.unique_times.begin(), at.unique_times.end(), at.times[i]) -
          at.unique_times.begin());
      emnet_values[i] = reference.values[p][u];
      if (at.compared[i]) peak = std::max(peak, std::abs(emnet_values[i]));
    }
    const bool zero = !(peak > 0.0);
    const std::string name = "outputs [" + probes[p].unit + "]";
    if (!rows.count(name)) {
      order.push_back(name);
      CrosscheckRow row;
      row.analysis = CrosscheckAnalysis::tran;
      row.quantity = name;
      row.tolerance = options.tran_tolerance_per_reltol * options.tran_reltol;
      row.basis = "relative to each output's peak |value| over the run; tolerance " +
                  number("%.4g", options.tran_tolerance_per_reltol) + " x reltol";
      rows[name] = row;
    }
    auto& row = rows[name];
    for (std::size_t i = 0; i < at.times.size(); ++i) {
      if (!at.compared[i]) continue;
      const double difference =
          std::abs(real_at(spice, at.indices[i]) - emnet_values[i]) / (zero ? 1.0 : peak);
      if (!std::isfinite(difference))
        throw CrosscheckFailure("non-finite tran difference at " + probes[p].name);
      if (difference >= row.largest_difference) {
        row.largest_difference = difference;
        row.where = probes[p].name + " at t = " + number("%.6g s", at.times[i]) +
                    (zero ? " (zero in emnet: absolute)" : "");
      }
    }
  }
  for (const auto& name : order) {
    auto& row = rows.at(name);
    row.pass = row.largest_difference <= row.tolerance;
    session.report_.rows.push_back(row);
  }
}

}  // namespace

// ---- tran ---------------------------------------------------------------------------------
void CrosscheckSession::tran() {
  Scene scene = model_.scene;
  bool ideal_drive = false;
  // (A scene with a [[circuit]] keeps its electrical loops, which the circuit drives.)
  if (scene.drive.electrical_dynamics && !scene.deas.empty() &&
      scene.drive.kind != DriveKind::none && scene.circuit.empty()) {
    set_electrical_dynamics(scene, false);
    ideal_drive = true;
  }
  const Model tran_model = ideal_drive ? build_model(scene) : Model{};
  const Model& m = ideal_drive ? tran_model : model_;
  const System sys = m.network.assemble();
  if (ideal_drive)
    report_.notes.push_back(
        "tran: compared with the ideal drive (drive.electrical_dynamics = false: force "
        "k_F*V(t)^2 from the source), " +
        std::string(scene.beam.kinematics == BeamKinematics::large
                        ? "as the small network's check (large kinematics keep it nonlinear)"
                        : "the linear network emnet's exact method solves"));
  const double mode_period = first_mode_period(sys);
  std::string period_from;
  const double period = run_period(scene, mode_period, period_from);
  if (!(period > 0.0)) {
    report_.notes.push_back("tran: no drive frequency and no oscillatory mode; not compared");
    return;
  }
  // The max step: the shorter of the run's period and the first mode's, over the points per
  // period (the drive's period where it is the shorter, as for the fish fin driven below f1).
  const double step_period = mode_period > 0.0 ? std::min(period, mode_period) : period;
  if (step_period < period)
    report_.notes.push_back("tran: ngspice's max step from the first mode's period " +
                            number("%.4g s", step_period) + ", shorter than " + period_from);
  SpiceDeckOptions d = deck_options(SpiceAnalysis::tran);
  d.end_time = options_.tran_periods * period;
  d.output_step = step_period / options_.tran_points_per_period;
  d.max_step = 0.0;  // the output step
  d.relative_tolerance = options_.tran_reltol;
  d.edge_fraction = options_.tran_edge_fraction;
  d.start = StartState::rest;
  SpiceDeck deck;
  const NgspiceResult ng = run_tran_deck(*this, m, step_period, d, deck);
  report_.notes.push_back("tran: " + number("%.4g", options_.tran_periods) + " x " + period_from +
                          " (" + number("%.6g s", d.end_time) + ") from rest, ngspice reltol " +
                          number("%.0e", d.relative_tolerance) + ", max step " +
                          number("%.4g s", d.output_step));
  const NgspiceVector* scale = ng.scale();
  if (!scale || scale->size() == 0) throw CrosscheckFailure("ngspice's tran run has no scale");
  const double last_time = real_at(*scale, scale->size() - 1);
  if (!(last_time >= d.end_time * (1.0 - 1e-9)))
    throw CrosscheckFailure("ngspice stopped its transient at t = " + number("%.6g s", last_time) +
                            " of " + number("%.6g s", d.end_time) + " (" + last_error_line(ng) +
                            ")");
  ComparedTimes at = compared_times(*scale, d.end_time, options_, report_.notes);

  const auto probes = spice_output_probes(m);
  TransientOptions t;
  t.end_time = d.end_time;
  t.output_times = at.unique_times;
  t.start = StartState::rest;
  const bool linear = !sys.is_nonlinear();
  const Stopwatch stopwatch;
  const TransientResult reference = tran_reference(sys, probes, t, report_.notes);
  const double emnet_seconds = stopwatch.seconds();
  if (!reference.status.ok())
    throw CrosscheckFailure("emnet tran (" + std::string(linear ? "exact" : "ida") +
                            "): " + reference.status.message);
  if (reference.times.size() != at.unique_times.size())
    throw CrosscheckFailure("emnet tran: reached " + std::to_string(reference.times.size()) +
                            " of " + std::to_string(at.unique_times.size()) + " output times");
  exclude_edges(sys, d.end_time, options_, at, report_.notes);
  add_tran_rows(*this, ng, deck, probes, at, reference);
  report_.timings.push_back(
      {CrosscheckAnalysis::tran, ng.ngspice_seconds, ng.seconds, emnet_seconds,
       std::string(linear
                       ? "run_transient_exact"
                       : "run_transient_ida (rtol " + number("%.0e", t.relative_tolerance) + ")") +
           " at " + std::to_string(at.unique_times.size()) + " of ngspice's time points"});
}

}  // namespace emnet::crosscheck_detail
