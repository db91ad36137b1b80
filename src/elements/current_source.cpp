// Through-source stamp: see include/emnet/elements/current_source.hpp.
#include "emnet/elements/current_source.hpp"

namespace emnet {

void CurrentSource::stamp(Stamper& s) const {
  const int w = s.source(to_, 1.0, waveform_);
  s.source(from_, -1.0, w);
}

}  // namespace emnet
