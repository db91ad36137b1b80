// Mathematical constants the library and its front-ends share, named once (C++17 has no
// std::numbers).
#pragma once

namespace emnet {

/// π to double precision.
inline constexpr double kPi = 3.14159265358979323846;
/// 2π [rad per cycle]: angular frequency [rad/s] from frequency [Hz].
inline constexpr double kTwoPi = 2 * kPi;

}  // namespace emnet
