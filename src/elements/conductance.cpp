// Conductance stamp: see include/emnet/elements/conductance.hpp for the physics.
#include "emnet/elements/conductance.hpp"

namespace emnet {

void Conductance::stamp(Stamper& s) const {
  s.g_between(a_, b_, conductance_);
}

}  // namespace emnet
