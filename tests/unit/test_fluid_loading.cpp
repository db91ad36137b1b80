// Fluid loading (emnet/model/fluid_loading.hpp, scene [environment]): Sader's hydrodynamic function
// against independent values and its classical limits, the loaded beam against the closed form,
// the fixed point at the loaded resonance, and the reader's checks of the environment table.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "cli_run.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/model/fluid_loading.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "fixtures.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using emnet::testing::kPi;
constexpr double kEulerGamma = 0.57721566490153286061;

struct HydrodynamicReference {
  double reynolds;
  std::complex<double> circular;     // Γ_circ, Sader 1998 Eq. (18)
  std::complex<double> rectangular;  // Γ = Ω·Γ_circ, Eqs. (20)–(21)
};

// Reference values computed independently with mpmath 1.3 (besselk at 30 significant digits)
// from the same formulas, printed to 12 (Γ_circ) and 10 (Γ) significant digits.
const HydrodynamicReference kReferences[] = {
    {1e-3, {233.539943332, 1068.92264242}, {212.1718223, 1018.733662}},
    {0.1, {11.7394085617, 23.8393161402}, {10.48487969, 21.82753122}},
    {1.0, {3.96801484714, 4.56657056633}, {3.733959493, 4.074610834}},
    {10.0, {1.90204270866, 1.08405007525}, {1.918318106, 0.9816219702}},
    {100.0, {1.28315159319, 0.302493335689}, {1.326272251, 0.2961017062}},
    {1e3, {1.08945341683, 0.0914315546972}, {1.117413862, 0.1006114832}},
    {1e4, {1.02828461986, 0.0284839177477}, {1.04204509, 0.03554598028}},
};

double relative_difference(std::complex<double> value, std::complex<double> reference) {
  return std::abs(value - reference) / std::abs(reference);
}

TEST(FluidLoading, CircularCylinderMatchesIndependentBesselValues) {
  // Tolerance 1e-10: the references carry 12 digits; the trapezoidal Bessel integrals are good
  // to ~1e-14.
  for (const auto& reference : kReferences)
    EXPECT_LT(relative_difference(circular_cylinder_hydrodynamic_function(reference.reynolds),
                                  reference.circular),
              1e-10)
        << "Re = " << reference.reynolds;
}

TEST(FluidLoading, RectangularBeamMatchesIndependentValues) {
  // Tolerance 1e-8: the references carry 10 digits. (Against Sader's numerical solution the
  // rational correction itself is accurate to 0.1 % for 1e-6 <= Re <= 1e4: that is the
  // method's accuracy, checked here is that the published coefficients are transcribed.)
  for (const auto& reference : kReferences)
    EXPECT_LT(relative_difference(rectangular_beam_hydrodynamic_function(reference.reynolds),
                                  reference.rectangular),
              1e-8)
        << "Re = " << reference.reynolds;
}

TEST(FluidLoading, CircularCylinderMatchesStokesLimitAtSmallReynolds) {
  // Re → 0: K₁(z) → 1/z, K₀(z) → −ln(z/2) − γ with z² = −i·Re, so
  // Γ_circ → 1 + 4/(z²·(−ln(z/2) − γ)) (Stokes' oscillating cylinder). The neglected terms are
  // O(z²·ln z) relative: ~1e-5 at Re = 1e-6; tolerance 1e-4.
  const double reynolds = 1e-6;
  const std::complex<double> i(0.0, 1.0);
  const std::complex<double> z = -i * std::sqrt(i * reynolds);
  const std::complex<double> limit = 1.0 + 4.0 / (z * z * (-std::log(z / 2.0) - kEulerGamma));
  EXPECT_LT(relative_difference(circular_cylinder_hydrodynamic_function(reynolds), limit), 1e-4);
}

TEST(FluidLoading, LargeReynoldsGivesThePotentialFlowAddedMass) {
  // Re → ∞: Γ_circ = 1 + 2√2·(1 + i)/√Re + O(1/Re) (K₁/K₀ = 1 + 1/(2z) + …); the O(1/Re) term
  // is 2/Re = 2e-6 at Re = 1e6: tolerance 5e-6.
  const double reynolds = 1e6;
  const std::complex<double> boundary_layer =
      2.0 * std::sqrt(2.0) * std::complex<double>(1.0, 1.0) / std::sqrt(reynolds);
  EXPECT_LT(std::abs(circular_cylinder_hydrodynamic_function(reynolds) - (1.0 + boundary_layer)),
            5e-6);
  // The plate's added mass tends to ρπb²/4 (the cylinder of diameter b): water, b = 25 mm at
  // 1 kHz is Re ≈ 1e6, where the boundary layer and Ω add 0.55 %: tolerance 1 %.
  const double density = 998.2, width = 0.025;
  const FluidLoading loading = rectangular_beam_fluid_loading(density, 1.002e-3, width, 1000.0);
  EXPECT_GT(loading.reynolds, 9e5);
  EXPECT_NEAR(loading.added_mass_per_length / (density * kPi * width * width / 4.0), 1.0, 0.01);
  EXPECT_NEAR(loading.hydrodynamic.real(), 1.0, 0.01);
}

TEST(FluidLoading, LoadingFollowsItsDefinition) {
  // m_a = (π/4)ρb²Γ_r, c_a = (π/4)ρb²ωΓ_i, Re = ρωb²/(4η): to rounding (1e-14).
  const double density = 998.2, viscosity = 1.002e-3, width = 0.025, frequency = 2.0;
  const FluidLoading loading = rectangular_beam_fluid_loading(density, viscosity, width, frequency);
  const double omega = 2.0 * kPi * frequency;
  const double section = kPi / 4.0 * density * width * width;
  EXPECT_NEAR(loading.reynolds / (density * omega * width * width / (4.0 * viscosity)), 1.0, 1e-14);
  const std::complex<double> gamma = rectangular_beam_hydrodynamic_function(loading.reynolds);
  EXPECT_NEAR(loading.added_mass_per_length / (section * gamma.real()), 1.0, 1e-14);
  EXPECT_NEAR(loading.damping_per_length / (section * omega * gamma.imag()), 1.0, 1e-14);
}

// ---------------------------------------------------------------------------------------------
// The loaded beam.

Scene cantilever_in_water(std::optional<double> frequency) {
  Scene scene = testing::cantilever_scene(20);
  scene.environment.fluid = Fluid::water;
  scene.environment.density = 998.2;
  scene.environment.dynamic_viscosity = 1.002e-3;
  scene.environment.width = 0.025;
  scene.environment.frequency = frequency;
  return scene;
}

std::vector<Mode> modes_of(const Model& model) {
  const System system = model.network.assemble();
  const ModalResult result = run_modes(system, Eigen::VectorXd::Zero(system.size()));
  EXPECT_TRUE(result.status.ok()) << result.status.message;
  return result.modes;
}

TEST(FluidLoading, AddedMassLowersEveryModeByTheClosedFormRatio) {
  // Added mass and fluid damping are lumped exactly like the beam's mass, so the fluid damping
  // is mass-proportional (C = α·M): every mode keeps its shape, its undamped frequency scales by
  // (1 + m_a/ρA)^(-1/2), |s| is that undamped frequency and ζ = α/(2ω). Exact up to the
  // eigensolver's rounding: tolerance 1e-10.
  const Scene vacuum = testing::cantilever_scene(20);
  const Model loaded = build_model(cantilever_in_water(10.0));
  ASSERT_TRUE(loaded.fluid.has_value());
  const FluidLoading& loading = loaded.fluid->loading;
  EXPECT_EQ(loaded.fluid->fixed_point_steps, 0);
  const double mass = vacuum.beam.mass_per_length;
  const double ratio = 1.0 / std::sqrt(1.0 + loading.added_mass_per_length / mass);
  const double alpha = loading.damping_per_length / (mass + loading.added_mass_per_length);
  const std::vector<Mode> bare = modes_of(build_model(vacuum));
  const std::vector<Mode> wet = modes_of(loaded);
  ASSERT_GE(bare.size(), 3u);
  ASSERT_GE(wet.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(wet[k].natural_frequency_hz / (bare[k].natural_frequency_hz * ratio), 1.0, 1e-10);
    const double omega = 2.0 * kPi * wet[k].natural_frequency_hz;
    EXPECT_NEAR(wet[k].damping_ratio / (alpha / (2.0 * omega)), 1.0, 1e-10);
  }
  // And against the continuum: f₁ = 1.875104²/(2πL²)·√(EI/(ρA + m_a)), with the 20-segment
  // lumped-mass error (0.9907 at 7 segments, O(N⁻²): ~0.1 % at 20): tolerance 0.3 %.
  const double length = vacuum.beam.length, stiffness = vacuum.beam.bending_stiffness;
  const double continuum = 1.875104 * 1.875104 / (2.0 * kPi * length * length) *
                           std::sqrt(stiffness / (mass + loading.added_mass_per_length));
  EXPECT_NEAR(wet[0].natural_frequency_hz / continuum, 1.0, 3e-3);
}

TEST(FluidLoading, HydrodynamicFunctionIsTakenAtTheLoadedFirstResonance) {
  // Without environment.frequency, Γ is evaluated at the loaded beam's first undamped
  // resonance: the fixed point stops at a relative change of 1e-10; tolerance 1e-9.
  const Model model = prepare_model(cantilever_in_water(std::nullopt));
  ASSERT_TRUE(model.fluid.has_value());
  EXPECT_GT(model.fluid->fixed_point_steps, 0);
  const std::vector<Mode> modes = modes_of(model);
  ASSERT_FALSE(modes.empty());
  EXPECT_NEAR(modes[0].natural_frequency_hz / model.fluid->loading.frequency, 1.0, 1e-9);
  EXPECT_LT(model.fluid->loading.frequency, model.fluid->vacuum_frequency);
}

TEST(FluidLoading, NoEnvironmentBuildsTheSameNetwork) {
  const Scene scene = testing::cantilever_scene(7);
  const Model model = build_model(scene);
  EXPECT_FALSE(model.fluid.has_value());
  Scene with_none = scene;
  with_none.environment.fluid = Fluid::none;
  with_none.environment.width = 0.025;
  EXPECT_EQ(build_model(with_none).network.elements().size(), model.network.elements().size());
}

// ---------------------------------------------------------------------------------------------
// Scene reader: the [environment] table.

const std::string kBeamScene = R"([scene]
name = "plate"

[beam]
length = "122.5 mm"
segments = 7
bending_stiffness = "2.2e-3 N*m^2"
mass_per_length = "73 g/m"
)";

std::optional<InputError> environment_error(const std::string& environment) {
  try {
    read_scene_text(kBeamScene + "\n[environment]\n" + environment, "x.toml");
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "expected an InputError";
  return std::nullopt;
}

TEST(SceneEnvironment, WaterTakesItsDefaultsAt20Celsius) {
  const Scene scene =
      read_scene_text(kBeamScene + "\n[environment]\nfluid = \"water\"\nwidth = \"25 mm\"\n", "x");
  EXPECT_EQ(scene.environment.fluid, Fluid::water);
  EXPECT_DOUBLE_EQ(scene.environment.density, 998.2);
  EXPECT_DOUBLE_EQ(scene.environment.dynamic_viscosity, 1.002e-3);
  EXPECT_DOUBLE_EQ(scene.environment.width, 0.025);
  EXPECT_FALSE(scene.environment.frequency.has_value());
  const Scene air = read_scene_text(
      kBeamScene +
          "\n[environment]\nfluid = \"air\"\nwidth = \"25 mm\"\ndensity = \"1.2 kg/m^3\"\n"
          "dynamic_viscosity = \"0.0181 mPa*s\"\nfrequency = \"6 Hz\"\n",
      "x");
  EXPECT_DOUBLE_EQ(air.environment.density, 1.2);
  EXPECT_NEAR(air.environment.dynamic_viscosity, 1.81e-5, 1e-20);
  EXPECT_DOUBLE_EQ(*air.environment.frequency, 6.0);
  EXPECT_EQ(read_scene_text(kBeamScene, "x").environment.fluid, Fluid::none);
}

TEST(SceneEnvironment, UnknownFluidNamesTheKey) {
  const auto error = environment_error("fluid = \"oil\"\nwidth = \"25 mm\"\n");
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->where(), "x.toml:11");
  EXPECT_EQ(error->key(), "environment.fluid");
  EXPECT_NE(std::string(error->what()).find("'oil'"), std::string::npos) << error->what();
}

TEST(SceneEnvironment, RejectsUnknownKeysMissingWidthAndUnusedValues) {
  auto error = environment_error("fluid = \"water\"\nwidht = \"25 mm\"\n");
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->key(), "environment.widht");
  EXPECT_NE(std::string(error->what()).find("environment.width"), std::string::npos);
  error = environment_error("fluid = \"water\"\n");
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->key(), "environment.width");
  error = environment_error("width = \"25 mm\"\n");  // fluid defaults to none
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->key(), "environment.width");
  error = environment_error("fluid = \"water\"\nwidth = \"25 mm\"\ndensity = \"998 kg\"\n");
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->key(), "environment.density");
}

TEST(SceneEnvironment, CommandLineUnknownFluidExitsWithTwo) {
  const std::string path = ::testing::TempDir() + "emnet_fluid_oil.toml";
  {
    std::ofstream file(path);
    file << kBeamScene << "\n[environment]\nfluid = \"oil\"\nwidth = \"25 mm\"\n";
  }
  const auto run = testing::run_emnet("modes " + path);
  std::remove(path.c_str());
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("emnet_fluid_oil.toml:11"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("environment.fluid"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace emnet
