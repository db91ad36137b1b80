// Ideal transformer (lever) with one secondary port and one or more primary ports.
//
//   secondary across:  y_s+ − y_s− = Σ_k ratio_k · (y_pk+ − y_pk−)
//   primary through:   i_pk = −ratio_k · j        (j: through quantity entering s+)
// so the power Σ across·through over all ports is zero: lossless, docs/model.md, Conventions
// ("lever arm a: v = a·Ω, M = a·F"). With one primary it is the classic ideal transformer of ratio
// a; ports may span domains (rotational primary, translational secondary: a lever of arm a [m]).
// Stamps: branch unknown j; KCL s+ (+j), s− (−j), pk+ (−a_k·j), pk− (+a_k·j); branch row as
// above (G only). The G block is symmetric.
#pragma once

#include "emnet/network/network.hpp"

namespace emnet {

/// An ideal transformer or lever (see above).
class Transformer : public Element {
 public:
  /// A primary port pk.
  struct Port {
    NodeId plus;   ///< pk+
    NodeId minus;  ///< pk−
    double ratio;  ///< ratio_k (a lever's arm a [m])
  };
  Transformer(std::string name, NodeId secondary_plus, NodeId secondary_minus,
              std::vector<Port> primaries, Domain secondary_domain)
      : Element(std::move(name)),
        secondary_plus_(secondary_plus),
        secondary_minus_(secondary_minus),
        primaries_(std::move(primaries)),
        secondary_domain_(secondary_domain) {}
  const char* kind() const override { return "transformer"; }
  std::vector<Unknown> branch_unknowns() const override {
    return {{"i_" + name(), Unknown::Kind::branch_through, secondary_domain_}};
  }
  void stamp(Stamper& s) const override;
  NodeId secondary_plus() const { return secondary_plus_; }
  NodeId secondary_minus() const { return secondary_minus_; }
  const std::vector<Port>& primaries() const { return primaries_; }

 private:
  NodeId secondary_plus_, secondary_minus_;
  std::vector<Port> primaries_;
  Domain secondary_domain_;
};

}  // namespace emnet
