// SPICE lines of a Transformer (a lever with one or more primaries),
// y_s+ − y_s− = Σ a_k·(y_pk+ − y_pk−): a 0 V sense source from s+ to an internal node, then
// one E source per primary in series (gain a_k on that primary's across) down to s−; the sense
// current is emnet's branch unknown (same sign) and each primary receives a_k·j through an F
// source. Primaries of ratio 0 or between ground and ground are left out; the op deck refuses
// a transformer between electrical and mechanical ports.
#include "emnet/elements/transformer.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

namespace {

// The primaries that take part, checked for the op deck.
std::vector<Transformer::Port> active_primaries(const Transformer& t, const DeckWriter& deck) {
  const bool secondary_mechanical = deck.mechanical(t.secondary_plus(), t.secondary_minus());
  std::vector<Transformer::Port> active;
  for (const auto& port : t.primaries()) {
    if (port.ratio == 0.0 || (port.plus == ground && port.minus == ground)) continue;
    if (deck.displacements() && deck.mechanical(port.plus, port.minus) != secondary_mechanical)
      throw InputError(deck.where(), t.name(),
                       "a transformer between electrical and mechanical ports is not written "
                       "to decks in displacements (op; ac with large kinematics)");
    active.push_back(port);
  }
  return active;
}

// The internal nodes of the secondary's series chain, from the sense source down to s−.
std::vector<std::string> secondary_chain(const Transformer& t, size_t primaries, DeckWriter& deck) {
  const std::string& name = t.name();
  const bool secondary_mechanical = deck.mechanical(t.secondary_plus(), t.secondary_minus());
  const NodeId secondary_node =
      t.secondary_plus() != ground ? t.secondary_plus() : t.secondary_minus();
  const std::string unit =
      secondary_node == ground ? "V" : across_unit(deck.network().node(secondary_node).domain);
  std::vector<std::string> chain;
  for (size_t k = 0; k < primaries; ++k)
    chain.push_back(deck.internal_node(
        name + "_" + std::to_string(k + 1),
        "internal node of " + name + ", in the series chain of its secondary [" +
            (deck.displacements() && secondary_mechanical ? (unit == "m/s" ? "m" : "rad") : unit) +
            "]"));
  chain.push_back(deck.node(t.secondary_minus()));
  return chain;
}

}  // namespace

void write_transformer(const Transformer& t, DeckWriter& deck) {
  const std::string& name = t.name();
  const std::vector<Transformer::Port> active = active_primaries(t, deck);
  std::string relation =
      deck.node(t.secondary_plus()) + " - " + deck.node(t.secondary_minus()) + " =";
  for (size_t k = 0; k < active.size(); ++k)
    relation += (k ? " + " : " ") + number(active[k].ratio) + "*" +
                deck.voltage(active[k].plus, active[k].minus);
  if (active.empty()) relation += " 0";
  deck.comment(name + ": ideal transformer, " + relation + "; sense source " +
               "carries its force j, each primary gets ratio*j");
  const std::string sense = deck.element_name('V', name);
  const std::vector<std::string> chain = secondary_chain(t, active.size(), deck);
  std::ostringstream& out = deck.body();
  out << sense << " " << deck.node(t.secondary_plus()) << " " << chain.front() << " DC 0\n";
  for (size_t k = 0; k < active.size(); ++k)
    out << deck.element_name('E', name + "_" + std::to_string(k + 1)) << " " << chain[k] << " "
        << chain[k + 1] << " " << deck.node(active[k].plus) << " " << deck.node(active[k].minus)
        << " " << deck.value(active[k].ratio, name) << "\n";
  for (size_t k = 0; k < active.size(); ++k)
    out << deck.element_name('F', name + "_" + std::to_string(k + 1)) << " "
        << deck.node(active[k].minus) << " " << deck.node(active[k].plus) << " " << sense << " "
        << deck.value(active[k].ratio, name) << "\n";
  deck.branch(name, 0, sense, 1.0);
}

}  // namespace emnet::spice_deck
