// The operating point the dynamic analyses (modes, ac, sweeps, sensitivity, cross-check)
// linearise about, by one policy:
//   - the static state when solve_static finds it;
//   - a nonlinear network without a static state: a failure (its linearisation needs one);
//   - a linear network without a static state (a free body, a mechanism): zero, which is exact
//     for a linear network's small-signal and modal analyses, with a note saying so.
// The `static` analysis itself requires the static state (require_static).
#pragma once

#include <string>

#include "emnet/analysis/analysis.hpp"

namespace emnet {

/// Options of operating_point.
struct OperatingPointOptions {
  StaticOptions static_options;
  bool require_static = false;  ///< fail when there is no static state, also for linear networks
};

/// The operating point of a System, as operating_point returns it.
struct OperatingPoint {
  Status status;            ///< failure: "static operating point: <why>"
  StaticResult rest;        ///< as solve_static returned it; operating_point filled in either way
  bool about_zero = false;  ///< a linear network without a static state, taken about zero
  std::string note;         ///< said when about_zero
  double seconds = 0.0;     ///< [s]
};

/// The operating point of `system`, by the policy above.
OperatingPoint operating_point(const System& system, const OperatingPointOptions& options = {});

}  // namespace emnet
