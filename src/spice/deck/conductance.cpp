// SPICE lines of a Conductance g: a resistor R = 1/g between its nodes; g = 0 is an open (a
// comment, no element). The op deck leaves out a mechanical one (a damper: no force at rest); a
// displacement ac deck writes it as a capacitor g (its force g·d(V_a − V_b)/dt).
#include "emnet/elements/conductance.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

void write_conductance(const Conductance& g, DeckWriter& deck) {
  const std::string& name = g.name();
  if (deck.op() && deck.mechanical(g.a(), g.b())) {
    deck.leave_out(name);  // a damper: no force at rest
    return;
  }
  if (g.conductance() == 0.0) {
    deck.comment(name + ": conductance 0 between " + deck.node(g.a()) + " and " + deck.node(g.b()) +
                 ": an open, no element");
    return;
  }
  if (deck.displacements() && deck.mechanical(g.a(), g.b())) {
    deck.body() << deck.element_name('C', name) << " " << deck.node(g.a()) << " "
                << deck.node(g.b()) << " " << deck.value(g.conductance(), name) << "\n";
    return;
  }
  deck.body() << deck.element_name('R', name) << " " << deck.node(g.a()) << " " << deck.node(g.b())
              << " " << deck.value(1.0 / g.conductance(), name) << "\n";
}

}  // namespace emnet::spice_deck
