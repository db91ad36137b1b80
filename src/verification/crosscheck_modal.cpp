// Cross-check, modal: the modes against the peaks of ngspice's AC response around them
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

// ---- modal --------------------------------------------------------------------------------
void CrosscheckSession::modal() {
  const System& sys = system();
  const StaticResult& operating = rest(sys);
  const Stopwatch stopwatch;
  const ModalResult modes = run_modes(sys, operating.operating_point);
  const double emnet_seconds = stopwatch.seconds();
  if (!modes.status.ok()) throw CrosscheckFailure("emnet modes: " + modes.status.message);
  // The output whose peaks are read: "tip", else the last deflection probe.
  const Probe* output = nullptr;
  for (const auto& probe : model_.probes)
    if (probe.name == "tip" && probe.integrations == 1) output = &probe;
  if (!output)
    for (const auto& probe : model_.probes)
      if (probe.integrations == 1) output = &probe;
  if (!output) {
    report_.notes.push_back("modal: the scene has no deflection probe; not compared");
    return;
  }
  double ngspice_seconds = 0.0, ngspice_total = 0.0;
  const int count = std::min<int>(options_.modal_count, static_cast<int>(modes.modes.size()));
  for (int m = 0; m < count; ++m) {
    const Mode& mode = modes.modes[static_cast<std::size_t>(m)];
    const std::string label = "f" + std::to_string(m + 1);
    if (!(mode.damping_ratio < 0.5)) {
      report_.notes.push_back("modal: " + label + " has damping ratio " +
                              number("%.3g", mode.damping_ratio) +
                              ": no sharp amplitude peak; not compared");
      continue;
    }
    const double zeta = mode.damping_ratio;
    const double predicted = mode.natural_frequency_hz * std::sqrt(1.0 - 2.0 * zeta * zeta);
    SpiceDeckOptions d = deck_options(SpiceAnalysis::ac);
    d.outputs = {*output};
    AcSpec spec;
    // The peak lies within about ±ζ of f_p; a wider mode gets a wider grid (±2ζ).
    const double half_width = std::min(0.5, std::max(options_.modal_half_width, 2.0 * zeta));
    spec.from = predicted * (1.0 - half_width);
    spec.to = predicted * (1.0 + half_width);
    spec.points = options_.modal_points;
    spec.log = false;
    d.ac = spec;
    const SpiceDeck deck = write_spice_deck(model_, d);
    const NgspiceResult ng = run_deck(CrosscheckAnalysis::modal, deck, "modal-" + label);
    ngspice_seconds += ng.ngspice_seconds;
    ngspice_total += ng.seconds;
    const NgspiceVector* scale = ng.scale();
    if (!scale || scale->size() == 0)
      throw CrosscheckFailure("ngspice's modal ac run has no scale");
    std::vector<double> frequencies, spice_magnitude, emnet_magnitude;
    for (std::size_t i = 0; i < scale->size(); ++i) frequencies.push_back(real_at(*scale, i));
    const auto& spice = vector(ng, deck.outputs.at(0).vector, "modal");
    for (std::size_t i = 0; i < frequencies.size(); ++i)
      spice_magnitude.push_back(std::abs(complex_at(spice, i)));
    const AcResult own = run_ac(sys, operating.operating_point, frequencies, {*output});
    if (!own.status.ok()) throw CrosscheckFailure("emnet ac (modal): " + own.status.message);
    for (const auto& v : own.values[0]) emnet_magnitude.push_back(std::abs(v));
    double spice_peak = 0.0, emnet_peak = 0.0;
    const bool spice_visible = parabolic_peak_frequency(frequencies, spice_magnitude, spice_peak);
    const bool emnet_visible = parabolic_peak_frequency(frequencies, emnet_magnitude, emnet_peak);
    if (!emnet_visible) {
      report_.notes.push_back("modal: " + label + " (" + number("%.6g Hz", predicted) +
                              ") is not visible in the response of " + output->name +
                              " (no peak inside the grid); not compared");
      continue;
    }
    CrosscheckRow row;
    row.analysis = CrosscheckAnalysis::modal;
    row.quantity = label + " peak of " + output->name + " [Hz]";
    row.basis = "relative to emnet's mode f_n*sqrt(1-2*zeta^2) = " + number("%.9g Hz", predicted) +
                "; tolerance: emnet's own AC peak offset " +
                number("%.2e", std::abs(emnet_peak - predicted) / predicted) + " + " +
                number("%.0e", options_.same_network_tolerance);
    row.tolerance = std::abs(emnet_peak - predicted) / predicted + options_.same_network_tolerance;
    if (!spice_visible) {
      row.largest_difference = INFINITY;
      row.where = "no peak in ngspice's response";
      row.pass = false;
    } else {
      row.largest_difference = std::abs(spice_peak - predicted) / predicted;
      row.where = "ngspice " + number("%.9g Hz", spice_peak) + ", emnet mode " +
                  number("%.9g Hz", predicted);
      row.pass = row.largest_difference <= row.tolerance;
    }
    report_.rows.push_back(row);
  }
  if (count < options_.modal_count)
    report_.notes.push_back("modal: emnet found " + std::to_string(modes.modes.size()) +
                            " oscillatory mode(s)");
  report_.timings.push_back({CrosscheckAnalysis::modal, ngspice_seconds, ngspice_total,
                             emnet_seconds,
                             "run_modes (" + method_name(modes.method) + ", " +
                                 std::to_string(modes.unknowns) + " unknowns)"});
}

}  // namespace emnet::crosscheck_detail
