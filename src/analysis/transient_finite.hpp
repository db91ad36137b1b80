// The last check of both transient analyses (transient_ida.cpp, transient_exact.cpp): a
// result with a non-finite output time or value is a failure naming the first output and time.
#pragma once

#include <string>
#include <vector>

#include "emnet/analysis/transient.hpp"

namespace emnet {

// Success when every output time and every value of `result` is finite; else a failure naming
// the first output (by its probe's name) and the time where it is not: "<what> gave a
// non-finite value of output 'x' at t = ... s".
Status check_finite_outputs(const TransientResult& result, const std::vector<Probe>& probes,
                            const std::string& what);

}  // namespace emnet
