// Left eigenvector by inverse iteration on the adjoint pencil; see left_eigenvector.hpp.
#include "left_eigenvector.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>

namespace emnet {

namespace {
using ComplexSparse = Eigen::SparseMatrix<std::complex<double>>;
}

bool left_eigenspace(const Eigen::SparseMatrix<double>& g_matrix,
                     const Eigen::SparseMatrix<double>& c_matrix, const DiagonalScaling& scaling,
                     std::complex<double> pole, int count, Eigen::MatrixXcd& left, double& residual,
                     std::string& why) {
  const Eigen::SparseMatrix<double> g_hat = scaled(g_matrix, scaling);
  const Eigen::SparseMatrix<double> c_hat = scaled(c_matrix, scaling, scaling.frequency);
  const std::complex<double> s_hat = pole / scaling.frequency;
  Eigen::SparseLU<ComplexSparse> lu;
  ComplexSparse adjoint;
  // The pencil is singular at the pole only to rounding; should the LU find an exact zero
  // pivot, a shift of 1e-12·|ŝ| changes ŷ by O(1e-12).
  for (double offset : {0.0, 1e-12, 1e-9}) {
    const std::complex<double> shift = s_hat * (1.0 + offset);
    adjoint = ComplexSparse(g_hat.transpose().cast<std::complex<double>>()) +
              std::conj(shift) * ComplexSparse(c_hat.transpose().cast<std::complex<double>>());
    adjoint.makeCompressed();
    lu.compute(adjoint);
    if (lu.info() == Eigen::Success) break;
  }
  if (lu.info() != Eigen::Success) {
    why = "the adjoint pencil at the pole could not be factorised";
    return false;
  }
  const ComplexSparse exact_adjoint =
      ComplexSparse(g_hat.transpose().cast<std::complex<double>>()) +
      std::conj(s_hat) * ComplexSparse(c_hat.transpose().cast<std::complex<double>>());
  const Eigen::Index n = g_matrix.rows();
  left.resize(n, count);
  residual = 0.0;
  const double scale = sparse_one_norm(g_hat) + std::abs(s_hat) * sparse_one_norm(c_hat);
  for (int column = 0; column < count; ++column) {
    // Start 0: all ones (the single-vector case); others: cos(0.7·(column + 1)·i + column),
    // deterministic and, for a cluster, independent of each other.
    Eigen::VectorXcd y_hat(n);
    for (Eigen::Index i = 0; i < n; ++i)
      y_hat[i] = column == 0 ? 1.0 : std::cos(0.7 * (column + 1) * static_cast<double>(i) + column);
    for (int step = 0; step < 2; ++step) {
      y_hat = lu.solve(y_hat);
      const double norm = y_hat.norm();
      if (!std::isfinite(norm) || norm == 0.0) {
        why = "inverse iteration for the left eigenvector gave no finite vector";
        return false;
      }
      y_hat /= norm;
    }
    residual = std::max(residual, (exact_adjoint * y_hat).norm() / scale);
    left.col(column) = scaling.row.cast<std::complex<double>>().cwiseProduct(y_hat);
  }
  return true;
}

bool left_eigenvector(const Eigen::SparseMatrix<double>& g_matrix,
                      const Eigen::SparseMatrix<double>& c_matrix, const DiagonalScaling& scaling,
                      std::complex<double> pole, Eigen::VectorXcd& left, double& residual,
                      std::string& why) {
  Eigen::MatrixXcd space;
  if (!left_eigenspace(g_matrix, c_matrix, scaling, pole, 1, space, residual, why)) return false;
  left = space.col(0);
  return true;
}

}  // namespace emnet
