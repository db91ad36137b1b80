// Time-domain analysis: SUNDIALS IDA on the network's DAE, and the exact solution of linear
// networks under piecewise-linear sources.
//
// Both integrate the displacement form of C·y' + G·y + g(y) = b(t) (src/analysis/
// displacement_form.hpp): mechanical across unknowns become displacements z (with a velocity
// v = z' where a mass or inertia needs one), and compliance / lever rows, which relate
// velocities only, are integrated once. Spring forces are then algebraic, massless rotation
// nodes a static condensation, and the DAE has index 1 — which IDA requires; deflections are
// states, read without a numerical integrator.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "emnet/analysis/method.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/network/network.hpp"
#include "emnet/network/output.hpp"

namespace emnet {

/// The state a transient run starts from.
enum class StartState {
  rest,    ///< every unknown zero at t = 0⁻; sources switch on at t = 0
  static_  ///< the static state under the sources' values at t = 0 (the first half-period)
};

/// IDA's relative tolerance: at least 1e-13 (below it the double-precision rounding of the
/// residual exceeds the tolerance) and below 1; false for NaN.
inline bool valid_relative_tolerance(double rtol) {
  return rtol >= 1e-13 && rtol < 1.0;
}
/// What valid_relative_tolerance accepts, in words for messages.
constexpr const char* kRelativeToleranceRange =
    "must be >= 1e-13 (below that, double-precision rounding of the residual exceeds the "
    "tolerance) and < 1";

/// Options of run_transient_ida and run_transient_exact.
struct TransientOptions {
  double end_time = 1.0;                ///< [s]
  std::vector<double> output_times;     ///< increasing, in [0, end_time]
  double relative_tolerance = 1e-6;     ///< IDA; valid_relative_tolerance
  double absolute_tolerance = 0.0;      ///< IDA; 0: relative_tolerance × a scale per unknown
  double max_step = 0.0;                ///< IDA; 0: unlimited
  StartState start = StartState::rest;  ///< see StartState
  /// IDA only: start from this displacement-form state instead (its differential components;
  /// the algebraic ones are made consistent). Used by shooting.
  std::optional<Eigen::VectorXd> initial_state;
  /// One report per output time; when cancelled, the run stops at the next output time (IDA: or
  /// the next return of its solver) with Status "cancelled".
  Progress* progress = nullptr;
};

/// The work a transient run took.
struct IntegratorStatistics {
  long steps = 0;
  long residual_evaluations = 0;
  long jacobian_evaluations = 0;
  long newton_iterations = 0;
  long error_test_failures = 0;
  long convergence_failures = 0;
  long restarts = 0;  ///< one per switching edge
};

/// Probe values at the output times, as the transient analyses return them.
struct TransientResult {
  Status status;
  Method method = Method::ida;  ///< ida or exact
  /// IDA: how it had to change its error test to get through, when it did ("algebraic
  /// unknowns out of the error test after: ..."); empty otherwise.
  std::string method_note;
  /// The method as reports print it: its name, and the note in parentheses when there is one.
  std::string method_text() const {
    return method_name(method) + (method_note.empty() ? std::string() : " (" + method_note + ")");
  }
  std::vector<double> times;                ///< output times reached
  std::vector<std::vector<double>> values;  ///< [probe][time]
  IntegratorStatistics statistics;
  Eigen::VectorXd final_state;  ///< IDA: the displacement-form state at end_time
  double seconds = 0.0;         ///< [s]
};

/// IDA (BDF, variable order and step) with a sparse KLU linear solver; stops exactly at every
/// source breakpoint and restarts there with consistent values (its own Newton iteration,
/// consistent_start.hpp; IDACalcIC only when that fails).
TransientResult run_transient_ida(const System& system, const std::vector<Probe>& probes,
                                  const TransientOptions& options);

/// The ends of the constant, affine (or smooth) intervals of the sources over (0, end_time]:
/// every source breakpoint, the last one being end_time itself.
std::vector<double> interval_ends(const System& system, double end_time);

/// Exact solution for a linear network whose sources are piecewise linear (dc, pulses with any
/// rise and fall, pwl): per interval between breakpoints, where every source is affine, one
/// matrix exponential (a larger one on a ramp; state_space.hpp). Fails (status) for a nonlinear
/// network, a sine source ("not piecewise linear; use --method ida"), and when an output is not
/// finite.
TransientResult run_transient_exact(const System& system, const std::vector<Probe>& probes,
                                    const TransientOptions& options);

}  // namespace emnet
