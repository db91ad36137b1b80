// The static operator of a linearised network (static.cpp): the s⁰ system of
// include/emnet/analysis/analysis.hpp ("static / operating point") factorised once by a sparse
// LU, for the AC sweep at f = 0 and the modal reduction's static correction. Private to the
// analyses, so that the public header holds no factorisation (and needs no <Eigen/SparseLU>).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <string>
#include <utility>
#include <vector>

#include "emnet/network/network.hpp"

namespace emnet {

/// The static operator of the linearised system, for reuse (AC at f = 0).
class StaticOperator {
 public:
  StaticOperator(const System& system, const Eigen::SparseMatrix<double>& linearised_g);
  /// Solves matrix()·z = rhs; false (with a reason) when the operator is singular.
  bool solve(const Eigen::VectorXcd& rhs, Eigen::VectorXcd& z, std::string& why) const;
  /// A right-hand side on a row divided by s is a constant velocity: no static state.
  bool excites_divided_rows(const Eigen::VectorXcd& rhs) const;
  const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }
  const std::vector<bool>& divided_rows() const { return divided_; }
  const std::vector<bool>& mechanical() const { return mechanical_; }
  bool factorised() const { return factorised_; }

 private:
  Eigen::SparseMatrix<double> matrix_;
  std::vector<bool> divided_;
  std::vector<bool> mechanical_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
  bool factorised_ = false;
};

// The s¹ and s² parts A₁, A₂ of the static form's operator A(s) = A₀ + s·A₁ + s²·A₂
// (A₀ = StaticOperator::matrix, on the same unknowns z): the modal reduction's Taylor series and
// the reduced cascade's exponents (modal_reduction.cpp).
std::pair<Eigen::SparseMatrix<double>, Eigen::SparseMatrix<double>> expansion_matrices(
    const System& system, const Eigen::SparseMatrix<double>& g_matrix,
    const StaticOperator& static_operator);

}  // namespace emnet
