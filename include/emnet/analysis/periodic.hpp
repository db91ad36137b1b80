// Periodic steady state under a periodic drive (paper Fig. 14: peak deflection to either side
// against the switching frequency), computed directly — never by integrating until it looks
// settled.
//
// Exact method (linear network, piecewise-linear sources: dc, pulses with any rise and fall,
// pwl): with the state equation x' = M·x + N·f (src/analysis/state_space.hpp) the state after
// one period is x(T) = Φ·x(0) + c, c holding the constant and the ramp intervals'
// contributions, so the periodic state solves (I − Φ)·x(0) = c. Inside each interval between
// breakpoints the sources are affine, f = f₀ + h·f₁, and with M = V·Λ·V⁻¹
// x(t) = x_p(h) + V·e^{Λh}·V⁻¹·(x_i − x_p(0)) (h = t − t_i) for the affine particular state
// x_p(h) = a + h·b, b = −M⁻¹·N·f₁, a = −M⁻¹·(N·f₀ − b) (per mode; b = 0 on a constant
// interval), so every probe is an affine function plus a sum of exponentials. Its global
// extrema come from the samples, a search that halves every gap between them where a bound on
// p'' (the exponentials' alone: the affine part has none) still allows a higher value (to 1e-11
// of the largest |p|), and Newton on the derivative to rounding: O(n) per evaluation, and the same
// extremes whatever the number of samples. M and its eigen-decomposition depend only on
// the network, not on the drive, so a sweep over switching frequencies decomposes once.
//
// Shooting (any network, with IDA): Newton on x(0) for x(T; x(0)) − x(0) = 0, each residual one
// period of IDA, the Jacobian that of the linearisation improved by Broyden's update (finite
// differences where that stalls); the converged period is sampled for the peaks
// (periodic_shooting.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "emnet/analysis/method.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/network/network.hpp"
#include "emnet/network/output.hpp"

namespace emnet {

/// The periodic steady state over one period, as PeriodicSolver::solve and
/// run_periodic_shooting return it.
struct PeriodicResult {
  Status status;
  Method method = Method::exact;                   ///< exact or shooting
  double period = 0.0;                             ///< T [s]
  std::vector<double> minimum, maximum;            ///< per probe, over one period
  std::vector<double> minimum_time, maximum_time;  ///< where, in [0, T)
  std::vector<double> times;                       ///< samples over one period
  std::vector<std::vector<double>> values;         ///< [probe][sample]
  double periodicity_residual = 0.0;  ///< ‖x(T) − x(0)‖ / ‖x(0)‖; above 1e-8: failed
  /// Reduced cascade (ReducedPeriodicSolver): the truncated poles' transients left out, where
  /// they add up most (each from its start at a switching edge, decaying at least at the
  /// largest kept |pole|), relative to each probe's largest |value|; 0 otherwise.
  double truncation_estimate = 0.0;
  int newton_iterations = 0;  ///< shooting
  /// Shooting: the one-period IDA runs it took (halved steps, finite differences and the last,
  /// sampled run included): where its time goes.
  int period_runs = 0;
  /// Shooting: the network's unknowns at t = 0 of the periodic state.
  Eigen::VectorXd start_state;
  /// Shooting: the unknowns at t = 0 of the periodic state of the network linearised about its
  /// static state, where Newton started from. start_state less this is the nonlinear part, from
  /// which a neighbouring period of a sweep starts (run_periodic_shooting's `nonlinear_part`).
  Eigen::VectorXd linear_start_state;
  double seconds = 0.0;  ///< [s]
};

/// The exact method (see above) for one network, reused over periods and drives.
class PeriodicSolver {
 public:
  /// Decomposes the network's state equation once; `system` fixes G and C.
  explicit PeriodicSolver(const System& system);
  ~PeriodicSolver();
  /// The periodic state of `system` (same G and C, sources of period `period`): the long-time
  /// limit, so a delayed pulse train is taken in its periodic regime, not in its first period
  /// (a pulse whose fall reaches into the next period is there from the start; shooting the
  /// same).
  /// @param period   T [s]
  /// @param samples  samples over one period, at t = T·s/samples
  PeriodicResult solve(const System& system, const std::vector<Probe>& probes, double period,
                       int samples = 256) const;
  /// Whether the solver serves its network: the decomposition succeeded and, for a cascade,
  /// the DEAs' voltages do not see the beam; a failed Status saying why not.
  Status usable() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Status status_;
};

/// Whether the exact method can serve `system` (before decomposing it): a linear network, or an
/// exact cascade — the DEAs' force k_F·u² its only nonlinearity, none with back-coupling, small
/// kinematics (src/analysis/periodic_cascade.hpp); a failed Status saying why not. That the
/// DEAs' voltages do not see the beam is checked on the decomposition (PeriodicSolver::usable).
Status exact_periodic_applies(const System& system);

/// What shooting keeps between calls: the network linearised about its static state, as a state
/// space with its modal basis (on the tweezer jaw's 222 unknowns about 110 ms, a third of one
/// frequency's shooting). A call on a network whose linearisation is bit for bit the same (a
/// sweep's periods; a circuit switched per frequency) reuses it; any other makes its own and
/// keeps that. Not to be shared between threads.
class ShootingCache {
 public:
  ShootingCache();
  ~ShootingCache();
  ShootingCache(const ShootingCache&) = delete;
  ShootingCache& operator=(const ShootingCache&) = delete;
  /// The calls that reused the kept linearisation.
  int reuses() const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Shooting with IDA at relative tolerance `rtol` (periodic_shooting.cpp: Newton–Broyden from
/// the linearisation's periodic state and Jacobian, both exact for a linear network). `progress`
/// is for cancellation only (Status "cancelled"): the one-period IDA runs of a solve do not
/// report, a sweep over frequencies does. A periodicity residual ‖x(T) − x(0)‖/‖x(0)‖ above
/// shooting_residual_limit(rtol) is a failure.
/// @param period          T [s]
/// @param samples         samples over one period, at t = T·s/samples
/// @param nonlinear_part  added to the linearisation's periodic state to start Newton from: a
///                        neighbouring period's start_state − linear_start_state (the
///                        unknowns at t = 0), or its extrapolation; null: none
/// @param cache           the linearisation kept between calls (a sweep's); null: none
PeriodicResult run_periodic_shooting(const System& system, const std::vector<Probe>& probes,
                                     double period, double rtol = 1e-9, int samples = 256,
                                     const Progress* progress = nullptr,
                                     const Eigen::VectorXd* nonlinear_part = nullptr,
                                     ShootingCache* cache = nullptr);

/// One period of IDA (relative tolerance `rtol`) from a periodic state that shooting found, its
/// PeriodicResult::start_state, sampled for `probes`: the extremes of other outputs over the
/// same periodic state without solving for it again (one run instead of a shooting solve).
/// periodicity_residual is ‖u(T) − u(0)‖/‖u(0)‖ over the differential unknowns (the state).
/// @param period       T [s], the one the start state is periodic for
/// @param samples      samples over one period, at t = T·s/samples
PeriodicResult sample_periodic_state(const System& system, const std::vector<Probe>& probes,
                                     double period, double rtol, int samples,
                                     const Eigen::VectorXd& start_state,
                                     const Progress* progress = nullptr);

/// The periodicity residual ‖x(T) − x(0)‖/‖x(0)‖ shooting holds itself to at IDA's relative
/// tolerance `rtol`: IDA's own noise, 1000·rtol (1e-7 of the state measured at rtol 1e-9 on the
/// fin at 400 V), or kResidualLimit where that is larger.
double shooting_residual_limit(double rtol);

/// Memory of the exact periodic method's dense eigen-decomposition of the state matrix, measured
/// on the fish fin: 31 MB at 306 unknowns, 104 MB at 606, 393 MB at 1206, 1.47 GB at 2406, about
/// 254 bytes per unknown squared (complex eigenvectors, their LU and inverse, work space); its
/// time grows as the cube (44 s at 1206 unknowns, 237 s at 2406 on this project's machine).
constexpr double kPeriodicDenseBytesPerUnknown2 = 256.0;
constexpr double kPeriodicDenseMemoryLimit = 4e9;  ///< bytes

/// Unknowns up to which an automatic choice takes the dense exact method: its decomposition
/// takes under a minute there (44 s at 1206 unknowns, above), a reduction beyond.
constexpr int kPeriodicDenseAutomaticUnknowns = 1000;
/// The bytes of the dense decomposition of `unknowns` unknowns (the estimate above).
inline double periodic_memory_bytes(int unknowns) {
  return kPeriodicDenseBytesPerUnknown2 * unknowns * static_cast<double>(unknowns);
}

/// Checks that the exact periodic method's decomposition of `unknowns` unknowns fits in memory.
/// @throws OptionError naming `field` (the option that sets the mesh: "segments") when the exact
///         periodic method's decomposition of `unknowns` unknowns would need more than
///         kPeriodicDenseMemoryLimit
void check_periodic_memory(int unknowns, const std::string& field);

}  // namespace emnet
