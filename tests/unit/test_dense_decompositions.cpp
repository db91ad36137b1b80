// Left eigenvectors from the real Schur form (analysis/dense_decompositions.hpp). Reference: the
// definition mᵀ·w = λ·w, and the left–right bi-orthogonality w_jᵀ·v_k = 0 for λ_j ≠ λ_k.
// Tolerance: a backward-stable substitution leaves a residual of a few ε·‖m‖ per vector
// (n = 40: 1e-13 relative is 450 ε, with room for the eigenvalues' own rounding).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <complex>
#include <random>

#include "analysis/dense_decompositions.hpp"

namespace emnet {
namespace {

// A real 40×40 matrix with both real eigenvalues and complex pairs: a damped chain's state
// matrix [0 I; −K −C] (K tridiagonal, C light damping: pairs), with a few rows of random entries
// (real poles), from a fixed seed.
Eigen::MatrixXd test_matrix() {
  const int half = 20;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(half, half), c = Eigen::MatrixXd::Zero(half, half);
  for (int i = 0; i < half; ++i) {
    k(i, i) = 2.0 + 0.1 * i;
    if (i > 0) k(i, i - 1) = k(i - 1, i) = -1.0;
    c(i, i) = 0.02 + (i % 5 == 0 ? 3.0 : 0.0);  // some overdamped: real poles
  }
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(2 * half, 2 * half);
  m.topRightCorner(half, half) = Eigen::MatrixXd::Identity(half, half);
  m.bottomLeftCorner(half, half) = -k;
  m.bottomRightCorner(half, half) = -c;
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> uniform(-0.05, 0.05);
  for (int j = 0; j < 2 * half; ++j) m(3, j) += uniform(generator);
  return m;
}

TEST(DenseDecompositions, LeftVectorsFromTheSchurFormSatisfyTheDefinition) {
  const Eigen::MatrixXd m = test_matrix();
  const RealEigenDecomposition d = real_eigen_decomposition(m, true);
  ASSERT_TRUE(d.converged);
  ASSERT_EQ(d.left_vectors.cols(), m.cols());
  int pairs = 0, reals = 0;
  const Eigen::MatrixXcd mt = m.transpose().cast<std::complex<double>>();
  for (Eigen::Index k = 0; k < m.cols(); ++k) {
    (std::abs(d.values[k].imag()) > 0.0 ? pairs : reals) += 1;
    const Eigen::VectorXcd w = d.left_vectors.col(k);
    EXPECT_NEAR(w.norm(), 1.0, 1e-14);
    const double residual = (mt * w - d.values[k] * w).norm() / m.lpNorm<1>();
    EXPECT_LT(residual, 1e-13) << "eigenvalue " << d.values[k];
  }
  EXPECT_GT(pairs, 0);
  EXPECT_GT(reals, 0);
  // Bi-orthogonality against Eigen's right vectors, for eigenvalues well apart.
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index k = 0; k < m.cols(); ++k) {
      if (std::abs(d.values[j] - d.values[k]) < 1e-3 * std::abs(d.values[k])) continue;
      const std::complex<double> product = d.left_vectors.col(j).transpose() * d.vectors.col(k);
      EXPECT_LT(std::abs(product), 1e-10) << j << " " << k;
    }
}

// Without the request the left vectors are not formed (the right decomposition is Eigen's).
TEST(DenseDecompositions, LeftVectorsOnlyWhenAsked) {
  const RealEigenDecomposition d = real_eigen_decomposition(test_matrix());
  ASSERT_TRUE(d.converged);
  EXPECT_EQ(d.left_vectors.size(), 0);
}

}  // namespace
}  // namespace emnet
