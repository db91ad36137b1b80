// Inductor: an electrical inductor, or a translational / rotational compliance (spring).
//
//   y_a − y_b = inductance · d(j)/dt,     j = through quantity from a to b (a branch unknown)
// electrical: u = L·di/dt [H]; translational: a spring of stiffness k is a compliance
// n = 1/k [m/N] carrying the spring force F, v_a − v_b = n·dF/dt; rotational: n = 1/k
// [rad/(N·m)] carrying the torque (docs/model.md, Conventions).
// Stamps: KCL rows a (+j) and b (−j); branch row  y_a − y_b − L·j' = 0  (G: ±1, C: −L).
// At rest the branch row says nothing about j (only about displacements), which is what lets
// the static analysis solve for displacements (src/analysis/static.cpp).
//
// Optional parallel conductance g_p (a damper r = g_p across a compliance: Kelvin–Voigt
// material damping with relaxation time τ = g_p·L; electrically a resistor 1/g_p across the
// coil). Its through quantity g_p·(y_a − y_b) equals g_p·L·j' by the branch row, and it is
// stamped in that form: KCL rows a (+g_p·L·j') and b (−g_p·L·j') on C. The two are the same
// equations, but the rounding differs: a stiff segment has a tiny compliance L and a huge
// g_p = τ/L, and g_p·(y_a − y_b) cancels y_a ≈ y_b against it (relative error ε·|y|/|y_a − y_b|,
// growing as N³ for a beam of N segments: 2e-4 on the fish fin's first damping ratio at
// N = 10 000), whereas τ·j' is the spring force's own rate. Total through quantity a → b:
// j + g_p·L·j' (j alone is the spring's share, the branch unknown).
#pragma once

#include "emnet/network/network.hpp"

namespace emnet {

/// An inductor or a compliance (see above).
class Inductor : public Element {
 public:
  /// @param inductance            L [H], or a compliance n = 1/k [m/N or rad/(N·m)]
  /// @param parallel_conductance  g_p across it (0: none); Kelvin–Voigt τ = g_p·L
  Inductor(std::string name, NodeId a, NodeId b, double inductance, Domain domain,
           double parallel_conductance = 0.0)
      : Element(std::move(name)),
        a_(a),
        b_(b),
        inductance_(inductance),
        parallel_conductance_(parallel_conductance),
        domain_(domain) {}
  const char* kind() const override { return "inductor"; }
  std::vector<Unknown> branch_unknowns() const override {
    return {{"i_" + name(), Unknown::Kind::branch_through, domain_}};
  }
  void stamp(Stamper& s) const override;
  NodeId a() const { return a_; }
  NodeId b() const { return b_; }
  double inductance() const { return inductance_; }
  double parallel_conductance() const { return parallel_conductance_; }

 private:
  NodeId a_, b_;
  double inductance_;
  double parallel_conductance_;
  Domain domain_;
};

}  // namespace emnet
