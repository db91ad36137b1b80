// Eigenvalue sensitivities (include/emnet/studies/sensitivity.hpp) against closed forms and finite
// differences of the poles.
//
// Closed form: the undamped lumped cantilever has f ∝ √(EI/ρA)/L² for any N (stiffnesses
// ∝ EI/l³, masses ∝ ρA·l), so the normalised sensitivities are +½ (EI), −½ (ρA), −2 (L) for every
// mode. The analytic derivative is exact up to the matrices' central difference, whose rounding is
// ε/δ ≈ 2e-10 relative (δ = 1e-6), times the eigenvalue's condition: 1e-8 is the tolerance.
//
// Reference: the poles re-computed at p·(1 ± h), h = 1e-4 and 2e-4. The test asks the
// analytic-minus-FD difference to be within 3× the FD's own estimated error (Richardson
// truncation + rounding of the poles) plus the analytic part's 1e-8.
//
// Components ([[section]], [[mass]], [[spring]], Timoshenko shear): the sensitivity of f1 to a
// tip mass and to an elastic clamp's rotational stiffness against a central difference of the
// network's own f1, computed here (set_parameter, run_modes) at p·(1 ± h), h = 1e-4. Its
// truncation error is bounded by Richardson's |D(2h) − D(h)|/3 and its rounding by
// 100ε·f/(2h·p) (eigenvalues to ~100ε relative); the analytic value must agree within 3× that
// plus 1e-8 relative (the matrices' difference, as above).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/sensitivity.hpp"
#include "fixtures.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using emnet::testing::kFishfin;

TEST(Sensitivity, UndampedCantileverScalesExactlyLikeTheContinuum) {
  const Scene scene = testing::cantilever_scene(7);
  SensitivityOptions options;
  options.modes = 7;
  const SensitivityResult result = run_sensitivity(
      scene, {"beam.bending_stiffness", "beam.mass_per_length", "beam.length"}, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.modes.size(), 7u);
  EXPECT_LT(result.left_vector_residual, 1e-12);
  const double expected[] = {0.5, -0.5, -2.0};
  ASSERT_EQ(result.parameters.size(), 3u);
  for (size_t p = 0; p < 3; ++p)
    for (size_t k = 0; k < result.modes.size(); ++k) {
      const ModeSensitivity& s = result.parameters[p].modes[k];
      EXPECT_NEAR(s.normalised, expected[p], 1e-8)
          << result.parameters[p].parameter.key << " mode " << k + 1;
      EXPECT_NEAR(s.normalised_natural, expected[p], 1e-8);
      EXPECT_NEAR(s.pole_derivative.real(), 0.0, 1e-8 * std::abs(result.modes[k].pole));
    }
}

TEST(Sensitivity, FishFinAnalyticMatchesFiniteDifferencesForEveryParameter) {
  const Scene scene = read_scene(kFishfin);
  SensitivityOptions options;
  options.modes = 3;
  options.check = true;
  const SensitivityResult result = run_sensitivity(scene, {}, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.modes.size(), 3u);
  EXPECT_LT(result.left_vector_residual, 1e-12);
  // Beam, damping and the two DEAs' six parameters each, and the drive voltage.
  EXPECT_EQ(result.parameters.size(), 3u + 2u + 12u + 1u);
  for (const auto& parameter : result.parameters)
    for (size_t k = 0; k < parameter.modes.size(); ++k) {
      const ModeSensitivity& s = parameter.modes[k];
      EXPECT_LE(s.check_difference, 3.0 * s.check_error_estimate + 1e-8)
          << parameter.parameter.key << " mode " << k + 1 << ": analytic " << s.pole_derivative
          << ", FD " << s.finite_difference_pole_derivative;
      EXPECT_LT(s.check_error_estimate, 1e-5) << parameter.parameter.key;
    }
  // The first mode of the damped fin still scales nearly as the undamped beam.
  EXPECT_NEAR(result.parameters[0].modes[0].normalised, -2.0, 0.01);
}

TEST(Sensitivity, UnknownAndZeroParametersAreInputErrors) {
  const Scene scene = read_scene(kFishfin);
  EXPECT_THROW(find_scene_parameter(scene, "beam.colour"), InputError);
  EXPECT_THROW(find_scene_parameter(scene, "dea[C].lever_arm"), InputError);
  EXPECT_THROW(find_scene_parameter(scene, "beam.rotary_inertia_per_length"), InputError);
  EXPECT_EQ(find_scene_parameter(scene, "dea.B.lever_arm").key, "dea[B].lever_arm");
  EXPECT_EQ(find_scene_parameter(scene, "dea.0.lever_arm").key, "dea[A].lever_arm");
}

// The parameters come from the parameter table's sensitivity keys; on the fish fin they are the
// list `emnet sensitivity` printed before there was a table (docs/commands.md, sensitivity), in its
// order and with its units: the beam, the loss factor pair, six per DEA and the drive voltage.
TEST(Sensitivity, FishFinParametersAreTheListPrintedBeforeTheTable) {
  const Scene scene = read_scene(kFishfin);
  std::vector<std::string> expected = {"beam.length m", "beam.bending_stiffness N*m^2",
                                       "beam.mass_per_length kg/m", "damping.loss_factor ",
                                       "damping.loss_factor_frequency Hz"};
  for (const char* dea : {"A", "B"})
    for (const char* key : {"lever_arm m", "relative_permittivity ", "dielectric_thickness m",
                            "force_thickness m", "electrode_width m", "electrode_resistance Ohm"})
      expected.push_back(std::string("dea[") + dea + "]." + key);
  expected.push_back("drive.voltage V");
  std::vector<std::string> listed;
  for (const SceneParameter& parameter : scene_parameters(scene))
    listed.push_back(parameter.key + " " + parameter.unit);
  EXPECT_EQ(listed, expected);
  // Without a loss factor the Kelvin-Voigt time takes its place (the reader allows one of the
  // two); zero, it is not listed, but it is found by name (and refused as a zero step).
  Scene kelvin_voigt = scene;
  kelvin_voigt.damping.loss_factor.reset();
  kelvin_voigt.damping.loss_factor_frequency.reset();
  kelvin_voigt.damping.kelvin_voigt_time = 1e-3;
  EXPECT_EQ(scene_parameters(kelvin_voigt)[3].key, "damping.kelvin_voigt_time");
  EXPECT_THROW(find_scene_parameter(scene, "damping.kelvin_voigt_time"), InputError);
}

// The damped frequency of mode 1 of `scene`.
double first_mode_hz(const Scene& scene) {
  const Model model = prepare_model(scene);
  const System system = model.network.assemble();
  const OperatingPoint point = operating_point(system);
  EXPECT_TRUE(point.status.ok()) << point.status.message;
  ModalOptions options;
  options.keep_vectors = false;
  const ModalResult modes = run_modes(system, point.rest.operating_point, options);
  EXPECT_TRUE(modes.status.ok() && !modes.modes.empty()) << modes.status.message;
  return modes.modes.empty() ? 0.0 : modes.modes[0].frequency_hz;
}

// df1/dp of `key` from run_sensitivity against the central difference of f1 described above.
void expect_first_mode_derivative_matches_differences(const Scene& scene, const std::string& key) {
  SensitivityOptions options;
  options.modes = 1;
  const SensitivityResult result = run_sensitivity(scene, {key}, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.parameters.size(), 1u);
  const double analytic = result.parameters[0].modes[0].frequency_derivative;
  const double p = get_parameter(scene, key);
  const double f1 = first_mode_hz(scene);
  auto difference = [&](double h) {
    Scene up = scene, down = scene;
    set_parameter(up, key, p * (1 + h));
    set_parameter(down, key, p * (1 - h));
    return (first_mode_hz(up) - first_mode_hz(down)) / (2 * h * p);
  };
  const double h = 1e-4;
  const double d_h = difference(h), d_2h = difference(2 * h);
  const double truncation = std::abs(d_2h - d_h) / 3;
  const double rounding = 100 * std::numeric_limits<double>::epsilon() * f1 / (2 * h * p);
  EXPECT_NEAR(analytic, d_h, 3 * (truncation + rounding) + 1e-8 * std::abs(analytic))
      << key << ": truncation " << truncation << ", rounding " << rounding;
  EXPECT_GT(std::abs(analytic) * p / f1, 1e-3) << key << " hardly moves f1";
}

TEST(Sensitivity, TipMassAgainstDifferencesOfTheNetworksFirstFrequency) {
  const Scene scene = read_scene_text(
      "[scene]\nname = \"tip_mass\"\n[beam]\nlength = 0.5\nsegments = 10\n"
      "bending_stiffness = 2.0\nmass_per_length = 0.3\n[[mass]]\nat = 0.5\nmass = 0.05\n",
      "tip_mass.toml");
  expect_first_mode_derivative_matches_differences(scene, "mass[0].mass");
}

TEST(Sensitivity, ElasticClampStiffnessAgainstDifferencesOfTheNetworksFirstFrequency) {
  const Scene scene = read_scene_text(
      "[scene]\nname = \"elastic_clamp\"\n[beam]\nlength = 0.5\nsegments = 10\n"
      "bending_stiffness = 2.0\nmass_per_length = 0.3\nleft = \"pinned\"\n"
      "[[spring]]\nname = \"clamp\"\nat = 0\nkind = \"rotational\"\nstiffness = 4.0\n",
      "elastic_clamp.toml");
  expect_first_mode_derivative_matches_differences(scene, "spring[clamp].stiffness");
  EXPECT_EQ(find_scene_parameter(scene, "spring.clamp.stiffness").unit, "N*m/rad");
}

// Every component parameter is a sensitivity parameter, and each one's analytic derivative
// agrees with the poles' own differences (the check of the fish fin test above).
TEST(Sensitivity, EveryComponentParameterMatchesFiniteDifferences) {
  const Scene scene = read_scene_text(
      "[scene]\nname = \"components\"\n[beam]\nlength = 0.5\nsegments = 10\n"
      "theory = \"timoshenko\"\nshear_stiffness = 5e4\nleft = \"pinned\"\n"
      "[[section]]\nlength = 0.3\nbending_stiffness = 2.0\nmass_per_length = 0.3\n"
      "rotary_inertia_per_length = 1e-5\n"
      "[[section]]\nlength = 0.2\nbending_stiffness = 0.5\nmass_per_length = 0.1\n"
      "shear_stiffness = 2e4\nkelvin_voigt_time = 1e-4\nviscous_per_length = 0.01\n"
      "[[mass]]\nname = \"sensor\"\nat = 0.5\nmass = 0.02\nrotary_inertia = 1e-6\n"
      "[[spring]]\nname = \"clamp\"\nat = 0\nkind = \"rotational\"\nstiffness = 4.0\n"
      "damping = 1e-3\n"
      "[[spring]]\nname = \"support\"\nat = 0.3\nkind = \"translational\"\n"
      "stiffness = 50\ndamping = 0.1\n",
      "components.toml");
  std::vector<std::string> keys;
  for (const SceneParameter& parameter : scene_parameters(scene)) keys.push_back(parameter.key);
  for (const char* key :
       {"beam.length", "beam.shear_stiffness", "section[0].bending_stiffness",
        "section[0].mass_per_length", "section[0].rotary_inertia_per_length",
        "section[1].bending_stiffness", "section[1].mass_per_length", "section[1].shear_stiffness",
        "section[1].kelvin_voigt_time", "section[1].viscous_per_length", "mass[sensor].mass",
        "mass[sensor].rotary_inertia", "spring[clamp].stiffness", "spring[clamp].damping",
        "spring[support].stiffness", "spring[support].damping"})
    EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end()) << key;
  SensitivityOptions options;
  options.modes = 3;
  options.check = true;
  const SensitivityResult result = run_sensitivity(scene, {}, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.parameters.size(), keys.size());
  for (const auto& parameter : result.parameters)
    for (size_t k = 0; k < parameter.modes.size(); ++k) {
      const ModeSensitivity& s = parameter.modes[k];
      EXPECT_LE(s.check_difference, 3.0 * s.check_error_estimate + 1e-8)
          << parameter.parameter.key << " mode " << k + 1 << ": analytic " << s.pole_derivative
          << ", FD " << s.finite_difference_pole_derivative;
    }
}

TEST(SensitivityCli, TableAndCheck) {
  const auto r =
      testing::run_emnet("sensitivity " + kFishfin + " --modes 2 --parameter beam.length --check");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("beam.length"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("-1.999"), std::string::npos) << r.out;
}

TEST(SensitivityCli, UnknownParameterExitsTwoNamingIt) {
  const auto r = testing::run_emnet("sensitivity " + kFishfin + " --parameter beam.colour");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("beam.colour"), std::string::npos) << r.err;
}

TEST(SensitivityCli, JsonHasEveryParameter) {
  const auto r = testing::run_emnet("sensitivity " + kFishfin + " --modes 1 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"dea[B].electrode_resistance\""), std::string::npos);
  EXPECT_NE(r.out.find("\"normalised\""), std::string::npos);
}

}  // namespace
}  // namespace emnet
