// A probe of a linear network under piecewise-constant sources, in modal coordinates: inside
// each constant interval a sum of exponentials. Shared by the exact periodic method
// (PeriodicSolver) and the reduced one (ReducedPeriodicSolver), which differ only in how they
// get the poles and the coefficients.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "emnet/analysis/periodic.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/network/network.hpp"

namespace emnet {

// p(t) = offset[i] + Re Σ_k coefficient[i]_k·e^{λ_k·(t − edges[i])} for edges[i] ≤ t < edges[i+1].
struct ExponentialSeries {
  std::vector<double> offset;
  std::vector<Eigen::VectorXcd> coefficient;
};

// 0, the switching instants of `system` inside (0, period), and period: its constant intervals.
std::vector<double> constant_intervals(const System& system, double period);

// The periodic state of ξ' = Λ·ξ + forcing, the forcing constant in each interval with
// particular state particular[i] (ξ_p,i = −Λ⁻¹·forcing_i): ξ at the start of every interval,
// from one period from ξ = 0 (c) and ξ₀ = c/(1 − e^{ΛT}). Coordinates with `fixed_at_zero`
// (a constraint's invariants) stay 0. The periodicity residual ‖ξ(T) − ξ₀‖/‖ξ₀‖ into
// `residual`. Failure: an undamped mode in exact resonance with the drive.
Status periodic_interval_starts(const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
                                const std::vector<Eigen::VectorXcd>& particular,
                                const std::vector<bool>& fixed_at_zero,
                                std::vector<Eigen::VectorXcd>& start_of, double& residual);

// Samples every series at `samples` uniform times over [0, edges.back()) into result.times and
// result.values, and finds its global extremes into result.minimum, maximum and their times
// (curvature-bounded search between the samples, then Newton: see periodic.hpp).
void sample_periodic_series(const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
                            const std::vector<ExponentialSeries>& series, int samples,
                            PeriodicResult& result);

}  // namespace emnet
