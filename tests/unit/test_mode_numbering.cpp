// What a numbered mode is (kModeRule): an oscillatory pole pair with damping ratio below 1/√2.
//
// Reference: closed-form poles of two uncoupled mass–spring–damper oscillators,
// s = ω_n·(−ζ ± j·√(1 − ζ²)): one lightly damped (ζ = 0.02, f_n = 5 Hz), one overdamped
// pair below it (ζ = 0.99, f_n = 1 Hz). Tolerance 1e-9 relative: rounding of a 4-pole dense
// solve (the modal tests' residual level).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "fixtures.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using emnet::testing::kTwoPi;

// One oscillator on its own node: mass m, stiffness m·ω_n², damping 2ζ·m·ω_n.
void add_oscillator(Network& network, const std::string& name, double natural_hz, double zeta) {
  const double m = 1.0, w = kTwoPi * natural_hz;
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
  EXPECT_TRUE(result.status.ok()) << result.status.message;
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

// Arnoldi asked for 3 modes of a network whose poles nearest s = 0 are 5 overdamped pairs
// (ζ = 0.95, f_n = 0.5 … 0.9 Hz) below 3 resonances (ζ = 0.02 at 5, 7 and 9 Hz). Counting the
// overdamped pairs as modes, the request stopped at 6 poles (3 overdamped pairs) and numbered
// no resonance; the dense pencil gives the reference. Tolerance 1e-9 relative: both solves
// converge to rounding (the Arnoldi tolerance is 1e-12).
TEST(ModeNumbering, ArnoldiRequestGrowsPastOverdampedPairsToTheWantedModes) {
  Network network;
  for (int k = 0; k < 5; ++k)
    add_oscillator(network, "overdamped" + std::to_string(k), 0.5 + 0.1 * k, 0.95);
  for (double f : {5.0, 7.0, 9.0}) add_oscillator(network, "resonant" + std::to_string(f), f, 0.02);
  const System system = network.assemble();
  auto solve = [&](int dense_limit) {
    ModalOptions options;
    options.dense_limit = dense_limit;
    options.count = 3;
    return run_modes(system, Eigen::VectorXd::Zero(system.size()), options);
  };
  const ModalResult dense = solve(100000), arnoldi = solve(0);
  ASSERT_TRUE(dense.status.ok() && arnoldi.status.ok()) << arnoldi.status.message;
  EXPECT_EQ(arnoldi.method, Method::arnoldi);
  ASSERT_EQ(dense.modes.size(), 3u);
  ASSERT_GE(arnoldi.modes.size(), 3u);
  for (size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(arnoldi.modes[k].frequency_hz / dense.modes[k].frequency_hz, 1.0, 1e-9)
        << "mode " << k + 1;
}

// The modes of a scene about its operating point: dense (every pole) or Arnoldi (dense_limit
// 0), with `refinement` (2: every segment halved, the 2N mesh).
ModalResult scene_modes(const std::string& name, bool dense, int refinement = 1) {
  Scene scene = read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/" + name + ".toml");
  scene.beam.refinement = refinement;
  const Model model = prepare_model(scene);
  const System system = model.network.assemble();
  const OperatingPoint point = operating_point(system);
  EXPECT_TRUE(point.status.ok()) << name << ": " << point.status.message;
  ModalOptions options;
  options.count = 3;
  options.dense_limit = dense ? 100000 : 0;
  options.keep_vectors = false;
  const ModalResult result = run_modes(system, point.rest.operating_point, options);
  EXPECT_TRUE(result.status.ok()) << name << ": " << result.status.message;
  return result;
}

// On every shipped scene the first three modes are the same modes on the dense and the Arnoldi
// solver (to 1e-8: both converge to rounding of the same pencil) and on N and 2N (by index,
// within 5 %: the discretisation moves a mode by its N/2N difference, under 2 % on these
// meshes, while a mismatch (the tweezer's overdamped 27.3 Hz pair as "mode 2" against its
// 42.1 Hz mode) is off by 50 %).
TEST(ModeNumbering, SameModesDenseAndArnoldiAndOnNAnd2N) {
  for (const char* name :
       {"cantilever", "fishfin", "fishfin-clamp", "fishfin-films", "fishfin-measured",
        "fishfin-shear", "fishfin-water", "gripper-finger", "rc-dea", "tweezer-jaw"}) {
    const ModalResult dense = scene_modes(name, true);
    const ModalResult arnoldi = scene_modes(name, false);
    const ModalResult fine = scene_modes(name, true, 2);
    ASSERT_GE(dense.modes.size(), 3u) << name;
    ASSERT_GE(arnoldi.modes.size(), 3u) << name;
    ASSERT_GE(fine.modes.size(), 3u) << name;
    for (size_t k = 0; k < 3; ++k) {
      const double f = dense.modes[k].frequency_hz;
      EXPECT_NEAR(arnoldi.modes[k].frequency_hz / f, 1.0, 1e-8) << name << " mode " << k + 1;
      EXPECT_NEAR(fine.modes[k].frequency_hz / f, 1.0, 0.05) << name << " mode " << k + 1;
    }
  }
}

}  // namespace
}  // namespace emnet
