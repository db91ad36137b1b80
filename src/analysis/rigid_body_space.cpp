// Rigid-body space of a pencil by rank-revealing sparse QR: see rigid_body_space.hpp.
#include "rigid_body_space.hpp"

#include <Eigen/SPQRSupport>
#include <algorithm>

#include "dense_decompositions.hpp"

namespace emnet {

namespace {

using Qr = Eigen::SPQR<Eigen::SparseMatrix<double>>;

// null(M) from the QR of Mᵀ: Mᵀ·P = Q·R of rank r, and the last n − r columns of Q span null(M).
Eigen::MatrixXd null_space_from_transpose_qr(const Qr& qr, Eigen::Index n) {
  const Eigen::Index rank = qr.rank();
  Eigen::MatrixXd basis(n, n - rank);
  for (Eigen::Index j = rank; j < n; ++j) {
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(n);
    unit[j] = 1.0;
    basis.col(j - rank) = qr.matrixQ() * unit;
  }
  return basis;
}

}  // namespace

RigidBodySpace rigid_body_space(const Eigen::SparseMatrix<double>& a,
                                const Eigen::SparseMatrix<double>& e) {
  RigidBodySpace space;
  const Eigen::Index n = a.rows();
  Eigen::SparseMatrix<double> a_compressed = a, a_transposed = a.transpose();
  a_compressed.makeCompressed();
  a_transposed.makeCompressed();
  Qr qr_of_a, qr_of_transpose;
  qr_of_a.compute(a_compressed);
  qr_of_transpose.compute(a_transposed);
  if (qr_of_a.info() != Eigen::Success || qr_of_transpose.info() != Eigen::Success) {
    space.failure = "the rank-revealing QR of the static operator failed";
    return space;
  }
  const Eigen::MatrixXd z0 = null_space_from_transpose_qr(qr_of_transpose, n);  // Â·z0 = 0
  const Eigen::MatrixXd w0 = null_space_from_transpose_qr(qr_of_a, n);          // Âᵀ·w0 = 0
  if (z0.cols() == 0 || z0.cols() != w0.cols()) {
    space.failure = "the static operator's right and left null spaces differ in size (" +
                    std::to_string(z0.cols()) + " and " + std::to_string(w0.cols()) + ")";
    return space;
  }
  // Semisimple part: the directions where W0ᵀ·Ê·Z0 is regular (a motion damped to ground);
  // the others start Jordan chains.
  const RealSingularValueDecomposition svd =
      jacobi_svd(w0.transpose() * (e * z0), Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd& values = svd.singular_values;
  const double largest = std::max(values.size() > 0 ? values[0] : 0.0, 1.0);
  Eigen::Index semisimple = 0;
  while (semisimple < values.size() && values[semisimple] > 1e-8 * largest) ++semisimple;
  const Eigen::Index chains = z0.cols() - semisimple;
  Eigen::MatrixXd right(n, z0.cols() + chains), left(n, z0.cols() + chains);
  right.leftCols(z0.cols()) = z0 * svd.v;
  left.leftCols(z0.cols()) = w0 * svd.u;
  const Eigen::SparseMatrix<double> e_transposed = e.transpose();
  for (Eigen::Index k = 0; k < chains; ++k) {
    const Eigen::VectorXd rhs_right = -(e * right.col(semisimple + k));
    const Eigen::VectorXd rhs_left = -(e_transposed * left.col(semisimple + k));
    const Eigen::VectorXd next_right = qr_of_a.solve(rhs_right);
    const Eigen::VectorXd next_left = qr_of_transpose.solve(rhs_left);
    if ((a * next_right - rhs_right).norm() > 1e-8 * rhs_right.norm() ||
        (a_transposed * next_left - rhs_left).norm() > 1e-8 * rhs_left.norm()) {
      space.failure = "a Jordan chain of the pole s = 0 could not be continued";
      return space;
    }
    right.col(z0.cols() + k) = next_right;
    left.col(z0.cols() + k) = next_left;
  }
  const Eigen::MatrixXd coupling = left.transpose() * (e * right);
  const Eigen::FullPivLU<Eigen::MatrixXd> coupling_lu(coupling);
  if (!coupling_lu.isInvertible()) {
    space.failure =
        "the left and right bases of the pole s = 0 do not pair (a Jordan chain longer than a "
        "displacement and a velocity)";
    return space;
  }
  space.null_vectors = z0;
  space.right = right;
  space.left = left;
  space.projector_left = coupling_lu.solve(left.transpose() * e).transpose();
  // Transposed pencil: V ↔ W, Ê ↔ Êᵀ, K ↔ Kᵀ.
  const Eigen::FullPivLU<Eigen::MatrixXd> transposed_coupling_lu(coupling.transpose());
  space.transposed_projector_left =
      transposed_coupling_lu.solve(right.transpose() * e_transposed).transpose();
  return space;
}

}  // namespace emnet
