// The linear displacement form E·u' + A·u = f as an explicit state equation, for exact
// solutions under piecewise-constant sources (transient and periodic).
//
// With E = U·S·Vᵀ (rank r), u = V·w and Â = Uᵀ·A·V, f̂ = Uᵀ·f, index 1 means Â₂₂ is invertible:
//   w₂ = Â₂₂⁻¹·(f̂₂ − Â₂₁·w₁),   x' = M·x + N·f  for the state x = w₁,
//   M = S₁⁻¹·(Â₁₂·Â₂₂⁻¹·Â₂₁ − Â₁₁),   N·f = S₁⁻¹·(f̂₁ − Â₁₂·Â₂₂⁻¹·f̂₂).
// Over an interval of constant f and length h: x(t+h) = Φ(h)·x(t) + Γ(h)·N·f, with Φ = e^{Mh}
// and Γ = ∫₀ʰ e^{Ms} ds from one exponential of [[M, I], [0, 0]]·h (Van Loan).
#pragma once

#include <Eigen/Dense>
#include <map>
#include <utility>

#include "displacement_form.hpp"

namespace emnet {

class LinearStateSpace {
 public:
  struct Propagator {
    Eigen::MatrixXd phi, gamma;
  };
  // Throws std::runtime_error when the form is nonlinear or not of index 1.
  explicit LinearStateSpace(const DisplacementForm& form);

  Eigen::Index state_size() const { return m_.rows(); }
  const Eigen::MatrixXd& m() const { return m_; }
  // N·f for a constant f.
  Eigen::VectorXd forcing(const Eigen::VectorXd& f) const;
  Propagator propagator(double h) const;
  // u and u' from the state x at a time where the sources are f.
  void full_state(const Eigen::VectorXd& x, const Eigen::VectorXd& f, Eigen::VectorXd& u,
                  Eigen::VectorXd& up) const;
  // The state of a consistent u.
  Eigen::VectorXd state_of(const Eigen::VectorXd& u) const;

 private:
  Eigen::Index n_ = 0, nd_ = 0, na_ = 0;
  Eigen::MatrixXd left_, right_, m_, a12_, a22_inv_a21_;
  Eigen::VectorXd sigma_inv_;
  Eigen::FullPivLU<Eigen::MatrixXd> a22_lu_;
};

// Propagators cached per interval length, quantised at `quantum` (rounding of t, not physics).
class PropagatorCache {
 public:
  PropagatorCache(const LinearStateSpace& space, double quantum)
      : space_(space), quantum_(quantum) {}
  const LinearStateSpace::Propagator& get(double h);
  size_t size() const { return cache_.size(); }

 private:
  const LinearStateSpace& space_;
  double quantum_;
  std::map<long long, LinearStateSpace::Propagator> cache_;
};

}  // namespace emnet
