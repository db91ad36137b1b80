// Beam chain builder and Hermite interpolation: see include/emnet/model/model.hpp for the physics.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/elements/transformer.hpp"
#include "emnet/model/model.hpp"

namespace emnet {

namespace {

std::string millimetres(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "x = %.4g mm", x * 1e3);
  return buffer;
}

// Segment index and local coordinate ξ ∈ [0, 1] of position x.
std::pair<int, double> locate(const BeamLayout& beam, double x) {
  const int segments = static_cast<int>(beam.x.size()) - 1;
  int s = static_cast<int>(std::floor(x / beam.segment_length));
  s = std::clamp(s, 0, segments - 1);
  double xi = (x - beam.x[static_cast<size_t>(s)]) / beam.segment_length;
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

}  // namespace

LinearTerms BeamLayout::deflection_terms(double x) const {
  const auto [s, xi] = locate(*this, x);
  const double l = segment_length;
  const size_t a = static_cast<size_t>(s), b = a + 1;
  return merge({{velocity[a], 1 - 3 * xi * xi + 2 * xi * xi * xi},
                {angular_velocity[a], l * (xi - 2 * xi * xi + xi * xi * xi)},
                {velocity[b], 3 * xi * xi - 2 * xi * xi * xi},
                {angular_velocity[b], l * (-xi * xi + xi * xi * xi)}});
}

LinearTerms BeamLayout::slope_terms(double x) const {
  const auto [s, xi] = locate(*this, x);
  const double l = segment_length;
  const size_t a = static_cast<size_t>(s), b = a + 1;
  return merge({{velocity[a], (-6 * xi + 6 * xi * xi) / l},
                {angular_velocity[a], 1 - 4 * xi + 3 * xi * xi},
                {velocity[b], (6 * xi - 6 * xi * xi) / l},
                {angular_velocity[b], -2 * xi + 3 * xi * xi}});
}

BeamLayout add_beam(Network& network, const BeamSpec& spec, const DampingSpec& damping,
                    ModelStructure* structure) {
  BeamLayout beam;
  const int n = spec.segments;
  const double l = spec.length / n;
  const double ei = spec.bending_stiffness;
  beam.length = spec.length;
  beam.segment_length = l;

  for (int k = 0; k <= n; ++k) {
    const double x = spec.length * k / n;
    beam.x.push_back(x);
    const bool left = k == 0, right = k == n;
    const EndCondition end = left ? spec.left : spec.right;
    const bool at_end = left || right;
    const bool hold_v = at_end && (end == EndCondition::clamped || end == EndCondition::pinned);
    const bool hold_r = at_end && (end == EndCondition::clamped || end == EndCondition::sliding);
    const std::string where = millimetres(x);
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

  // Lumped mass, rotary inertia and viscous damping: half a segment's share at each end.
  for (int k = 0; k <= n; ++k) {
    const double share = (k == 0 || k == n) ? 0.5 * l : l;
    const size_t i = static_cast<size_t>(k);
    const std::string id = std::to_string(k);
    auto record = [&](ElementPart part, const std::string& what) {
      return ElementRecord{
          Component::beam_node, part, k, "", -1, -1, what + " lumped at beam node " + id};
    };
    if (beam.velocity[i] != ground) {
      add_recorded<Capacitor>(network, structure, record(ElementPart::mass, "mass [kg]"),
                              "mass" + id, beam.velocity[i], ground, spec.mass_per_length * share);
      if (damping.viscous_per_length > 0.0)
        add_recorded<Conductance>(
            network, structure, record(ElementPart::viscous_damper, "viscous damper [N*s/m]"),
            "damper" + id, beam.velocity[i], ground, damping.viscous_per_length * share);
    }
    if (beam.angular_velocity[i] != ground && spec.rotary_inertia_per_length > 0.0)
      add_recorded<Capacitor>(
          network, structure, record(ElementPart::rotary_inertia, "rotary inertia [kg*m^2]"),
          "inertia" + id, beam.angular_velocity[i], ground, spec.rotary_inertia_per_length * share);
  }

  const double tau = damping.effective_kelvin_voigt_time();
  const double rotational_compliance = l / ei;
  const double translational_compliance = l * l * l / (12.0 * ei);
  for (int k = 0; k < n; ++k) {
    const size_t a = static_cast<size_t>(k), b = a + 1;
    const std::string id = std::to_string(k);
    const NodeId middle = add_recorded_node(
        network, structure, {NodeRole::segment_middle, k, ""}, "m" + id, Domain::translational,
        "segment " + id + " branch between spring and lever [m/s]");
    auto record = [&](ElementPart part, const std::string& what) {
      return ElementRecord{Component::beam_segment,        part, k, "", -1, -1,
                           what + " of beam segment " + id};
    };
    // Kelvin–Voigt: a damper τ/n across each compliance n, stamped as τ·(spring force)'.
    add_recorded<Inductor>(
        network, structure,
        record(ElementPart::rotational_compliance, "rotational compliance l/EI [rad/(N*m)]"),
        "nR" + id, beam.angular_velocity[a], beam.angular_velocity[b], rotational_compliance,
        Domain::rotational, tau / rotational_compliance);
    add_recorded<Inductor>(
        network, structure,
        record(ElementPart::translational_compliance, "translational compliance l^3/(12*EI) [m/N]"),
        "nT" + id, beam.velocity[a], middle, translational_compliance, Domain::translational,
        tau / translational_compliance);
    add_recorded<Transformer>(
        network, structure, record(ElementPart::lever, "lever (l/2)*(Omega_k + Omega_k+1)"),
        "lever" + id, beam.velocity[b], middle,
        std::vector<Transformer::Port>{{beam.angular_velocity[a], ground, 0.5 * l},
                                       {beam.angular_velocity[b], ground, 0.5 * l}},
        Domain::translational);
  }
  return beam;
}

}  // namespace emnet
