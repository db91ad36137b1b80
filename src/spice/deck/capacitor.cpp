// SPICE lines of a Capacitor C: a capacitor C between its nodes (a mass or inertia to ground,
// or an electrical capacitor); C = 0 writes no element. The op deck leaves out a mechanical one
// (a mass or inertia: no force at rest); a displacement ac deck draws C·d²(V_a − V_b)/dt² from
// a into b: an F source of the current a capacitor C takes from the nodes' rates.
#include "emnet/elements/capacitor.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

void write_capacitor(const Capacitor& c, DeckWriter& deck) {
  const std::string& name = c.name();
  if (deck.op() && deck.mechanical(c.a(), c.b())) {
    deck.leave_out(name);  // a mass or inertia: no force at rest
    return;
  }
  if (c.capacitance() == 0.0) {
    deck.comment(name + ": capacitance 0: no element");
    return;
  }
  if (deck.displacements() && deck.mechanical(c.a(), c.b())) {
    // The rate nodes first: each writes its own lines.
    const std::string rate_a = deck.rate(c.a()), rate_b = deck.rate(c.b());
    const std::string sense = deck.internal_node(name + "_sense", name + ": its force's sense");
    const std::string source = deck.element_name('V', name + "_sense");
    deck.body() << deck.element_name('C', name) << " " << rate_a << " " << sense << " "
                << deck.value(c.capacitance(), name) << "\n";
    deck.body() << source << " " << sense << " " << rate_b << " DC 0\n";
    deck.body() << deck.element_name('F', name) << " " << deck.node(c.a()) << " "
                << deck.node(c.b()) << " " << source << " 1\n";
    return;
  }
  deck.body() << deck.element_name('C', name) << " " << deck.node(c.a()) << " " << deck.node(c.b())
              << " " << deck.value(c.capacitance(), name) << "\n";
}

}  // namespace emnet::spice_deck
