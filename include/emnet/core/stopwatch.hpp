// Wall time since a start: what every Result's `seconds` and every study's cost is measured with
// (std::chrono::steady_clock, which never jumps).
#pragma once

#include <chrono>

namespace emnet {

/// Wall time since construction or the last restart.
class Stopwatch {
 public:
  /// Seconds since construction (or the last restart).
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  /// Starts again from now.
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace emnet
