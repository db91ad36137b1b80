// Independent across source: a voltage source, a velocity source or an angular-velocity source.
//
//   y_plus − y_minus = waveform(t),   j = through quantity from plus, through the source, to minus
// Units: V, m/s or rad/s. A zero source to ground is a clamp; j is then the reaction.
// Stamps: KCL rows plus (+j), minus (−j); branch row y_plus − y_minus = value(t).
#pragma once

#include "emnet/network/network.hpp"

namespace emnet {

/// A voltage, velocity or angular-velocity source (see above).
class VoltageSource : public Element {
 public:
  /// @param waveform  y_plus − y_minus [V, m/s or rad/s]
  VoltageSource(std::string name, NodeId plus, NodeId minus, Waveform waveform, Domain domain)
      : Element(std::move(name)),
        plus_(plus),
        minus_(minus),
        waveform_(std::move(waveform)),
        domain_(domain) {}
  const char* kind() const override { return "voltage_source"; }
  std::vector<Unknown> branch_unknowns() const override {
    return {{"i_" + name(), Unknown::Kind::branch_through, domain_}};
  }
  void stamp(Stamper& s) const override;
  NodeId plus() const { return plus_; }
  NodeId minus() const { return minus_; }
  const Waveform& waveform() const { return waveform_; }

 private:
  NodeId plus_, minus_;
  Waveform waveform_;
  Domain domain_;
};

}  // namespace emnet
