// Capacitor: an electrical capacitor, a mass, or a rotary inertia.
//
//   through = capacitance · d(y_a − y_b)/dt
// electrical: i = C·du/dt [F]; translational: a mass m [kg] is a capacitor from its velocity
// node to ground, F = m·dv/dt; rotational: an inertia J [kg·m²], M = J·dΩ/dt (docs/model.md,
// Conventions). Through quantity positive from a to b. Stamps C only.
#pragma once

#include "emnet/network/network.hpp"

namespace emnet {

/// A capacitor, a mass or a rotary inertia (see above).
class Capacitor : public Element {
 public:
  /// @param capacitance  C [F], a mass m [kg] or an inertia J [kg·m²]
  Capacitor(std::string name, NodeId a, NodeId b, double capacitance)
      : Element(std::move(name)), a_(a), b_(b), capacitance_(capacitance) {}
  const char* kind() const override { return "capacitor"; }
  void stamp(Stamper& s) const override;
  NodeId a() const { return a_; }
  NodeId b() const { return b_; }
  double capacitance() const { return capacitance_; }

 private:
  NodeId a_, b_;
  double capacitance_;
};

}  // namespace emnet
