// SPICE lines of an Inductor n: an inductor L = n whose branch current is emnet's branch
// unknown (same sign), with its parallel conductance as a resistor across it; n = 0 is a short,
// a 0 V source. In the op deck a mechanical compliance is a resistor R = n between displacement
// nodes (z_a − z_b = n·F), without a branch vector, and its damper is left out; a displacement
// ac deck writes the compliance the same way and its damper as a capacitor g across it.
#include "emnet/elements/inductor.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

void write_inductor(const Inductor& l, DeckWriter& deck) {
  const std::string& name = l.name();
  std::ostringstream& out = deck.body();
  if (l.inductance() == 0.0) {
    const std::string spice = deck.element_name('V', name);
    deck.comment(name + ": inductance 0: a short, written as a 0 V source");
    out << spice << " " << deck.node(l.a()) << " " << deck.node(l.b()) << " DC 0\n";
    deck.branch(name, 0, spice, 1.0);
    return;
  }
  if (deck.displacements() && deck.mechanical(l.a(), l.b())) {
    // z_a − z_b = n·F: the compliance is a resistor n between displacement nodes (a damper
    // across it carries no force at rest).
    if (l.parallel_conductance() != 0.0 && deck.op()) deck.leave_out(name + " (its damper)");
    out << deck.element_name('R', name) << " " << deck.node(l.a()) << " " << deck.node(l.b()) << " "
        << deck.value(l.inductance(), name) << "\n";
    if (l.parallel_conductance() != 0.0 && !deck.op())
      out << deck.element_name('C', name) << " " << deck.node(l.a()) << " " << deck.node(l.b())
          << " " << deck.value(l.parallel_conductance(), name) << "\n";
    deck.branch(name, 0, "", 1.0);
    return;
  }
  const std::string spice = deck.element_name('L', name);
  out << spice << " " << deck.node(l.a()) << " " << deck.node(l.b()) << " "
      << deck.value(l.inductance(), name) << "\n";
  deck.branch(name, 0, spice, 1.0);
  // Its parallel conductance as a resistor across it (the same equations; in an op deck it
  // carries no force at rest and is left out above with the coil written as a resistor).
  if (l.parallel_conductance() != 0.0)
    out << deck.element_name('R', name) << " " << deck.node(l.a()) << " " << deck.node(l.b()) << " "
        << deck.value(1.0 / l.parallel_conductance(), name) << "\n";
}

}  // namespace emnet::spice_deck
