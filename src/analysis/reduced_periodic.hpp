// The pieces ReducedPeriodicSolver's two paths share (modal_reduction_sweeps.cpp for a linear
// network, reduced_cascade.cpp for a cascade): the inputs on each interval between switching
// edges, the modal coordinates' affine particular states under them, and a probe's series.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/network/network.hpp"
#include "exponential_series.hpp"
#include "static_operator.hpp"

namespace emnet {

// reduce_modal with the linearised G at `operating_point` and its StaticOperator made by the
// caller, who needs them again (the reduced cascade's truncated part).
ModalReduction reduce_modal(const System& system, const Eigen::VectorXd& operating_point,
                            const Eigen::SparseMatrix<double>& g_matrix,
                            const StaticOperator& static_operator,
                            const std::vector<Eigen::VectorXcd>& inputs,
                            const ReductionOptions& options);

// Each input (a waveform of the system's excitation) affine on each interval between `edges`:
// u_j = value[i][j] + h·slope[i][j] (slope 0 where it is constant; ramp[i]: some input ramps).
struct InputPieces {
  std::vector<std::vector<double>> value, slope;
  std::vector<bool> ramp;
  bool any_ramp() const;
};
InputPieces input_pieces(const System& system, const std::vector<int>& waveforms,
                         const std::vector<double>& edges);

// The affine particular state a_ik + h·b_ik of each modal coordinate q_k' = λ_k·q_k + Σ_j
// β(k, j)·u_j: b = −q₁/λ, a = −(q₀ − b)/λ for its forcing q = Σ_j β_kj·u_j
// (exponential_series.hpp). `slope` is left empty when no interval ramps.
void affine_particulars(const Eigen::VectorXcd& lambda, const Eigen::MatrixXcd& beta,
                        const InputPieces& inputs, std::vector<Eigen::VectorXcd>& particular,
                        std::vector<Eigen::VectorXcd>& slope);

// A probe's static correction of each of the first `inputs` inputs of `reduction`: Σ c·D_j[index]
// over its terms (real: the inputs are real sources).
std::vector<double> input_feed(const ModalReduction& reduction, const Probe& probe, size_t inputs);

// A probe p(h) = Σ_j feed_j·u_j(h) + Re Σ_k g_k·(a_ik + h·b_ik) + Re Σ_k g_k·c_ik·e^{λ_k h}, with
// c = homogeneous[i]: its series on every interval (`g` the probe's row of the modal
// coordinates, `feed` its static correction of each input).
ExponentialSeries affine_series(const Eigen::VectorXcd& g, const std::vector<double>& feed,
                                const InputPieces& inputs,
                                const std::vector<Eigen::VectorXcd>& particular,
                                const std::vector<Eigen::VectorXcd>& slope,
                                const std::vector<Eigen::VectorXcd>& homogeneous);

}  // namespace emnet
