// A position along the beam as messages and records give it, private to the model layer.
#pragma once

#include <cstdio>
#include <string>

namespace emnet {

// "x = 12.5 mm" for x = 0.0125 m.
inline std::string position_text(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "x = %.4g mm", x * 1e3);
  return buffer;
}

}  // namespace emnet
