// The model's record of its nodes and elements: see include/emnet/model/structure.hpp.
#include "emnet/model/structure.hpp"

#include <stdexcept>

namespace emnet {

const char* component_name(Component component) {
  switch (component) {
    case Component::beam_node:
      return "beam node";
    case Component::beam_segment:
      return "beam segment";
    case Component::load:
      return "load";
    case Component::dea:
      return "DEA";
    case Component::drive_source:
      return "drive source";
    case Component::point_mass:
      return "point mass";
    case Component::spring:
      return "spring";
    case Component::circuit:
      return "circuit";
  }
  return "?";
}

const char* element_part_name(ElementPart part) {
  switch (part) {
    case ElementPart::mass:
      return "mass";
    case ElementPart::viscous_damper:
      return "viscous damper";
    case ElementPart::rotary_inertia:
      return "rotary inertia";
    case ElementPart::rotational_compliance:
      return "rotational compliance";
    case ElementPart::translational_compliance:
      return "translational compliance";
    case ElementPart::lever:
      return "lever";
    case ElementPart::corotational_segment:
      return "co-rotational segment";
    case ElementPart::axial_mass:
      return "axial mass";
    case ElementPart::axial_damper:
      return "axial viscous damper";
    case ElementPart::point_axial_mass:
      return "point axial mass";
    case ElementPart::nodal_load:
      return "nodal load";
    case ElementPart::electrode_resistance:
      return "electrode resistance";
    case ElementPart::transducer:
      return "transducer";
    case ElementPart::source_voltage:
      return "source voltage";
    case ElementPart::ideal_force:
      return "ideal force";
    case ElementPart::point_mass:
      return "point mass";
    case ElementPart::point_rotary_inertia:
      return "point rotary inertia";
    case ElementPart::spring_compliance:
      return "spring compliance";
    case ElementPart::spring_damper:
      return "spring damper";
    case ElementPart::resistor:
      return "resistor";
    case ElementPart::capacitor:
      return "capacitor";
    case ElementPart::inductor:
      return "inductor";
    case ElementPart::voltage_source:
      return "voltage source";
    case ElementPart::current_source:
      return "current source";
  }
  return "?";
}

void check_record_in_step(const Network& network, const ModelStructure& structure) {
  if (structure.elements.size() != network.elements().size() ||
      structure.nodes.size() != network.nodes().size())
    throw std::logic_error(
        "model structure: " + std::to_string(structure.elements.size()) + " element and " +
        std::to_string(structure.nodes.size()) + " node records for a network of " +
        std::to_string(network.elements().size()) + " elements and " +
        std::to_string(network.nodes().size()) + " nodes (something was added without its record)");
}

NodeId add_recorded_node(Network& network, ModelStructure* structure, NodeRecord record,
                         std::string name, Domain domain, std::string meaning) {
  const NodeId id = network.add_node(std::move(name), domain, std::move(meaning));
  if (structure) {
    structure->nodes.push_back(std::move(record));
    check_record_in_step(network, *structure);
  }
  return id;
}

}  // namespace emnet
