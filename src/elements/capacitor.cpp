// Capacitor stamp: see include/emnet/elements/capacitor.hpp for the physics.
#include "emnet/elements/capacitor.hpp"

namespace emnet {

void Capacitor::stamp(Stamper& s) const {
  s.c(a_, a_, capacitance_);
  s.c(b_, b_, capacitance_);
  s.c(a_, b_, -capacitance_);
  s.c(b_, a_, -capacitance_);
}

}  // namespace emnet
