// Conductance stamp: see include/emnet/elements/conductance.hpp for the physics.
#include "emnet/elements/conductance.hpp"

namespace emnet {

void Conductance::stamp(Stamper& s) const {
  s.g(a_, a_, conductance_);
  s.g(b_, b_, conductance_);
  s.g(a_, b_, -conductance_);
  s.g(b_, a_, -conductance_);
}

}  // namespace emnet
