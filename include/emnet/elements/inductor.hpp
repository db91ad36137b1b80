// Inductor: an electrical inductor, or a translational / rotational compliance (spring).
//
//   y_a − y_b = inductance · d(j)/dt,     j = through quantity from a to b (a branch unknown)
// electrical: u = L·di/dt [H]; translational: a spring of stiffness k is a compliance
// n = 1/k [m/N] carrying the spring force F, v_a − v_b = n·dF/dt; rotational: n = 1/k
// [rad/(N·m)] carrying the torque (DESIGN §1).
// Stamps: KCL rows a (+j) and b (−j); branch row  y_a − y_b − L·j' = 0  (G: ±1, C: −L).
// At rest the branch row says nothing about j (only about displacements), which is what lets
// the static analysis solve for displacements (src/analysis/static.cpp).
#pragma once

#include "emnet/network.hpp"

namespace emnet {

class Inductor : public Element {
 public:
  Inductor(std::string name, NodeId a, NodeId b, double inductance, Domain domain)
      : Element(std::move(name)), a_(a), b_(b), inductance_(inductance), domain_(domain) {}
  const char* kind() const override { return "inductor"; }
  std::vector<Unknown> branch_unknowns() const override {
    return {{"i_" + name(), Unknown::Kind::branch_through, domain_}};
  }
  void stamp(Stamper& s) const override;
  NodeId a() const { return a_; }
  NodeId b() const { return b_; }
  double inductance() const { return inductance_; }

 private:
  NodeId a_, b_;
  double inductance_;
  Domain domain_;
};

}  // namespace emnet
