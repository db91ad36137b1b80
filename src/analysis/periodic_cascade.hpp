// The exact cascade: the periodic state of a network whose only nonlinearity is the DEAs' force
// F = k_F·u² (no back-coupling, small kinematics), used by PeriodicSolver.
//
// Such a network is its linear part E·u' + A·u = f(t) (the DEAs' capacitors and circuits, the
// beam) plus, per DEA j, the source d_j·u_j(t)² on the mechanical rows of its coupling
// (d_j = k_F·c, the face's elongation rate ẋ = c·y, dea.hpp). Where the DEA voltages do not see
// the beam (checked: no mode carries both a voltage and a DEA force), the stages follow one
// another: the linear network under the piecewise-linear sources gives each u_j exactly as
// (exponential_series.hpp) u(h) = o_i + s_i·h + Σ_k a_ik·e^{λ_k·h} (the sum over conjugate
// pairs is real), its square is again such a sum,
//   u² = (o + s·h)² + Σ_k 2·(o + s·h)·a_k·e^{λ_k h} + Σ_{k≤l} (2 − δ_kl)·a_k·a_l·e^{(λ_k+λ_l)h},
// i.e. Σ_m P_m(h)·e^{μ_m h} with polynomials P_m of degree ≤ 2 over the exponents μ = 0, λ_k,
// λ_k + λ_l of the poles k the voltages carry; and each mode ξ_k' = λ_k·ξ_k + Σ_j m_kj·u_j²
// (m_j = V⁻¹·N·d_j) has the particular state Σ_m Q_km(h)·e^{μ_m h} with
//   (μ_m − λ_k)·Q + Q' = Σ_j m_kj·P_jm   (Q of degree ≤ 2, solved from its top coefficient).
// The periodic state then follows from the particular states at each interval's ends as for
// the linear network, and every probe is a sum of exponentials and polynomial-times-exponentials
// whose extremes the curvature-bounded search finds (periodic_series.cpp). Exact to rounding,
// apart from two refusals: an exponent μ_m within 1e-7/T of a pole λ_k that it forces (the
// particular state's 1/(μ − λ) would cancel to rounding, and exact coincidence needs h·e^{λh}
// terms), and a free body that the force reaches.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "displacement_form.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/network/network.hpp"
#include "emnet/network/output.hpp"
#include "exponential_series.hpp"

namespace emnet {

// One DEA's force as a source of the linear part: d·u(t)² with u its voltage.
struct SquaredSource {
  std::string name;           // the DEA's
  Probe voltage;              // u = y[e+] − y[e−], a linear probe
  Eigen::VectorXd direction;  // d [N/V² per row]: k_F·c_k on the form's rows of the coupling
};

// The squared sources of `system`: one per DEA, in the order of its nonlinear elements; a failed
// Status saying why the network is not such a cascade (an element other than a DEA is
// nonlinear, a DEA has its back-coupling, …). The stages' independence is checked by
// PeriodicSolver on the modes.
Status cascade_sources(const System& system, const DisplacementForm& form,
                       std::vector<SquaredSource>& sources);

// Whether two systems' nonlinear elements are the same squared sources (the same DEAs, nodes and
// constants).
bool same_cascade(const std::vector<std::shared_ptr<const Element>>& a,
                  const std::vector<std::shared_ptr<const Element>>& b);

// Why `element` is not a squared source: nonlinear otherwise than by a DEA's force k_F·u²
// without back-coupling, the only nonlinearity `method` ("the exact cascade") takes.
Status not_a_squared_source(const Element& element, const std::string& method);

// A squared source's voltage u (element->squared_source's `voltage` terms) as a probe, under a
// name no scene can give.
Probe squared_voltage_probe(const std::string& element_name, const LinearTerms& voltage);

// The exponents of the squares: 0, then λ_k for each kept pole k, then λ_k + λ_l (k ≤ l).
struct SquareExponents {
  std::vector<Eigen::Index> kept;  // the poles the voltages carry
  Eigen::VectorXcd mu;
};

// The poles any of `voltages` carries above 1e-12 of its scale (max_i |o_i| + |s_i|·h_i +
// Σ_k |a_ik|) in any interval, and the exponents of their squares.
SquareExponents square_exponents(const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
                                 const std::vector<ExponentialSeries>& voltages);

// u(h)² per interval as Σ_m (c₀ + c₁·h + c₂·h²)_m·e^{μ_m h} on `exponents` (the formula above).
std::vector<ExponentialSeries::ForcedTerms> squared_terms(const ExponentialSeries& voltage,
                                                          const SquareExponents& exponents);

// The modes' particular states under the squared sources, per interval: Q (state_size × 3M, the
// polynomial coefficients of exponent m in columns 3m, 3m+1, 3m+2), and their values at the
// interval's start (Σ_m Q_km(0)) and end (Σ_m Q_km(h_i)·e^{μ_m h_i}).
struct ForcedModalResponse {
  std::vector<Eigen::MatrixXcd> coefficients;
  std::vector<Eigen::VectorXcd> start, end;
};

// The particular states (above) of ξ' = Λ·ξ + Σ_j modal_forcing.col(j)·u_j², `squares[j]` being
// u_j²'s terms per interval. Modes in `fixed_at_zero` stay 0 (a constraint's invariant; with
// `free_body`, a zero pole the force reaches fails).
Status forced_modal_response(
    const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
    const SquareExponents& exponents, const Eigen::MatrixXcd& modal_forcing,
    const std::vector<std::vector<ExponentialSeries::ForcedTerms>>& squares,
    const std::vector<bool>& fixed_at_zero, bool free_body, ForcedModalResponse& response);

}  // namespace emnet
