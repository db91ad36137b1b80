// Independent through source: a current source, a force source, or a torque source.
//
// Drives the through quantity `waveform(t)` out of node `from` and into node `to`
// (a force source from ground into a velocity node pushes that node in +v).
// Units: A, N or N·m. Its AC phasor is the waveform's ac_magnitude/ac_phase.
#pragma once

#include "emnet/network/network.hpp"

namespace emnet {

/// A current, force or torque source (see above).
class CurrentSource : public Element {
 public:
  /// @param waveform  the through quantity driven out of `from` into `to` [A, N or N·m]
  CurrentSource(std::string name, NodeId from, NodeId to, Waveform waveform)
      : Element(std::move(name)), from_(from), to_(to), waveform_(std::move(waveform)) {}
  const char* kind() const override { return "current_source"; }
  void stamp(Stamper& s) const override;
  NodeId from() const { return from_; }
  NodeId to() const { return to_; }
  const Waveform& waveform() const { return waveform_; }

 private:
  NodeId from_, to_;
  Waveform waveform_;
};

}  // namespace emnet
