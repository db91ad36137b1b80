// Eigen's dense decompositions, instantiated once: see dense_decompositions.hpp.
#include "dense_decompositions.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <complex>
#include <limits>
#include <vector>

namespace emnet {

namespace {

// The singular values and the vectors `options` asked for of an Eigen SVD.
template <typename Result, typename Decomposition>
Result singular_value_decomposition(const Decomposition& svd, int options) {
  Result result;
  result.singular_values = svd.singularValues();
  if (options & (Eigen::ComputeThinU | Eigen::ComputeFullU)) result.u = svd.matrixU();
  if (options & (Eigen::ComputeThinV | Eigen::ComputeFullV)) result.v = svd.matrixV();
  return result;
}

// Eigen's EigenSolver with its real Schur form m = U·T·Uᵀ kept (its protected member).
class SchurKeepingEigenSolver : public Eigen::EigenSolver<Eigen::MatrixXd> {
 public:
  explicit SchurKeepingEigenSolver(const Eigen::MatrixXd& m) : EigenSolver(m, true) {}
  const Eigen::MatrixXd& schur_t() const { return m_realSchur.matrixT(); }
  const Eigen::MatrixXd& schur_u() const { return m_realSchur.matrixU(); }
};

using Complex = std::complex<double>;

// The left null vector (z₀, z₁) of the singular 2×2 block [[a, b], [c, d]] − λ·I: of the two
// candidates (c, −a) and (d, −b), the larger.
Eigen::Vector2cd block_left_null_vector(const Eigen::MatrixXd& t, Eigen::Index k, Complex lambda) {
  const Complex a = t(k, k) - lambda, b = t(k, k + 1), c = t(k + 1, k),
                d = t(k + 1, k + 1) - lambda;
  const Eigen::Vector2cd first(c, -a), second(d, -b);
  return first.squaredNorm() >= second.squaredNorm() ? first : second;
}

// z with zᵀ·(T − λ·I) = 0, z zero before λ's block starting at `start` (of size 1 or 2).
Eigen::VectorXcd schur_left_vector(const Eigen::MatrixXd& t, Eigen::Index start, Eigen::Index size,
                                   Complex lambda, double smallest_pivot) {
  const Eigen::Index n = t.rows();
  Eigen::VectorXcd z = Eigen::VectorXcd::Zero(n);
  if (size == 1)
    z[start] = 1.0;
  else
    z.segment<2>(start) = block_left_null_vector(t, start, lambda);
  auto raised = [&](Complex pivot) {
    return std::abs(pivot) < smallest_pivot ? Complex(smallest_pivot, 0.0) : pivot;
  };
  for (Eigen::Index j = start + size; j < n;) {
    const bool pair = j + 1 < n && t(j + 1, j) != 0.0;
    Complex r0 = 0.0, r1 = 0.0;  // Σ_{i<j} z_i·T(i, j), and for column j + 1
    for (Eigen::Index i = start; i < j; ++i) {
      r0 += z[i] * t(i, j);
      if (pair) r1 += z[i] * t(i, j + 1);
    }
    if (pair) {  // (z_j, z_{j+1})·B = −(r0, r1), B the block minus λ
      const Complex a = t(j, j) - lambda, b = t(j, j + 1), c = t(j + 1, j),
                    d = t(j + 1, j + 1) - lambda;
      const Complex determinant = raised(a * d - b * c);
      z[j] = (-r0 * d + r1 * c) / determinant;
      z[j + 1] = (r0 * b - r1 * a) / determinant;
    } else {
      z[j] = -r0 / raised(t(j, j) - lambda);
    }
    // Far from overflow (raised pivots can grow z by 1/ε a step): the direction is what counts.
    if (std::abs(z[j]) > 1e100 || (pair && std::abs(z[j + 1]) > 1e100)) z /= z.norm();
    j += pair ? 2 : 1;
  }
  return z;
}

// The left eigenvectors W (mᵀ·w_k = λ_k·w_k) from the real Schur form, unit columns. A 2×2
// block's second eigenvalue is the first's conjugate, and so is its vector (m is real); U is
// real, so U·Z is two real products.
Eigen::MatrixXcd left_eigenvectors(const SchurKeepingEigenSolver& solver) {
  const Eigen::MatrixXd& t = solver.schur_t();
  const Eigen::Index n = t.rows();
  const Eigen::VectorXcd& values = solver.eigenvalues();
  const double smallest_pivot =
      std::numeric_limits<double>::epsilon() * std::max(t.lpNorm<1>(), 1e-300);
  Eigen::MatrixXcd z = Eigen::MatrixXcd::Zero(n, n);  // a pair's second column stays 0
  std::vector<bool> conjugate_of_previous(static_cast<size_t>(n), false);
  for (Eigen::Index k = 0; k < n;) {
    const Eigen::Index size = k + 1 < n && t(k + 1, k) != 0.0 ? 2 : 1;
    z.col(k) = schur_left_vector(t, k, size, values[k], smallest_pivot);
    if (size == 2) conjugate_of_previous[static_cast<size_t>(k + 1)] = true;
    k += size;
  }
  const Eigen::MatrixXd& u = solver.schur_u();
  const Eigen::MatrixXd real_part = u * z.real(), imaginary_part = u * z.imag();
  Eigen::MatrixXcd w(n, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    if (conjugate_of_previous[static_cast<size_t>(k)]) {
      w.col(k) = w.col(k - 1).conjugate();
      continue;
    }
    w.col(k).real() = real_part.col(k);
    w.col(k).imag() = imaginary_part.col(k);
    w.col(k).normalize();
  }
  return w;
}

}  // namespace

RealSingularValueDecomposition divide_and_conquer_svd(const Eigen::MatrixXd& m, int options) {
  return singular_value_decomposition<RealSingularValueDecomposition>(
      Eigen::BDCSVD<Eigen::MatrixXd>(m, static_cast<unsigned int>(options)), options);
}

RealSingularValueDecomposition jacobi_svd(const Eigen::MatrixXd& m, int options) {
  return singular_value_decomposition<RealSingularValueDecomposition>(
      Eigen::JacobiSVD<Eigen::MatrixXd>(m, static_cast<unsigned int>(options)), options);
}

ComplexSingularValueDecomposition complex_jacobi_svd(const Eigen::MatrixXcd& m, int options) {
  return singular_value_decomposition<ComplexSingularValueDecomposition>(
      Eigen::JacobiSVD<Eigen::MatrixXcd>(m, static_cast<unsigned int>(options)), options);
}

RealEigenDecomposition real_eigen_decomposition(const Eigen::MatrixXd& m, bool left) {
  RealEigenDecomposition result;
  const SchurKeepingEigenSolver solver(m);
  result.converged = solver.info() == Eigen::Success;
  if (!result.converged) return result;
  result.values = solver.eigenvalues();
  result.vectors = solver.eigenvectors();
  if (left) result.left_vectors = left_eigenvectors(solver);
  return result;
}

}  // namespace emnet
