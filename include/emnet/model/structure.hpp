// What each element and node of a model's network realises, recorded by the model builder as it
// adds them.
//
// Every element the builder adds gets one ElementRecord (at its index in Network::elements()),
// every node one NodeRecord (at its index in Network::nodes()): the component of the scene it
// belongs to (a beam node's lumped mass, damper or rotary inertia; a beam segment's compliances
// and lever; a point load; a DEA's electrical loop and transducer; the drive source of a DEA),
// its group (the beam node or segment index, the load index, the DEA's name) and what it is, in
// words. Whoever needs a model's structure (the SPICE writer's groups, the drive's excitation at
// another frequency) reads this record; nothing parses element names.
//
// Supports are no elements: a clamped or pinned end holds its velocity node at ground, a
// clamped or sliding end its rotation node (BeamLayout holds `ground` there). Elements added to a
// model's network after the model was built have no record (ModelStructure::element gives
// nullptr for them).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "emnet/network/network.hpp"

namespace emnet {

/// What part of the scene an element of the model's network was built for.
enum class Component {
  beam_node,     ///< lumped at a beam node: mass, viscous damper, rotary inertia
  beam_segment,  ///< one beam segment: rotational and translational compliance, lever
  load,          ///< a point load of the scene, as consistent nodal loads
  dea,           ///< a DEA's electrical loop: electrode resistance, capacitor and transducer
  drive_source,  ///< what the scene's drive applies to a DEA: its source voltage, or the ideal
                 ///< drive's force k_F·V(t)² along one coupling node
  point_mass,    ///< a [[mass]] entry: its mass and rotary inertia at one beam node
  spring,        ///< a [[spring]] entry: its compliance 1/k and its dashpot
  circuit,       ///< a [[circuit]] entry: one resistor, capacitor, inductor or source
};
/// The name of `component` as messages give it.
const char* component_name(Component component);

/// Which element of its Component an element is.
enum class ElementPart {
  mass,                      ///< beam node: ρA·l share [kg], a capacitor to ground
  viscous_damper,            ///< beam node: c·l share [N·s/m], a conductance to ground
  rotary_inertia,            ///< beam node: ρI·l share [kg·m²], a capacitor to ground
  rotational_compliance,     ///< segment: n_R = l/EI [rad/(N·m)], an inductor
  translational_compliance,  ///< segment: n_T = l³/(12·EI) [m/N], an inductor
  lever,                     ///< segment: the ideal transformer adding (l/2)·(Ω_k + Ω_k+1)
  /// segment (large kinematics): chord, translational and axial compliance in the chord's frame
  corotational_segment,
  axial_mass,        ///< beam node (large kinematics): ρA·l share [kg] on the x velocity node
  axial_damper,      ///< beam node (large kinematics): c·l share [N·s/m] on the x velocity node
  point_axial_mass,  ///< [[mass]] (large kinematics): m [kg] on the x velocity node
  nodal_load,        ///< load: its share on one node [N or N·m], a current source
  electrode_resistance,  ///< DEA: R_e between source and capacitor [Ω], a conductance
  transducer,            ///< DEA: capacitor C₀ and force k_F·u² (the Dea element)
  source_voltage,        ///< drive source: the DEA's source voltage V(t), a voltage source
  ideal_force,           ///< drive source: one part of k_F·V(t)² on one coupling node
  point_mass,            ///< [[mass]]: m [kg], a capacitor from the velocity node to ground
  point_rotary_inertia,  ///< [[mass]]: J [kg·m²], a capacitor from the rotation node to ground
  spring_compliance,     ///< [[spring]]: n = 1/k [m/N or rad/(N·m)], an inductor
  spring_damper,         ///< [[spring]]: its dashpot [N·s/m or N·m·s/rad], a conductance
  resistor,              ///< [[circuit]]: R [Ω], a conductance 1/R
  capacitor,             ///< [[circuit]]: C [F], a capacitor
  inductor,              ///< [[circuit]]: L [H], an inductor
  voltage_source,        ///< [[circuit]]: v(t) [V], V(from) − V(to) = v(t)
  current_source,        ///< [[circuit]]: i(t) [A] from `from` through it into `to`
};
/// The name of `part` as messages give it.
const char* element_part_name(ElementPart part);

/// What one element of the model's network stands for.
struct ElementRecord {
  Component component = Component::beam_node;
  ElementPart part = ElementPart::mass;
  int index = -1;   ///< beam node or segment index, load, mass, spring or circuit entry index;
                    ///< -1 for the DEA parts
  std::string dea;  ///< dea, drive_source: the DEA's name
  /// ideal_force: which waveform of k_F·V(t)² it carries (0: the level or fundamental, 1: a sine
  /// drive's 2f part) and on which coupling node (index into DeaLayout::coupling).
  int force_part = -1;
  int coupling = -1;    ///< see force_part
  std::string meaning;  ///< "lumped mass at beam node 3 [kg]"
};

/// What one node of the model's network stands for.
enum class NodeRole {
  beam_velocity,          ///< v_k: translational velocity at beam node k [m/s]
  beam_angular_velocity,  ///< r_k: angular velocity at beam node k [rad/s]
  beam_axial_velocity,    ///< u_k: fixed-frame x velocity at beam node k [m/s] (large kinematics)
  segment_middle,         ///< m_k: segment k between its spring and its lever [m/s]
  dea_source,             ///< s_X: DEA X's source terminal [V]
  dea_electrode,          ///< e_X: DEA X's capacitor voltage [V]
  circuit,                ///< a [[circuit]] node; the network's node has the scene's name [V]
};

/// What one node of the model's network stands for, with its index.
struct NodeRecord {
  NodeRole role = NodeRole::beam_velocity;
  int index = -1;   ///< beam node or segment index, circuit node in order of appearance; -1 for
                    ///< DEA nodes
  std::string dea;  ///< DEA nodes: the DEA's name
};

/// The record of every node and element the model builder added, by index.
struct ModelStructure {
  std::vector<ElementRecord> elements;  ///< one per element the builder added, in network order
  std::vector<NodeRecord> nodes;        ///< one per node the builder added
  /// nullptr for an element or node the builder did not add.
  const ElementRecord* element(std::size_t index) const {
    return index < elements.size() ? &elements[index] : nullptr;
  }
  /// nullptr for a node the builder did not add.
  const NodeRecord* node(NodeId id) const {
    return id >= 0 && static_cast<std::size_t>(id) < nodes.size()
               ? &nodes[static_cast<std::size_t>(id)]
               : nullptr;
  }
};

/// Adds a node or an element to `network` and its record to `structure` (when given), keeping the
/// two in step.
/// @throws std::logic_error when the record would not land at the element's index
NodeId add_recorded_node(Network& network, ModelStructure* structure, NodeRecord record,
                         std::string name, Domain domain, std::string meaning);
template <class ElementType, class... Args>
ElementType& add_recorded(Network& network, ModelStructure* structure, ElementRecord record,
                          Args&&... args);

// ---- implementation ------------------------------------------------------------------------

void check_record_in_step(const Network& network, const ModelStructure& structure);

template <class ElementType, class... Args>
ElementType& add_recorded(Network& network, ModelStructure* structure, ElementRecord record,
                          Args&&... args) {
  ElementType& element = network.add<ElementType>(std::forward<Args>(args)...);
  if (structure) {
    structure->elements.push_back(std::move(record));
    check_record_in_step(network, *structure);
  }
  return element;
}

}  // namespace emnet
