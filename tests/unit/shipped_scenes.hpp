// The shipped scene files and the constants the tests share, named once so that every test file
// means the same thing by them (and the test files can be compiled together as one unit).
#pragma once

#include <string>

namespace emnet::testing {

/// Absolute path of a scene file shipped in netlists/ (EMNET_SOURCE_DIR is the source tree).
inline std::string shipped_scene(const std::string& file_name) {
  return std::string(EMNET_SOURCE_DIR) + "/netlists/" + file_name;
}

/// netlists/fishfin.toml, the flagship scene.
inline const std::string kFishfin = shipped_scene("fishfin.toml");
/// netlists/cantilever.toml, the uniform clamped-free beam.
inline const std::string kCantilever = shipped_scene("cantilever.toml");

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2 * kPi;

}  // namespace emnet::testing
