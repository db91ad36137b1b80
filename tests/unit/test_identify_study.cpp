// The identification study as a library call (emnet::identify, emnet/studies/identify.hpp):
// its fitted values against closed forms and round trips, and its failures as Status.
//
// References:
// (1) Closed form: a bare cantilever (no DEA, no damping, no fluid: tests/unit/fixtures.hpp) is
//     a lumped network whose stiffnesses are all ∝ EI and whose masses do not depend on it, so
//     every frequency is exactly ∝ √EI and the EI that puts mode 1 at f_target is
//     EI0·(f_target/f0)², f0 computed independently at EI0 (run_modes). The fixed point reaches
//     it at its second iteration; the fit stops at |f − f_target| ≤ 1e-10·f_target, so EI is
//     within 2e-10 relative (EI ∝ f²) plus the eigenvalues' rounding (~1e-13): 3e-10.
// (2) Round trip: the periodic peak of the fish fin computed at a known loss factor and EI
//     (periodic_extremes at f1, the damped mode-1 frequency there, from run_modes) is given as
//     the target to an identify that starts from other values; it must give back the known
//     values. The rounds stop when η and EI change by at most 1e-9 relative between rounds, the
//     bisection brackets η to 1e-12, and the stiffness fit meets f1 to 1e-10: 1e-7 relative
//     leaves a factor 100 over the rounds' tolerance. The fish fin's DEAs add stiffness and its
//     loss factor damping, so its frequency is not ∝ √EI: this also tests the fixed point.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <string_view>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/identify.hpp"
#include "emnet/studies/periodic_peak.hpp"
#include "emnet/studies/resolve.hpp"
#include "fixtures.hpp"

namespace {

// The damped frequency of mode 1 of `scene` about its operating point.
double first_mode_hz(const emnet::Scene& scene) {
  const emnet::Model model = emnet::prepare_model(scene);
  const emnet::System system = model.network.assemble();
  const emnet::OperatingPoint point = emnet::operating_point(system);
  EXPECT_TRUE(point.status.ok) << point.status.message;
  emnet::ModalOptions options;
  options.keep_vectors = false;
  const emnet::ModalResult modes = emnet::run_modes(system, point.rest.operating_point, options);
  EXPECT_TRUE(modes.status.ok) << modes.status.message;
  return modes.modes.empty() ? std::nan("") : modes.modes[0].frequency_hz;
}

emnet::Scene fish_fin() {
  return emnet::read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml");
}

TEST(IdentifyStudy, BareCantileverStiffnessScalesWithTheSquareOfTheFrequency) {
  const emnet::Scene scene = emnet::testing::cantilever_scene(10);
  const double stiffness0 = scene.beam.bending_stiffness;
  const double f0 = first_mode_hz(scene);
  for (const double ratio : {0.5, 1.3}) {
    emnet::IdentifyOptions options;
    options.target_hz = ratio * f0;
    const emnet::IdentifyResult result = emnet::identify(scene, options);
    ASSERT_TRUE(result.status.ok) << result.status.message;
    EXPECT_NEAR(result.bending_stiffness, stiffness0 * ratio * ratio,
                3e-10 * stiffness0 * ratio * ratio);
    EXPECT_NEAR(result.achieved_hz, options.target_hz, 1e-10 * options.target_hz);
    EXPECT_LE(std::abs(result.frequency_residual), 1e-10);
    EXPECT_EQ(result.stiffness_iterations, 2);  // one update is exact when f ∝ √EI
    ASSERT_EQ(result.fitted.size(), 1u);
    EXPECT_EQ(result.fitted[0].key, "beam.bending_stiffness");
    EXPECT_EQ(result.fitted[0].value, result.bending_stiffness);
    EXPECT_FALSE(result.validity.has_value());  // no peak target, no peak to check
    EXPECT_EQ(result.modal_solves, 2);
  }
}

TEST(IdentifyStudy, PeakFitGivesBackTheLossFactorThePeakWasComputedAt) {
  const double known_stiffness = 1.9e-3, known_loss_factor = 0.03;
  emnet::Scene known = fish_fin();
  emnet::set_parameter(known, "beam.bending_stiffness", known_stiffness);
  emnet::set_parameter(known, "damping.loss_factor", known_loss_factor);
  const double f1 = first_mode_hz(known);
  emnet::PeriodicExtremesOptions extremes_options;
  extremes_options.frequency_hz = f1;
  extremes_options.output = "P4";
  const emnet::PeriodicExtremesResult extremes = emnet::periodic_extremes(known, extremes_options);
  ASSERT_TRUE(extremes.status.ok) << extremes.status.message;
  // A linear network under the symmetric square wave: the swing is odd, min = −max.
  EXPECT_NEAR(extremes.minimum, -extremes.maximum, 1e-10 * extremes.peak);

  emnet::Scene start = known;  // other start values
  emnet::set_parameter(start, "beam.bending_stiffness", 1.2 * known_stiffness);
  emnet::set_parameter(start, "damping.loss_factor", 0.05);
  emnet::IdentifyOptions options;
  options.target_hz = f1;
  options.peak = emnet::PeakTarget{"P4", extremes.peak, 0.0};
  const emnet::IdentifyResult result = emnet::identify(start, options);
  ASSERT_TRUE(result.status.ok) << result.status.message;
  EXPECT_NEAR(result.loss_factor, known_loss_factor, 1e-7 * known_loss_factor);
  EXPECT_NEAR(result.bending_stiffness, known_stiffness, 1e-7 * known_stiffness);
  EXPECT_LE(std::abs(result.peak_residual), 1e-7);
  EXPECT_LE(std::abs(result.frequency_residual), 1e-10);
  ASSERT_EQ(result.fitted.size(), 2u);
  EXPECT_EQ(result.fitted[1].key, "damping.loss_factor");
  EXPECT_GE(result.peak_rounds, 2);  // the stiffness moves with the damping: at least 2 rounds
  EXPECT_LT(result.peak_rounds, options.peak_rounds);
  EXPECT_TRUE(result.notes.empty());
  ASSERT_TRUE(result.validity.has_value());
}

TEST(IdentifyStudy, UnreachablePeakIsAFailureWithItsReasonAndNoNaN) {
  emnet::IdentifyOptions options;
  options.target_hz = 5.0;
  options.peak = emnet::PeakTarget{"P4", 100.0, 0.0};  // 100 m: no damping gives that
  const emnet::IdentifyResult result = emnet::identify(fish_fin(), options);
  ASSERT_FALSE(result.status.ok);
  EXPECT_NE(result.status.message.find("no loss factor in [1e-5, 2] gives the peak 100 m"),
            std::string::npos)
      << result.status.message;
  EXPECT_TRUE(std::isfinite(result.bending_stiffness));
  EXPECT_TRUE(std::isfinite(result.loss_factor));
  EXPECT_TRUE(std::isfinite(result.achieved_peak));
  EXPECT_TRUE(result.fitted.empty());
  // The peak at the least damping (1e-5) is already below the target: one solve, no bisection.
  EXPECT_EQ(result.periodic_solves, 1);
}

TEST(IdentifyStudy, NoSuchModeIsAFailure) {
  emnet::IdentifyOptions options;
  options.target_hz = 5.0;
  options.mode_number = 1000;  // a 10-segment cantilever has 20 modes
  const emnet::IdentifyResult result =
      emnet::identify(emnet::testing::cantilever_scene(10), options);
  ASSERT_FALSE(result.status.ok);
  EXPECT_EQ(result.status.message, "identify: mode 1000 not found");
}

// A progress that asks to stop at once.
struct StopAtOnce : emnet::Progress {
  void report(long, long, std::string_view) override {}
  bool cancelled() const override { return true; }
};

TEST(IdentifyStudy, CancelledBeforeTheFirstTrialIsTheCancelledStatus) {
  StopAtOnce stop;
  emnet::IdentifyOptions options;
  options.target_hz = 5.0;
  options.progress = &stop;
  const emnet::IdentifyResult result =
      emnet::identify(emnet::testing::cantilever_scene(10), options);
  ASSERT_FALSE(result.status.ok);
  EXPECT_EQ(result.status.message, emnet::kCancelledMessage);
  EXPECT_EQ(result.modal_solves, 0);
  EXPECT_TRUE(result.fitted.empty());
}

TEST(IdentifyStudy, GivenValuesAndBadTargetsAreInputErrors) {
  emnet::Scene given = emnet::testing::cantilever_scene(10);
  given.provenance["beam.bending_stiffness"] = "paper: Table 1";
  emnet::IdentifyOptions options;
  options.target_hz = 5.0;
  EXPECT_THROW(emnet::identify(given, options), emnet::InputError);
  options.target_hz = -1.0;
  EXPECT_THROW(emnet::identify(emnet::testing::cantilever_scene(10), options), emnet::InputError);
  options.target_hz = 5.0;
  options.peak = emnet::PeakTarget{"tip", 1e-3, 0.0};  // the bare cantilever sets no loss factor
  EXPECT_THROW(emnet::identify(emnet::testing::cantilever_scene(10), options), emnet::InputError);
}

}  // namespace
