// Whether gnuplot is on PATH: the plot tests that draw an image skip without it.
#pragma once

#include <cstdlib>

namespace emnet::testing {

inline bool gnuplot_available() {
  return std::system("command -v gnuplot >/dev/null 2>&1") == 0;
}

}  // namespace emnet::testing
