// SPICE lines of a VoltageSource: V plus minus, whose branch current is emnet's branch unknown
// (from plus through the source to minus, same sign). The op deck holds a mechanical one at
// 0 (a clamp), and so does a displacement ac deck; a non-zero velocity source has no static
// state and is refused.
#include "emnet/elements/voltage_source.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

void write_voltage_source(const VoltageSource& v, DeckWriter& deck) {
  const std::string& name = v.name();
  const std::string spice = deck.element_name('V', name);
  std::ostringstream& out = deck.body();
  if (deck.displacements() && deck.mechanical(v.plus(), v.minus())) {
    if (v.waveform().value(0.0) != 0.0)
      throw InputError(deck.where(), name,
                       "a constant velocity source (" + number(v.waveform().value(0.0)) +
                           ") has no static state: no deck in displacements");
    if (deck.ac() && v.waveform().ac_magnitude != 0.0)
      throw InputError(deck.where(), name,
                       "an AC velocity source is not written to the ac deck in displacements "
                       "(beam.kinematics = \"large\")");
    out << spice << " " << deck.node(v.plus()) << " " << deck.node(v.minus()) << " DC 0\n";
  } else {
    out << spice << " " << deck.node(v.plus()) << " " << deck.node(v.minus()) << " "
        << deck.source(v.waveform(), name) << "\n";
  }
  deck.branch(name, 0, spice, 1.0);
}

}  // namespace emnet::spice_deck
