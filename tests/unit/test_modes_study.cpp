// The modes study (emnet/studies/modes_study.hpp) against the Euler–Bernoulli continuum.
//
// References:
//   - Cantilever frequencies f_n = (β_n L)²/(2π L²)·√(EI/ρA), β_1 L = 1.875104068711961
//     (cos βL·cosh βL = −1).
//   - Cantilever first mode shape φ(x) = cosh βx − cos βx − σ·(sinh βx − sin βx),
//     σ = (cosh βL + cos βL)/(sinh βL + sin βL), largest (at the tip) scaled to 1; its slope
//     φ'(x) = β·(sinh βx + sin βx − σ·(cosh βx − cos βx)) with the same scale.
//   - Rigid-body motions: a pinned–free beam rotates about its pin (x = 0), a sliding–free beam
//     translates, a free–free beam does both.
#include <gtest/gtest.h>

#include <cmath>

#include "emnet/studies/modes_study.hpp"
#include "fixtures.hpp"

namespace emnet {
namespace {

constexpr double beta1_l = 1.875104068711961;

double continuum_f1(const Scene& scene) {
  const double length = scene.beam.length;
  return beta1_l * beta1_l / (2 * M_PI * length * length) *
         std::sqrt(scene.beam.bending_stiffness / scene.beam.mass_per_length);
}

ModesStudyResult study_of(const Scene& scene, bool shapes = false) {
  ModesStudyOptions options;
  options.count = 3;
  options.shapes = shapes;
  ModesStudyResult result = run_modes_study(scene, options);
  EXPECT_TRUE(result.status.ok()) << result.status.message;
  return result;
}

// The N/2N (Richardson) estimate of f1's relative error against its true error, the distance
// from the continuum value. The lumped network's error is a/N² + b/N⁴ + …; Richardson removes the
// N⁻² term, so the estimate differs from the true error by O(N⁻²) of it: measured
// |estimate/true − 1| = 0.0045, 0.0011, 0.00029 at N = 5, 10, 20, i.e. 0.11/N². We accept
// 0.3/N² (about 3 times the measured coefficient), and require that the deviation shrinks at
// least twice per doubling of N (second order: 4 times).
TEST(ModesStudy, DiscretisationErrorEstimateOfACantileverMatchesTheTrueError) {
  double previous_deviation = 0.0;
  for (int segments : {5, 10, 20}) {
    const Scene scene = testing::cantilever_scene(segments);
    const ModesStudyResult result = study_of(scene);
    ASSERT_GE(result.modes.size(), 1u);
    ASSERT_TRUE(result.modes[0].discretisation_error_estimated);
    EXPECT_TRUE(result.error_estimate_computed);
    const double f_continuum = continuum_f1(scene);
    const double true_error =
        std::abs(result.modes[0].mode.frequency_hz - f_continuum) / f_continuum;
    const double estimate = result.modes[0].discretisation_error;
    const double deviation = std::abs(estimate / true_error - 1.0);
    EXPECT_LE(deviation, 0.3 / (segments * segments)) << "N = " << segments;
    if (previous_deviation > 0.0) EXPECT_LT(deviation, 0.5 * previous_deviation) << segments;
    previous_deviation = deviation;
  }
}

// Without the estimate: none given, and a note says why.
TEST(ModesStudy, NoEstimateWhenNotAsked) {
  ModesStudyOptions options;
  options.error_estimate = false;
  const ModesStudyResult result = run_modes_study(testing::cantilever_scene(6), options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_FALSE(result.error_estimate_computed);
  ASSERT_FALSE(result.modes.empty());
  EXPECT_FALSE(result.modes[0].discretisation_error_estimated);
  ASSERT_EQ(result.notes.size(), 1u);
  EXPECT_NE(result.notes[0].find("not asked"), std::string::npos);
  EXPECT_EQ(result.seconds_error_estimate, 0.0);
}

// The first mode's shape (deflection and rotation at the nodes) against the continuum shape.
// Its error is second order in 1/N like the frequency's: measured max |w − φ/φ(L)| = 6.7e-4 and
// 1.7e-4, max |w' − φ'/φ(L)|·L = 3.8e-3 and 9.6e-4 at N = 10 and 20, against the study's own f1
// error estimate e = 4.6e-3 and 1.1e-3. We accept 0.5·e for the deflection and 2·e for the
// rotation (3 and 2.4 times the measured ratios), and a convergence ratio in [3.5, 4.5] from
// N = 10 to 20 (second order: 4). The undamped shape is real: imaginary part at rounding.
TEST(ModesStudy, CantileverFirstModeShapeIsTheContinuumShape) {
  std::vector<double> deflection_errors, rotation_errors;
  for (int segments : {10, 20}) {
    const Scene scene = testing::cantilever_scene(segments);
    const ModesStudyResult result = study_of(scene, true);
    ASSERT_GE(result.modes.size(), 1u);
    const ModeShape& shape = result.modes[0].shape;
    ASSERT_EQ(shape.x_m.size(), static_cast<size_t>(segments + 1));
    const double length = scene.beam.length, beta = beta1_l / length;
    const double sigma =
        (std::cosh(beta1_l) + std::cos(beta1_l)) / (std::sinh(beta1_l) + std::sin(beta1_l));
    auto phi = [&](double x) {
      return std::cosh(beta * x) - std::cos(beta * x) -
             sigma * (std::sinh(beta * x) - std::sin(beta * x));
    };
    auto phi_slope = [&](double x) {
      return beta * (std::sinh(beta * x) + std::sin(beta * x) -
                     sigma * (std::cosh(beta * x) - std::cos(beta * x)));
    };
    const double tip = phi(length);
    double deflection_error = 0.0, rotation_error = 0.0;
    for (size_t i = 0; i < shape.x_m.size(); ++i) {
      deflection_error = std::max(deflection_error,
                                  std::abs(shape.deflection[i].real() - phi(shape.x_m[i]) / tip));
      rotation_error =
          std::max(rotation_error,
                   std::abs(shape.rotation[i].real() - phi_slope(shape.x_m[i]) / tip) * length);
      EXPECT_LT(std::abs(shape.deflection[i].imag()), 1e-12);
    }
    EXPECT_NEAR(shape.deflection.back().real(), 1.0, 1e-12);  // the tip is the largest
    const double estimate = result.modes[0].discretisation_error;
    EXPECT_LE(deflection_error, 0.5 * estimate) << "N = " << segments;
    EXPECT_LE(rotation_error, 2.0 * estimate) << "N = " << segments;
    deflection_errors.push_back(deflection_error);
    rotation_errors.push_back(rotation_error);
  }
  const double deflection_ratio = deflection_errors[0] / deflection_errors[1];
  const double rotation_ratio = rotation_errors[0] / rotation_errors[1];
  EXPECT_GE(deflection_ratio, 3.5);
  EXPECT_LE(deflection_ratio, 4.5);
  EXPECT_GE(rotation_ratio, 3.5);
  EXPECT_LE(rotation_ratio, 4.5);
}

// The rigid-body motions of beams with a free end and a support that leaves one: a pinned–free
// beam rotates about its pin at x = 0, a sliding–free one translates, a free–free one does both.
// Each is a linear network without a static state, so the study runs about zero and says so.
TEST(ModesStudy, RigidBodyMotionsAreNamed) {
  Scene pinned = testing::cantilever_scene(8);
  pinned.beam.left = EndCondition::pinned;
  Scene sliding = pinned;
  sliding.beam.left = EndCondition::sliding;
  Scene free_free = pinned;
  free_free.beam.left = EndCondition::free;
  const std::pair<Scene, std::string> cases[] = {
      {pinned, "rotation about x = 0 mm"},
      {sliding, "translation"},
      {free_free, "translation and rotation (a free body)"}};
  for (const auto& [scene, name] : cases) {
    const ModesStudyResult result = study_of(scene);
    ASSERT_EQ(result.rigid_body_motions.size(), 1u) << name;
    EXPECT_EQ(result.rigid_body_motions[0], name);
    ASSERT_EQ(result.notes.size(), 1u) << name;  // the operating point about zero
    EXPECT_EQ(result.model.notes.back(), result.notes[0]);
  }
  // A clamped end leaves none.
  EXPECT_TRUE(study_of(testing::cantilever_scene(8)).rigid_body_motions.empty());
}

}  // namespace
}  // namespace emnet
