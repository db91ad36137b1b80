// Modal reduction with static correction (mode acceleration) for AC and periodic analyses.
//
// The linearised network is the descriptor pencil (G + J_g) + s·C, with algebraic unknowns
// (infinite eigenvalues). For a simple finite pole s_k with right vector v and left vector w,
// (G + s_k·C)·v = 0, wᵀ·(G + s_k·C) = 0, normalised by the pencil's bi-orthogonality
// wᵀ·C·v = 1, the response to an input vector b is
//   y(s) = (G + sC)⁻¹·b = Σ_k v_k·(w_kᵀ·b)/(s − s_k) + (the infinite eigenvalues' part).
// Responses are wanted in the static form z (analysis.hpp): displacements on mechanical
// nodes (z = y/s there, a deflection probe is velocity/(jω)), y elsewhere. Mode k's z-vector
// is v_k with its mechanical entries divided by s_k (partial fractions of v/(s(s − s_k)); the
// 1/s parts of all modes cancel because the network has a static state), so
//   z(s) = Σ_k v^z_k·β_k/(s − s_k) + D,   β_k = w_kᵀ·b.
// Kept: the poles with |s_k| < 2π·f_c (oscillatory ones with their conjugate, real ones — RC
// loops, overdamped relaxations — alone), from run_modes on the equilibrated pencil: dense up to
// ReductionOptions::dense_limit unknowns (all poles), Arnoldi beyond (the request doubled until
// a pole beyond f_c is found, or it stops converging: then `all_found` is false and said). The
// truncated ones and the infinite part are replaced by their value at s = 0 (static correction):
//   D = z_static − Σ_kept v^z_k·β_k/(−s_k),
// z_static from one static solve (StaticOperator, the same one the AC sweep uses at f = 0), so
// the reduced response equals the static one at f = 0 exactly, whatever is kept.
//
// Cut-off. A truncated oscillatory pair at natural frequency f_k with damping ratio ζ_k is
// 1/(1 − (f/f_k)² + 2jζ_k·f/f_k) times its static part; the static correction keeps that
// static part, so the error left is its static part times
//   ρ_k(f) = |(f/f_k)² − 2jζ_k·f/f_k| / |1 − (f/f_k)² + 2jζ_k·f/f_k| ≈ (f/f_k)²  (2ζ_k ≪ f/f_k).
// Inside the band f ≤ f_band this is ≤ tol when f_k ≥ f_band/√tol, so
//   f_c = f_band / √tol.
// A truncated static part is itself a fraction of the total response (for a beam mode k's
// static flexibility falls like 1/f_k²), so the error relative to the largest response is
// usually far below tol: the rule is conservative. A real pole −a has ρ = f/√(f² + (a/2π)²),
// first order: damping-dominated relaxations (Kelvin–Voigt damping turns every mode with
// ω_k·τ > 2 into two real poles, one in a cluster near −1/τ, one near −τ·ω_k²) are the case
// where the cut-off alone does not bound the error. Hence both an estimate and a measurement:
//   estimate: max over probes of ρ_max(f)·|static-correction part at f| / max|o| at the band's
//             edge f (or the sweep's, when it reaches beyond the band),
//             ρ_max over the truncated poles the eigen-solver found (the undamped (f/f_c)²
//             bound beyond them);
//   measured: |o_reduced − o_full| / max|o_full| at check frequencies (5 spread over the sweep
//             and each probe's largest response), o_full from run_ac on the same system.
// Poles not found. Above dense_limit, Arnoldi (nearest s = 0 first) can stop below f_c: on the
// fish fin the Kelvin–Voigt relaxations put ~N real poles in [−1.35/τ, −1/τ] (159 Hz at loss
// factor 0.04), the creep of every overdamped mode, each carrying that mode's static flexibility
// (not zero), and a request that ends inside them does not converge, so the fin's 4th mode
// (206 Hz) and the cluster itself are never found. With the static value alone such a real pole
// −a leaves a first-order error f/√(f² + (a/2π)²) (6 % of its static part at 10 Hz) and the
// heavily damped 4th mode (ζ ≈ 0.7) about 2ζ·f/f_k, also first order: measured 2.9e-4 and
// 1.5e-4 at N = 100 and 500 against tol 1e-4. Then (`series_correction`, AC only) the truncated
// part is matched to its Taylor series at s = 0 to order m, z(s) = Σ_kept + Σ_{i ≤ m} s^i·D_i:
// the full model's coefficients z_i from A₀·z_i = −A₁·z_(i−1) − A₂·z_(i−2) (A(s) the static
// form's operator, A₀ the one StaticOperator factorises: m more solves with its LU), minus the
// kept terms' (R/(s − s_k) = −Σ_i R·s^i/s_k^(i+1)). A truncated real pole is then wrong by
// (f/f_a)^(m+1)/|1 − s/a| of its static part, so m is the lowest with r^(m+1)/(1 − r) ≤ tol,
// r = f_band/f_found (the largest pole found bounds the unfound ones from below), at most 4.
// The series only holds inside the radius of the nearest unkept pole (f < f_found), which the
// band is. Measured at tol 1e-4 (m = 3, r = 10/113), against run_ac over 1000 points, ideal
// drive: 8.9e-9 at N = 100, 3.8e-6 at N = 500.
//
// Poles repeated to rounding (|Δs| < 1e-6·|s|: the two DEAs' equal RC loops, Kelvin–Voigt
// relaxations near −1/τ) have no unique left vectors; a group of m of them is kept or truncated
// as a whole, with m left vectors spanning its left space and β = (Wᵀ·C·V)⁻¹·Wᵀ·b
// (left_eigenvector.hpp). A group whose Wᵀ·C·V is singular (rcond < 1e-10 after scaling)
// goes to the static correction.
//
// Periodic (piecewise-linear drive b(t) = Σ_w b_w·u_w(t): constant or ramping between edges):
// each kept pole is a modal coordinate q_k' = s_k·q_k + Σ_w β_kw·u_w(t), and
// z(t) = Σ_k v^z_k·q_k + c.c. + Σ_w D_w·u_w(t) (the static correction as a direct feed-through
// of the forcing, following its ramps). The periodic state of each q_k is exact (one period from
// 0, then q(0) = c/(1 − e^{s_k·T}), with an affine particular state on a ramp); only the
// truncated modes' dynamics are lost: on a ramp their lag behind the static value (of order
// u_w'/|s_k|), and their transients after each switching edge — whose amplitude is their static
// part, decayed by their own damping, and no band argument makes it smaller: a square wave's
// edges excite every pole. So the periodic cut-off is f_c = f_band/tol (f_band: the highest
// switching frequency), chosen from measurement, not derived: on the fish fin (N = 7, 5 Hz) f_c =
// band/√tol left 1.1e-2 at tol 1e-3 (the relaxation poles at 252 and 435 Hz carry 0.2 % and 0.13 %
// of the tip's static deflection, more of P2's), band/tol 6e-4 at tol 1e-2. The error is measured
// against the exact solution (periodic_difference), never assumed. The poles come from a dense
// eigen-decomposition up to 600 unknowns, as PeriodicSolver's (the Kelvin–Voigt cluster at
// −1/τ lies below f_c and stops Arnoldi). Probes must be displacement-like (deflections,
// rotations: no velocity, which would need the derivative of the square wave).
#pragma once

#include <Eigen/Core>
#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/network/network.hpp"
#include "emnet/network/output.hpp"

namespace emnet {

/// Options of the modal reductions (reduce_modal, run_ac_reduced, ReducedPeriodicSolver).
struct ReductionOptions {
  double band = 0.0;        ///< f_band [Hz]: highest frequency of interest; > 0
  double tolerance = 1e-3;  ///< relative error wanted; in (0, 1)
  /// Unknowns up to which all poles come from a dense eigen-decomposition; above it, Arnoldi
  /// (Spectra shift-invert) for the poles below f_c only.
  int dense_limit = 200;
  /// Keep every computed finite pole, whatever f_c (for checks; dense networks only).
  bool keep_all = false;
  /// When > 0, the cut-off f_c [Hz] instead of band/√tol (ReducedPeriodicSolver: band/tol).
  double cutoff_hz = 0.0;
  /// When not every pole below f_c was found (Arnoldi stopped at a cluster), match the
  /// truncated part's Taylor series at s = 0 to the order the unfound poles need (D + Σ s^m·D_m,
  /// see above). AC only: ReducedPeriodicSolver turns it off (its feed-through cannot carry
  /// derivatives of a square wave).
  bool series_correction = true;
  /// > 0: no Arnoldi request (modes asked, doubled from 4) beyond this one; the poles it found
  /// are kept as if the next had stopped at a cluster (`all_found` false). A design study sets
  /// it for its variants to the nominal reduction's `useful_request` where a larger request
  /// only ran into a cluster (ten restarts without a new pole: two thirds of the tweezer jaw's
  /// pole search).
  int last_request = 0;
  /// > 0: at that last request, the Arnoldi run's request (poles) to start from
  /// (ModalOptions::first_request): a design study's variants take the nominal reduction's
  /// `useful_arnoldi_request` (the tweezer jaw's first run of 6 poles was outgrown every time).
  int arnoldi_request = 0;
};

/// The checks of ReductionOptions.
/// @throws OptionError naming the field ("band", "tolerance", "dense_limit", "cutoff_hz",
///         "last_request", "arnoldi_request") for values outside the ranges
void validate(const ReductionOptions& options);
/// f_c = f_band / √tol, or options.cutoff_hz when set.
double cutoff_frequency(const ReductionOptions& options);

/// A pole the reduced model keeps.
struct KeptPole {
  std::complex<double> pole;  ///< Im ≥ 0
  bool oscillatory = false;   ///< with its conjugate
  Eigen::VectorXcd z_vector;  ///< v^z (see above), wᵀ·C·v = 1
  Eigen::VectorXcd left;      ///< w (a basis vector of its group's left space), physical rows
  double left_residual = 0.0;
};

/// The reduced model for a set of input vectors b_j (one for AC: B_ac; one per waveform for a
/// periodic drive).
struct ModalReduction {
  Status status;
  double band_hz = 0.0, tolerance = 0.0, cutoff_hz = 0.0;  ///< f_band [Hz], tol, f_c [Hz]
  int full_unknowns = 0;                                   ///< of the system
  Method modal_method = Method::dense;                     ///< dense or arnoldi
  std::vector<KeptPole> kept;                              ///< the poles kept
  int kept_modes = 0, kept_real_poles = 0;                 ///< oscillatory pairs; real poles
  int truncated_poles = 0;  ///< computed but not kept (above f_c or inseparable)
  int unreached_poles = 0;  ///< below f_c, but the inputs do not reach them (dropped)
  int clustered_poles = 0;  ///< in groups repeated to rounding (kept as a group, or truncated)
  bool all_found = true;    ///< every pole below f_c was computed
  /// The last Arnoldi request (modes asked) that found a pole the one before had not; 0 dense.
  int useful_request = 0;
  /// The Arnoldi run's own request (poles) at useful_request (ModalResult::last_request).
  int useful_arnoldi_request = 0;
  /// ρ_max(f_band) of the truncated poles found ((f_band/f_c)² when none were found).
  double truncation_factor = 0.0;
  std::vector<std::pair<std::complex<double>, bool>> truncated;  ///< (pole, oscillatory)
  double largest_found = 0.0;                                    ///< largest |s| computed [1/s]
  /// ρ_max at ω of the truncated poles (and the undamped bound beyond the largest found when
  /// not all poles below f_c were found); truncation_factor is this at the band's edge.
  /// @param omega  angular frequency ω [rad/s]
  double truncation_factor_at(double omega) const;
  std::vector<bool> mechanical;                         ///< unknowns that are velocities
  std::vector<Eigen::VectorXcd> inputs;                 ///< b_j
  std::vector<std::vector<std::complex<double>>> beta;  ///< [pole][input] w_kᵀ·b_j
  std::vector<Eigen::VectorXcd> correction;             ///< D_j, static form
  /// [input][m − 1]: D_m, the s^m term of the truncated part (empty: the static one alone).
  std::vector<std::vector<Eigen::VectorXcd>> correction_series;
  int correction_order = 0;  ///< the highest m
  std::string note;
  double seconds = 0.0;

  /// The reduced response of `probe` at s = jω to input j (ω = 0: the static limit, as run_ac).
  /// @param omega  angular frequency ω [rad/s]
  std::complex<double> response(const Probe& probe, double omega, int input = 0) const;
  /// The static-correction part of that response alone.
  std::complex<double> correction_response(const Probe& probe, double omega, int input = 0) const;
};

/// The reduced model of the network linearised about `operating_point` for `inputs` (the b_j).
/// @throws OptionError when `options` is out of range (validate)
ModalReduction reduce_modal(const System& system, const Eigen::VectorXd& operating_point,
                            const std::vector<Eigen::VectorXcd>& inputs,
                            const ReductionOptions& options);

// ---- AC ----------------------------------------------------------------------------------

/// A reduced AC sweep with its check, as run_ac_reduced returns it.
struct AcReductionResult {
  Status status;                          ///< numerical failure of the reduction or of the check
  AcResult ac;                            ///< the sweep, evaluated by the reduced model
  ModalReduction model;                   ///< (its vectors are kept)
  double error_estimate = 0.0;            ///< a priori, see above
  std::vector<double> check_frequencies;  ///< where the check compared with run_ac [Hz]
  std::vector<double> probe_errors;       ///< measured, per probe
  double measured_error = 0.0;            ///< max of probe_errors
  bool tolerance_met = false;             ///< measured_error ≤ tolerance
  double reduce_seconds = 0.0, evaluate_seconds = 0.0, check_seconds = 0.0;
  double seconds = 0.0;
};

/// Per probe p: max_f |values[p][f] − reference[p][f]| / max_f |reference[p][f]| (0 when both
/// are zero, 1 when only the reference is): the error measure of every reduction check.
std::vector<double> errors_relative_to_peak(
    const std::vector<std::vector<std::complex<double>>>& values,
    const std::vector<std::vector<std::complex<double>>>& reference);

/// Reduced AC sweep of B_ac (System::b_ac) with its check against run_ac. options.band 0 means
/// the sweep's highest frequency.
/// @throws OptionError when `options` is out of range (validate)
AcReductionResult run_ac_reduced(const System& system, const Eigen::VectorXd& operating_point,
                                 const std::vector<double>& frequencies,
                                 const std::vector<Probe>& probes, ReductionOptions options);

/// Check frequencies: `spread` points spread over the grid (first and last included) and each
/// probe's largest |value|, sorted, without repeats.
std::vector<double> check_frequencies(const std::vector<double>& grid,
                                      const std::vector<std::vector<std::complex<double>>>& values,
                                      int spread = 5);

// ---- periodic ----------------------------------------------------------------------------

/// The reduced counterpart of PeriodicSolver (piecewise-linear sources): for a linear network,
/// and for an exact cascade (periodic_cascade.hpp: the DEAs' force k_F·u² the only
/// nonlinearity, their voltages set by the circuit alone).
///
/// The reduced cascade. The DEA voltages u_j come from the kept poles and the static
/// correction of the sources' inputs, as any probe of a linear network; their squares are
/// sums Σ_m P_m(h)·e^{μ_m h} over exponents μ fixed by the voltages' poles (0, λ_k, λ_k + λ_l),
/// whatever the switching frequency. The beam's response to them is the kept poles' particular
/// and periodic homogeneous states (exact, as the full cascade's) plus the truncated poles'
/// particular state, also exact: for P(h)·e^{μh} it is (z(μ)·P + z'(μ)·P' + z''(μ)/2·P'')·e^{μh}
/// with z(s) the full model's response to the DEA's direction less the kept terms
/// Σ R_k/(s − λ_k), from one sparse LU of the static form's operator A(μ) = A₀ + μ·A₁ + μ²·A₂
/// per exponent (over the unknowns the force reaches, which the circuit's poles are not). No
/// static correction is assumed for the beam, so a Kelvin–Voigt cluster of relaxations close to
/// the squares' exponents (the tweezer jaw's: −1/τ = −4712 1/s against −2296 1/s) costs no
/// accuracy. Only the truncated poles' homogeneous transients are left out: each starts at a
/// switching edge from the jump of their particular state there (the square's slope changes,
/// its value does not) and decays with their own damping; `truncation_estimate` of the result
/// sums them where they add up most, each decaying at the largest kept |pole| (a bound for real
/// truncated poles, all at least that large; an estimate for a lightly damped truncated pair),
/// relative to each probe's largest |value|. Measured on the tweezer jaw: 9e-4 to 4e-3 on the
/// samples right after an edge, its extremes exact to 1e-11 (the transients decay within
/// 1 ms, where a deflection's extremes do not lie).
class ReducedPeriodicSolver {
 public:
  /// Reduces `system` for its drive's waveforms, one input per waveform, and for a cascade one
  /// more per DEA (its force's direction).
  /// @throws OptionError when `options` is out of range (validate)
  ReducedPeriodicSolver(const System& system, const ReductionOptions& options);
  /// A cascade's squared sources and their exponents' feed-through (defined and used in the
  /// library only).
  struct Cascade;
  /// The reduced model.
  const ModalReduction& reduction() const { return reduction_; }
  /// Whether the network is a cascade (the reduced cascade, above).
  bool cascade() const { return cascade_ != nullptr; }
  /// As PeriodicSolver::solve, and with the same sampling and global extremes
  /// (src/analysis/exponential_series.hpp): samples at t = T·s/samples.
  PeriodicResult solve(const System& system, const std::vector<Probe>& probes, double period,
                       int samples = 256) const;
  /// The error the static correction makes at the switching edges, for when no full solution
  /// fits: an edge starts the truncated poles' transients from their static part, which the
  /// feed-through D follows at once, so the reduced state is off by up to
  ///   max over probes of Σ_j |probe·D_j|·(largest step of input j's waveform) / scale[p]
  /// just after an edge (scale[p]: the probe's largest |value|). An estimate: an underdamped
  /// truncated pair can overshoot its static part (up to twice it), and a slowly decaying one
  /// carries over from the edges before. Sine inputs count their peak-to-peak as a step.
  double edge_error_estimate(const System& system, const std::vector<Probe>& probes,
                             const std::vector<double>& scale) const;

 private:
  // The cascade's reduction: `inputs` (the waveforms') and one per DEA, reduced with
  // `periodic`, then the feed-through of every exponent (reduced_cascade.cpp).
  void reduce_cascade(const System& system, const ReductionOptions& periodic,
                      std::vector<Eigen::VectorXcd> inputs);
  PeriodicResult solve_cascade(const System& system, const std::vector<Probe>& probes,
                               double period, int samples) const;
  ModalReduction reduction_;
  std::vector<int> waveforms_;  // input j ↔ system.excitation().waveforms[waveforms_[j]]
  std::shared_ptr<const Cascade> cascade_;  // null for a linear network
};

/// max over probes of max over samples |reduced − full| / max over samples |full|; both solved
/// with the same samples. −1 when they do not match.
double periodic_difference(const PeriodicResult& reduced, const PeriodicResult& full);

/// max over probes of the larger |difference| of the periodic minimum and maximum, relative to
/// max over samples |full| (the basis of periodic_difference). −1 when they do not match.
double extremes_difference(const PeriodicResult& reduced, const PeriodicResult& full);

}  // namespace emnet
