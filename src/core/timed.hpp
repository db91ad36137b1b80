// A result with its wall time: every analysis returns a Result carrying a Status and the
// seconds it took; this fills both at each return.
#pragma once

#include <chrono>
#include <utility>

#include "emnet/core/errors.hpp"

namespace emnet {

template <class Result>
class Timed {
 public:
  Result result;
  Result finish(Status status) {
    result.status = std::move(status);
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return result;
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace emnet
