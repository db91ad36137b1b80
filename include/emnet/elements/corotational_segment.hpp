// Co-rotational segment: the translational and axial part of one planar, geometrically exact
// beam segment (beam.kinematics = "large"; docs/model.md, Large deflection).
//
// The segment's ends a and b each carry the fixed-frame velocities (v_x, v_y) [m/s] and the
// angular velocity Ω [rad/s] of the section. Its local network is the small segment's (a
// rotational compliance n_R = l/EI, an Inductor beside this element, and a translational
// compliance n_T = l³/(12·EI) [+ l/(κGA)] with its lever), written in the frame of the chord,
// whose angle θ is a state. Its own branch unknowns:
//   d = (d_x, d_y)  the chord's change [m]: d' = v_b − v_a (integrated node velocities)
//   θ               the chord's angle [rad]: −sin θ·(l + d_x) + cos θ·d_y = 0
//   F               the translational compliance's force [N]:
//                     n_T·F' = (l/2)·(Ω_a + Ω_b) − l·θ'     (at rest n_T·F = l·(ψ_a + ψ_b)/2 − l·θ)
//   N               the axial force [N], tension positive: n_A·N = ℓ − l with the chord's length
//                     ℓ = cos θ·(l + d_x) + sin θ·d_y and n_A = l/EA; inextensible (n_A = 0):
//                     ℓ = l, N its multiplier
//   Q               with Kelvin–Voigt damping τ only: the total force [N], the spring's and its
//                     damper's τ/n_T: Q = F + (τ/n_T)·((l/2)·(Ω_a + Ω_b) − l·θ') = F + τ·F',
//                     with l·θ' = (l/ℓ)·e₂·(v_b − v_a) from the velocities (so that no force is
//                     both a state and fixed by the displacements: the DAE stays index 1)
//   P               with τ and an axial compliance: the total axial force
//                     P = N + (τ/n_A)·ℓ' = N + τ·N', ℓ' = e₁·(v_b − v_a)
//   f_x, f_y        only at a held end (the model's reaction probes read them): the force the
//                     segment draws from that end's node, in the fixed frame [N] (below), an
//                     algebraic unknown equal to its expression
// Forces on the nodes (KCL rows, the through quantity the element draws from each node):
//   (v_x, v_y)_a: +Q·(l/ℓ)·e₂ − P·e₁,   (v_x, v_y)_b: the opposite,   Ω_a, Ω_b: +(l/2)·Q,
// with e₁ = (cos θ, sin θ), e₂ = (−sin θ, cos θ). They are the gradient of the stored energy
// ½·n_T·F² + ½·n_A·N² (Q = F and P = N without τ), so the element is lossless but for τ. Linearised
// at rest (θ = 0, d = 0) the element is the small segment's compliance and lever exactly, plus an
// axial compliance that decouples: that linearisation is stamped in G and C, the remainder in g(y).
// Sign: d_y and θ positive toward +w; N positive in tension.
// Sources: the co-rotational formulation of Crisfield, "Non-linear Finite Element Analysis of
// Solids and Structures" vol. 1 (1991), ch. 7, and Felippa and Haugen, Comput. Methods Appl.
// Mech. Engrg. 194 (2005), in network form (bond graphs' modulated transformer).
#pragma once

#include <vector>

#include "emnet/network/network.hpp"

namespace emnet {

/// The translational and axial part of a large-deflection beam segment (see above).
class CoRotationalSegment : public Element {
 public:
  /// The nodes of one end: fixed-frame x and y velocity, angular velocity (ground where held).
  struct End {
    NodeId x = ground;
    NodeId y = ground;
    NodeId rotation = ground;
  };
  /// @param length                 l [m], the undeformed chord, along +x
  /// @param transverse_compliance  n_T [m/N] (> 0)
  /// @param axial_compliance       n_A = l/EA [m/N]; 0: inextensible
  /// Which end's force the segment carries as unknowns f_x, f_y (a held end's: its reaction).
  enum class EndForce { none, a, b };
  /// @param kelvin_voigt_time      τ [s] of the transverse compliance (0: none)
  /// @param end_force              the end whose force is an unknown (EndForce::none: neither)
  /// @throws std::invalid_argument for a non-positive length or compliance, a negative one
  CoRotationalSegment(std::string name, End a, End b, double length, double transverse_compliance,
                      double axial_compliance, double kelvin_voigt_time,
                      EndForce end_force = EndForce::none);
  const char* kind() const override { return "corotational_segment"; }
  std::vector<Unknown> branch_unknowns() const override;
  void stamp(Stamper& s) const override;
  bool is_nonlinear() const override { return true; }
  void add_nonlinear(const Eigen::VectorXd& y, int branch_offset, Eigen::VectorXd& g,
                     std::vector<Eigen::Triplet<double>>* jacobian) const override;

  /// Branch unknowns, in order (offsets from the element's first; the totals only with τ).
  enum Branch : int {
    chord_x = 0,
    chord_y = 1,
    chord_angle = 2,
    transverse_force = 3,
    axial_force = 4,
    total_transverse_force = 5,
    total_axial_force = 6
  };
  /// The offset of the end force's x component (f_y follows), or −1 without one.
  int end_force_branch() const;
  EndForce end_force() const { return end_force_; }
  /// The branch unknown that carries the transverse force into the nodes: Q with τ, else F.
  int force_branch() const {
    return kelvin_voigt_time_ > 0.0 ? total_transverse_force : transverse_force;
  }
  /// The branch unknown that carries the axial force into the nodes: P with τ and an axial
  /// compliance, else N.
  int axial_branch() const {
    return kelvin_voigt_time_ > 0.0 && axial_compliance_ > 0.0 ? total_axial_force : axial_force;
  }
  const End& end_a() const { return a_; }
  const End& end_b() const { return b_; }
  double length() const { return length_; }
  double transverse_compliance() const { return transverse_compliance_; }
  double axial_compliance() const { return axial_compliance_; }
  double kelvin_voigt_time() const { return kelvin_voigt_time_; }

 private:
  struct ChordState;     // the geometry at y (corotational_segment.cpp)
  struct NonlinearSink;  // where g and ∂g/∂y go
  // add_nonlinear's phases: the chord's angle and axial rows, the dampers' rates, the forces on
  // the nodes (see above), at the state `st` add_nonlinear computes once.
  void add_chord_rows(const Eigen::VectorXd& y, const ChordState& st,
                      const NonlinearSink& sink) const;
  void add_damper_rows(const ChordState& st, const NonlinearSink& sink) const;
  // +1 where the end force is end a's (f_a), −1 where it is end b's (f_b = −f_a).
  double end_force_sign() const { return end_force_ == EndForce::a ? 1.0 : -1.0; }
  void add_node_forces(double force, double tension, const ChordState& st,
                       const NonlinearSink& sink, int end_force_x) const;

  End a_, b_;
  double length_;
  double transverse_compliance_;
  double axial_compliance_;
  double kelvin_voigt_time_;
  EndForce end_force_;
};

}  // namespace emnet
