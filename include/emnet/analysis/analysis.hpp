// Analyses over one assembled System (docs/model.md, The analyses). Each takes the System (and,
// where it linearises, an operating point) and returns a Result with a Status; numerical failure is
// a status, never an exception.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <complex>
#include <string>
#include <vector>

#include "emnet/analysis/method.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/network/network.hpp"
#include "emnet/network/output.hpp"

namespace emnet {

/// A linear solve whose relative residual ‖A·x − b‖/‖b‖ is above this, or not finite, has not
/// solved its system: the analyses return a failed Status then (static, AC, the exact periodic
/// state), never a result. Rounding of the equilibrated systems is 1e-16..1e-13; 1e-8 leaves
/// room for ill-conditioned but meaningful networks and none for a garbage answer.
inline constexpr double kResidualLimit = 1e-8;
/// The failed Status for `residual` of `what` above `limit` or not finite; success otherwise.
/// @param limit  kResidualLimit for a direct solve; an integrator's result is held to what its
///               tolerance allows (run_periodic_shooting)
Status check_residual(double residual, const std::string& what, double limit = kResidualLimit);

// ---- static / operating point -----------------------------------------------------------
//
// A mechanical network at rest has zero velocities; what is wanted is displacements. Write
// every mechanical across unknown as s·(displacement) and expand (G + s·C)·y = b about s = 0:
// rows whose s⁰ part vanishes (compliance and lever rows, which relate velocities only) are
// divided by s. What is left at s = 0 is the static system K·z + g(z) = b(0) in
//   z = [displacements (m, rad) on mechanical nodes; voltages on electrical nodes;
//        through quantities (forces, torques, currents) on branches],
// solved by Newton with a sparse LU. Built from G and C alone: no element is special-cased.
// Where Newton fails on the whole load (large deflection, a strongly nonlinear drive), the load
// b(0) is applied in steps λ·b(0), λ → 1, each from the state of the last (load stepping); a
// load past which no step converges is a limit point, and the solve fails naming the λ reached.

/// Options of solve_static.
struct StaticOptions {
  double tolerance = 1e-12;  ///< Newton: relative step size
  int max_iterations = 50;   ///< Newton iterations at most, per load step
  /// Nonlinear networks: where Newton fails on the whole load, the load is applied in steps,
  /// halved after a failure down to this fraction of the whole (then the solve fails, naming
  /// the load factor it reached) and doubled after a step of at most 4 iterations.
  double smallest_load_step = 1.0 / 4096;
  Progress* progress = nullptr;  ///< a report per Newton iteration; cancelled: Status "cancelled"
};

/// The static state of a System, as solve_static returns it.
struct StaticResult {
  Status status;
  Eigen::VectorXd state;            ///< z, see above
  Eigen::VectorXd operating_point;  ///< y at rest: velocities 0, everything else from z
  double relative_residual = 0.0;  ///< ‖K·z + g − b‖ / ‖b‖ (above kResidualLimit: failed)
  int newton_iterations = 0;       ///< over every load step
  int load_steps = 0;              ///< load steps solved (1: the whole load at once)
  double seconds = 0.0;            ///< [s]
};

/// The static state of `system` (see above), by Newton with a sparse LU.
StaticResult solve_static(const System& system, const StaticOptions& options = {});
/// Value of a probe at rest (deflections and rotations; velocities are zero; through quantities
/// as solved; rate terms zero; squares evaluated as they are).
double static_probe_value(const System& system, const StaticResult& result, const Probe& probe);

/// Which unknowns are mechanical across values (velocities), and which rows have no s⁰ part
/// once those are written as s·(displacement) (compliance and lever rows): `divided`.
struct RowClassification {
  std::vector<bool> mechanical;
  std::vector<bool> divided;
};
RowClassification classify_rows(const System& system, const Eigen::SparseMatrix<double>& g_matrix);

/// G + ∂g/∂y at y.
Eigen::SparseMatrix<double> linearised_g(const System& system, const Eigen::VectorXd& y);

/// The phasors Y of (g_matrix + jω·C)·Y = b_ac() by a sparse LU, for a quick estimate of the
/// small-signal response at one frequency (IDA's tolerance scales, the automatic kinematics'
/// swing); run_ac is the analysis, with its residual checks. Empty when the factorisation fails.
/// @param g_matrix           linearised_g at the operating point
/// @param omega              angular frequency [rad/s]
/// @param relative_residual  when given, ‖A·Y − b‖/‖b‖ of the solve (infinity when it failed)
Eigen::VectorXcd small_signal_phasors(const System& system,
                                      const Eigen::SparseMatrix<double>& g_matrix, double omega,
                                      double* relative_residual = nullptr);

// ---- AC ----------------------------------------------------------------------------------
//
// Small-signal response about the operating point: (G + J_g + jω·C)·Y = B_ac with B_ac the
// sources' AC phasors plus direct excitations (System::b_ac). At f = 0 a displacement probe
// is the static response to B_ac (the limit of V/(jω)).

/// `points` frequencies from `from` to `to` [Hz], both included, spaced logarithmically when
/// `log`, else linearly; {from} for one point, empty for fewer.
std::vector<double> frequency_grid(double from, double to, int points, bool log);

/// How the sweep is solved.
///   direct: (G + J_g + jω·C)·Y = B_ac by a sparse LU at every frequency; accuracy: the residual.
///   pole_residue: every pole of the network (a dense eigen-decomposition of its state matrix)
///     and each probe's residues, then O(poles) work per frequency: p(jω) = Σ_k (a_k + jω·b_k)/
///     (jω − λ_k) + its direct part (src/analysis/ac_pole_residue.hpp). Exact but for rounding,
///     which grows with the eigenvectors' condition; so the result is compared with the direct
///     solve at the check points (ends, peaks, the frequencies of the least damped poles) and is
///     only returned when they agree to kPoleResidueAgreement of each probe's peak.
///   automatic: pole_residue for networks of at most kPoleResidueUnknowns unknowns and sweeps of
///     at least kPoleResidueFrequencies points, falling back to direct (with a note) where the
///     form does not apply or its check fails; direct otherwise.
enum class AcMethod { automatic, direct, pole_residue };
inline constexpr int kPoleResidueUnknowns = 160;       ///< see AcMethod::automatic
inline constexpr size_t kPoleResidueFrequencies = 20;  ///< see AcMethod::automatic
/// Largest difference between the two forms at a check point, relative to the probe's peak
/// |value| over the sweep, that lets the pole–residue sweep stand. The direct solve's own error
/// is its residual (≤ 1e-13 on the equilibrated systems) times the condition; 1e-10 leaves that
/// room and no more.
inline constexpr double kPoleResidueAgreement = 1e-10;

/// Options of run_ac.
struct AcOptions {
  AcMethod method = AcMethod::automatic;
  Progress* progress = nullptr;  ///< one report per frequency; cancelled: Status "cancelled"
};

/// The small-signal response of a sweep, as run_ac returns it.
struct AcResult {
  Status status;
  std::vector<double> frequencies;                        ///< Hz
  std::vector<std::vector<std::complex<double>>> values;  ///< [probe][frequency]
  double max_relative_residual = 0.0;  ///< worst ‖A·Y − B‖/‖B‖ over the sweep
  int pivot_searches = 0;  ///< factorisations with a pivot search (the first, and where reused
                           ///< pivots gave 4× the residual of the last search)
  Method method = Method::direct;  ///< direct, pole_residue (or reduced: run_ac_reduced)
  /// pole-residue: the frequencies where it was compared with the direct solve (whose residuals
  /// are max_relative_residual), the largest difference there relative to each probe's peak, and
  /// the condition κ₁ of the eigenvector basis.
  int check_points = 0;
  double check_deviation = 0.0;
  double basis_condition = 0.0;
  std::string note;  ///< why automatic fell back to the direct solve, when it did
  /// pole-residue: every pole of the linearised network [1/s] (of the state equation, the
  /// levers' spurious ones at 0 removed), as the sweep used them; empty for direct.
  std::vector<std::complex<double>> poles;
  double seconds = 0.0;  ///< [s]
};

/// A relative residual above kResidualLimit at any frequency is a failed Status naming it; so is
/// a probe value that is not finite ("non-finite result for an AC response: probe 'x' at
/// f = … Hz"): `values` never holds a NaN or an infinity.
AcResult run_ac(const System& system, const Eigen::VectorXd& operating_point,
                const std::vector<double>& frequencies, const std::vector<Probe>& probes,
                const AcOptions& options = {});
/// Probes with squares are linearised about `operating_point` (linearised_probe) by run_ac;
/// probe_phasor (emnet/network/output.hpp) takes linear probes only.

// ---- modal -------------------------------------------------------------------------------
//
// Poles s of the network, from its displacement form (src/analysis/displacement_form.hpp):
// every mechanical across unknown written as s·(displacement), rows without an s⁰ part divided
// by s, and a velocity unknown v = s·z for every node with mass, so that the pencil
//     P(s) = A + s·E,    A = ∂F/∂u, E = ∂F/∂u' at the operating point,
// is the static operator plus damping and inertia. Unlike the velocity form (G + J_g) + s·C it
// has no pole at s = 0 for a statically indeterminate beam (a self-stress carries no motion),
// and its rows relate forces to strains without differences of nearly equal velocities.
// Shift-invert: with T = (Â + σÊ)⁻¹·Ê on the equilibrated pencil (equilibration.hpp),
// T·x = μ·x gives s = σ − 1/μ; the pencil's infinite eigenvalues (algebraic unknowns) map to
// μ = 0 and drop out. Small pencils: dense eigen-decomposition of T, every finite pole. Large
// ones: implicitly restarted Arnoldi (Spectra) for the poles nearest σ, one sparse LU.
//
// Rigid-body motions (a free or sliding end, a pin without a spring) make A singular: s = 0 is a
// pole, defective (displacement and velocity chain) when nothing damps the motion to ground. It
// is found first, as the invariant subspace of T for μ = 1/σ at a small positive shift σ (block
// shift-invert iteration, right and left), reported as rigid-body modes (displacement fields),
// and projected out of T (the spectral projector along the other poles), so that rounding of a
// Jordan block cannot pollute the elastic poles.
//
// Accuracy of each pole: a residual is a backward error; the pole's own error is the residual
// times its condition. For each pole (a group of poles equal to within 1e-6, such as the two
// DEAs' RC loops, is treated together) with right vectors X, left vectors Y (inverse iteration
// on the adjoint pencil) and residuals R = Â·X + Ê·X·Λ evaluated in extended precision, the
// first-order bound |δŝ| ≤ ‖Y‖₂·‖R‖_F·‖(Yᴴ·Ê·X)⁻¹‖₂ holds against the exact poles of the stored
// pencil (Wilkinson; Tisseur, "Backward error and condition of polynomial eigenvalue
// problems", Linear Algebra Appl. 309 (2000)). A pole whose bound cannot be formed (no left
// vector, Yᴴ·Ê·X singular) or is not small (relative bound above 1e-3, where first order is no
// longer a bound) is marked unbounded, with the reason.

/// A pole with |Im s| ≤ kNearlyReal·|s| (damping ratio above 1 − 5e-11) is real: rounding splits a
/// repeated real pole into a complex pair ~√ε apart. Measured: the fish fin with the ideal drive
/// and loss factor 1e-5 has repeated Kelvin–Voigt poles at −1/τ (τ = 2.5e-7 s) that came out as
/// a "mode" at 0.0071 Hz with |Im s|/|s| = 1.1e-8.
inline constexpr double kNearlyReal = 1e-5;

/// A numbered mode is a resonance: an oscillatory pole pair with damping ratio below 1/√2, where
/// a second-order response |1/(1 − (ω/ω_n)² + 2jζω/ω_n)| has a peak (at ω_n·√(1 − 2ζ²)); the
/// Bode markers use the same limit. A pair at or above it (an overdamped pair formed by
/// relaxation poles, e.g. Kelvin–Voigt or RC branches coupled through the structure) shows no
/// peak and moves with the mesh; it is listed apart, in ModalResult::overdamped_pairs.
inline constexpr double kResonanceDampingLimit = 0.70710678118654752;
/// Whether `pole` [rad/s] (either one of its conjugate pair) is a numbered mode by kModeRule:
/// oscillatory (|Im s| above kNearlyReal·|s|) with damping ratio −Re s/|s| below
/// kResonanceDampingLimit. The one test of the modes, the AC markers and the Arnoldi request.
inline bool is_resonance(std::complex<double> pole) {
  const double magnitude = std::abs(pole);
  return std::abs(pole.imag()) > kNearlyReal * magnitude &&
         -pole.real() < kResonanceDampingLimit * magnitude;
}
inline constexpr const char* kModeRule =
    "a mode is an oscillatory pole pair with damping ratio below 1/sqrt(2) (a resonance with a "
    "peak); pairs at or above it are listed apart as overdamped pairs";

/// Options of run_modes.
struct ModalOptions {
  int count = 0;  ///< large pencils: oscillatory poles wanted (0: the 10 lowest)
  /// System unknowns up to which the dense method is used (every pole, O(n³)). Measured on the
  /// fish fin with the default request (tools/bench, "modes"): dense/Arnoldi time 0.22 at 36
  /// unknowns, 0.76 at 66, 2.1 at 126, 114 at 606, so the crossover lies near 80.
  int dense_limit = 80;
  bool keep_vectors = true;  ///< fill Mode::vector
  bool error_bounds = true;  ///< compute each pole's error bound (from the transposed pencil)
  /// Arnoldi: > 0, the request (poles) of the first run, in place of twice the wanted modes (at
  /// most 6), grown as that one would be. A design study's variants start from their nominal's
  /// ModalResult::last_request: the runs the nominal outgrew would be thrown away again.
  int first_request = 0;
  /// Reports each phase (equilibration, factorisation, rigid-body space, eigenvalues, left
  /// vectors, bounds) and, inside the Arnoldi iterations, the operator applications; cancelled,
  /// the analysis stops at the next phase or application with cancelled_status().
  Progress* progress = nullptr;
};

/// One pole of the network, with its accuracy.
struct Mode {
  std::complex<double> pole;          ///< s [1/s], Im ≥ 0
  double frequency_hz = 0.0;          ///< |Im s| / 2π (damped)
  double natural_frequency_hz = 0.0;  ///< |s| / 2π
  double damping_ratio = 0.0;         ///< −Re s / |s|
  /// ‖(Â + ŝÊ)·x̂‖ / ((‖Â‖ + |ŝ|·‖Ê‖)·‖x̂‖) on the equilibrated pencil (unit-free): the backward
  /// error.
  double relative_residual = 0.0;
  /// First-order bound on |δs| [1/s] (see above); valid when error_bounded. The frequency's error
  /// is at most pole_error/2π [Hz], the damping ratio's at most pole_error/|s|.
  double pole_error = 0.0;
  bool error_bounded = false;
  std::string unbounded_reason;  ///< why not, when !error_bounded
  Eigen::VectorXcd vector;       ///< y-space eigenvector (across values are velocities)
};

/// The poles of the network, as run_modes returns them.
struct ModalResult {
  Status status;
  std::vector<Mode> modes;       ///< oscillatory poles (Im s > 0), sorted by frequency
  std::vector<Mode> real_poles;  ///< non-oscillatory poles (RC, overdamped), sorted by |s|
  /// Oscillatory pairs with damping ratio ≥ kResonanceDampingLimit (no peak), sorted by |s|
  std::vector<Mode> overdamped_pairs;
  /// Rigid-body motions (pole s = 0): displacement fields on the system's unknowns (m and rad on
  /// mechanical across unknowns, 0 elsewhere), an orthonormal basis, largest entry positive.
  std::vector<Eigen::VectorXd> rigid_body_modes;
  Method method = Method::dense;  ///< dense or arnoldi
  int unknowns = 0;               ///< of the system
  int pencil_size = 0;            ///< of the displacement-form pencil
  double shift = 0.0;             ///< σ of the shift-invert operator [1/s]
  double seconds = 0.0;
  double bound_seconds = 0.0;  ///< of that, the error bounds
  bool complete = false;       ///< true when every finite pole was computed
  std::string note;            ///< e.g. how many of the requested poles converged
  int last_request = 0;        ///< Arnoldi: the request (poles) of the run kept; 0 dense
  long iterations = 0;         ///< Arnoldi restarts over all attempts (0 for dense)
};

/// The checks of ModalOptions.
/// @throws OptionError naming the field ("count", "dense_limit", "first_request") for a negative
///         value
void validate(const ModalOptions& options);

/// `operating_point`: y at rest (velocities zero) to linearise about; empty means zero.
/// @throws OptionError as validate(options)
ModalResult run_modes(const System& system, const Eigen::VectorXd& operating_point,
                      const ModalOptions& options = {});

}  // namespace emnet
