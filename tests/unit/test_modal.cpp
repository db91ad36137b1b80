// Modal analysis of the cantilever network against the Euler–Bernoulli continuum.
//
// Reference (docs/model.md, The beam segment): f_n = (β_n L)²/(2π L²)·√(EI/ρA), β_n L
// = 1.875104, 4.694091, 7.854757. The lumped-mass network converges at second order in 1/N, so the
// error ratio between N = 7, 14 and 28 approaches 4; we accept [3.5, 4.5] (the next term of the
// expansion moves the ratio by O(1/N²) ≈ 2 % at N = 7). f1 at N = 7 must be within 1 %
// (docs/model.md: 0.9907 of the continuum value). Mode residuals are checked to 1e-9 (relative,
// rounding of a dense solve).
#include <gtest/gtest.h>

#include <cmath>

#include "emnet/scene/scene_reader.hpp"
#include "fixtures.hpp"

namespace emnet {
namespace {

constexpr double beta_l[] = {1.875104068711961, 4.694091132974175, 7.854757438237613};

double continuum_frequency(int mode, double length, double ei, double mass_per_length) {
  return beta_l[mode] * beta_l[mode] / (2 * M_PI * length * length) *
         std::sqrt(ei / mass_per_length);
}

std::vector<double> network_frequencies(int segments) {
  const Scene scene = testing::cantilever_scene(segments);
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  EXPECT_TRUE(rest.status.ok()) << rest.status.message;
  ModalOptions every_pole;  // the dense method, whatever the size: every pole of the chain
  every_pole.dense_limit = 100000;
  const ModalResult modes = run_modes(system, rest.operating_point, every_pole);
  EXPECT_TRUE(modes.status.ok()) << modes.status.message;
  EXPECT_TRUE(modes.complete);
  std::vector<double> f;
  for (const Mode& mode : modes.modes) {
    EXPECT_LT(mode.relative_residual, 1e-9);
    EXPECT_NEAR(mode.damping_ratio, 0.0, 1e-9);  // undamped network
    f.push_back(mode.frequency_hz);
  }
  return f;
}

TEST(CantileverModes, EveryPoleOfTheUndampedChainIsFound) {
  // N segments with one free translational mass per non-clamped node: N modes.
  for (int n : {1, 2, 7}) EXPECT_EQ(network_frequencies(n).size(), static_cast<size_t>(n));
}

TEST(CantileverModes, FirstFrequencyAtSevenSegmentsWithinOnePercent) {
  const auto f = network_frequencies(7);
  const double exact = continuum_frequency(0, 0.5, 2.0, 0.3);
  EXPECT_NEAR(f[0] / exact, 1.0, 0.01);
  EXPECT_NEAR(f[0] / exact, 0.9907, 0.0005);  // docs/model.md, mass lumping
}

TEST(CantileverModes, FirstThreeFrequenciesConvergeAtSecondOrder) {
  const auto f7 = network_frequencies(7), f14 = network_frequencies(14),
             f28 = network_frequencies(28);
  for (int mode = 0; mode < 3; ++mode) {
    const double exact = continuum_frequency(mode, 0.5, 2.0, 0.3);
    const double e7 = std::abs(f7[mode] - exact), e14 = std::abs(f14[mode] - exact),
                 e28 = std::abs(f28[mode] - exact);
    EXPECT_NEAR(e7 / e14, 4.0, 0.5) << "mode " << mode + 1;
    EXPECT_NEAR(e14 / e28, 4.0, 0.5) << "mode " << mode + 1;
    EXPECT_LT(e28 / exact, e7 / exact);
  }
}

TEST(CantileverModes, ArnoldiAgreesWithDense) {
  // Same system, both methods: the lowest poles must agree to rounding (1e-9 relative).
  const Model model = build_model(testing::cantilever_scene(40));
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  ModalOptions dense_options;
  dense_options.dense_limit = 100000;
  ModalOptions arnoldi_options;
  arnoldi_options.count = 6;
  arnoldi_options.dense_limit = 0;
  const ModalResult dense = run_modes(system, rest.operating_point, dense_options);
  const ModalResult arnoldi = run_modes(system, rest.operating_point, arnoldi_options);
  ASSERT_EQ(dense.method, Method::dense);
  ASSERT_EQ(arnoldi.method, Method::arnoldi);
  ASSERT_GE(arnoldi.modes.size(), 5u);
  for (size_t k = 0; k < 5; ++k)
    EXPECT_NEAR(arnoldi.modes[k].frequency_hz / dense.modes[k].frequency_hz, 1.0, 1e-9);
}

}  // namespace
}  // namespace emnet

namespace emnet {
namespace {

// Pinned–pinned beam: f_n = n²·π/(2L²)·√(EI/ρA) (closed form). The lumped-mass error is
// O(N⁻²); at N = 28 it measures 1e-7, 2e-6 and 9e-6 for n = 1..3, so the tolerance is 1e-4.
// Free–free beam: first elastic mode from β₁L = 4.730041; its lumping error at N = 28 is
// 0.39 %, so 5e-3; its rigid-body motions must come out as poles at s ≈ 0, not as garbage.
TEST(SupportedBeamModes, PinnedPinnedMatchesClosedForm) {
  Scene scene = testing::cantilever_scene(28);
  scene.beam.left = scene.beam.right = EndCondition::pinned;
  const System system = build_model(scene).network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok());
  const ModalResult modes = run_modes(system, rest.operating_point);
  ASSERT_TRUE(modes.status.ok());
  for (int n = 1; n <= 3; ++n) {
    const double exact = n * n * M_PI / (2 * 0.25) * std::sqrt(2.0 / 0.3);
    EXPECT_NEAR(modes.modes[static_cast<size_t>(n - 1)].frequency_hz / exact, 1.0, 1e-4) << n;
  }
}

TEST(SupportedBeamModes, FreeFreeHasRigidBodyPolesAndElasticModes) {
  Scene scene = testing::cantilever_scene(28);
  scene.beam.left = scene.beam.right = EndCondition::free;
  const System system = build_model(scene).network.assemble();
  const ModalResult modes = run_modes(system, Eigen::VectorXd::Zero(system.size()));
  ASSERT_TRUE(modes.status.ok()) << modes.status.message;
  const double exact = 4.730040745 * 4.730040745 / (2 * M_PI * 0.25) * std::sqrt(2.0 / 0.3);
  ASSERT_FALSE(modes.modes.empty());
  EXPECT_NEAR(modes.modes[0].frequency_hz / exact, 1.0, 5e-3);
  // Rigid-body motion: translation and rotation, reported as such (the pole s = 0, double for
  // each), and no pole near s = 0 among the modes and real poles (rounding of a Jordan block at
  // s = 0 made spurious poles ~1e-8·|s₁| there before it was projected out).
  EXPECT_EQ(modes.rigid_body_modes.size(), 2u);
  for (const Mode& pole : modes.real_poles)
    EXPECT_GT(std::abs(pole.pole), 1e-3 * 2 * M_PI * exact) << pole.pole;
  for (const Mode& mode : modes.modes) {
    EXPECT_GT(std::abs(mode.pole), 1e-3 * 2 * M_PI * exact) << mode.pole;
    EXPECT_TRUE(mode.error_bounded) << mode.unbounded_reason;
  }
}

// An undamped free–free beam has no real pole (reference: its poles are ±iω and the double
// s = 0 of each rigid-body motion). By Arnoldi the Jordan chains at s = 0 left, after rounding,
// a real "pole" of ±6e3 1/s with an error bound 1e4 to 1e5 times its size at N = 30 and 35 (one
// scaling) or 40 (another): such a computed eigenvalue cannot be told from s = 0 and is left out,
// with a note.
TEST(SupportedBeamModes, FreeFreeArnoldiReportsNoSpuriousRealPole) {
  for (int segments : {30, 35, 40}) {
    Scene scene = testing::cantilever_scene(segments);
    scene.beam.left = scene.beam.right = EndCondition::free;
    const System system = build_model(scene).network.assemble();
    const ModalResult modes = run_modes(system, Eigen::VectorXd::Zero(system.size()));
    ASSERT_TRUE(modes.status.ok()) << modes.status.message;
    EXPECT_EQ(modes.method, Method::arnoldi) << segments;
    EXPECT_EQ(modes.rigid_body_modes.size(), 2u) << segments;
    EXPECT_TRUE(modes.real_poles.empty()) << segments << ": " << modes.real_poles.front().pole;
    for (const Mode& mode : modes.modes) EXPECT_TRUE(mode.error_bounded) << segments;
  }
}

// Repeated real poles are not modes. With the loss factor 1e-5 the fish fin's seven Kelvin–Voigt
// dashpots relax at the same rate 1/τ = 2π·f_ref/η (f_ref = 6.385 Hz), a repeated pole that
// rounding splits into complex pairs ~1e-8·|s| apart (it came out as a 0.0071 Hz "mode").
// Reference: the undamped 7-segment chain has 7 modes (one per free mass, all below 1 kHz), and
// the dashpots' 7 poles are real at −1/τ (to 1e-6: the split of a double root, ~√ε).
TEST(FishFinModes, RepeatedKelvinVoigtPolesAreRealPoles) {
  const Scene scene = read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml",
                                 {"damping.loss_factor=1e-5", "drive.electrical_dynamics=false"});
  const System system = build_model(scene).network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok()) << rest.status.message;
  const ModalResult modes = run_modes(system, rest.operating_point);
  ASSERT_TRUE(modes.status.ok()) << modes.status.message;
  EXPECT_EQ(modes.modes.size(), 7u);
  for (const Mode& mode : modes.modes) EXPECT_LT(mode.natural_frequency_hz, 1e3);
  const double relaxation_rate = 2 * M_PI * 6.385 / 1e-5;
  EXPECT_EQ(modes.real_poles.size(), 7u);
  for (const Mode& pole : modes.real_poles) {
    EXPECT_EQ(pole.pole.imag(), 0.0);
    EXPECT_NEAR(-pole.pole.real() / relaxation_rate, 1.0, 1e-6);
  }
}

}  // namespace
}  // namespace emnet

namespace emnet {
namespace {

// The fish fin's damped first mode at large N. Its Kelvin–Voigt damping is τ·K exactly, so each
// continuum mode of the uniform cantilever has the pole s = −τω²/2 ± iω·√(1 − (τω/2)²): damping
// ratio ζ = τω/2 = π·τ·f and damped frequency f·√(1 − ζ²), f = (β₁L)²/(2πL²)·√(EI/ρA)
// (closed form; the DEAs' electrical loops do not couple back without back-coupling, so they
// leave the mechanical poles alone). The network's discretisation error is O(N⁻²) with the
// coefficient 0.46 measured at N = 7 (6.385 against 6.446 Hz): 5e-9 at N = 10 000, so the
// tolerance 1e-7 leaves a factor 20. Before the dampers were stamped as τ times the spring
// force's rate, rounding in τ/n·(v_a − v_b) gave 6.4430 Hz at N = 10 000 (2.7e-4) and 7.02 Hz at
// N = 30 000.
TEST(FishFinModes, DampedFirstModeAtLargeNMatchesTheContinuum) {
  const std::string fin = std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml";
  for (int segments : {10000, 30000}) {
    const Scene scene = read_scene(fin, {"beam.segments=" + std::to_string(segments)});
    const Model model = build_model(scene);  // the System refers to its elements
    const System system = model.network.assemble();
    const StaticResult rest = solve_static(system);
    ASSERT_TRUE(rest.status.ok()) << rest.status.message;
    ModalOptions options;
    options.count = 2;
    const ModalResult modes = run_modes(system, rest.operating_point, options);
    ASSERT_TRUE(modes.status.ok()) << modes.status.message;
    ASSERT_FALSE(modes.modes.empty());
    const double tau = scene.damping.effective_kelvin_voigt_time();
    const double f = continuum_frequency(0, scene.beam.length, scene.beam.bending_stiffness,
                                         scene.beam.mass_per_length);
    const double zeta = M_PI * tau * f;
    EXPECT_NEAR(modes.modes[0].frequency_hz / (f * std::sqrt(1 - zeta * zeta)), 1.0, 1e-7)
        << "N = " << segments;
    EXPECT_NEAR(modes.modes[0].damping_ratio / zeta, 1.0, 1e-7) << "N = " << segments;
  }
}

}  // namespace
}  // namespace emnet
