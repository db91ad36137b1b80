// What a numbered mode is (kModeRule): an oscillatory pole pair with damping ratio below 1/√2.
//
// Reference: closed-form poles of two uncoupled mass–spring–damper oscillators,
// s = ω_n·(−ζ ± j·√(1 − ζ²)): one lightly damped (ζ = 0.02, f_n = 5 Hz), one overdamped
// pair below it (ζ = 0.99, f_n = 1 Hz). Tolerance 1e-9 relative: rounding of a 4-pole dense
// solve (the modal tests' residual level).
#include <gtest/gtest.h>

#include <cmath>

#include "emnet/analysis/analysis.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/inductor.hpp"
#include "fixtures.hpp"

namespace emnet {
namespace {

constexpr double two_pi = 2 * M_PI;

// One oscillator on its own node: mass m, stiffness m·ω_n², damping 2ζ·m·ω_n.
void add_oscillator(Network& network, const std::string& name, double natural_hz, double zeta) {
  const double m = 1.0, w = two_pi * natural_hz;
  const NodeId v = network.add_node(name, Domain::translational, name);
  network.add<Capacitor>(name + ".m", v, ground, m);
  network.add<Inductor>(name + ".k", v, ground, 1.0 / (m * w * w), Domain::translational);
  network.add<Conductance>(name + ".c", v, ground, 2.0 * zeta * m * w);
}

ModalResult oscillator_poles(int dense_limit) {
  Network network;
  add_oscillator(network, "overdamped", 1.0, 0.99);
  add_oscillator(network, "resonant", 5.0, 0.02);
  const System system = network.assemble();
  ModalOptions options;
  options.dense_limit = dense_limit;
  options.count = 1;
  const ModalResult result = run_modes(system, Eigen::VectorXd::Zero(system.size()), options);
  EXPECT_TRUE(result.status.ok) << result.status.message;
  return result;
}

// Fails before the rule (the ζ = 0.99 pair at 0.14 Hz was mode 1); passes after.
TEST(ModeNumbering, OverdampedPairBelowTheResonanceIsListedApart) {
  const ModalResult result = oscillator_poles(100000);
  ASSERT_EQ(result.modes.size(), 1u);
  const double resonant_damped_hz = 5.0 * std::sqrt(1.0 - 0.02 * 0.02);
  EXPECT_NEAR(result.modes[0].frequency_hz / resonant_damped_hz, 1.0, 1e-9);
  EXPECT_NEAR(result.modes[0].damping_ratio, 0.02, 1e-9);
  ASSERT_EQ(result.overdamped_pairs.size(), 1u);
  EXPECT_NEAR(result.overdamped_pairs[0].frequency_hz / std::sqrt(1.0 - 0.99 * 0.99), 1.0, 1e-9);
  EXPECT_NEAR(result.overdamped_pairs[0].damping_ratio, 0.99, 1e-9);
  EXPECT_TRUE(result.real_poles.empty());
}

}  // namespace
}  // namespace emnet
