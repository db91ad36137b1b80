// Dense decompositions for the analyses (singular values, the eigenvalues of a real matrix),
// Eigen's templates instantiated once in dense_decompositions.cpp: inline, they made
// state_space.cpp and modal.cpp the slowest files of the build to compile, and four other
// analyses instantiated JacobiSVD or EigenSolver again.
//
// Each function is Eigen's decomposition with Eigen's options (Eigen::ComputeThinU,
// ComputeFullV, ...: which singular vectors to form), so the results are Eigen's, bit for bit;
// only the left eigenvectors, when asked for, are formed here from Eigen's real Schur form.
// Singular values are in decreasing order; a vector not asked for is an empty matrix.
#pragma once

#include <Eigen/Core>

namespace emnet {

/// A real matrix's singular values and the singular vectors asked for: m = U·diag(σ)·Vᵀ.
struct RealSingularValueDecomposition {
  Eigen::VectorXd singular_values;  ///< σ, decreasing
  Eigen::MatrixXd u, v;             ///< U and V, or empty when not asked for
};

/// A complex matrix's singular values and the singular vectors asked for: m = U·diag(σ)·Vᴴ.
struct ComplexSingularValueDecomposition {
  Eigen::VectorXd singular_values;  ///< σ, decreasing
  Eigen::MatrixXcd u, v;            ///< U and V, or empty when not asked for
};

/// Divide and conquer (Eigen::BDCSVD): the fast one for large matrices.
/// @param m        the matrix
/// @param options  Eigen's ComputeThinU, ComputeFullU, ComputeThinV, ComputeFullV, or'ed; 0 for
///                 the singular values alone
RealSingularValueDecomposition divide_and_conquer_svd(const Eigen::MatrixXd& m, int options);

/// Two-sided Jacobi (Eigen::JacobiSVD): the accurate one for small matrices and small singular
/// values.
/// @param m        the matrix
/// @param options  as for divide_and_conquer_svd
RealSingularValueDecomposition jacobi_svd(const Eigen::MatrixXd& m, int options);

/// Two-sided Jacobi of a complex matrix (Eigen::JacobiSVD).
/// @param m        the matrix
/// @param options  as for divide_and_conquer_svd
ComplexSingularValueDecomposition complex_jacobi_svd(const Eigen::MatrixXcd& m, int options);

/// A real square matrix's eigenvalues and eigenvectors: m·V = V·diag(λ), each column of V of unit
/// norm, complex pairs in consecutive entries.
struct RealEigenDecomposition {
  bool converged = false;    ///< Eigen's QR iteration converged; nothing else is set otherwise
  Eigen::VectorXcd values;   ///< λ
  Eigen::MatrixXcd vectors;  ///< V
  /// When asked for: W with Wᵀ·m = diag(λ)·Wᵀ (column k: mᵀ·w_k = λ_k·w_k), unit columns.
  Eigen::MatrixXcd left_vectors;
};

/// The eigen-decomposition of a real square matrix by the real Schur form (Eigen::EigenSolver),
/// and, when asked, its left eigenvectors from the same Schur form m = U·T·Uᵀ: zᵀ·(T − λ·I) = 0
/// by substitution forward from λ's diagonal block (a 2×2 block's left null vector to start,
/// 2×2 solves across the others, pivots below ε·‖T‖ raised to it as LAPACK's trevc does), and
/// w = U·z. That is O(n²) a vector against the second Schur form of mᵀ (~10 n³) it replaces.
/// @param m     the matrix
/// @param left  also the left eigenvectors
RealEigenDecomposition real_eigen_decomposition(const Eigen::MatrixXd& m, bool left = false);

}  // namespace emnet
