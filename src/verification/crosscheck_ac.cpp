// Cross-check, ac: the small-signal response at every frequency, magnitude and phase
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

// Outputs: magnitude and weighted phase, each relative to the output's own peak; an integral
// output is not compared at f = 0 (the deck's integrator gives 0 there, emnet the static limit).
void add_ac_output_rows(CrosscheckSession& session, const NgspiceResult& ng, const SpiceDeck& deck,
                        const std::vector<Probe>& probes, std::size_t output_count,
                        const std::vector<double>& frequencies, const AcResult& result) {
  CrosscheckRow magnitude, phase;
  magnitude.analysis = phase.analysis = CrosscheckAnalysis::ac;
  magnitude.quantity = "outputs |Y|";
  phase.quantity = "outputs arg Y (x |Y|/peak) [rad]";
  magnitude.tolerance = phase.tolerance = session.options_.same_network_tolerance;
  magnitude.basis = "relative to each output's peak |Y| over the sweep";
  phase.basis = "phase difference weighted by |Y|/peak";
  bool skipped_zero_frequency = false;
  for (std::size_t p = 0; p < output_count; ++p) {
    const auto& spice = session.vector(ng, deck.outputs[p].vector, "ac");
    if (spice.size() != frequencies.size())
      throw CrosscheckFailure("ngspice's ac vector " + deck.outputs[p].vector +
                              " has a different length than its frequency vector");
    // (a deck in displacements writes the integral itself: compared at f = 0 too)
    const bool integral = probes[p].integrations > 0 && !deck.displacement_nodes;
    double peak = 0.0;
    for (std::size_t f = 0; f < frequencies.size(); ++f)
      if (!(integral && frequencies[f] == 0.0))
        peak = std::max(peak, std::abs(result.values[p][f]));
    const bool zero = !(peak > 0.0);
    if (zero) peak = 1.0;  // zero in emnet (the clamp probe): absolute, SI units
    for (std::size_t f = 0; f < frequencies.size(); ++f) {
      if (integral && frequencies[f] == 0.0) {
        skipped_zero_frequency = true;
        continue;
      }
      const std::complex<double> e = result.values[p][f], s = complex_at(spice, f);
      const double dm = std::abs(std::abs(s) - std::abs(e)) / peak;
      const double dp = (std::abs(e) > 0.0 && std::abs(s) > 0.0)
                            ? std::abs(std::arg(s / e)) * std::abs(e) / peak
                            : std::abs(s - e) / peak;
      if (!std::isfinite(dm) || !std::isfinite(dp))
        throw CrosscheckFailure("non-finite ac difference at " + probes[p].name);
      const std::string where = probes[p].name + " at " + number("%.6g Hz", frequencies[f]) +
                                (zero ? " (zero in emnet: absolute)" : "");
      if (dm >= magnitude.largest_difference) {
        magnitude.largest_difference = dm;
        magnitude.where = where;
      }
      if (dp >= phase.largest_difference) {
        phase.largest_difference = dp;
        phase.where = where;
      }
    }
  }
  magnitude.pass = magnitude.largest_difference <= magnitude.tolerance;
  phase.pass = phase.largest_difference <= phase.tolerance;
  session.report_.rows.push_back(magnitude);
  session.report_.rows.push_back(phase);
  if (skipped_zero_frequency)
    session.report_.notes.push_back(
        "ac: integrator outputs (deflections) are not compared at f = 0, where the deck's "
        "integrator gives 0 and emnet the static limit");
}

// Every unknown with a vector, complex difference relative to its group's largest value; the
// unknowns' responses follow the outputs' in `result`.
void add_ac_unknown_rows(CrosscheckSession& session, const NgspiceResult& ng, const SpiceDeck& deck,
                         const System& sys, const std::vector<std::size_t>& unknown_of_probe,
                         std::size_t output_count, const std::vector<double>& frequencies,
                         const AcResult& result) {
  std::map<std::string, Group> groups;
  std::vector<std::string> order;
  for (std::size_t q = 0; q < unknown_of_probe.size(); ++q) {
    const std::size_t k = unknown_of_probe[q];
    const auto& map = deck.unknowns[k];
    const auto& spice = session.vector(ng, map.vector, "ac");
    const std::string name = group_name(sys.unknowns[k], false);
    if (!groups.count(name)) order.push_back(name);
    auto& group = groups[name];
    for (std::size_t f = 0; f < frequencies.size(); ++f) {
      group.names.push_back(sys.unknowns[k].name + " at " + number("%.6g Hz", frequencies[f]));
      group.emnet.push_back(result.values[output_count + q][f]);
      group.spice.push_back(map.sign * complex_at(spice, f));
    }
  }
  for (const auto& name : order)
    session.add_group_row(CrosscheckAnalysis::ac, name + " (complex)", groups.at(name));
}

}  // namespace

// ---- ac -----------------------------------------------------------------------------------
void CrosscheckSession::ac() {
  const SpiceDeck deck = write_spice_deck(model_, deck_options(SpiceAnalysis::ac));
  const NgspiceResult ng = run_deck(CrosscheckAnalysis::ac, deck, "ac");
  const NgspiceVector* scale = ng.scale();
  if (!scale || scale->size() == 0) throw CrosscheckFailure("ngspice's ac run has no scale");
  std::vector<double> frequencies;
  for (std::size_t i = 0; i < scale->size(); ++i) frequencies.push_back(real_at(*scale, i));
  const System& sys = system();
  const StaticResult& operating = rest(sys);
  // The outputs, then one probe per unknown that has a vector in the deck.
  std::vector<Probe> probes = spice_output_probes(model_);
  const std::size_t output_count = probes.size();
  std::vector<std::size_t> unknown_of_probe;
  for (std::size_t k = 0; k < deck.unknowns.size(); ++k) {
    if (deck.unknowns[k].vector.empty()) continue;
    Probe probe;
    probe.name = sys.unknowns[k].name;
    probe.terms = {{static_cast<int>(k), 1.0}};
    probes.push_back(probe);
    unknown_of_probe.push_back(k);
  }
  const Stopwatch stopwatch;
  const AcResult result = run_ac(sys, operating.operating_point, frequencies, probes);
  const double emnet_seconds = stopwatch.seconds();
  if (!result.status.ok()) throw CrosscheckFailure("emnet ac: " + result.status.message);
  add_ac_output_rows(*this, ng, deck, probes, output_count, frequencies, result);
  add_ac_unknown_rows(*this, ng, deck, sys, unknown_of_probe, output_count, frequencies, result);
  report_.timings.push_back(
      {CrosscheckAnalysis::ac, ng.ngspice_seconds, ng.seconds, emnet_seconds,
       "run_ac at " + std::to_string(frequencies.size()) + " frequencies, every unknown"});
}

}  // namespace emnet::crosscheck_detail
