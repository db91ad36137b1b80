// Gyrator stamp: see include/emnet/elements/gyrator.hpp.
#include "emnet/elements/gyrator.hpp"

namespace emnet {

void Gyrator::stamp(Stamper& s) const {
  const double k = gyration_;
  // port 1 through = K·(y_c − y_d), entering a, leaving b
  s.g(a_, c_, k);
  s.g(a_, d_, -k);
  s.g(b_, c_, -k);
  s.g(b_, d_, k);
  // port 2 through = −K·(y_a − y_b), entering c, leaving d
  s.g(c_, a_, -k);
  s.g(c_, b_, k);
  s.g(d_, a_, k);
  s.g(d_, b_, -k);
}

}  // namespace emnet
