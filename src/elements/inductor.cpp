// Inductor stamp: see include/emnet/elements/inductor.hpp for the physics.
#include "emnet/elements/inductor.hpp"

namespace emnet {

void Inductor::stamp(Stamper& s) const {
  const int j = s.branch(0);
  s.g(a_, j, 1.0);
  s.g(b_, j, -1.0);
  s.g(j, a_, 1.0);
  s.g(j, b_, -1.0);
  s.c(j, j, -inductance_);
  const double relaxation_time = parallel_conductance_ * inductance_;
  if (relaxation_time != 0.0) {
    s.c(a_, j, relaxation_time);
    s.c(b_, j, -relaxation_time);
  }
}

}  // namespace emnet
