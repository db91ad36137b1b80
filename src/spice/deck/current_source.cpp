// SPICE lines of a CurrentSource: I from → to (SPICE's current flows from its first node
// through the source into its second, so it is injected into `to`, as in emnet), with the
// waveform's time function (tran) or its value at t = 0 and AC phasor (op, ac).
#include "emnet/elements/current_source.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

void write_current_source(const CurrentSource& i, DeckWriter& deck) {
  const std::string& name = i.name();
  deck.body() << deck.element_name('I', name) << " " << deck.node(i.from()) << " "
              << deck.node(i.to()) << " " << deck.source(i.waveform(), name) << "\n";
}

}  // namespace emnet::spice_deck
