// SPICE lines of a Capacitor C: a capacitor C between its nodes (a mass or inertia to ground,
// or an electrical capacitor); C = 0 writes no element. The op deck leaves out a mechanical one
// (a mass or inertia: no force at rest).
#include "emnet/elements/capacitor.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

void write_capacitor(const Capacitor& c, DeckWriter& deck) {
  const std::string& name = c.name();
  if (deck.op() && (deck.mechanical(c.a()) || deck.mechanical(c.b()))) {
    deck.leave_out(name);  // a mass or inertia: no force at rest
    return;
  }
  if (c.capacitance() == 0.0) {
    deck.comment(name + ": capacitance 0: no element");
    return;
  }
  deck.body() << deck.element_name('C', name) << " " << deck.node(c.a()) << " " << deck.node(c.b())
              << " " << deck.value(c.capacitance(), name) << "\n";
}

}  // namespace emnet::spice_deck
