// A result with its wall time: every analysis returns a Result carrying a Status and the
// seconds it took; this fills both at each return.
#pragma once

#include <utility>

#include "emnet/core/errors.hpp"
#include "emnet/core/stopwatch.hpp"

namespace emnet {

template <class Result>
class Timed {
 public:
  Result result;
  Result finish(Status status) {
    result.status = std::move(status);
    result.seconds = stopwatch_.seconds();
    return result;
  }

 private:
  Stopwatch stopwatch_;
};

}  // namespace emnet
