// The SPICE writer's table of element kinds: each element type and the function that writes
// its lines (deck/<element>.cpp, one file per element kind), found by the element's exact type
// (std::type_index) as gnucap's dispatcher finds a device by name. The writer is a writer over
// element ports and parameters, not a method of each element: the elements know nothing of it.
//
// A new element kind is one file, deck/<element>.cpp with its write_<element>, and one entry
// here: its header's include, its declaration and its line in the table. The list is explicit on
// purpose. A self-registering static object in each deck/<element>.cpp would need no entry here,
// but emnet is a static library (libemnet.a): the linker takes an object file from it only when
// something references a symbol in it, so a file that only registers itself is silently left
// out and its element has no SPICE form. One list in the file that the writer references
// cannot be dropped, and reads in one place which kinds the writer knows.
#include <typeindex>
#include <unordered_map>

#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/corotational_segment.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/elements/gyrator.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/elements/transformer.hpp"
#include "emnet/elements/voltage_source.hpp"
#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

void write_capacitor(const Capacitor& element, DeckWriter& deck);
void write_conductance(const Conductance& element, DeckWriter& deck);
void write_corotational_segment(const CoRotationalSegment& element, DeckWriter& deck);
void write_current_source(const CurrentSource& element, DeckWriter& deck);
void write_dea(const Dea& element, DeckWriter& deck);
void write_gyrator(const Gyrator& element, DeckWriter& deck);
void write_inductor(const Inductor& element, DeckWriter& deck);
void write_transformer(const Transformer& element, DeckWriter& deck);
void write_voltage_source(const VoltageSource& element, DeckWriter& deck);

namespace {

using ElementWriter = void (*)(const Element& element, DeckWriter& deck);

// The writer of ElementType as an ElementWriter: the table found the type, so the cast holds.
template <class ElementType, void (*write)(const ElementType&, DeckWriter&)>
void write_as(const Element& element, DeckWriter& deck) {
  write(static_cast<const ElementType&>(element), deck);
}

template <class ElementType, void (*write)(const ElementType&, DeckWriter&)>
std::pair<const std::type_index, ElementWriter> entry() {
  return {std::type_index(typeid(ElementType)), &write_as<ElementType, write>};
}

const std::unordered_map<std::type_index, ElementWriter>& element_writers() {
  static const std::unordered_map<std::type_index, ElementWriter> writers = {
      entry<Capacitor, write_capacitor>(),
      entry<Conductance, write_conductance>(),
      entry<CoRotationalSegment, write_corotational_segment>(),
      entry<CurrentSource, write_current_source>(),
      entry<Dea, write_dea>(),
      entry<Gyrator, write_gyrator>(),
      entry<Inductor, write_inductor>(),
      entry<Transformer, write_transformer>(),
      entry<VoltageSource, write_voltage_source>(),
  };
  return writers;
}

}  // namespace

void DeckWriter::write_element(const Element& element) {
  const auto& writers = element_writers();
  const auto writer = writers.find(std::type_index(typeid(element)));
  if (writer == writers.end())
    throw InputError(where(), element.name(),
                     std::string("element kind '") + element.kind() +
                         "' has no SPICE equivalent in this writer");
  writer->second(element, *this);
}

}  // namespace emnet::spice_deck
