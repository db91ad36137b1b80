// Capacitor stamp: see include/emnet/elements/capacitor.hpp for the physics.
#include "emnet/elements/capacitor.hpp"

namespace emnet {

void Capacitor::stamp(Stamper& s) const {
  s.c_between(a_, b_, capacitance_);
}

}  // namespace emnet
