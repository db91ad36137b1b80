// Across-source stamp: see include/emnet/elements/voltage_source.hpp.
#include "emnet/elements/voltage_source.hpp"

namespace emnet {

void VoltageSource::stamp(Stamper& s) const {
  const int j = s.branch(0);
  s.g(plus_, j, 1.0);
  s.g(minus_, j, -1.0);
  s.g(j, plus_, 1.0);
  s.g(j, minus_, -1.0);
  s.source(j, 1.0, waveform_);
}

}  // namespace emnet
