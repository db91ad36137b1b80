// The eigen-decomposition of the state matrix M and the modal increments stepped by ModalClock:
// see state_space.hpp.
#include <cmath>
#include <complex>
#include <vector>

#include "dense_decompositions.hpp"
#include "state_space.hpp"

namespace emnet {

namespace {

// Eigenvalues equal to rounding, as the relaxation poles −1/τ of identical Kelvin–Voigt dashpots
// are (one per rotational compliance of a uniform beam), form a semi-simple repeated pole whose
// eigenspace has its full dimension; the eigen-solver may still return nearly parallel vectors
// for it (measured: a fish-fin variant with seven poles at −1002.95/s, vector condition 6.5e16).
// Each such cluster's vectors are replaced by an orthonormal basis of the null space of
// M − λ̄·I (SVD; real for a real λ̄), when that null space has the cluster's dimension: its
// smallest singular values below 1e-10 of ‖M‖₁. A defective cluster (a Jordan block: fewer
// null vectors) is left as it is, and the condition check after this fails as before.
void orthonormalise_repeated(const Eigen::MatrixXd& m, Eigen::VectorXcd& lambda,
                             Eigen::MatrixXcd& vectors) {
  const Eigen::Index n = lambda.size();
  const double norm = m.cwiseAbs().colwise().sum().maxCoeff();
  std::vector<bool> seen(static_cast<size_t>(n), false);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (seen[static_cast<size_t>(i)]) continue;
    std::vector<Eigen::Index> cluster;
    for (Eigen::Index j = i; j < n; ++j)
      if (!seen[static_cast<size_t>(j)] &&
          std::abs(lambda[j] - lambda[i]) <= 1e-9 * std::max(std::abs(lambda[i]), 1e-300)) {
        cluster.push_back(j);
        seen[static_cast<size_t>(j)] = true;
      }
    const Eigen::Index k = static_cast<Eigen::Index>(cluster.size());
    if (k < 2) continue;
    std::complex<double> mean = 0.0;
    for (Eigen::Index j : cluster) mean += lambda[j];
    mean /= static_cast<double>(k);
    Eigen::MatrixXcd basis;
    Eigen::VectorXd singular;
    if (std::abs(mean.imag()) <= 1e-12 * std::abs(mean)) {
      const RealSingularValueDecomposition svd =
          jacobi_svd(m - mean.real() * Eigen::MatrixXd::Identity(n, n), Eigen::ComputeFullV);
      singular = svd.singular_values;
      basis = svd.v.rightCols(k).cast<std::complex<double>>();
      mean = mean.real();
    } else {
      const ComplexSingularValueDecomposition svd = complex_jacobi_svd(
          m.cast<std::complex<double>>() - mean * Eigen::MatrixXcd::Identity(n, n),
          Eigen::ComputeFullV);
      singular = svd.singular_values;
      basis = svd.v.rightCols(k);
    }
    if (!(singular[n - k] <= 1e-10 * norm)) continue;  // defective: fewer null vectors
    for (Eigen::Index c = 0; c < k; ++c) {
      vectors.col(cluster[static_cast<size_t>(c)]) = basis.col(c);
      lambda[cluster[static_cast<size_t>(c)]] = mean;
    }
  }
}

}  // namespace

const LinearStateSpace::ModalBasis* LinearStateSpace::modal_basis() const {
  if (modes_state_ == 0) modes_state_ = ModalBasis::of(m_, basis_) ? 1 : -1;
  return modes_state_ > 0 ? &basis_ : nullptr;
}

bool LinearStateSpace::ModalBasis::of(const Eigen::MatrixXd& m, ModalBasis& basis) {
  Eigen::VectorXd scale;
  Eigen::MatrixXd balanced;
  balance(m, scale, balanced);
  const RealEigenDecomposition solver = real_eigen_decomposition(balanced);
  if (!solver.converged) return false;
  basis.values = solver.values;
  basis.vectors = scale.cast<std::complex<double>>().asDiagonal() * solver.vectors;
  basis.vectors_lu.compute(basis.vectors);
  // κ₁ by the LU's estimate of ‖V⁻¹‖₁ (Hager–Higham, as LAPACK's gecon): O(n²), where the
  // explicit inverse was O(n³); the estimate is a lower bound, within a factor of a few of κ₁.
  basis.condition = 1.0 / basis.vectors_lu.rcond();
  if (!(basis.condition < 1e6)) {
    // Repeated semi-simple poles (identical dashpots, two identical DEAs' RC loops) with nearly
    // parallel computed vectors: an orthonormal basis of each cluster's eigenspace instead.
    orthonormalise_repeated(m, basis.values, basis.vectors);
    basis.vectors_lu.compute(basis.vectors);
    basis.condition = 1.0 / basis.vectors_lu.rcond();
  }
  std::vector<double> factors;
  conjugate_pairs(
      basis.values,
      [&](Eigen::Index k) { return basis.vectors.col(k + 1) == basis.vectors.col(k).conjugate(); },
      basis.half, factors);
  basis.half_factor =
      Eigen::Map<Eigen::VectorXd>(factors.data(), static_cast<Eigen::Index>(factors.size()));
  return basis.condition < 1e6 && basis.vectors.allFinite();
}

std::complex<double> LinearStateSpace::ModalBasis::increment(std::complex<double> lambda,
                                                             double h) {
  const std::complex<double> z = lambda * h;
  // φ₁ by its series where e^z − 1 would cancel (error below z⁴/120 ≈ 1e-14 there).
  const std::complex<double> phi = std::abs(z) < 1e-3
                                       ? 1.0 + z * (1.0 / 2.0 + z * (1.0 / 6.0 + z / 24.0))
                                       : (std::exp(z) - 1.0) / z;
  return h * phi;
}

std::complex<double> LinearStateSpace::ModalBasis::ramp_increment(std::complex<double> lambda,
                                                                  double h) {
  const std::complex<double> z = lambda * h;
  // φ₂(z) = Σ_m z^m/(m + 2)! below |z| = 1, where (e^z − 1 − z)/z² would lose up to
  // ε/|z|² to cancellation; 17 terms (Horner from the highest) leave |z|¹⁷/19! < 1e-17.
  // From |z| = 1 on the quotient is fine: |e^z − 1 − z| ≥ e⁻¹ on the unit circle against
  // terms of at most e + 2, so its rounding stays near 10 ε.
  std::complex<double> phi = 0.0;
  if (std::abs(z) < 1.0) {
    double coefficient = 1.0;  // 1/(m + 2)! for m = 16
    for (int j = 2; j <= 18; ++j) coefficient /= j;
    for (int m = 16; m >= 0; --m) {
      phi = phi * z + coefficient;
      coefficient *= m + 2;
    }
  } else {
    phi = (std::exp(z) - 1.0 - z) / (z * z);
  }
  return h * h * phi;
}

Eigen::VectorXcd LinearStateSpace::ModalBasis::increments(double h) const {
  Eigen::VectorXcd out(values.size());
  for (Eigen::Index k = 0; k < values.size(); ++k) out[k] = increment(values[k], h);
  return out;
}

Eigen::VectorXcd LinearStateSpace::ModalBasis::ramp_increments(double h) const {
  Eigen::VectorXcd out(values.size());
  for (Eigen::Index k = 0; k < values.size(); ++k) out[k] = ramp_increment(values[k], h);
  return out;
}

ModalClock::ModalClock(const LinearStateSpace::ModalBasis& basis) {
  poles_.resize(static_cast<Eigen::Index>(basis.half.size()));
  for (size_t k = 0; k < basis.half.size(); ++k)
    poles_[static_cast<Eigen::Index>(k)] = basis.values[basis.half[k]];
  restart(false);
}

void ModalClock::restart(bool ramp) {
  ramp_ = ramp;
  offset_ = 0.0;
  exponential_ = Eigen::VectorXcd::Ones(poles_.size());
  integral_ = ramp_integral_ = Eigen::VectorXcd::Zero(poles_.size());
}

const ModalClock::Step& ModalClock::step(double delta) {
  for (const Step& cached : steps_)
    if (cached.delta == delta && (!ramp_ || cached.with_ramp)) return cached;
  Step fresh;
  fresh.delta = delta;
  fresh.with_ramp = ramp_;
  fresh.exponential.resize(poles_.size());
  fresh.integral.resize(poles_.size());
  fresh.ramp_integral.resize(poles_.size());
  for (Eigen::Index k = 0; k < poles_.size(); ++k) {
    fresh.exponential[k] = std::exp(poles_[k] * delta);
    fresh.integral[k] = LinearStateSpace::ModalBasis::increment(poles_[k], delta);
    fresh.ramp_integral[k] = ramp_ ? LinearStateSpace::ModalBasis::ramp_increment(poles_[k], delta)
                                   : std::complex<double>(NAN, NAN);
  }
  if (steps_.size() < 4) {
    steps_.push_back(std::move(fresh));
    return steps_.back();
  }
  Step& slot = steps_[next_slot_];
  next_slot_ = (next_slot_ + 1) % steps_.size();
  slot = std::move(fresh);
  return slot;
}

void ModalClock::advance_to(double offset) {
  const double delta = offset - offset_;
  if (delta == 0.0) return;
  const Step& s = step(delta);
  if (ramp_) ramp_integral_ += delta * integral_ + exponential_.cwiseProduct(s.ramp_integral);
  integral_ += exponential_.cwiseProduct(s.integral);
  exponential_ = exponential_.cwiseProduct(s.exponential);
  offset_ = offset;
}

}  // namespace emnet
