// Diagonal equilibration of sparse matrices and matrix pencils, applied before every
// factorisation, SVD and eigen-decomposition whose rank or accuracy decisions depend on the
// size of entries.
//
// The network mixes units: a 100 µm silicon beam in SI has lumped masses of 1e-13 kg beside
// rotational compliances of 1e8 rad/(N·m), unit incidence entries and ohms. A threshold
// relative to the largest entry then mistakes the masses for zeros. Scaling rows (equations)
// and columns (unknowns) by powers of two changes no solution and no pole, only the rounding:
//
//   matrix:  Â = diag(r)·A·diag(c);       A·x = b  ⇔  Â·x̂ = diag(r)·b,  x = diag(c)·x̂.
//   pencil:  A + s·B  →  Â + ŝ·B̂,  Â = diag(r)·A·diag(c),  B̂ = ω₀·diag(r)·B·diag(c),  s = ω₀·ŝ
//            (ω₀ [1/s] also makes time dimensionless: t̂ = ω₀·t).
//
// r and c come from Ruiz's iteration (each sweep divides every row and column by the square
// root of its largest entry, so all become ≈ 1), on |A| + ω₀·|B| for a pencil; ω₀ is the ratio of
// the geometric means of the non-zero entries of |Â| and |B̂ / ω₀|. Both are invariant under a
// change of units: a micrometre and a metre beam give the same scaled problem (to rounding).
// Reference: D. Ruiz, "A scaling algorithm to equilibrate both rows and columns norms in
// matrices", RAL-TR-2001-034.
#pragma once

#include <Eigen/Sparse>

namespace emnet {

// ‖·‖₁ of a sparse matrix (largest column sum).
double sparse_one_norm(const Eigen::SparseMatrix<double>& m);

struct DiagonalScaling {
  Eigen::VectorXd row, column;  // powers of two; 1 on empty rows and columns
  double frequency = 1.0;       // ω₀ [1/s] of a pencil; 1 for a single matrix
};

DiagonalScaling equilibrate(const Eigen::SparseMatrix<double>& matrix);
DiagonalScaling equilibrate_pencil(const Eigen::SparseMatrix<double>& a,
                                   const Eigen::SparseMatrix<double>& b, double frequency = 0.0);

// diag(row)·matrix·diag(column)·factor.
Eigen::SparseMatrix<double> scaled(const Eigen::SparseMatrix<double>& matrix,
                                   const DiagonalScaling& scaling, double factor = 1.0);

}  // namespace emnet
