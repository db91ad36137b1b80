// The shipped scene files and the constants the tests share, named once so that every test file
// means the same thing by them (and the test files can be compiled together as one unit).
#pragma once

#include <cstdlib>
#include <string>

#include "emnet/core/constants.hpp"

namespace emnet::testing {

/// Absolute path of a scene file shipped in netlists/ (EMNET_SOURCE_DIR is the source tree).
inline std::string shipped_scene(const std::string& file_name) {
  return std::string(EMNET_SOURCE_DIR) + "/netlists/" + file_name;
}

/// netlists/fishfin.toml, the flagship scene.
inline const std::string kFishfin = shipped_scene("fishfin.toml");
/// netlists/cantilever.toml, the uniform clamped-free beam.
inline const std::string kCantilever = shipped_scene("cantilever.toml");

/// Whether the ngspice program is on PATH (the cross-checks skip without it).
inline bool ngspice_available() {
  return std::system("command -v ngspice > /dev/null 2>&1") == 0;
}

using emnet::kPi;
using emnet::kTwoPi;

}  // namespace emnet::testing
