// Left eigenvector of the pencil (G + J_g) + s·C at a computed pole, for eigenvalue
// sensitivities (sensitivity.cpp) and the bi-orthogonal modal expansion (modal_reduction.cpp).
//
// y with yᴴ·(G + s·C) = 0, by two steps of inverse iteration on the equilibrated adjoint pencil
// (equilibration.hpp) (Ĝᵀ + conj(ŝ)·Ĉᵀ)·ŷ = ŷ_previous, from ŷ = 1, mapped back to physical
// rows: y = diag(r)·ŷ. The pole is exact to rounding, so the adjoint is singular to rounding and
// one step already amplifies the wanted direction by ~1/ε; the second cleans up. A pole
// repeated to rounding (a cluster of m poles) has no unique left vector: LeftEigenSolver gives
// m vectors from m different starts with one factorisation, which span the cluster's left
// space (to the cluster's width over its distance to the next pole), not the individual left
// vectors; a caller combines them by the bi-orthogonality matrix Wᵀ·C·V.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <complex>
#include <string>

#include "equilibration.hpp"

namespace emnet {

// The equilibrated adjoint pencil Ĝᵀ + conj(ŝ)·Ĉᵀ of one network, for left vectors at many
// poles: its pattern is the same at every pole, so the sparse LU's ordering is found once and
// each pole costs a numeric factorisation only.
class LeftEigenSolver {
 public:
  // `scaling`: equilibrate_pencil(g_matrix, c_matrix), once for all the poles asked about (at
  // large N the equilibration costs more than the inverse iteration). The matrices are copied
  // (scaled, transposed, complex).
  LeftEigenSolver(const Eigen::SparseMatrix<double>& g_matrix,
                  const Eigen::SparseMatrix<double>& c_matrix, const DiagonalScaling& scaling);
  // `count` left vectors at `pole` (1/s) as the columns of `left`, from different starts, the
  // first from ŷ = 1 (a simple pole's left vector for count = 1). `residual`: the worst
  // ‖(Ĝᵀ + conj(ŝ)Ĉᵀ)·ŷ‖ / (‖Ĝ‖₁ + |ŝ|·‖Ĉ‖₁) with ‖ŷ‖ = 1, on the equilibrated pencil
  // (unit-free). False, with `why`, when the adjoint cannot be factorised or the iteration gives
  // no finite vector.
  bool space(std::complex<double> pole, int count, Eigen::MatrixXcd& left, double& residual,
             std::string& why);

 private:
  using ComplexSparse = Eigen::SparseMatrix<std::complex<double>>;
  ComplexSparse adjoint_at(std::complex<double> s_hat) const;
  DiagonalScaling scaling_;
  ComplexSparse g_adjoint_, c_adjoint_;
  double scale_g_ = 0.0, scale_c_ = 0.0;  // ‖Ĝ‖₁, ‖Ĉ‖₁
  Eigen::SparseLU<ComplexSparse> lu_;
  bool analysed_ = false;
};

}  // namespace emnet
