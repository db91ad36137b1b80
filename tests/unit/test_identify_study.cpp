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
// (3) Round trips of other keys (--fit): the network's own mode-1 frequency at a known value p0
//     (an elastic clamp's rotational stiffness, a tip mass, a section's EI) is the target of a
//     fit started 10× off. The root find stops at |f − f_target| ≤ 1e-10·f_target, so p is
//     within 1e-10/|S| relative, S = (p/f)·df/dp the normalised sensitivity there (measured in
//     each test by a central difference), plus the eigenvalues' rounding (~1e-13/|S|): the
//     tolerance is 2e-10/|S|.
// (4) Limits: the frequency of a beam pinned at x = 0 with a rotational spring k rises
//     monotonically with k to the clamped beam's (k → ∞: the same network with the rotation
//     held); a target above that is out of reach of any k.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <string_view>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/core/units.hpp"
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
  EXPECT_TRUE(point.status.ok()) << point.status.message;
  emnet::ModalOptions options;
  options.keep_vectors = false;
  const emnet::ModalResult modes = emnet::run_modes(system, point.rest.operating_point, options);
  EXPECT_TRUE(modes.status.ok()) << modes.status.message;
  return modes.modes.empty() ? std::nan("") : modes.modes[0].frequency_hz;
}

// A 0.5 m cantilever (EI = 2 N·m², ρA = 0.3 kg/m, 10 segments) whose left end is pinned and
// held by a rotational spring "clamp" of stiffness k [N·m/rad]: an elastic clamp.
std::string elastic_clamp_text(double k) {
  return "[scene]\nname = \"elastic_clamp\"\n[beam]\nlength = 0.5\nsegments = 10\n"
         "bending_stiffness = 2.0\nmass_per_length = 0.3\nleft = \"pinned\"\nright = \"free\"\n"
         "[[spring]]\nname = \"clamp\"\nat = 0\nkind = \"rotational\"\nstiffness = " +
         std::to_string(k) + "\n";
}

emnet::Scene elastic_clamp(double k) {
  return emnet::read_scene_text(elastic_clamp_text(k), "elastic_clamp.toml");
}

// The cantilever of fixtures.hpp with a point mass m [kg] at its tip.
emnet::Scene cantilever_with_tip_mass(double m) {
  return emnet::read_scene_text(
      "[scene]\nname = \"tip_mass\"\n[beam]\nlength = 0.5\nsegments = 10\n"
      "bending_stiffness = 2.0\nmass_per_length = 0.3\n[[mass]]\nname = \"sensor\"\n"
      "at = 0.5\nmass = " +
          std::to_string(m) + "\n",
      "tip_mass.toml");
}

// A cantilever of two sections: 0.3 m (EI 2, ρA 0.3) then 0.2 m (EI e1, ρA 0.1).
emnet::Scene two_sections(double e1) {
  return emnet::read_scene_text(
      "[scene]\nname = \"stepped\"\n[beam]\nlength = 0.5\nsegments = 10\n"
      "[[section]]\nlength = 0.3\nbending_stiffness = 2.0\nmass_per_length = 0.3\n"
      "[[section]]\nlength = 0.2\nbending_stiffness = " +
          std::to_string(e1) + "\nmass_per_length = 0.1\n",
      "stepped.toml");
}

// (p/f)·df/dp of mode 1 at key = p, by a central difference at p·(1 ± 1e-5) (a check of the
// tolerance's size, not a reference: a few digits suffice).
double normalised_sensitivity(const emnet::Scene& scene, const std::string& key) {
  const double p = emnet::get_parameter(scene, key);
  emnet::Scene up = scene, down = scene;
  emnet::set_parameter(up, key, p * (1 + 1e-5));
  emnet::set_parameter(down, key, p * (1 - 1e-5));
  return (first_mode_hz(up) - first_mode_hz(down)) / (2e-5 * first_mode_hz(scene));
}

// The round trip of reference (3): fit `key` of `start` to the mode-1 frequency of `known`.
void expect_round_trip(const emnet::Scene& known, const emnet::Scene& start, const std::string& key,
                       const std::string& canonical, const std::string& unit) {
  const double p0 = emnet::get_parameter(known, key);
  const double sensitivity = std::abs(normalised_sensitivity(known, key));
  ASSERT_GT(sensitivity, 1e-3) << key;  // the frequency moves with it
  emnet::IdentifyOptions options;
  options.target_hz = first_mode_hz(known);
  options.parameter = key;
  const emnet::IdentifyResult result = emnet::identify(start, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.fitted.size(), 1u);
  EXPECT_EQ(result.fitted[0].key, canonical);
  EXPECT_EQ(result.fitted[0].unit, unit);
  EXPECT_EQ(result.parameter.value, result.fitted[0].value);
  EXPECT_NEAR(result.fitted[0].value, p0, 2e-10 / sensitivity * p0)
      << key << ": S = " << sensitivity << ", " << result.stiffness_iterations << " solves";
  EXPECT_LE(std::abs(result.frequency_residual), 1e-10);
  EXPECT_EQ(result.modal_solves, result.stiffness_iterations);
  EXPECT_LT(result.stiffness_iterations, 40);
  // The beam's EI is not what was fitted: it is the scene's.
  EXPECT_EQ(result.bending_stiffness, start.beam.bending_stiffness);
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
    ASSERT_TRUE(result.status.ok()) << result.status.message;
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
  ASSERT_TRUE(extremes.status.ok()) << extremes.status.message;
  // A linear network under the symmetric square wave: the swing is odd, min = −max.
  EXPECT_NEAR(extremes.minimum, -extremes.maximum, 1e-10 * extremes.peak);

  emnet::Scene start = known;  // other start values
  emnet::set_parameter(start, "beam.bending_stiffness", 1.2 * known_stiffness);
  emnet::set_parameter(start, "damping.loss_factor", 0.05);
  emnet::IdentifyOptions options;
  options.target_hz = f1;
  options.peak = emnet::PeakTarget{"P4", extremes.peak, 0.0};
  const emnet::IdentifyResult result = emnet::identify(start, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
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
  ASSERT_FALSE(result.status.ok());
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

TEST(IdentifyStudy, RotationalClampStiffnessFromTenTimesOffEitherWay) {
  const double k0 = 4.0;  // N·m/rad, EI/L: the clamp is as stiff as the beam
  for (const double start : {0.1 * k0, 10.0 * k0})
    expect_round_trip(elastic_clamp(k0), elastic_clamp(start), "spring.clamp.stiffness",
                      "spring[clamp].stiffness", "N*m/rad");
}

TEST(IdentifyStudy, TipMassFromTenTimesOff) {
  const double m0 = 0.05;  // kg, a third of the beam's 0.15 kg
  for (const double start : {0.1 * m0, 10.0 * m0})
    expect_round_trip(cantilever_with_tip_mass(m0), cantilever_with_tip_mass(start), "mass[0].mass",
                      "mass[sensor].mass", "kg");
}

TEST(IdentifyStudy, SectionBendingStiffnessFromTenTimesOff) {
  const double e0 = 0.5;  // N·m², the outer section's
  expect_round_trip(two_sections(e0), two_sections(10.0 * e0), "section[1].bending_stiffness",
                    "section[1].bending_stiffness", "N*m^2");
}

TEST(IdentifyStudy, TargetAboveTheClampedBeamIsOutOfReachOfAnyClampStiffness) {
  emnet::Scene clamped = emnet::testing::cantilever_scene(10);
  const double clamped_hz = first_mode_hz(clamped);
  emnet::IdentifyOptions options;
  options.target_hz = 1.1 * clamped_hz;
  options.parameter = "spring[clamp].stiffness";
  const emnet::IdentifyResult result = emnet::identify(elastic_clamp(4.0), options);
  ASSERT_FALSE(result.status.ok());
  const std::string& why = result.status.message;
  EXPECT_NE(
      why.find("the target " + emnet::format_with_unit(options.target_hz, "Hz") +
               " lies above what any spring[clamp].stiffness reaches (" +
               emnet::format_number("%.6g", clamped_hz) + " Hz at spring[clamp].stiffness → ∞"),
      std::string::npos)
      << why << "\nclamped: " << emnet::format_number("%.10g", clamped_hz);
  EXPECT_TRUE(result.fitted.empty());
  EXPECT_TRUE(std::isfinite(result.achieved_hz));
}

TEST(IdentifyStudy, BadFitKeysAreOptionErrorsNamingTheFieldAndTheKey) {
  const emnet::Scene scene = elastic_clamp(4.0);
  emnet::IdentifyOptions options;
  options.target_hz = 5.0;
  auto message_of = [&](const std::string& key) {
    options.parameter = key;
    try {
      emnet::identify(scene, options);
    } catch (const emnet::OptionError& error) {
      EXPECT_EQ(error.field(), "parameter") << key;
      EXPECT_EQ(error.where(), "parameter") << key;
      return std::string(error.what());
    }
    ADD_FAILURE() << key << " was accepted";
    return std::string();
  };
  EXPECT_NE(message_of("beam.colour").find("colour"), std::string::npos);
  EXPECT_NE(message_of("spring[other].stiffness").find("other"), std::string::npos);
  const std::string not_numeric = message_of("beam.left");
  EXPECT_NE(not_numeric.find("key 'beam.left': is not a number"), std::string::npos) << not_numeric;
  const std::string integer = message_of("beam.segments");
  EXPECT_NE(integer.find("key 'beam.segments': is an integer key"), std::string::npos) << integer;
  const std::string unused = message_of("beam.shear_stiffness");  // Euler-Bernoulli beam
  EXPECT_NE(unused.find("key 'beam.shear_stiffness': is not used by scene 'elastic_clamp'"),
            std::string::npos)
      << unused;
  const std::string zero = message_of("spring[clamp].damping");  // 0: no logarithm
  EXPECT_NE(zero.find("key 'spring[clamp].damping': is 0"), std::string::npos) << zero;
  // Given by the scene: refused whichever form the [provenance] entry names it by.
  emnet::Scene given = scene;
  given.provenance["spring.clamp.stiffness"] = "data sheet: clamp";
  options.parameter = "spring[0].stiffness";
  EXPECT_THROW(emnet::identify(given, options), emnet::InputError);
}

TEST(IdentifyStudy, NoSuchModeIsAFailure) {
  emnet::IdentifyOptions options;
  options.target_hz = 5.0;
  options.mode_number = 1000;  // a 10-segment cantilever has 20 modes
  const emnet::IdentifyResult result =
      emnet::identify(emnet::testing::cantilever_scene(10), options);
  ASSERT_FALSE(result.status.ok());
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
  ASSERT_FALSE(result.status.ok());
  EXPECT_TRUE(result.status.cancelled());
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
