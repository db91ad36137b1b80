// The planar elastica of a cantilever by shooting, a reference for the large-deflection tests.
//
// A cantilever of length 1 and bending stiffness 1, clamped at s = 0 (ψ = 0) and loaded at its
// free tip by a dead force (P_x, P_y): EI·ψ'' = −P_y·cos ψ + P_x·sin ψ with ψ'(1) = 0 (no tip
// moment); x' = cos ψ, y' = sin ψ. The root curvature ψ'(0) is found by bisection on ψ'(1) = 0
// over [0, 2·(|P_x| + |P_y|)], where ψ'(1) grows with it for the loads the tests use; each trial
// is integrated by classical Runge-Kutta in 20 000 steps (global error of order 1e-16 at these
// curvatures).
#pragma once

#include <array>
#include <cmath>

namespace emnet::testing {

/// The tip of the elastica (see above).
struct ElasticaTip {
  double x = 0.0, y = 0.0;  ///< along and across the undeformed beam, in units of its length
  double rotation = 0.0;    ///< ψ at the tip [rad]
};

inline ElasticaTip elastica_by_shooting(double force_x, double force_y) {
  constexpr int steps = 20000;
  constexpr double h = 1.0 / steps;
  ElasticaTip tip;
  auto integrate = [&](double curvature) {
    std::array<double, 4> state = {0.0, curvature, 0.0, 0.0};  // ψ, ψ', x, y
    auto rate = [&](const std::array<double, 4>& s) {
      return std::array<double, 4>{s[1], -force_y * std::cos(s[0]) + force_x * std::sin(s[0]),
                                   std::cos(s[0]), std::sin(s[0])};
    };
    for (int i = 0; i < steps; ++i) {
      std::array<double, 4> k1 = rate(state), k2, k3, k4, mid;
      for (int j = 0; j < 4; ++j) mid[j] = state[j] + 0.5 * h * k1[j];
      k2 = rate(mid);
      for (int j = 0; j < 4; ++j) mid[j] = state[j] + 0.5 * h * k2[j];
      k3 = rate(mid);
      for (int j = 0; j < 4; ++j) mid[j] = state[j] + h * k3[j];
      k4 = rate(mid);
      for (int j = 0; j < 4; ++j) state[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
    }
    tip = {state[2], state[3], state[0]};
    return state[1];  // ψ'(1)
  };
  double low = 0.0, high = 2.0 * (std::abs(force_x) + std::abs(force_y));
  for (int i = 0; i < 80; ++i) {
    const double middle = 0.5 * (low + high);
    (integrate(middle) < 0.0 ? low : high) = middle;
  }
  integrate(0.5 * (low + high));
  return tip;
}

}  // namespace emnet::testing
