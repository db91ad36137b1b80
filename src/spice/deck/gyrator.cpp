// SPICE lines of a Gyrator K: two G sources, K·(y_c − y_d) out of a into b and −K·(y_a − y_b)
// out of c into d. The op deck leaves out a source controlled by a mechanical port (its
// across is a velocity there, zero at rest); a displacement ac deck controls it by the port's
// rate nodes.
#include "emnet/elements/gyrator.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

void write_gyrator(const Gyrator& y, DeckWriter& deck) {
  const std::string& name = y.name();
  const double k = y.gyration();
  std::ostringstream& out = deck.body();
  deck.comment(name + ": gyrator K = " + number(k) + ": current K*V(port 2) out of port 1, " +
               "-K*V(port 1) out of port 2");
  // The across of a port as the deck holds it: a mechanical one's rate in displacements.
  auto across = [&](NodeId plus, NodeId minus) {
    if (!deck.displacements() || !deck.mechanical(plus, minus))
      return deck.node(plus) + " " + deck.node(minus);
    return deck.rate(plus) + " " + deck.rate(minus);
  };
  // (each across before its line: a rate node writes its own lines)
  if (!(deck.op() && deck.mechanical(y.c(), y.d()))) {
    const std::string control = across(y.c(), y.d());
    out << deck.element_name('G', name + "_1") << " " << deck.node(y.a()) << " " << deck.node(y.b())
        << " " << control << " " << deck.value(k, name) << "\n";
  }
  if (!(deck.op() && deck.mechanical(y.a(), y.b()))) {
    const std::string control = across(y.a(), y.b());
    out << deck.element_name('G', name + "_2") << " " << deck.node(y.c()) << " " << deck.node(y.d())
        << " " << control << " " << deck.value(-k, name) << "\n";
  }
}

}  // namespace emnet::spice_deck
