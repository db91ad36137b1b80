// A probe of a linear network under piecewise-linear sources, in modal coordinates: inside
// each interval between breakpoints an affine part plus a sum of exponentials. Shared by the exact
// periodic method (PeriodicSolver) and the reduced one (ReducedPeriodicSolver), which differ only
// in how they get the poles and the coefficients.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <optional>
#include <tuple>
#include <vector>

#include "emnet/analysis/periodic.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/network/network.hpp"

namespace emnet {

// |z| as √(Re² + Im²), without std::abs's guard against overflow (hypot): the series' terms are
// far from 1e±154, and a sweep takes millions of these (hypot was 11 % of the tweezer jaw's).
inline double modulus(std::complex<double> z) {
  return std::sqrt(std::norm(z));
}
// |z_k| of every entry, the same way.
inline Eigen::VectorXd moduli(const Eigen::VectorXcd& z) {
  return z.cwiseAbs2().cwiseSqrt();
}
// 1/z as z̄/|z|², without the library's complex division (its scaling against overflow and
// Annex G cases, a function call per division); the same bounds on |z| as modulus.
inline std::complex<double> reciprocal(std::complex<double> z) {
  return std::conj(z) / std::norm(z);
}

// p(t) = offset[i] + slope[i]·h + Re Σ_k coefficient[i]_k·e^{λ_k·h}, h = t − edges[i], for
// edges[i] ≤ t < edges[i+1]. The affine part comes from the sources' ramps (slope 0 where they
// are constant); it adds nothing to p'', so the curvature bounds of the extremum search hold as
// they are.
//
// The exact cascade (periodic_cascade.hpp) adds a forced part over further exponents μ_m, shared
// by every series and interval: + Re Σ_m (c₀ + c₁·h + c₂·h²)_m·e^{μ_m·h}, the polynomial's
// coefficients in the columns of forced[i] (one row per exponent). Its curvature has bounds of
// its own (periodic_series.cpp).
struct ExponentialSeries {
  using ForcedTerms = Eigen::Matrix<std::complex<double>, Eigen::Dynamic, 3>;
  std::vector<double> offset;
  std::vector<double> slope;  // as many as offset, or empty: all 0
  std::vector<Eigen::VectorXcd> coefficient;
  std::vector<ForcedTerms> forced;  // as many as offset, or empty: none
};

// A bound on |Σ_m (c₀ + c₁·h + c₂·h²)_m·e^{μ_m h}| over 0 ≤ h ≤ length (forced terms `c` on
// the exponents `mu`; an exponent with Re μ > 0, rounding of a sum of stable poles, taken at
// h = length).
double forced_bound(const ExponentialSeries::ForcedTerms& c, const Eigen::VectorXcd& mu,
                    double length);

// The system with its sources over one period of their periodic regime, or nullopt when [0, T)
// already is one. A periodic pulse with a delay stays at its low level before it, so the first
// period need not be a period of the drive the network settles to: a pulse reaching past the
// end of its period (the antagonistic drive's second DEA, delay T/2 and width T/2 − t_r, falls
// during [T, T + t_r)) is missing from [0, t_r) of the first period only. The periodic state is
// the long-time limit, so the periodic solvers take the sources shifted by k·T, the first
// multiple of T at or past every periodic pulse's delay (its delay becomes delay − k·T ≤ 0, and
// value(t) follows the pulse train from its past). Sources that are not periodic (dc, pwl, a
// single pulse) are kept as they are. With zero rise time no pulse reaches past its period and
// nothing changes.
std::optional<System> steady_period_system(const System& system, double period);

// 0, the breakpoints of `system` inside (0, period), and period: its intervals on which every
// source is affine (constant or a ramp).
std::vector<double> constant_intervals(const System& system, double period);

// The periodic state of ξ' = Λ·ξ + q₀,i + q₁,i·h, the forcing affine in each interval with the
// affine particular state ξ_p,i(h) = particular[i] + h·particular_slope[i] — with
// ξ_p' = Λ·ξ_p + q₀ + q₁·h, particular_slope = −Λ⁻¹·q₁ and particular = −Λ⁻¹·(q₀ −
// particular_slope) (particular_slope empty: every interval constant): ξ at the start of every
// interval, from one period from ξ = 0 (c) and ξ₀ = c/(1 − e^{ΛT}), each interval advancing ξ ↦
// ξ_p,i(h_i) + e^{Λh_i}·(ξ − ξ_p,i(0)). Coordinates with `fixed_at_zero` (a constraint's
// invariants) stay 0. The periodicity residual ‖ξ(T) − ξ₀‖/‖ξ₀‖ into `residual`. Failure: an
// undamped mode in exact resonance with the drive.
Status periodic_interval_starts(const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
                                const std::vector<Eigen::VectorXcd>& particular,
                                const std::vector<Eigen::VectorXcd>& particular_slope,
                                const std::vector<bool>& fixed_at_zero,
                                std::vector<Eigen::VectorXcd>& start_of, double& residual);

// The same for any particular state ξ_p,i (the cascade's is not affine): given at the start
// (particular_start[i]) and the end (particular_end[i]) of each interval, each interval advances
// ξ ↦ ξ_p,i(h_i) + e^{Λh_i}·(ξ − ξ_p,i(0)).
Status periodic_starts_from_particulars(const Eigen::VectorXcd& lambda,
                                        const std::vector<double>& edges,
                                        const std::vector<Eigen::VectorXcd>& particular_start,
                                        const std::vector<Eigen::VectorXcd>& particular_end,
                                        const std::vector<bool>& fixed_at_zero,
                                        std::vector<Eigen::VectorXcd>& start_of, double& residual);

// Samples every series at `samples` uniform times over [0, edges.back()) into result.times and
// result.values, and finds its global extremes into result.minimum, maximum and their times
// (curvature-bounded search between the samples, then Newton: see periodic.hpp).
// `forced_exponents`: the μ_m of the series' forced parts (none when empty).
void sample_periodic_series(const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
                            const std::vector<ExponentialSeries>& series, int samples,
                            PeriodicResult& result,
                            const Eigen::VectorXcd& forced_exponents = Eigen::VectorXcd());

// Extremes of every probe over one period from samples (times, values), the sampled ones
// refined by `refine(probe, lowest sample, highest sample)` → {(time, value) of the minimum,
// (time, value) of the maximum}.
template <class Refine>
void fill_extremes(PeriodicResult& result, const Refine& refine) {
  const size_t probes = result.values.size();
  result.minimum.assign(probes, 0.0);
  result.maximum.assign(probes, 0.0);
  result.minimum_time.assign(probes, 0.0);
  result.maximum_time.assign(probes, 0.0);
  for (size_t p = 0; p < probes; ++p) {
    const auto& v = result.values[p];
    if (v.empty()) continue;
    const size_t low = static_cast<size_t>(std::min_element(v.begin(), v.end()) - v.begin());
    const size_t high = static_cast<size_t>(std::max_element(v.begin(), v.end()) - v.begin());
    const std::array<std::pair<double, double>, 2> extremes = refine(p, low, high);
    std::tie(result.minimum_time[p], result.minimum[p]) = extremes[0];
    std::tie(result.maximum_time[p], result.maximum[p]) = extremes[1];
  }
}

}  // namespace emnet
