// Cross-check, op: the static network, every node: emnet's static state against ngspice's operating
// point (include/emnet/verification/crosscheck.hpp says why each tolerance).
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

void CrosscheckSession::op() {
  const SpiceDeck deck = write_spice_deck(model_, deck_options(SpiceAnalysis::op));
  const NgspiceResult ng = run_deck(CrosscheckAnalysis::op, deck, "op");
  const System& sys = system();
  const Stopwatch stopwatch;
  const StaticResult result = solve_static(sys);
  const double emnet_seconds = stopwatch.seconds();
  if (!result.status.ok()) throw CrosscheckFailure("emnet static: " + result.status.message);
  std::map<std::string, Group> groups;
  std::vector<std::string> order;
  for (std::size_t k = 0; k < deck.unknowns.size(); ++k) {
    const auto& map = deck.unknowns[k];
    if (map.vector.empty()) continue;
    const std::string name = group_name(sys.unknowns[k], true);
    if (!groups.count(name)) order.push_back(name);
    auto& group = groups[name];
    group.names.push_back(sys.unknowns[k].name);
    group.emnet.emplace_back(result.state[static_cast<Eigen::Index>(k)]);
    group.spice.emplace_back(map.sign * real_at(vector(ng, map.vector, "op"), 0));
  }
  const auto probes = spice_output_probes(model_);
  std::map<std::string, Group> outputs;
  for (std::size_t p = 0; p < deck.outputs.size() && p < probes.size(); ++p) {
    const std::string name = "outputs [" + deck.outputs[p].unit + "]";
    if (!outputs.count(name)) order.push_back(name);
    auto& group = outputs[name];
    group.names.push_back(deck.outputs[p].probe);
    group.emnet.emplace_back(static_probe_value(sys, result, probes[p]));
    group.spice.emplace_back(real_at(vector(ng, deck.outputs[p].vector, "op"), 0));
  }
  // Static currents: every capacitor is open and every DEA film too, so in a circuit the
  // static currents are zero but for rounding of order ε·(volts / ohms); below 1 pA (1 kV
  // across 1 PΩ) a current is compared against 1 pA, not against its own rounding.
  constexpr double kStaticCurrentFloor = 1e-12;  // [A]
  for (const auto& name : order)
    add_group_row(CrosscheckAnalysis::op, name,
                  groups.count(name) ? groups.at(name) : outputs.at(name), "",
                  name.find("[A]") != std::string::npos ? kStaticCurrentFloor : 0.0);
  report_.timings.push_back({CrosscheckAnalysis::op, ng.ngspice_seconds, ng.seconds, emnet_seconds,
                             "solve_static (Newton, sparse LU)"});
}

}  // namespace emnet::crosscheck_detail
