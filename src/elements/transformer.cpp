// Ideal transformer / lever stamp: see include/emnet/elements/transformer.hpp.
#include "emnet/elements/transformer.hpp"

namespace emnet {

void Transformer::stamp(Stamper& s) const {
  const int j = s.branch(0);
  s.g(secondary_plus_, j, 1.0);
  s.g(secondary_minus_, j, -1.0);
  s.g(j, secondary_plus_, 1.0);
  s.g(j, secondary_minus_, -1.0);
  for (const Port& port : primaries_) {
    s.g(port.plus, j, -port.ratio);
    s.g(port.minus, j, port.ratio);
    s.g(j, port.plus, -port.ratio);
    s.g(j, port.minus, port.ratio);
  }
}

}  // namespace emnet
