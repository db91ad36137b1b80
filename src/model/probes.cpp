// The probes of a model: Model::make_probe and Model::parse_probe, and the terms of each probe
// quantity on the model's network (beam motion from the shape functions or, with large
// kinematics, from the nodes; reactions and spring forces from branch unknowns; DEA quantities
// from their electrical nodes). See include/emnet/model/model.hpp and outputs.hpp.
#include "probes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "emnet/core/errors.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/units.hpp"
#include "emnet/elements/corotational_segment.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/model/model.hpp"
#include "position_text.hpp"

namespace emnet {

Probe Model::make_probe(const ProbeSpec& spec) const {
  return make_probe_on(*this, spec, find_dea(spec.dea));
}

namespace {

// The index in Network::elements() of the element recorded as (component, part, index); -1 when
// there is none (a spring between two held nodes is left out).
int recorded_element(const Model& model, Component component, ElementPart part, int index) {
  const std::vector<ElementRecord>& records = model.structure.elements;
  for (std::size_t e = 0; e < records.size(); ++e)
    if (records[e].component == component && records[e].part == part && records[e].index == index)
      return static_cast<int>(e);
  return -1;
}

// The first branch unknown (its index in y) of the element recorded as (component, part, index).
int recorded_branch(const Model& model, Component component, ElementPart part, int index) {
  const int element = recorded_element(model, component, part, index);
  if (element < 0)
    throw std::logic_error(std::string("make_probe: no ") + component_name(component) + " " +
                           element_part_name(part) + " " + std::to_string(index));
  return model.network.branch_unknown_index(static_cast<std::size_t>(element));
}

std::string electrical_dynamics_missing(const Model& model, const std::string& what) {
  const bool automatic = std::any_of(
      model.automatic_choices.begin(), model.automatic_choices.end(),
      [](const AutomaticChoice& choice) { return choice.key == "drive.electrical_dynamics"; });
  return what + " (drive.electrical_dynamics = " +
         (automatic ? std::string("\"auto\" chose false") : "false") + "; set it true)";
}

// The spring probe[].spring names: by its name, else by its index.
int spring_index(const Model& model, const ProbeSpec& spec) {
  const std::vector<SpringSpec>& springs = model.scene.beam.springs;
  for (std::size_t n = 0; n < springs.size(); ++n)
    if (!springs[n].name.empty() && springs[n].name == spec.spring) return static_cast<int>(n);
  for (std::size_t n = 0; n < springs.size(); ++n)
    if (spec.spring == std::to_string(n)) return static_cast<int>(n);
  throw InputError("probe " + spec.name, "spring",
                   "no spring named '" + spec.spring + "' (nor of that index)");
}

// The through quantity a spring element of record index n sends from the held node `held`
// into the rest of the network, for the reaction at `held` (see reaction_terms).
void add_spring_share(const Model& model, int n, double end_x, ProbeQuantity quantity,
                      Probe& probe) {
  const SpringSpec& spring = model.scene.beam.springs[static_cast<std::size_t>(n)];
  const ProbeQuantity carried =
      spring.kind == SpringKind::rotational ? ProbeQuantity::reaction_moment
      : spring.kind == SpringKind::axial    ? ProbeQuantity::axial_reaction_force
                                            : ProbeQuantity::reaction_force;
  if (carried != quantity) return;
  const int node_index = model.beam.node_at(end_x);
  const bool at_held = model.beam.node_at(spring.at) == node_index;
  const bool to_held = spring.to && model.beam.node_at(*spring.to) == node_index;
  if (!at_held && !to_held) return;
  const int element = recorded_element(model, Component::spring, ElementPart::spring_compliance, n);
  if (element < 0) return;  // both ends held: left out, carries nothing
  const auto& inductor =
      static_cast<const Inductor&>(*model.network.elements()[static_cast<std::size_t>(element)]);
  // Through quantity a → b: j + c·(y_a − y_b); the held end's row gets +that at a, −that at b.
  const double sign = at_held ? 1.0 : -1.0;
  const NodeId other = at_held ? inductor.b() : inductor.a();
  probe.terms.emplace_back(model.network.branch_unknown_index(static_cast<std::size_t>(element)),
                           sign);
  if (spring.damping > 0.0 && other != ground) probe.terms.emplace_back(other, -spring.damping);
}

// The held end a reaction probe names (at = 0 or L), checked: the support takes the quantity
// (a force: clamped or pinned; an axial force: clamped, pinned or sliding, large kinematics only;
// a moment: clamped or sliding), no load acts on it.
struct HeldEnd {
  int node = 0;
  bool left = true;
  std::string name;
};

HeldEnd held_end(const Model& model, const ProbeSpec& spec) {
  const BeamLayout& beam = model.beam;
  const bool moment = spec.quantity == ProbeQuantity::reaction_moment;
  const bool axial = spec.quantity == ProbeQuantity::axial_reaction_force;
  const int node = beam.node_at(spec.at);
  const int last = static_cast<int>(beam.x.size()) - 1;
  if (node != 0 && node != last)
    throw InputError("probe " + spec.name, "at",
                     std::string("a reaction is measured at a held end: at = 0 or beam.length (") +
                         format_number("%.6g", beam.length) + " m), not at " +
                         position_text(spec.at));
  const bool left = node == 0;
  const EndCondition end = left ? model.scene.beam.left : model.scene.beam.right;
  const std::string end_key = left ? "beam.left" : "beam.right";
  const std::string end_name = end_condition_name(end);
  const bool holds = moment  ? end == EndCondition::clamped || end == EndCondition::sliding
                     : axial ? end != EndCondition::free
                             : end == EndCondition::clamped || end == EndCondition::pinned;
  if (!holds) {
    std::string why = "the end at " + position_text(spec.at) + " is " + end_name + " (" + end_key +
                      "): its support takes no " +
                      (moment  ? "moment"
                       : axial ? "force along x"
                               : "force");
    if (end == EndCondition::free)
      why += "; a spring support there carries it: probe quantity spring_force with probe[].spring";
    throw InputError("probe " + spec.name, "quantity", why);
  }
  if (beam.kinematics == BeamKinematics::large && last == 1 && beam.axial_velocity[0] == ground &&
      beam.axial_velocity[1] == ground)
    throw InputError("probe " + spec.name, "quantity",
                     "a reaction of a one-segment beam held at both ends is not an output with "
                     "beam.kinematics = \"large\": give beam.segments >= 2");
  int load_index = 0;
  for (const LoadSpec& load : model.scene.loads) {
    if ((load.kind == LoadKind::moment) == moment && load.value != 0.0 &&
        beam.node_at(load.at) == node)
      throw InputError("probe " + spec.name, "at",
                       "load " + std::to_string(load_index) + " (a " +
                           (moment ? "moment" : "force") + " at " + position_text(load.at) +
                           ") acts on the held end and goes straight into the support; the "
                           "reaction probe leaves such loads out: move the load off the end");
    ++load_index;
  }
  return {node, left, end_name};
}

// A DEA with an end on the held rotation node `node` adds −c_H·k_F·u² to its reaction moment
// (c_H = ∓z, its coupling there), a square of its capacitor voltage.
void add_dea_moments_at(const Model& model, const ProbeSpec& spec, int node, Probe& probe) {
  const BeamLayout& beam = model.beam;
  for (const DeaSpec& dea : model.scene.deas) {
    const bool from_here = beam.node_at(dea.from) == node, to_here = beam.node_at(dea.to) == node;
    if (!from_here && !to_here) continue;
    const DeaLayout* layout = model.find_dea(dea.name);
    if (!layout || layout->electrode_node == ground)
      throw InputError("probe " + spec.name, "quantity",
                       electrical_dynamics_missing(
                           model, "DEA '" + dea.name +
                                      "' ends on the held end; its moment there is the "
                                      "ideal drive's k_F*V(t)^2, no output of the network"));
    // Coupling at the held rotation node (ψ there has coefficient 1): −s·z at `from`, +s·z at
    // `to`, s = −1 on the top face (model.cpp dea_layout).
    const double face_sign = dea.face == Face::top ? -1.0 : 1.0;
    const double coupling = (to_here ? 1.0 : -1.0) * face_sign * dea.lever_arm;
    probe.squares.push_back({-coupling * layout->force_constant, {{layout->electrode_node, 1.0}}});
  }
}

// The support's force (translational) or moment (rotational) on the beam at the held end x = 0
// or L: the through quantities of the elements attached to the held node, which the support
// takes (R = Σ through quantities leaving the held node into elements − loads on it; see
// docs/model.md, Outputs).
//   force, left end:   R = −j_lever,0   (the lever's current is −(j + τ·j') of the segment's
//                                        translational compliance: the whole segment force)
//   force, right end:  R = +j_lever,N−1
//   moment, left end:  M = j_R,0 − g_p·Ω₁ − (l/2)·j_lever,0
//   moment, right end: M = −j_R,N−1 − g_p·Ω_N−1 − (l/2)·j_lever,N−1
// with g_p = τ/n_R the Kelvin–Voigt damper across the rotational compliance, whose through
// quantity g_p·(y_a − y_b) is entered from the across values (the held one is zero); springs with
// an end on the held node add their force; a DEA with an end on the held rotation node adds
// −c_H·k_F·u² (c_H = ∓z, its coupling there), a square.
// With large kinematics the end segment's co-rotational element carries the force it draws from
// the held node in the fixed frame (f_x, f_y, corotational_segment.hpp): R_y = f_y,
// R_x = f_x (axial_reaction_force), and the moment's lever share is +(l/2)·Q at either end.
// The large-kinematics end segment at the held end and its first branch unknown's index.
std::pair<const CoRotationalSegment*, int> corotational_segment_at(const Model& model,
                                                                   int segment) {
  const int element =
      recorded_element(model, Component::beam_segment, ElementPart::corotational_segment, segment);
  return {static_cast<const CoRotationalSegment*>(
              model.network.elements()[static_cast<std::size_t>(element)].get()),
          model.network.branch_unknown_index(static_cast<std::size_t>(element))};
}

// The end segment's force on the support: small kinematics ∓j_lever; large kinematics the
// segment's end force unknown (f_x for the axial reaction, f_y for the transverse one).
void add_segment_force(const Model& model, const ProbeSpec& spec, const HeldEnd& held, int segment,
                       Probe& probe) {
  if (model.beam.kinematics != BeamKinematics::large) {
    const int lever = recorded_branch(model, Component::beam_segment, ElementPart::lever, segment);
    probe.terms.emplace_back(lever, held.left ? -1.0 : 1.0);
    return;
  }
  const auto [chord, first] = corotational_segment_at(model, segment);
  if (chord->end_force_branch() < 0)
    throw InputError("probe " + spec.name, "quantity",
                     "a reaction force with beam.kinematics = \"large\" is an output of the "
                     "scene's [[probe]] entries only (the end segment then carries the force "
                     "as unknowns of its own): add it there");
  const bool axial = spec.quantity == ProbeQuantity::axial_reaction_force;
  probe.terms.emplace_back(first + chord->end_force_branch() + (axial ? 0 : 1), 1.0);
}

// The end segment's moment on the support: its rotational compliance's ±j_R and damper, and the
// translational force's lever share, −(l/2)·j_lever (small) or +(l/2)·Q (large).
void add_segment_moment(const Model& model, const HeldEnd& held, int segment, Probe& probe) {
  const int element =
      recorded_element(model, Component::beam_segment, ElementPart::rotational_compliance, segment);
  const auto& compliance =
      static_cast<const Inductor&>(*model.network.elements()[static_cast<std::size_t>(element)]);
  probe.terms.emplace_back(model.network.branch_unknown_index(static_cast<std::size_t>(element)),
                           held.left ? 1.0 : -1.0);
  const NodeId other = held.left ? compliance.b() : compliance.a();
  if (compliance.parallel_conductance() != 0.0 && other != ground)
    probe.terms.emplace_back(other, -compliance.parallel_conductance());
  const double half = 0.5 * model.beam.segment_lengths[static_cast<std::size_t>(segment)];
  if (model.beam.kinematics == BeamKinematics::large) {
    const auto [chord, first] = corotational_segment_at(model, segment);
    probe.terms.emplace_back(first + chord->force_branch(), half);
  } else {
    probe.terms.emplace_back(
        recorded_branch(model, Component::beam_segment, ElementPart::lever, segment), -half);
  }
}

void reaction_terms(const Model& model, const ProbeSpec& spec, Probe& probe) {
  const bool moment = spec.quantity == ProbeQuantity::reaction_moment;
  const bool axial = spec.quantity == ProbeQuantity::axial_reaction_force;
  const HeldEnd held = held_end(model, spec);
  const int segment = held.left ? 0 : held.node - 1;
  if (moment)
    add_segment_moment(model, held, segment, probe);
  else
    add_segment_force(model, spec, held, segment, probe);
  for (std::size_t n = 0; n < model.scene.beam.springs.size(); ++n)
    add_spring_share(model, static_cast<int>(n), spec.at, spec.quantity, probe);
  if (moment) add_dea_moments_at(model, spec, held.node, probe);
  const std::string kind = moment ? "moment" : axial ? "axial force" : "force";
  probe.description = std::string("reaction ") + kind + " of the " + held.name + " support at " +
                      position_text(spec.at) + " on the beam (" +
                      (moment  ? "positive as +psi"
                       : axial ? "positive along +x, fixed frame"
                               : "positive along +w") +
                      ")";
}

// A spring's force (a rotational spring: its moment) for probe[].spring: its compliance's branch
// current plus its dashpot's c*(y_a - y_b).
void spring_force_terms(const Model& model, const ProbeSpec& spec, Probe& probe) {
  const int n = spring_index(model, spec);
  const SpringSpec& spring = model.scene.beam.springs[static_cast<std::size_t>(n)];
  const bool rotational = spring.kind == SpringKind::rotational;
  probe.unit = rotational ? "N*m" : "N";
  const std::string id = spring.name.empty() ? std::to_string(n) : spring.name;
  const std::string what = rotational ? "moment" : "force";
  const std::string to = spring.to ? position_text(*spring.to) : std::string("ground");
  probe.description = "spring " + id + "'s " + what + " k*(" + (rotational ? "phi" : "w") + "(" +
                      position_text(spring.at) + ") - " + (rotational ? "phi" : "w") + "(" + to +
                      ")) + c*rate: positive stretched along +" + (rotational ? "psi" : "w") +
                      " at its 'at' end, which it pulls back";
  const int element = recorded_element(model, Component::spring, ElementPart::spring_compliance, n);
  if (element < 0) {
    probe.description += " (both ends held: it carries nothing)";
    return;
  }
  probe.terms.emplace_back(model.network.branch_unknown_index(static_cast<std::size_t>(element)),
                           1.0);
  const int damper = recorded_element(model, Component::spring, ElementPart::spring_damper, n);
  if (damper >= 0) {
    const auto& inductor =
        static_cast<const Inductor&>(*model.network.elements()[static_cast<std::size_t>(element)]);
    if (inductor.a() != ground) probe.terms.emplace_back(inductor.a(), spring.damping);
    if (inductor.b() != ground) probe.terms.emplace_back(inductor.b(), -spring.damping);
  }
}

// With large kinematics a beam quantity reads the nodes' own unknowns: the probe must sit on a
// node (the mesher puts one at every scene probe) and be one the co-rotational network carries.
// Returns true when it filled `probe`; false for quantities that are not the beam's.
// @throws InputError for a position between nodes or a quantity not yet carried
bool large_kinematics_probe(const BeamLayout& beam, const ProbeSpec& spec, Probe& probe) {
  const std::string who = "probe " + spec.name;
  if (spec.quantity == ProbeQuantity::strain || spec.quantity == ProbeQuantity::spring_force)
    throw InputError(who, "quantity",
                     std::string("'") + probe_quantity_name(spec.quantity) +
                         "' is not available with beam.kinematics = \"large\" yet (deflection, "
                         "axial_displacement, rotation, their rates and the reactions are)");
  if (!is_beam_motion(spec.quantity)) return false;
  const int node = beam.node_at(spec.at);
  if (node < 0)
    throw InputError(who, "at",
                     "is between the beam's nodes; with beam.kinematics = \"large\" a probe reads "
                     "a node: name it in the scene's [[probe]] entries, which get a node each");
  const size_t k = static_cast<size_t>(node);
  const bool axial = spec.quantity == ProbeQuantity::axial_displacement;
  const bool rotational =
      spec.quantity == ProbeQuantity::rotation || spec.quantity == ProbeQuantity::angular_velocity;
  const NodeId id =
      axial ? beam.axial_velocity[k] : (rotational ? beam.angular_velocity[k] : beam.velocity[k]);
  if (id != ground) probe.terms = {{id, 1.0}};
  probe.integrations =
      spec.quantity == ProbeQuantity::velocity || spec.quantity == ProbeQuantity::angular_velocity
          ? 0
          : 1;
  probe.description = std::string(probe_quantity_name(spec.quantity)) + " at " +
                      position_text(spec.at) + " (fixed frame)";
  return true;
}

}  // namespace

Probe make_probe_on(const Model& model, const ProbeSpec& spec, const DeaLayout* dea) {
  const BeamLayout& beam = model.beam;
  Probe probe;
  probe.name = spec.name;
  probe.quantity = spec.quantity;
  probe.unit = probe_unit(spec.quantity);
  const std::string where = position_text(spec.at);
  auto electrical_dea = [&]() {
    if (!dea) throw InputError("probe " + spec.name, "dea", "no DEA named '" + spec.dea + "'");
    if (dea->electrode_node == ground)
      throw InputError(
          "probe " + spec.name, "dea",
          electrical_dynamics_missing(
              model, "DEA '" + spec.dea + "' has no electrical model" +
                         (spec.quantity == ProbeQuantity::dea_force
                              ? ": its force is the ideal drive's k_F*V(t)^2 of its source "
                                "voltage, not an output of the network"
                              : "")));
  };
  if (beam.kinematics == BeamKinematics::large && large_kinematics_probe(beam, spec, probe))
    return probe;
  switch (spec.quantity) {
    case ProbeQuantity::axial_displacement:
      throw InputError("probe " + spec.name, "quantity",
                       "'axial_displacement' needs beam.kinematics = \"large\": with small "
                       "deflections the beam has no axial motion (it is of second order in the "
                       "rotations)");
    case ProbeQuantity::deflection:
    case ProbeQuantity::velocity:
      probe.terms = beam.deflection_terms(spec.at);
      probe.integrations = spec.quantity == ProbeQuantity::deflection ? 1 : 0;
      probe.description = std::string(probe_quantity_name(spec.quantity)) + " at " + where;
      break;
    case ProbeQuantity::rotation:
    case ProbeQuantity::angular_velocity:
      probe.terms = beam.slope_terms(spec.at);
      probe.integrations = spec.quantity == ProbeQuantity::rotation ? 1 : 0;
      probe.description = std::string(probe_quantity_name(spec.quantity)) + " at " + where;
      break;
    case ProbeQuantity::dea_voltage:
    case ProbeQuantity::dea_current: {
      electrical_dea();
      if (spec.quantity == ProbeQuantity::dea_voltage) {
        probe.terms = {{dea->electrode_node, 1.0}};
        probe.description = "capacitor voltage of DEA " + spec.dea;
      } else {
        const double g = 1.0 / dea->electrode_resistance;
        probe.terms = {{dea->source_node, g}, {dea->electrode_node, -g}};
        probe.description = "current into DEA " + spec.dea;
      }
      break;
    }
    case ProbeQuantity::dea_force:
      electrical_dea();
      probe.squares.push_back({dea->force_constant, {{dea->electrode_node, 1.0}}});
      probe.description = "force k_F*u^2 of DEA " + spec.dea +
                          " on its face (k_F = " + format_number("%.6g", dea->force_constant) +
                          " N/V^2)";
      break;
    case ProbeQuantity::axial_reaction_force:
      if (beam.kinematics != BeamKinematics::large)
        throw InputError("probe " + spec.name, "quantity",
                         "'axial_reaction_force' needs beam.kinematics = \"large\": with small "
                         "deflections the beam carries no axial force");
      [[fallthrough]];
    case ProbeQuantity::reaction_force:
    case ProbeQuantity::reaction_moment:
      reaction_terms(model, spec, probe);
      break;
    case ProbeQuantity::spring_force:
      spring_force_terms(model, spec, probe);
      break;
    case ProbeQuantity::strain: {
      // ε = ∓z·dψ/dx: −z on the top face (+w side), +z on the bottom; the time integral of the
      // curvature rate from the velocities.
      const double z = spec.face == Face::top ? -spec.distance : spec.distance;
      for (const auto& [node, c] : beam.curvature_terms(spec.at))
        probe.terms.emplace_back(node, z * c);
      probe.integrations = 1;
      probe.description = std::string("strain of the ") +
                          (spec.face == Face::top ? "top" : "bottom") + " face at " + where +
                          ", z = " + format_number("%.4g", spec.distance * 1e3) +
                          " mm from the neutral plane (positive stretched)";
      break;
    }
  }
  return probe;
}

Probe Model::parse_probe(const std::string& text) const {
  for (const Probe& probe : probes)
    if (probe.name == text) return probe;
  ProbeSpec spec;
  spec.name = text;
  const auto at_sign = text.find('@');
  const auto colon = text.find(':');
  const std::string quantity = text.substr(0, std::min(at_sign, colon));
  bool known = false;
  for (ProbeQuantity q : probe_quantities())
    if (quantity == probe_quantity_name(q)) {
      spec.quantity = q;
      known = true;
    }
  const bool named =
      spec.quantity == ProbeQuantity::dea_voltage || spec.quantity == ProbeQuantity::dea_current ||
      spec.quantity == ProbeQuantity::dea_force || spec.quantity == ProbeQuantity::spring_force;
  if (!known || (named ? colon == std::string::npos || colon + 1 == text.size()
                       : at_sign == std::string::npos))
    throw OptionError("probe",
                      "expected a probe name of the scene, QUANTITY@POSITION (e.g. "
                      "deflection@70mm, velocity@0.1, reaction_force@0, reaction_moment@0), "
                      "strain@POSITION,FACE,DISTANCE (e.g. strain@20mm,top,1.5mm), "
                      "dea_voltage:NAME / dea_current:NAME / dea_force:NAME or "
                      "spring_force:NAME (a spring's name or index)",
                      text);
  // A plain number is SI (metres); anything else must carry a length unit.
  auto length = [&](const std::string& written) {
    try {
      size_t used = 0;
      double plain = 0.0;
      try {
        plain = std::stod(written, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      return used == written.size() && std::isfinite(plain) ? plain
                                                            : parse_quantity(written, dim::length);
    } catch (const std::exception& e) {
      throw OptionError("probe", e.what(), text);
    }
  };
  if (named) {
    (spec.quantity == ProbeQuantity::spring_force ? spec.spring : spec.dea) =
        text.substr(colon + 1);
  } else {
    std::string position = text.substr(at_sign + 1);
    if (spec.quantity == ProbeQuantity::strain) {
      const auto first = position.find(','), second = position.find(',', first + 1);
      if (first == std::string::npos || second == std::string::npos)
        throw OptionError("probe",
                          "a strain needs its face and its distance from the neutral plane: "
                          "strain@POSITION,FACE,DISTANCE (e.g. strain@20mm,top,1.5mm)",
                          text);
      const std::string face = position.substr(first + 1, second - first - 1);
      if (face != "top" && face != "bottom")
        throw OptionError("probe", "the face must be top or bottom, got '" + face + "'", text);
      spec.face = face == "top" ? Face::top : Face::bottom;
      spec.distance = length(position.substr(second + 1));
      if (!(spec.distance > 0.0))
        throw OptionError("probe", "the distance from the neutral plane must be > 0", text);
      position = position.substr(0, first);
    }
    spec.at = length(position);
    if (!(spec.at >= 0.0 && spec.at <= beam.length))
      throw OptionError(
          "probe", "position outside the beam [0, " + std::to_string(beam.length) + " m]", text);
  }
  return make_probe(spec);
}

}  // namespace emnet
