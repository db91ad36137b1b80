// Ideal gyrator between two ports (electromechanical transducer in the mobility analogy).
//
//   i_1 = K · (y_c − y_d),    i_2 = −K · (y_a − y_b)
// port 1 = (a, b), port 2 = (c, d); i_k is the through quantity entering the port's + node.
// Lossless: u_1·i_1 + u_2·i_2 = 0. A linearised electrostatic transducer biased at U₀ is a
// gyrator with K = U₀·∂C/∂x [N/V = A·s/m] (docs/model.md, The DEA transducer): F = K·u, i = K·v.
// Stamps G only (four VCCS entries per port).
#pragma once

#include "emnet/network/network.hpp"

namespace emnet {

/// An ideal gyrator between ports (a, b) and (c, d) (see above).
class Gyrator : public Element {
 public:
  /// @param gyration  K, e.g. [N/V = A·s/m] for an electromechanical transducer
  Gyrator(std::string name, NodeId a, NodeId b, NodeId c, NodeId d, double gyration)
      : Element(std::move(name)), a_(a), b_(b), c_(c), d_(d), gyration_(gyration) {}
  const char* kind() const override { return "gyrator"; }
  void stamp(Stamper& s) const override;
  double gyration() const { return gyration_; }
  NodeId a() const { return a_; }
  NodeId b() const { return b_; }
  NodeId c() const { return c_; }
  NodeId d() const { return d_; }

 private:
  NodeId a_, b_, c_, d_;
  double gyration_;
};

}  // namespace emnet
