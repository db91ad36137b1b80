// The linear displacement form E·u' + A·u = f as an explicit state equation, for exact
// solutions under piecewise-linear sources (transient and periodic).
//
// With E = U·[T 0; 0 0]·Vᵀ (U and V orthogonal, T r × r upper triangular and nonsingular, r the
// rank), u = V·w and Â = Uᵀ·A·V, f̂ = Uᵀ·f, index 1 means Â₂₂ is invertible:
//   w₂ = Â₂₂⁻¹·(f̂₂ − Â₂₁·w₁),   x' = M·x + N·f  for the state x = w₁,
//   M = T⁻¹·(Â₁₂·Â₂₂⁻¹·Â₂₁ − Â₁₁),   N·f = T⁻¹·(f̂₁ − Â₁₂·Â₂₂⁻¹·f̂₂),
// and, differentiating the algebraic part, w₂' = Â₂₂⁻¹·(f̂₂' − Â₂₁·x'): on a ramp of the sources
// the algebraic unknowns' rates carry the sources' slope (full_state). T comes from a QR of E
// where E has full column rank on its nonzero columns (V then a permutation: the state is those
// unknowns themselves), else from the SVD (T = S, the nonzero singular values).
// Over an interval of constant f and length h: x(t+h) = x(t) + Γ(h)·(M·x(t) + N·f), with
// Γ = ∫₀ʰ e^{Ms} ds = h·φ₁(M·h) (so Φ = e^{Mh} = I + Γ·M) from one exponential of
// [[M, I], [0, 0]]·h (Van Loan). Written as an increment, a state at equilibrium (M·x + N·f = 0)
// stays there to the rounding of M·x + N·f, not of Φ·x + Γ·N·f, whose terms are each far larger.
// Over an interval where the sources are affine, f(t + s) = f₀ + s·f₁ (a ramp of a pulse or of a
// piecewise-linear source), variation of constants gives
//   x(t+h) = x(t) + Γ(h)·(M·x(t) + N·f₀) + Γ₂(h)·N·f₁,   Γ₂ = ∫₀ʰ ∫₀ˢ e^{Mr} dr ds = h²·φ₂(M·h),
// φ₂(z) = (e^z − 1 − z)/z², with Γ and Γ₂ from one exponential of [[M, I, 0], [0, 0, I],
// [0, 0, 0]]·h (its top-right blocks are Γ and Γ₂). That exponential is only taken for
// intervals with a slope; constant intervals keep the smaller one.
//
// E and A are equilibrated first (equilibration.hpp: rows, columns and a time unit ω₀), so the
// rank decision on E and the exponentials do not depend on the units: the reduction works on
// Ê = ω₀·R·E·C, Â = R·A·C for the scaled unknowns û = C⁻¹·u and scaled time t̂ = ω₀·t; the
// interface below speaks physical time and physical u.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <map>
#include <utility>
#include <vector>

#include "displacement_form.hpp"

namespace emnet {

// A source vector on one interval between breakpoints, affine there: value(t) = start +
// slope·(t − t₀), start being the right limit at t₀. The slope is exactly zero when every
// source is constant on the interval.
struct AffinePiece {
  Eigen::VectorXd start, slope;
  bool ramp() const { return (slope.array() != 0.0).any(); }
  Eigen::VectorXd at(double offset) const { return start + offset * slope; }
};

// b(t) of `system` on [t0, t1] (no breakpoint inside), in the displacement form's rows (`size`
// entries, zero beyond the system's): value and slope at the midpoint, so that a jump at either
// end is not seen, and start = b(mid) − slope·(mid − t0) (b(mid) itself when the slope is 0).
AffinePiece affine_piece(const System& system, int size, double t0, double t1);

// 2π × the highest drive frequency of the system's periodic sources, at least 2π/end_time.
double characteristic_angular_frequency(const System& system, double end_time);

// Osborne's balancing (as in LAPACK's dgebal, powers of two): D = diag(scale) such that every row
// and column of balanced = D⁻¹·M·D, off the diagonal, has the same 1-norm. The exponential's
// rounding error is relative to ‖M·h‖, which balancing makes as small as a diagonal similarity can.
void balance(const Eigen::MatrixXd& m, Eigen::VectorXd& scale, Eigen::MatrixXd& balanced);

class LinearStateSpace {
 public:
  struct Propagator {
    Eigen::MatrixXd gamma;   // Γ(h); Φ(h) = I + Γ(h)·M is never formed
    Eigen::MatrixXd gamma2;  // Γ₂(h) for ramps (ramp_propagator); empty from propagator()
  };
  // Throws std::runtime_error when the form is nonlinear or not of index 1. angular_frequency
  // [rad/s]: the time unit ω₀ of the equilibration, the rate the solution is wanted at (the
  // drive's); 0 chooses one from the pencil alone (equilibration.hpp). Measured on a
  // Kelvin–Voigt damped cantilever (N = 10, ζ1 = 0.01, driven at f1/2): ω₀ from 0.5·ω1 to 50·ω1
  // gives the exact transient to 8e-11 of the static deflection (IDA at rtol 1e-11 as the
  // reference), ω₀ = 0.005·ω1 9e-9, the automatic choice (~2500·ω1) 1e-9..5e-9.
  LinearStateSpace(const DisplacementForm& form, double angular_frequency);
  // The same for the pencil E·u' + A·u of a linearisation (DisplacementForm::linearised about
  // an operating point): nonlinear networks are accepted, the matrices describe the small
  // signal. Throws when the pencil is not of index 1. `split`: how E's leading block T is
  // found (the header comment); singular_values forces the SVD, which tests compare against.
  enum class Split { automatic, singular_values };
  LinearStateSpace(const DisplacementForm& form, const Eigen::SparseMatrix<double>& a,
                   const Eigen::SparseMatrix<double>& e, double angular_frequency,
                   Split split = Split::automatic);

  Eigen::Index state_size() const { return m_.rows(); }
  const Eigen::MatrixXd& m() const { return m_; }
  // N·f for a constant f.
  Eigen::VectorXd forcing(const Eigen::VectorXd& f) const;
  Propagator propagator(double h) const;
  // Γ and Γ₂ together, for an interval where the sources ramp.
  Propagator ramp_propagator(double h) const;
  // The state after h from x under constant forcing nf = forcing(f), with p = propagator(h).
  Eigen::VectorXd advance(const Propagator& p, const Eigen::VectorXd& x,
                          const Eigen::VectorXd& nf) const {
    return x + p.gamma * (m_ * x + nf);
  }
  // The same under the affine forcing nf + s·nf_slope (nf_slope = forcing(f₁)), with
  // p = ramp_propagator(h).
  Eigen::VectorXd advance(const Propagator& p, const Eigen::VectorXd& x, const Eigen::VectorXd& nf,
                          const Eigen::VectorXd& nf_slope) const {
    return x + p.gamma * (m_ * x + nf) + p.gamma2 * nf_slope;
  }
  // M = V·Λ·V⁻¹, for evaluating many outputs cheaply: over a constant interval,
  // x(t₀ + h) = x₀ + V·diag(increments(h))·V⁻¹·(M·x₀ + N·f), increments(h)_k = h·φ₁(λ_k h),
  // φ₁(z) = (e^z − 1)/z: O(n) exponentials and O(n²) products per time instead of an
  // exponential of M; over a ramp, plus V·diag(ramp_increments(h))·V⁻¹·N·f₁,
  // ramp_increments(h)_k = h²·φ₂(λ_k h). Null (made on first use, then kept) when V's condition
  // exceeds 1e6, so that rounding stays below ~1e-10; use propagator() then.
  struct ModalBasis {
    Eigen::VectorXcd values;
    Eigen::MatrixXcd vectors;
    Eigen::PartialPivLU<Eigen::MatrixXcd> vectors_lu;
    double condition = 0.0;  // κ₁(V) = ‖V‖₁·‖V⁻¹‖₁: rounding of V⁻¹·b grows with it
    // One pole of each conjugate pair and the real poles, with their factors 2 and 1
    // (conjugate_pairs below, a pair's vectors exactly conjugate).
    std::vector<Eigen::Index> half;
    Eigen::VectorXd half_factor;
    Eigen::VectorXcd increments(double h) const;
    Eigen::VectorXcd ramp_increments(double h) const;
    // The decomposition of `m` (balanced first; repeated semi-simple poles given an orthonormal
    // eigenspace basis when the computed vectors are nearly parallel); false when the
    // eigen-solver fails or κ₁(V) reaches 1e6, where rounding could exceed ~1e-10 (`basis` is
    // filled all the same when the solver succeeded, with its condition).
    static bool of(const Eigen::MatrixXd& m, ModalBasis& basis);
    // h·φ₁(λh) and h²·φ₂(λh) for one pole.
    static std::complex<double> increment(std::complex<double> lambda, double h);
    static std::complex<double> ramp_increment(std::complex<double> lambda, double h);
  };
  const ModalBasis* modal_basis() const;
  // The hidden constraints H·u = 0 as rows on the state (H·u_of_state(), k × state_size();
  // no rows without them). Their derivatives are rows of the form, so H·u_x·M = 0: each is a
  // left null vector of M (a pole at 0 that no consistent state excites), and the null space
  // of these rows is invariant under M.
  Eigen::MatrixXd hidden_constraints_on_state() const;
  // x moved along M's null vectors until the hidden constraints hold under sources f (no-op
  // without them), in two parts: H·u(x, f) is H·u_of_state()·x plus H·u of the sources alone,
  // which sources_in_constraints(f) gives (empty without hidden constraints) and project_with
  // takes, at O(k·n): a caller meeting the same sources again forms the second part once.
  Eigen::VectorXd sources_in_constraints(const Eigen::VectorXd& f) const;
  Eigen::VectorXd project_with(const Eigen::VectorXd& x,
                               const Eigen::VectorXd& sources_in_constraints) const;
  // u and u' from the state x at a time where the sources are f (and constant).
  void full_state(const Eigen::VectorXd& x, const Eigen::VectorXd& f, Eigen::VectorXd& u,
                  Eigen::VectorXd& up) const;
  // The same where the sources are f with slope f' = f_slope: the algebraic unknowns' rates
  // w₂' = Â₂₂⁻¹·(f̂₂' − Â₂₁·x') include the sources' slope.
  void full_state(const Eigen::VectorXd& x, const Eigen::VectorXd& f,
                  const Eigen::VectorXd& f_slope, Eigen::VectorXd& u, Eigen::VectorXd& up) const;
  // u of a state under zero sources: u = u_of_state()·x (n × state_size()).
  Eigen::MatrixXd u_of_state() const;
  // The state of a consistent u.
  Eigen::VectorXd state_of(const Eigen::VectorXd& u) const;
  // One linear output p = on_u·u + on_up·u' as rows, as full_state and forcing give it, at
  // O(n²) (maps of every unknown, which the exact periodic method formed before, are O(n³)):
  // under constant sources p = state_row·x + source_row·f, and a slope f' of the sources adds
  // slope_row·f' (the algebraic unknowns' rates).
  struct OutputRows {
    Eigen::RowVectorXd state, source, slope;
  };
  OutputRows output_rows(const Eigen::RowVectorXd& on_u, const Eigen::RowVectorXd& on_up) const;

 private:
  Eigen::Index n_ = 0, nd_ = 0, na_ = 0;
  double time_scale_ = 1.0;                   // ω₀
  Eigen::VectorXd row_scale_, column_scale_;  // R, C
  Eigen::MatrixXd left_, right_, m_, a12_, a22_inv_a21_;
  Eigen::VectorXd balance_;  // D of the balanced D⁻¹·M·D
  Eigen::MatrixXd balanced_m_;
  // H (hidden constraints); M's null vectors and the LU of H·(u of them), made on the first
  // projection (a QR of Mᵀ that only the exact transient needs). Like modal_basis(), a lazy
  // member: one LinearStateSpace is not shared between threads.
  Eigen::MatrixXd hidden_rows_;  // H (k × n), as given by the form
  mutable Eigen::MatrixXd constraint_, null_vectors_;
  mutable Eigen::MatrixXd constraint_on_state_;  // H·u_of_state()
  mutable Eigen::PartialPivLU<Eigen::MatrixXd> constraint_lu_;
  mutable bool projection_prepared_ = false;
  void prepare_projection() const;
  // Eigen-decomposition of M for modal_basis(), made on first use.
  mutable int modes_state_ = 0;  // 0 not tried, 1 usable, −1 ill-conditioned
  mutable ModalBasis basis_;
  Eigen::MatrixXd leading_;  // T of Ê = U·[T 0; 0 0]·Vᵀ, upper triangular
  // ω₀·T⁻¹·x: the scaled equations' leading block solved, in physical time.
  Eigen::MatrixXd leading_solve(Eigen::MatrixXd x) const;
  Eigen::VectorXd leading_solve(Eigen::VectorXd x) const;
  Eigen::FullPivLU<Eigen::MatrixXd> a22_lu_;
};

// One pole of each conjugate pair (Im λ > 0, factor 2) and the real poles (factor 1) of
// `lambda`, in `half` and `factor`: for data (weights, coefficients) conjugate over each pair,
// Re Σ_k w_k·g(λ_k) = Σ_{k ∈ half} factor_k·Re(w_k·g(λ_k)), at half the work. A pair is two
// adjacent, exactly conjugate poles (as the real Schur form gives them) for which
// `conjugate(k)` says the data of poles k and k + 1 are conjugate too. Where any pole is not so
// paired: every pole, factor 1, and false.
template <class Conjugate>
bool conjugate_pairs(const Eigen::VectorXcd& lambda, Conjugate conjugate,
                     std::vector<Eigen::Index>& half, std::vector<double>& factor) {
  half.clear();
  factor.clear();
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    if (lambda[k].imag() == 0.0) {
      half.push_back(k);
      factor.push_back(1.0);
    } else if (lambda[k].imag() > 0.0 && k + 1 < lambda.size() &&
               lambda[k + 1] == std::conj(lambda[k]) && conjugate(k)) {
      half.push_back(k);
      factor.push_back(2.0);
      ++k;
    } else {
      half.resize(static_cast<size_t>(lambda.size()));
      for (Eigen::Index j = 0; j < lambda.size(); ++j) half[static_cast<size_t>(j)] = j;
      factor.assign(half.size(), 1.0);
      return false;
    }
  }
  return true;
}

// The modal increments at successive offsets 0 ≤ h₁ ≤ h₂ ≤ … into one interval, on the poles
// of ModalBasis::half: E = e^{λh}, I = ∫₀ʰ e^{λs} ds = h·φ₁(λh) (ModalBasis::increments) and
// J = ∫₀ʰ I = h²·φ₂(λh) (ramp_increments). A step by δ uses the addition theorem
//   E(h+δ) = E(h)·E(δ),  I(h+δ) = I(h) + E(h)·I(δ),  J(h+δ) = J(h) + δ·I(h) + E(h)·J(δ),
// with E, I and J of δ kept for the last four step lengths (outputs on a uniform grid repeat
// one or two, to the last bit): a few products per pole and output instead of exponentials.
// Each step adds one rounding of the size of the terms, so k steps leave k·ε relative
// (50 outputs per interval: ~1e-14).
class ModalClock {
 public:
  explicit ModalClock(const LinearStateSpace::ModalBasis& basis);
  // h = 0; J is only kept (and its steps only formed) with `ramp`.
  void restart(bool ramp);
  void advance_to(double offset);
  const Eigen::VectorXcd& integral() const { return integral_; }            // I(h)
  const Eigen::VectorXcd& ramp_integral() const { return ramp_integral_; }  // J(h)

 private:
  struct Step {
    double delta = 0.0;
    bool with_ramp = false;
    Eigen::VectorXcd exponential, integral, ramp_integral;
  };
  const Step& step(double delta);
  Eigen::VectorXcd poles_;
  double offset_ = 0.0;
  bool ramp_ = false;
  Eigen::VectorXcd exponential_, integral_, ramp_integral_;
  std::vector<Step> steps_;
  size_t next_slot_ = 0;
};

// Propagators cached per interval length, quantised at `quantum` (rounding of t, not physics).
class PropagatorCache {
 public:
  PropagatorCache(const LinearStateSpace& space, double quantum)
      : space_(space), quantum_(quantum) {}
  const LinearStateSpace::Propagator& get(double h);
  // Γ and Γ₂ (LinearStateSpace::ramp_propagator), cached apart.
  const LinearStateSpace::Propagator& get_ramp(double h);
  size_t size() const { return cache_.size() + ramp_cache_.size(); }

 private:
  const LinearStateSpace& space_;
  double quantum_;
  std::map<long long, LinearStateSpace::Propagator> cache_, ramp_cache_;
};

}  // namespace emnet
