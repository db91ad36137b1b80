// The exponentials of the state equation (Γ and Γ₂ from one exponential of an augmented matrix)
// and their cache: see state_space.hpp.
#include <cmath>
#include <unsupported/Eigen/MatrixFunctions>

#include "state_space.hpp"

namespace emnet {

LinearStateSpace::Propagator LinearStateSpace::propagator(double h) const {
  // On the balanced M_b = D⁻¹·M·D: Γ = D·Γ_b·D⁻¹.
  Eigen::MatrixXd augmented = Eigen::MatrixXd::Zero(2 * nd_, 2 * nd_);
  augmented.topLeftCorner(nd_, nd_) = balanced_m_ * h;
  augmented.topRightCorner(nd_, nd_) = Eigen::MatrixXd::Identity(nd_, nd_) * h;
  const Eigen::MatrixXd exponential = augmented.exp();
  return {balance_.asDiagonal() * exponential.topRightCorner(nd_, nd_) *
              balance_.cwiseInverse().asDiagonal(),
          Eigen::MatrixXd()};
}

LinearStateSpace::Propagator LinearStateSpace::ramp_propagator(double h) const {
  // exp([[M_b, I, 0], [0, 0, I], [0, 0, 0]]·h) = [[Φ, Γ, Γ₂], [0, I, h·I], [0, 0, I]]; with
  // diag(D, D, D) the similarity to M's blocks, Γ = D·Γ_b·D⁻¹ and Γ₂ = D·Γ₂_b·D⁻¹.
  Eigen::MatrixXd augmented = Eigen::MatrixXd::Zero(3 * nd_, 3 * nd_);
  augmented.topLeftCorner(nd_, nd_) = balanced_m_ * h;
  augmented.block(0, nd_, nd_, nd_) = Eigen::MatrixXd::Identity(nd_, nd_) * h;
  augmented.block(nd_, 2 * nd_, nd_, nd_) = Eigen::MatrixXd::Identity(nd_, nd_) * h;
  const Eigen::MatrixXd exponential = augmented.exp();
  const auto d = balance_.asDiagonal();
  const auto d_inverse = balance_.cwiseInverse().asDiagonal();
  return {d * exponential.block(0, nd_, nd_, nd_) * d_inverse,
          d * exponential.block(0, 2 * nd_, nd_, nd_) * d_inverse};
}

const LinearStateSpace::Propagator& PropagatorCache::get(double h) {
  const long long key = std::llround(h / quantum_);
  auto found = cache_.find(key);
  if (found != cache_.end()) return found->second;
  return cache_.emplace(key, space_.propagator(h)).first->second;
}

const LinearStateSpace::Propagator& PropagatorCache::get_ramp(double h) {
  const long long key = std::llround(h / quantum_);
  auto found = ramp_cache_.find(key);
  if (found != ramp_cache_.end()) return found->second;
  return ramp_cache_.emplace(key, space_.ramp_propagator(h)).first->second;
}

}  // namespace emnet
