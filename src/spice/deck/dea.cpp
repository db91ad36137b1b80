// SPICE lines of a Dea: its capacitor C₀ (e+, e−), and per coupling node k a B source
// injecting c_k·k_F·u² with u = V(e+) − V(e−) (the force follows the capacitor voltage); with
// back-coupling a B source drawing the motional current 2·k_F·u·ẋ from e+ to e−,
// ẋ = Σ c_k·V(k) (left out of the op deck: zero at rest). Its direct AC force (the
// antagonistic drive) is an AC-only current source c_k·ac_force into each coupling node, in
// the ac deck only.
#include "emnet/elements/dea.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

namespace {

using NodeCoupling = std::vector<std::pair<NodeId, double>>;

// Coupling coefficients summed per node, in order of first appearance.
NodeCoupling coupling_by_node(const Dea& d) {
  NodeCoupling coupling;
  for (const Dea::Coupling& c : d.coupling()) {
    if (c.node == ground) continue;
    auto at = std::find_if(coupling.begin(), coupling.end(),
                           [&](const auto& p) { return p.first == c.node; });
    if (at == coupling.end())
      coupling.emplace_back(c.node, c.coefficient);
    else
      at->second += c.coefficient;
  }
  return coupling;
}

void write_motional_current(const Dea& d, const NodeCoupling& coupling, DeckWriter& deck) {
  const std::string& name = d.name();
  const std::string u = deck.voltage(d.electrode_plus(), d.electrode_minus());
  std::string rate;
  for (const auto& [n, c] : coupling) {  // velocities: in displacements the nodes' rates
    if (c == 0.0) continue;
    rate += (rate.empty() ? "" : "+") + deck.value(c, name) + "*V(" +
            (deck.displacements() ? deck.rate(n) : deck.node(n)) + ")";
  }
  if (rate.empty()) return;
  deck.comment(name + ": motional current u*dC/dx*dx/dt = 2*k_F*u*(elongation rate)");
  deck.body() << deck.element_name('B', name + "_motional") << " " << deck.node(d.electrode_plus())
              << " " << deck.node(d.electrode_minus())
              << " I = " << deck.value(2.0 * d.force_constant(), name) << "*" << u << "*(" << rate
              << ")\n";
}

void write_ac_force(const Dea& d, const NodeCoupling& coupling, DeckWriter& deck) {
  const std::string& name = d.name();
  deck.comment(name + ": AC input, the force amplitude " + number(d.ac_force()) +
               " N along the coupling (AC only, no DC part)");
  for (const auto& [n, c] : coupling) {
    const double amplitude = c * d.ac_force();
    if (amplitude == 0.0) continue;
    deck.body() << deck.element_name('I', name + "_ac_" + deck.network().node(n).name) << " 0 "
                << deck.node(n) << " DC 0 AC " << deck.value(std::abs(amplitude), name) << " "
                << (amplitude < 0.0 ? "180" : "0") << "\n";
  }
}

}  // namespace

void write_dea(const Dea& d, DeckWriter& deck) {
  const std::string& name = d.name();
  const std::string u = deck.voltage(d.electrode_plus(), d.electrode_minus());
  std::ostringstream& out = deck.body();
  if (d.capacitance() != 0.0)
    out << deck.element_name('C', name) << " " << deck.node(d.electrode_plus()) << " "
        << deck.node(d.electrode_minus()) << " " << deck.value(d.capacitance(), name) << "\n";
  const NodeCoupling coupling = coupling_by_node(d);
  deck.comment(name + ": force k_F*u^2 on the capacitor voltage u = " + u +
               ", entering node k as c_k*k_F*u^2 (c_k: elongation rate per unit across)");
  for (const auto& [n, c] : coupling) {
    if (c == 0.0) continue;
    out << deck.element_name('B', name + "_" + deck.network().node(n).name) << " 0 " << deck.node(n)
        << " I = " << deck.value(c * d.force_constant(), name) << "*" << u << "*" << u << "\n";
  }
  if (d.back_coupling() && !deck.op())
    write_motional_current(d, coupling, deck);
  else if (d.back_coupling())
    deck.comment(name + ": motional current left out (zero at rest)");
  if (deck.ac() && d.ac_force() != 0.0) write_ac_force(d, coupling, deck);
}

}  // namespace emnet::spice_deck
