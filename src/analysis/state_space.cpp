// Linear state equation of the displacement form: see state_space.hpp.
#include "state_space.hpp"

#include <cmath>
#include <stdexcept>
#include <unsupported/Eigen/MatrixFunctions>

namespace emnet {

LinearStateSpace::LinearStateSpace(const DisplacementForm& form) {
  if (form.system().is_nonlinear())
    throw std::runtime_error(
        "the exact method needs a linear network; this one has nonlinear DEAs (set "
        "drive.electrical_dynamics = false for ideal voltage-driven DEAs, or use IDA)");
  n_ = form.size();
  const Eigen::MatrixXd e = Eigen::MatrixXd(form.e()), a = Eigen::MatrixXd(form.a());
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(e, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd sigma = svd.singularValues();
  while (nd_ < sigma.size() && sigma[nd_] > 1e-12 * sigma[0]) ++nd_;
  na_ = n_ - nd_;
  left_ = svd.matrixU();
  right_ = svd.matrixV();
  const Eigen::MatrixXd a_hat = left_.transpose() * a * right_;
  const Eigen::MatrixXd a11 = a_hat.topLeftCorner(nd_, nd_), a21 = a_hat.bottomLeftCorner(na_, nd_),
                        a22 = a_hat.bottomRightCorner(na_, na_);
  a12_ = a_hat.topRightCorner(nd_, na_);
  a22_lu_.compute(a22);
  if (na_ > 0 && !a22_lu_.isInvertible())
    throw std::runtime_error("the network's DAE has index > 1 or no unique solution");
  a22_inv_a21_ = na_ > 0 ? Eigen::MatrixXd(a22_lu_.solve(a21)) : Eigen::MatrixXd(0, nd_);
  sigma_inv_ = sigma.head(nd_).cwiseInverse();
  m_ = sigma_inv_.asDiagonal() * (a12_ * a22_inv_a21_ - a11);
  if (!m_.allFinite()) throw std::runtime_error("the reduced state matrix is not finite");
}

Eigen::VectorXd LinearStateSpace::forcing(const Eigen::VectorXd& f) const {
  const Eigen::VectorXd f_hat = left_.transpose() * f;
  if (na_ == 0) return sigma_inv_.asDiagonal() * f_hat.head(nd_);
  const Eigen::VectorXd a22_inv_f2 = a22_lu_.solve(f_hat.tail(na_));
  return sigma_inv_.asDiagonal() * (f_hat.head(nd_) - a12_ * a22_inv_f2);
}

LinearStateSpace::Propagator LinearStateSpace::propagator(double h) const {
  Eigen::MatrixXd augmented = Eigen::MatrixXd::Zero(2 * nd_, 2 * nd_);
  augmented.topLeftCorner(nd_, nd_) = m_ * h;
  augmented.topRightCorner(nd_, nd_) = Eigen::MatrixXd::Identity(nd_, nd_) * h;
  const Eigen::MatrixXd exponential = augmented.exp();
  return {exponential.topLeftCorner(nd_, nd_), exponential.topRightCorner(nd_, nd_)};
}

void LinearStateSpace::full_state(const Eigen::VectorXd& x, const Eigen::VectorXd& f,
                                  Eigen::VectorXd& u, Eigen::VectorXd& up) const {
  const Eigen::VectorXd xp = m_ * x + forcing(f);
  Eigen::VectorXd w(n_), wp(n_);
  w.head(nd_) = x;
  wp.head(nd_) = xp;
  if (na_ > 0) {
    const Eigen::VectorXd f_hat = left_.transpose() * f;
    w.tail(na_) = a22_lu_.solve(f_hat.tail(na_)) - a22_inv_a21_ * x;
    wp.tail(na_) = -a22_inv_a21_ * xp;
  }
  u = right_ * w;
  up = right_ * wp;
}

Eigen::VectorXd LinearStateSpace::state_of(const Eigen::VectorXd& u) const {
  return (right_.transpose() * u).head(nd_);
}

const LinearStateSpace::Propagator& PropagatorCache::get(double h) {
  const long long key = std::llround(h / quantum_);
  auto found = cache_.find(key);
  if (found != cache_.end()) return found->second;
  return cache_.emplace(key, space_.propagator(h)).first->second;
}

}  // namespace emnet
