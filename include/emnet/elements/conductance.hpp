// Conductance: an electrical resistor, a viscous damper, or a rotational damper.
//
//   through = conductance · (y_a − y_b)
// electrical: i = u/R, conductance = 1/R [S]; translational damper: F = r·(v_a − v_b),
// conductance = r [N·s/m]; rotational damper: M = r·(Ω_a − Ω_b), r [N·m·s/rad].
// Firestone analogy (docs/model.md, Conventions): a damper's coefficient is the conductance itself.
// Through quantity positive from a to b. Stamps G only.
#pragma once

#include "emnet/network/network.hpp"

namespace emnet {

/// A resistor, a viscous damper or a rotational damper (see above).
class Conductance : public Element {
 public:
  /// @param conductance  1/R [S], a damper's r [N·s/m] or a rotational damper's r [N·m·s/rad]
  Conductance(std::string name, NodeId a, NodeId b, double conductance)
      : Element(std::move(name)), a_(a), b_(b), conductance_(conductance) {}
  const char* kind() const override { return "conductance"; }
  void stamp(Stamper& s) const override;
  NodeId a() const { return a_; }
  NodeId b() const { return b_; }
  double conductance() const { return conductance_; }

 private:
  NodeId a_, b_;
  double conductance_;
};

}  // namespace emnet
