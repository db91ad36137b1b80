// SPICE lines of a Gyrator K: two G sources, K·(y_c − y_d) out of a into b and −K·(y_a − y_b)
// out of c into d. The op deck leaves out a source controlled by a mechanical port (its
// across is a velocity there, zero at rest).
#include "emnet/elements/gyrator.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

void write_gyrator(const Gyrator& y, DeckWriter& deck) {
  const std::string& name = y.name();
  const double k = y.gyration();
  std::ostringstream& out = deck.body();
  deck.comment(name + ": gyrator K = " + number(k) + ": current K*V(port 2) out of port 1, " +
               "-K*V(port 1) out of port 2");
  if (!(deck.op() && (deck.mechanical(y.c()) || deck.mechanical(y.d()))))
    out << deck.element_name('G', name + "_1") << " " << deck.node(y.a()) << " " << deck.node(y.b())
        << " " << deck.node(y.c()) << " " << deck.node(y.d()) << " " << deck.value(k, name) << "\n";
  if (!(deck.op() && (deck.mechanical(y.a()) || deck.mechanical(y.b()))))
    out << deck.element_name('G', name + "_2") << " " << deck.node(y.c()) << " " << deck.node(y.d())
        << " " << deck.node(y.a()) << " " << deck.node(y.b()) << " " << deck.value(-k, name)
        << "\n";
}

}  // namespace emnet::spice_deck
