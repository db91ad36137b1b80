// AC by the pole–residue form of the small-signal state equation, for small networks.
//
// The linearised displacement form E·u' + A·u = f (displacement_form.hpp) reduced to the state
// equation x' = M·x + N·f (state_space.hpp), with M = V·Λ·V⁻¹ (every pole, a dense
// eigen-decomposition), gives for the phasor F of the sources at s = jω
//   X = V·diag(1/(s − λ_k))·V⁻¹·N·F,   U = U_x·X + U_f·F,   U' = s·U,
// and a probe p = α·U + β·U' (DisplacementForm::probe_rows) is
//   p(s) = Σ_k (a_k + s·b_k)/(s − λ_k) + (α + s·β)·U_f·F,
//   a_k = (α·U_x·V)_k·r_k,  b_k = (β·U_x·V)_k·r_k,  r = V⁻¹·N·F.
// This is not a truncation: with every pole it is the exact transfer function, and its only
// error is the rounding of the decomposition, which grows with κ(V) (the eigenvector basis's
// condition) and near a pole with the residue's size. Each frequency then costs O(poles) per
// probe instead of a sparse complex factorisation (fish fin N = 7: 28 poles, 1000 frequencies).
//
// The sweep is never taken on trust: run_ac compares it with the direct solve at the points
// where its rounding is largest (the response's peaks, the grid points nearest each lightly
// damped pole, the ends) and solves directly when they differ.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#include <string>
#include <vector>

#include "emnet/network/network.hpp"
#include "emnet/network/output.hpp"

namespace emnet {

struct PoleResidueSweep {
  bool applies = false;
  std::string why_not;  // when !applies: why the form does not apply (the direct solve is used)
  std::vector<std::vector<std::complex<double>>> values;  // [probe][frequency]
  std::vector<std::complex<double>> poles;                // λ_k [1/s]
  double basis_condition = 0.0;                           // κ₁(V)
};

// `probes` are linear (linearised about `operating_point`); `operating_point` is y at rest and
// `linearised_g_matrix` G + J_g there (linearised_g), as the direct solve has it.
PoleResidueSweep pole_residue_sweep(const System& system, const Eigen::VectorXd& operating_point,
                                    const Eigen::SparseMatrix<double>& linearised_g_matrix,
                                    const std::vector<double>& frequencies,
                                    const std::vector<Probe>& probes);

// Indices into `frequencies` where the pole–residue form is checked against the direct solve:
// both ends, each probe's largest |value|, and the points nearest the lightly damped poles in
// the band (the `pole_limit` least damped). Sorted, without repeats.
std::vector<size_t> pole_residue_check_points(const PoleResidueSweep& sweep,
                                              const std::vector<double>& frequencies,
                                              size_t pole_limit = 8);

}  // namespace emnet
