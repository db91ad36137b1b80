// Beam chain builder and Hermite interpolation: see include/emnet/model/model.hpp for the physics.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/corotational_segment.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/elements/transformer.hpp"
#include "emnet/model/mesh.hpp"
#include "emnet/model/model.hpp"
#include "position_text.hpp"

namespace emnet {

namespace {

// Segment index and local coordinate ξ ∈ [0, 1] of position x.
std::pair<int, double> locate(const BeamLayout& beam, double x) {
  const int segments = static_cast<int>(beam.x.size()) - 1;
  int s = 0;
  if (beam.uniform) {
    s = static_cast<int>(std::floor(x / beam.segment_length));
  } else {
    s = static_cast<int>(std::upper_bound(beam.x.begin(), beam.x.end(), x) - beam.x.begin()) - 1;
  }
  s = std::clamp(s, 0, segments - 1);
  const double l = beam.segment_lengths[static_cast<size_t>(s)];
  double xi = (x - beam.x[static_cast<size_t>(s)]) / l;
  // A position on a node within rounding is that node exactly (no 1e-17 coefficients).
  if (std::abs(xi - 1.0) < 1e-9 && s + 1 < segments) ++s, xi = 0.0;
  if (std::abs(xi) < 1e-9) xi = 0.0;
  if (std::abs(xi - 1.0) < 1e-9) xi = 1.0;
  return {s, std::clamp(xi, 0.0, 1.0)};
}

LinearTerms merge(const std::vector<std::pair<NodeId, double>>& raw) {
  std::map<int, double> sum;
  for (const auto& [node, c] : raw)
    if (node != ground && c != 0.0) sum[node] += c;
  LinearTerms out;
  for (const auto& [node, c] : sum)
    if (c != 0.0) out.emplace_back(node, c);
  return out;
}

// Shape-function coefficients of (w_a, ψ_a, w_b, ψ_b) at ξ: the exact solution of a massless
// segment loaded at its ends. Euler–Bernoulli: the cubic Hermite functions. With shear
// (Φ = 12·EI/(κGA·l²), μ = 1/(1 + Φ)): the shear-corrected cubics, whose shear strain
// w' − ψ is constant along the segment, as the constant shear force of a massless segment makes
// it:
//   w: μ(2ξ³ − 3ξ² − Φξ + 1 + Φ), μl(ξ³ − (2 + Φ/2)ξ² + (1 + Φ/2)ξ), μ(−2ξ³ + 3ξ² + Φξ),
//      μl(ξ³ − (1 − Φ/2)ξ² − (Φ/2)ξ);
//   ψ: 6μ(ξ² − ξ)/l, μ(3ξ² − (4 + Φ)ξ + 1 + Φ), −6μ(ξ² − ξ)/l, μ(3ξ² − (2 − Φ)ξ).
// Φ = 0 gives the Hermite functions and their derivatives.
struct Shape {
  double w_a, psi_a, w_b, psi_b;
};

enum class ShapeOf { deflection, rotation, curvature };

Shape shape(ShapeOf what, double xi, double l, double phi) {
  if (phi == 0.0) {
    switch (what) {
      case ShapeOf::deflection:
        return {1 - 3 * xi * xi + 2 * xi * xi * xi, l * (xi - 2 * xi * xi + xi * xi * xi),
                3 * xi * xi - 2 * xi * xi * xi, l * (-xi * xi + xi * xi * xi)};
      case ShapeOf::rotation:
        return {(-6 * xi + 6 * xi * xi) / l, 1 - 4 * xi + 3 * xi * xi, (6 * xi - 6 * xi * xi) / l,
                -2 * xi + 3 * xi * xi};
      case ShapeOf::curvature:
        return {(-6 + 12 * xi) / (l * l), (-4 + 6 * xi) / l, (6 - 12 * xi) / (l * l),
                (-2 + 6 * xi) / l};
    }
  }
  const double mu = 1.0 / (1.0 + phi), xi2 = xi * xi, xi3 = xi2 * xi;
  switch (what) {
    case ShapeOf::deflection:
      return {mu * (2 * xi3 - 3 * xi2 - phi * xi + 1 + phi),
              mu * l * (xi3 - (2 + phi / 2) * xi2 + (1 + phi / 2) * xi),
              mu * (-2 * xi3 + 3 * xi2 + phi * xi),
              mu * l * (xi3 - (1 - phi / 2) * xi2 - (phi / 2) * xi)};
    case ShapeOf::rotation:
      return {6 * mu * (xi2 - xi) / l, mu * (3 * xi2 - (4 + phi) * xi + 1 + phi),
              -6 * mu * (xi2 - xi) / l, mu * (3 * xi2 - (2 - phi) * xi)};
    case ShapeOf::curvature:
      return {6 * mu * (2 * xi - 1) / (l * l), mu * (6 * xi - (4 + phi)) / l,
              -6 * mu * (2 * xi - 1) / (l * l), mu * (6 * xi - (2 - phi)) / l};
  }
  return {0, 0, 0, 0};
}

LinearTerms shape_terms(const BeamLayout& beam, ShapeOf what, double x) {
  const auto [s, xi] = locate(beam, x);
  const size_t a = static_cast<size_t>(s), b = a + 1;
  const Shape c = shape(what, xi, beam.segment_lengths[a], beam.shear_parameter[a]);
  return merge({{beam.velocity[a], c.w_a},
                {beam.angular_velocity[a], c.psi_a},
                {beam.velocity[b], c.w_b},
                {beam.angular_velocity[b], c.psi_b}});
}

}  // namespace

LinearTerms BeamLayout::deflection_terms(double x) const {
  return shape_terms(*this, ShapeOf::deflection, x);
}

LinearTerms BeamLayout::slope_terms(double x) const {
  return shape_terms(*this, ShapeOf::rotation, x);
}

LinearTerms BeamLayout::curvature_terms(double x) const {
  return shape_terms(*this, ShapeOf::curvature, x);
}

int BeamLayout::node_at(double position) const {
  const double tolerance = 1e-9 * length;
  const auto above = std::lower_bound(x.begin(), x.end(), position - tolerance);
  if (above != x.end() && std::abs(*above - position) <= tolerance)
    return static_cast<int>(above - x.begin());
  return -1;
}

namespace {

// The node at `position` that the mesh put there for `what` (a mass, a spring's end).
size_t attachment_node(const BeamLayout& beam, double position, const std::string& what) {
  const int node = beam.node_at(position);
  if (node < 0)
    throw std::logic_error("add_beam: no node at " + position_text(position) + " for " + what);
  return static_cast<size_t>(node);
}

// Point masses: a capacitor m to ground on the velocity node, J on the angular velocity node
// (see model.hpp).
void add_point_masses(Network& network, const BeamSpec& spec, const BeamLayout& beam,
                      ModelStructure* structure) {
  for (size_t m = 0; m < spec.masses.size(); ++m) {
    const MassSpec& mass = spec.masses[m];
    const std::string id = mass.name.empty() ? std::to_string(m) : mass.name;
    const size_t k = attachment_node(beam, mass.at, "mass " + id);
    auto record = [&](ElementPart part, const std::string& what) {
      return ElementRecord{Component::point_mass,
                           part,
                           static_cast<int>(m),
                           "",
                           -1,
                           -1,
                           what + " of point mass " + id + " at " + position_text(mass.at)};
    };
    if (beam.velocity[k] != ground && mass.mass > 0.0)
      add_recorded<Capacitor>(network, structure, record(ElementPart::point_mass, "mass [kg]"),
                              "pm" + std::to_string(m), beam.velocity[k], ground, mass.mass);
    if (!beam.axial_velocity.empty() && beam.axial_velocity[k] != ground && mass.mass > 0.0)
      add_recorded<Capacitor>(network, structure,
                              record(ElementPart::point_axial_mass, "mass along x [kg]"),
                              "pmx" + std::to_string(m), beam.axial_velocity[k], ground, mass.mass);
    if (beam.angular_velocity[k] != ground && mass.rotary_inertia > 0.0)
      add_recorded<Capacitor>(
          network, structure, record(ElementPart::point_rotary_inertia, "rotary inertia [kg*m^2]"),
          "pj" + std::to_string(m), beam.angular_velocity[k], ground, mass.rotary_inertia);
  }
}

// Springs: an inductor 1/k between their ends' nodes (ground for none), a dashpot c across it
// (see model.hpp).
void add_springs(Network& network, const BeamSpec& spec, const BeamLayout& beam,
                 ModelStructure* structure) {
  for (size_t n = 0; n < spec.springs.size(); ++n) {
    const SpringSpec& spring = spec.springs[n];
    const std::string id = spring.name.empty() ? std::to_string(n) : spring.name;
    const bool rotational = spring.kind == SpringKind::rotational;
    const bool axial = spring.kind == SpringKind::axial;  // along x: large kinematics only
    if (axial && beam.axial_velocity.empty())
      throw std::logic_error("add_beam: an axial spring needs large kinematics");
    const std::vector<NodeId>& nodes =
        rotational ? beam.angular_velocity : (axial ? beam.axial_velocity : beam.velocity);
    const NodeId a = nodes[attachment_node(beam, spring.at, "spring " + id)];
    const NodeId b = spring.to ? nodes[attachment_node(beam, *spring.to, "spring " + id)] : ground;
    if (a == b) continue;  // both ends held (or the same node): no force
    const Domain domain = rotational ? Domain::rotational : Domain::translational;
    const std::string where = "spring " + id + " (" +
                              (rotational ? "rotational"
                               : axial    ? "axial"
                                          : "translational") +
                              ") at " + position_text(spring.at);
    add_recorded<Inductor>(
        network, structure,
        {Component::spring, ElementPart::spring_compliance, static_cast<int>(n), "", -1, -1,
         "compliance 1/k " + std::string(rotational ? "[rad/(N*m)]" : "[m/N]") + " of " + where},
        "ks" + std::to_string(n), a, b, 1.0 / spring.stiffness, domain);
    if (spring.damping > 0.0)
      add_recorded<Conductance>(
          network, structure,
          {Component::spring, ElementPart::spring_damper, static_cast<int>(n), "", -1, -1,
           "dashpot " + std::string(rotational ? "[N*m*s/rad]" : "[N*s/m]") + " of " + where},
          "cs" + std::to_string(n), a, b, spring.damping);
  }
}

// The layout's grid: node positions, each segment's length, section and shear parameter
// Φ = 12·EI/(κGA·l²) (0 for Euler–Bernoulli).
void lay_out_segments(const BeamSpec& spec, const BeamMesh& mesh,
                      const std::vector<SectionSpec>& sections, BeamLayout& beam) {
  const int n = mesh.segments();
  beam.length = spec.length;
  beam.segment_length = spec.length / n;
  beam.uniform = mesh.uniform;
  beam.x = mesh.x;
  beam.raised_from = mesh.raised_from;
  beam.segment_section = mesh.section;
  const bool timoshenko = spec.theory == BeamTheory::timoshenko;
  for (int k = 0; k < n; ++k) {
    const size_t i = static_cast<size_t>(k);
    const SectionSpec& section = sections[static_cast<size_t>(mesh.section[i])];
    const double l = mesh.uniform ? beam.segment_length : mesh.x[i + 1] - mesh.x[i];
    beam.segment_lengths.push_back(l);
    const double shear = section.shear_stiffness.value_or(spec.shear_stiffness);
    beam.shear_parameter.push_back(
        timoshenko && shear > 0.0 ? 12.0 * section.bending_stiffness / (shear * l * l) : 0.0);
  }
}

// The velocity and angular velocity node of each grid point; ground where an end holds it.
void add_beam_nodes(Network& network, const BeamSpec& spec, BeamLayout& beam,
                    ModelStructure* structure) {
  const int n = static_cast<int>(beam.x.size()) - 1;
  for (int k = 0; k <= n; ++k) {
    const double x = beam.x[static_cast<size_t>(k)];
    const bool left = k == 0, right = k == n;
    const EndCondition end = left ? spec.left : spec.right;
    const bool at_end = left || right;
    const bool hold_v = at_end && (end == EndCondition::clamped || end == EndCondition::pinned);
    const bool hold_r = at_end && (end == EndCondition::clamped || end == EndCondition::sliding);
    // Large kinematics: a clamped, pinned or sliding end holds x too (a sliding end slides
    // across the beam, not along it).
    const bool hold_x = at_end && end != EndCondition::free;
    const std::string where = position_text(x);
    if (beam.kinematics == BeamKinematics::large)
      beam.axial_velocity.push_back(
          hold_x ? ground
                 : add_recorded_node(network, structure, {NodeRole::beam_axial_velocity, k, ""},
                                     "u" + std::to_string(k), Domain::translational,
                                     "x velocity at " + where + " [m/s]"));
    beam.velocity.push_back(
        hold_v ? ground
               : add_recorded_node(network, structure, {NodeRole::beam_velocity, k, ""},
                                   "v" + std::to_string(k), Domain::translational,
                                   "velocity at " + where + " [m/s]"));
    beam.angular_velocity.push_back(
        hold_r ? ground
               : add_recorded_node(network, structure, {NodeRole::beam_angular_velocity, k, ""},
                                   "r" + std::to_string(k), Domain::rotational,
                                   "angular velocity at " + where + " [rad/s]"));
  }
}

// Lumped mass, rotary inertia and viscous damping: half of each adjacent segment's share.
void add_lumped_node_elements(Network& network, const BeamMesh& mesh,
                              const std::vector<SectionSpec>& sections, const DampingSpec& damping,
                              const BeamLayout& beam, ModelStructure* structure) {
  const int n = mesh.segments();
  for (int k = 0; k <= n; ++k) {
    const size_t i = static_cast<size_t>(k);
    double mass = 0.0, inertia = 0.0, viscous = 0.0;
    for (const int segment : {k - 1, k}) {
      if (segment < 0 || segment >= n) continue;
      const size_t s = static_cast<size_t>(segment);
      const SectionSpec& section = sections[static_cast<size_t>(mesh.section[s])];
      const double half = 0.5 * beam.segment_lengths[s];
      mass += section.mass_per_length * half;
      inertia += section.rotary_inertia_per_length * half;
      viscous += section.viscous_per_length.value_or(damping.viscous_per_length) * half;
    }
    const std::string id = std::to_string(k);
    auto record = [&](ElementPart part, const std::string& what) {
      return ElementRecord{
          Component::beam_node, part, k, "", -1, -1, what + " lumped at beam node " + id};
    };
    if (beam.velocity[i] != ground) {
      add_recorded<Capacitor>(network, structure, record(ElementPart::mass, "mass [kg]"),
                              "mass" + id, beam.velocity[i], ground, mass);
      if (viscous > 0.0)
        add_recorded<Conductance>(network, structure,
                                  record(ElementPart::viscous_damper, "viscous damper [N*s/m]"),
                                  "damper" + id, beam.velocity[i], ground, viscous);
    }
    if (beam.angular_velocity[i] != ground && inertia > 0.0)
      add_recorded<Capacitor>(network, structure,
                              record(ElementPart::rotary_inertia, "rotary inertia [kg*m^2]"),
                              "inertia" + id, beam.angular_velocity[i], ground, inertia);
    // Large kinematics: the mass and the viscous damping act in the fixed frame's x too.
    if (beam.axial_velocity.empty() || beam.axial_velocity[i] == ground) continue;
    add_recorded<Capacitor>(network, structure,
                            record(ElementPart::axial_mass, "mass along x [kg]"), "massx" + id,
                            beam.axial_velocity[i], ground, mass);
    if (viscous > 0.0)
      add_recorded<Conductance>(network, structure,
                                record(ElementPart::axial_damper, "viscous damper along x [N*s/m]"),
                                "damperx" + id, beam.axial_velocity[i], ground, viscous);
  }
}

// One segment's values as its section gives them: length l, EI, the Kelvin–Voigt time τ, the
// rotational compliance l/EI, the translational compliance l³/(12·EI) (+ l/(κGA) with shear)
// and, for large kinematics, the axial compliance l/EA (0: inextensible).
struct SegmentValues {
  double length = 0.0;
  double kelvin_voigt_time = 0.0;
  double rotational_compliance = 0.0;
  double translational_compliance = 0.0;
  bool sheared = false;
  double axial_compliance = 0.0;
};

SegmentValues segment_values(const BeamSpec& spec, const BeamMesh& mesh,
                             const std::vector<SectionSpec>& sections, const DampingSpec& damping,
                             const BeamLayout& beam, int k) {
  const size_t a = static_cast<size_t>(k);
  const SectionSpec& section = sections[static_cast<size_t>(mesh.section[a])];
  SegmentValues values;
  const double l = beam.segment_lengths[a];
  const double ei = section.bending_stiffness;
  values.length = l;
  values.kelvin_voigt_time =
      section.kelvin_voigt_time.value_or(damping.effective_kelvin_voigt_time());
  values.rotational_compliance = l / ei;
  values.translational_compliance = l * l * l / (12.0 * ei);
  values.sheared = beam.shear_parameter[a] > 0.0;
  if (values.sheared)
    values.translational_compliance += l / section.shear_stiffness.value_or(spec.shear_stiffness);
  const double axial_stiffness = effective_axial_stiffness(spec, section);
  values.axial_compliance = axial_stiffness > 0.0 ? l / axial_stiffness : 0.0;
  return values;
}

// The record of part `part` of beam segment k.
ElementRecord segment_record(int k, ElementPart part, const std::string& what) {
  return ElementRecord{
      Component::beam_segment, part, k, "", -1, -1, what + " of beam segment " + std::to_string(k)};
}

// Segment k's rotational compliance l/EI between its rotation nodes, with the Kelvin–Voigt
// damper τ/n across it (stamped as τ·(spring force)'): the same with either kinematics.
void add_rotational_compliance(Network& network, const BeamLayout& beam,
                               const SegmentValues& segment, int k, ModelStructure* structure) {
  const size_t a = static_cast<size_t>(k), b = a + 1;
  add_recorded<Inductor>(network, structure,
                         segment_record(k, ElementPart::rotational_compliance,
                                        "rotational compliance l/EI [rad/(N*m)]"),
                         "nR" + std::to_string(k), beam.angular_velocity[a],
                         beam.angular_velocity[b], segment.rotational_compliance,
                         Domain::rotational,
                         segment.kelvin_voigt_time / segment.rotational_compliance);
}

// Large kinematics: each segment's rotational compliance l/EI (as with small kinematics) and
// its co-rotational element: chord, translational compliance l³/(12·EI) (+ l/(κGA)) in the
// chord's frame and axial compliance l/EA (none: inextensible); see corotational_segment.hpp.
void add_corotational_segments(Network& network, const BeamSpec& spec, const BeamMesh& mesh,
                               const std::vector<SectionSpec>& sections, const DampingSpec& damping,
                               const BeamLayout& beam, ModelStructure* structure,
                               ReactionEnds reactions) {
  // A held end whose reaction force is an output: its segment carries the force it draws from
  // it (only then: two more algebraic unknowns change IDA's steps).
  auto held = [&](size_t node) {
    return beam.axial_velocity[node] == ground || beam.velocity[node] == ground;
  };
  const size_t last = static_cast<size_t>(mesh.segments());
  const bool left_force = reactions.left && held(0);
  const bool right_force = reactions.right && held(last) && !(left_force && last == 1);
  for (int k = 0; k < mesh.segments(); ++k) {
    const size_t a = static_cast<size_t>(k), b = a + 1;
    const SegmentValues segment = segment_values(spec, mesh, sections, damping, beam, k);
    const CoRotationalSegment::EndForce end_force =
        a == 0 && left_force       ? CoRotationalSegment::EndForce::a
        : b == last && right_force ? CoRotationalSegment::EndForce::b
                                   : CoRotationalSegment::EndForce::none;
    add_rotational_compliance(network, beam, segment, k, structure);
    add_recorded<CoRotationalSegment>(
        network, structure,
        segment_record(k, ElementPart::corotational_segment,
                       std::string("chord, translational compliance [m/N] and ") +
                           (segment.axial_compliance > 0.0 ? "axial compliance l/EA [m/N]"
                                                           : "inextensible axis")),
        "seg" + std::to_string(k),
        CoRotationalSegment::End{beam.axial_velocity[a], beam.velocity[a],
                                 beam.angular_velocity[a]},
        CoRotationalSegment::End{beam.axial_velocity[b], beam.velocity[b],
                                 beam.angular_velocity[b]},
        segment.length, segment.translational_compliance, segment.axial_compliance,
        segment.kelvin_voigt_time, end_force);
  }
}

// Each segment's rotational compliance l/EI, translational compliance l³/(12·EI) (+ l/(κGA) with
// shear) to its middle node, and the lever (l/2)·(Ω_k + Ω_k+1) from there to the next node.
void add_segment_elements(Network& network, const BeamSpec& spec, const BeamMesh& mesh,
                          const std::vector<SectionSpec>& sections, const DampingSpec& damping,
                          const BeamLayout& beam, ModelStructure* structure,
                          ReactionEnds reactions) {
  if (spec.kinematics == BeamKinematics::large) {
    add_corotational_segments(network, spec, mesh, sections, damping, beam, structure, reactions);
    return;
  }
  for (int k = 0; k < mesh.segments(); ++k) {
    const size_t a = static_cast<size_t>(k), b = a + 1;
    const SegmentValues segment = segment_values(spec, mesh, sections, damping, beam, k);
    const double l = segment.length, tau = segment.kelvin_voigt_time;
    const double translational_compliance = segment.translational_compliance;
    const bool sheared = segment.sheared;
    const std::string id = std::to_string(k);
    const NodeId middle = add_recorded_node(
        network, structure, {NodeRole::segment_middle, k, ""}, "m" + id, Domain::translational,
        "segment " + id + " branch between spring and lever [m/s]");
    auto record = [&](ElementPart part, const std::string& what) {
      return segment_record(k, part, what);
    };
    add_rotational_compliance(network, beam, segment, k, structure);
    add_recorded<Inductor>(
        network, structure,
        record(ElementPart::translational_compliance,
               sheared ? "translational compliance l^3/(12*EI) + l/(kappa*G*A) [m/N]"
                       : "translational compliance l^3/(12*EI) [m/N]"),
        "nT" + id, beam.velocity[a], middle, translational_compliance, Domain::translational,
        tau / translational_compliance);
    add_recorded<Transformer>(
        network, structure, record(ElementPart::lever, "lever (l/2)*(Omega_k + Omega_k+1)"),
        "lever" + id, beam.velocity[b], middle,
        std::vector<Transformer::Port>{{beam.angular_velocity[a], ground, 0.5 * l},
                                       {beam.angular_velocity[b], ground, 0.5 * l}},
        Domain::translational);
  }
}

}  // namespace

BeamLayout add_beam(Network& network, const BeamSpec& spec, const DampingSpec& damping,
                    const std::vector<double>& attachments, ModelStructure* structure,
                    ReactionEnds reactions) {
  BeamLayout beam;
  beam.kinematics = spec.kinematics;
  const BeamMesh mesh = mesh_beam(spec, attachments);
  const std::vector<SectionSpec> sections = effective_sections(spec);
  lay_out_segments(spec, mesh, sections, beam);
  add_beam_nodes(network, spec, beam, structure);
  add_lumped_node_elements(network, mesh, sections, damping, beam, structure);
  add_segment_elements(network, spec, mesh, sections, damping, beam, structure, reactions);
  add_point_masses(network, spec, beam, structure);
  add_springs(network, spec, beam, structure);
  return beam;
}

}  // namespace emnet
