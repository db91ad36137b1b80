// Left eigenvector by inverse iteration on the adjoint pencil; see left_eigenvector.hpp.
#include "left_eigenvector.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>

namespace emnet {

LeftEigenSolver::LeftEigenSolver(const Eigen::SparseMatrix<double>& g_matrix,
                                 const Eigen::SparseMatrix<double>& c_matrix,
                                 const DiagonalScaling& scaling)
    : scaling_(scaling) {
  const Eigen::SparseMatrix<double> g_hat = scaled(g_matrix, scaling);
  const Eigen::SparseMatrix<double> c_hat = scaled(c_matrix, scaling, scaling.frequency);
  g_adjoint_ = ComplexSparse(g_hat.transpose().cast<std::complex<double>>());
  c_adjoint_ = ComplexSparse(c_hat.transpose().cast<std::complex<double>>());
  scale_g_ = sparse_one_norm(g_hat);
  scale_c_ = sparse_one_norm(c_hat);
}

LeftEigenSolver::ComplexSparse LeftEigenSolver::adjoint_at(std::complex<double> s_hat) const {
  ComplexSparse adjoint = g_adjoint_ + std::conj(s_hat) * c_adjoint_;
  adjoint.makeCompressed();
  return adjoint;
}

bool LeftEigenSolver::space(std::complex<double> pole, int count, Eigen::MatrixXcd& left,
                            double& residual, std::string& why) {
  const std::complex<double> s_hat = pole / scaling_.frequency;
  // The pencil is singular at the pole only to rounding; should the LU find an exact zero
  // pivot, a shift of 1e-12·|ŝ| changes ŷ by O(1e-12).
  for (double offset : {0.0, 1e-12, 1e-9}) {
    const ComplexSparse adjoint = adjoint_at(s_hat * (1.0 + offset));
    if (!analysed_) {
      lu_.analyzePattern(adjoint);
      analysed_ = true;
    }
    lu_.factorize(adjoint);
    if (lu_.info() == Eigen::Success) break;
  }
  if (lu_.info() != Eigen::Success) {
    why = "the adjoint pencil at the pole could not be factorised";
    return false;
  }
  const ComplexSparse exact_adjoint = adjoint_at(s_hat);
  const Eigen::Index n = g_adjoint_.rows();
  left.resize(n, count);
  residual = 0.0;
  const double scale = scale_g_ + std::abs(s_hat) * scale_c_;
  for (int column = 0; column < count; ++column) {
    // Start 0: all ones (the single-vector case); others: cos(0.7·(column + 1)·i + column),
    // deterministic and, for a cluster, independent of each other.
    Eigen::VectorXcd y_hat(n);
    for (Eigen::Index i = 0; i < n; ++i)
      y_hat[i] = column == 0 ? 1.0 : std::cos(0.7 * (column + 1) * static_cast<double>(i) + column);
    for (int step = 0; step < 2; ++step) {
      y_hat = lu_.solve(y_hat);
      const double norm = y_hat.norm();
      if (!std::isfinite(norm) || norm == 0.0) {
        why = "inverse iteration for the left eigenvector gave no finite vector";
        return false;
      }
      y_hat /= norm;
    }
    residual = std::max(residual, (exact_adjoint * y_hat).norm() / scale);
    left.col(column) = scaling_.row.cast<std::complex<double>>().cwiseProduct(y_hat);
  }
  return true;
}

}  // namespace emnet
