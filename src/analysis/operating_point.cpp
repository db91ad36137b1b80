// One policy for the operating point; see emnet/analysis/operating_point.hpp.
#include "emnet/analysis/operating_point.hpp"

#include "emnet/core/progress.hpp"
#include "emnet/core/stopwatch.hpp"

namespace emnet {

OperatingPoint operating_point(const System& system, const OperatingPointOptions& options) {
  const Stopwatch stopwatch;
  OperatingPoint point;
  point.rest = solve_static(system, options.static_options);
  if (!point.rest.status.ok()) {
    if (options.require_static || system.is_nonlinear() || point.rest.status.cancelled()) {
      point.status = point.rest.status.with_context("static operating point: ");
      point.seconds = stopwatch.seconds();
      return point;
    }
    point.about_zero = true;
    point.note = "no static state (" + point.rest.status.message +
                 "); the linear network is analysed about zero";
    point.rest.operating_point = Eigen::VectorXd::Zero(system.size());
  }
  point.seconds = stopwatch.seconds();
  return point;
}

}  // namespace emnet
