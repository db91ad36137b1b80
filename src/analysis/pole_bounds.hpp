// First-order error bounds for computed poles of a pencil Â + s·Ê (equilibrated, unit-free).
//
// A computed pole ŝ with right vector x has the residual r = (Â + ŝÊ)·x, a backward error; the
// forward error is that times the pole's condition, which needs its left vector y
// (yᴴ·(Â + ŝÊ) = 0): to first order |δŝ| ≤ ‖y‖·‖r‖ / |yᴴ·Ê·x| against the exact pole of the
// stored pencil (Wilkinson; for pencils Tisseur, "Backward error and condition of polynomial
// eigenvalue problems", Linear Algebra Appl. 309 (2000) 339–361). Poles equal to within
// `group_width` (relative) have no individual left vectors (two equal DEA loops, a beam's
// Kelvin–Voigt relaxations at −1/τ); they are bounded together: with orthonormal bases X, Y of
// their right and left spaces and residuals R = (Â + ŝ_c·Ê)·X at the group's first pole ŝ_c,
// every exact pole of the group lies within ‖R‖_F·‖(Yᴴ·Ê·X)⁻¹‖₂ of ŝ_c (Bauer–Fike on the
// projected pencil), and a member's bound adds its distance to ŝ_c. Fewer independent vectors
// than poles (a defective group) has no such bound.
//
// r is evaluated in extended precision (long double, 64-bit mantissa) from the stored double
// entries, with its own rounding γ·‖(|Â| + |ŝ|·|Ê|)·|x|‖ added (γ = (k + 2)·2⁻⁶⁴, k the most
// entries of a row or column): evaluated in double, r is itself rounding noise of the size of
// the terms that cancel in it, which hides exactly the errors this bound is for (a damper
// τ/n across a tiny compliance n cancels nearly equal velocities). Left vectors come from the
// caller (the transposed pencil's eigenvectors, paired by pole) or, when those do not pair with
// a group, from inverse iteration on the adjoint pencil (left_eigenvector.hpp, one complex LU).
//
// A bound that cannot be formed (no left vector; Yᴴ·Ê·X singular: a defective pole) or that is
// not small (relative to |ŝ| above `largest_bound`, where first order no longer bounds) marks
// the pole unbounded, with the reason.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#include <string>
#include <vector>

namespace emnet {

struct PoleEstimate {
  std::complex<double> pole;  // ŝ
  Eigen::VectorXcd right;     // x
  double bound = 0.0;         // |δŝ|
  bool bounded = false;
  std::string reason;  // when !bounded
};

// An eigenpair of the transposed pencil Âᵀ + s·Êᵀ: left vectors of Â + s·Ê (y = conj(vector)),
// one of each conjugate pair as for the poles (the same convention: Im ≥ 0).
struct TransposedEigenpair {
  std::complex<double> pole;
  Eigen::VectorXcd vector;
};

// A repeated pole's vectors from an eigensolver can be nearly parallel (the dense solver's seven
// vectors of the fish fin's seven equal Kelvin–Voigt relaxations at −1/τ span fewer dimensions):
// for each group of poles within `group_width` whose right vectors are not independent, they
// are replaced by an orthonormal basis of the group's right space from inverse iteration at the
// group's first pole (LeftEigenSolver on the transposed pencil; one complex LU per such group).
void span_repeated_poles(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                         std::vector<PoleEstimate>& poles, double group_width = 1e-6);

void bound_poles(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                 const std::vector<TransposedEigenpair>& left_pairs,
                 std::vector<PoleEstimate>& poles, double group_width = 1e-6,
                 double largest_bound = 1e-3);

}  // namespace emnet
