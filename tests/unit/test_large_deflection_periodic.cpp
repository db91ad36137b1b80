// The periodic state under switching with large kinematics (beam.kinematics = "large"): the
// switching sweep by shooting (periodic_shooting.cpp) against exact references.
//
// References:
//   - the exact periodic state of the small network (the exact method: the state equation's
//     eigen-decomposition, periodic.hpp) where the drive is small enough that the geometric
//     terms, of order (w/L)² of the swing, are below the tolerance;
//   - a transient of the same nonlinear network from rest by IDA, run until it has settled: no
//     Newton iteration, no linearisation, only time;
//   - each compared where the small model is off by far more than the tolerance, so a wrong
//     nonlinear model could not pass.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "emnet/analysis/periodic.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/switching_sweep.hpp"
#include "one_mesh_fin.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using testing::one_mesh_fin;

SwitchingSweepResult sweep(const Scene& scene, const std::vector<double>& frequencies) {
  const SweptModel swept =
      prepare_swept_model(scene, SwitchingSweepMethod::automatic, {}, PrepareOptions{}, 7.0);
  SwitchingSweepOptions options;
  options.frequencies = frequencies;
  options.outputs = switching_sweep_outputs(swept.model, {"tip"});
  options.first_mode = false;
  // Shooting's extremes are sampled and refined by a parabola: 2048 samples put that below 1e-7
  // of the swing (the exact method's are exact).
  options.samples = 2048;
  return run_switching_sweep(swept.model, swept.scene, options);
}

// At 400 V (a hundredth of the DEAs' moment at 4 kV) the tip swings 0.13 mm at resonance, 1e-3
// of L: the geometric terms are ~(w/L)² = 1.1e-6 of the swing, shooting's IDA (rtol 1e-9) ~1e-8.
// The large model's periodic state is the small network's exact one to 2e-6 of the swing at a
// quarter of the resonance and at it (measured: 2.8e-8 and 2.5e-7).
TEST(LargeKinematicsPeriodic, SmallDriveGivesTheSmallNetworksExactPeriodicState) {
  const std::vector<double> frequencies = {1.6, 6.4};
  const SwitchingSweepResult small =
      sweep(one_mesh_fin("small", {"drive.voltage=400 V"}), frequencies);
  const SwitchingSweepResult large =
      sweep(one_mesh_fin("large", {"drive.voltage=400 V"}), frequencies);
  ASSERT_TRUE(small.status.ok()) << small.status.message;
  ASSERT_TRUE(large.status.ok()) << large.status.message;
  EXPECT_EQ(small.method, Method::exact);
  EXPECT_EQ(large.method, Method::shooting);
  for (size_t k = 0; k < frequencies.size(); ++k) {
    const double swing = small.outputs[0].right[k] - small.outputs[0].left[k];
    EXPECT_NEAR(large.outputs[0].left[k], small.outputs[0].left[k], 2e-6 * swing);
    EXPECT_NEAR(large.outputs[0].right[k], small.outputs[0].right[k], 2e-6 * swing);
  }
}

// At 8 kV with a loss factor of 0.2 (damping ratio ~0.1: the transient settles to 1e-7 within
// 26 periods at 6.4 Hz) the tip swings ~7 % of L. Shooting's period equals the last period of the
// transient from rest at every sample to 1e-6 of the swing (IDA at rtol 1e-9 over 30 periods,
// the settling residual below 1e-7; measured 7.2e-8), while the small network's differs by more
// than 100 times that (measured 9.9e-4).
TEST(LargeKinematicsPeriodic, ShootingIsTheSettledTransient) {
  const std::vector<std::string> overrides = {"drive.voltage=8 kV", "damping.loss_factor=0.2",
                                              "drive.frequency=6.4 Hz"};
  PrepareOptions dynamics;
  dynamics.large_kinematics = LargeKinematicsUse::dynamics;
  const Model model = prepare_model(one_mesh_fin("large", overrides), dynamics);
  const Model small_model = prepare_model(one_mesh_fin("small", overrides));
  const std::vector<Probe> tip = switching_sweep_outputs(model, {"tip"});
  const double period = 1.0 / 6.4;
  const int samples = 64, periods = 30;
  const System system = model.network.assemble();
  const PeriodicResult shooting = run_periodic_shooting(system, tip, period, 1e-9, samples);
  ASSERT_TRUE(shooting.status.ok()) << shooting.status.message;
  TransientOptions options;
  options.end_time = periods * period;
  options.relative_tolerance = 1e-9;
  for (int s = 0; s < samples; ++s)
    options.output_times.push_back((periods - 1 + s / static_cast<double>(samples)) * period);
  const TransientResult settled = run_transient_ida(system, tip, options);
  ASSERT_TRUE(settled.status.ok()) << settled.status.message;
  const System small_system = small_model.network.assemble();
  const PeriodicResult small =
      PeriodicSolver(small_system)
          .solve(small_system, switching_sweep_outputs(small_model, {"tip"}), period, samples);
  ASSERT_TRUE(small.status.ok()) << small.status.message;
  const double swing = shooting.maximum[0] - shooting.minimum[0];
  EXPECT_GT(swing, 0.05 * model.scene.beam.length);
  double difference = 0.0, small_difference = 0.0;
  for (int s = 0; s < samples; ++s) {
    difference = std::max(difference, std::abs(shooting.values[0][s] - settled.values[0][s]));
    small_difference =
        std::max(small_difference, std::abs(small.values[0][s] - settled.values[0][s]));
  }
  EXPECT_LT(difference, 1e-6 * swing);
  EXPECT_GT(small_difference, 1e-4 * swing);
}

// The exact and the reduced periodic methods need a linear network: with large kinematics they
// are refused naming beam.kinematics; the automatic choice takes shooting and says why.
TEST(LargeKinematicsPeriodic, TheExactAndReducedMethodsAreRefusedNamingTheKey) {
  const Scene scene = one_mesh_fin("large");
  try {
    prepare_swept_model(scene, SwitchingSweepMethod::exact, {}, PrepareOptions{}, 7.0);
    ADD_FAILURE() << "the exact method took a large-kinematics scene";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "beam.kinematics");
  }
  const SweptModel swept =
      prepare_swept_model(scene, SwitchingSweepMethod::automatic, {}, PrepareOptions{}, 7.0);
  SwitchingSweepOptions options;
  options.frequencies = {5.0};
  options.outputs = switching_sweep_outputs(swept.model, {"tip"});
  options.reduce = true;
  try {
    run_switching_sweep(swept.model, swept.scene, options);
    ADD_FAILURE() << "the reduced method took a large-kinematics scene";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "beam.kinematics");
  }
  options.reduce = false;
  options.first_mode = false;
  const SwitchingSweepResult result = run_switching_sweep(swept.model, swept.scene, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_FALSE(result.notes.empty());
  EXPECT_NE(result.notes[0].find("large kinematics"), std::string::npos) << result.notes[0];
}

// The paper's fin at 4 kV across its switching sweep, small (exact) and large (shot) side by side
// on one mesh. At resonance (6.4 Hz) the tip swings 10.2 % of L and the large swing is 0.52 % of
// it below the small one; at 6.5 Hz above it (the first mode hardens); away from resonance the two
// agree to ~(w/L)² of the swing (1e-5 at 1 mm). The small result's stated geometric error,
// max((w/L)², ψ²) = 2.0 % (ψ = 0.142 rad at the tip), is above the largest difference at every
// frequency; shooting's own error (~1e-7 of the swing) is far below all of these.
TEST(LargeKinematicsPeriodic, FinAt4kVSmallAndLargeSideBySideAcrossTheSweep) {
  const std::vector<double> frequencies = {1.0, 2.1, 3.2, 5.0, 6.0, 6.3, 6.4, 6.5, 7.0};
  const SwitchingSweepResult small = sweep(one_mesh_fin("small"), frequencies);
  const SwitchingSweepResult large = sweep(one_mesh_fin("large"), frequencies);
  ASSERT_TRUE(small.status.ok()) << small.status.message;
  ASSERT_TRUE(large.status.ok()) << large.status.message;
  std::vector<double> difference;
  for (size_t k = 0; k < frequencies.size(); ++k) {
    const double half_swing = 0.5 * (large.outputs[0].right[k] - large.outputs[0].left[k]);
    difference.push_back(std::max(std::abs(large.outputs[0].right[k] - small.outputs[0].right[k]),
                                  std::abs(large.outputs[0].left[k] - small.outputs[0].left[k])) /
                         half_swing);
    EXPECT_LT(difference.back(), small.validity.geometric_error) << frequencies[k] << " Hz";
  }
  EXPECT_GT(difference[6], 3e-3);  // 6.4 Hz: the geometry matters
  EXPECT_LT(large.outputs[0].right[6], small.outputs[0].right[6]);
  EXPECT_GT(large.outputs[0].right[7], small.outputs[0].right[7]);  // 6.5 Hz: hardened
  EXPECT_LT(difference[0], 1e-4);                                   // 1 Hz: 1 mm swing
  EXPECT_LT(difference[8], 1e-4);                                   // 7 Hz
  // What shooting cost: at least two one-period runs per frequency (a residual and the sampled
  // last one); the exact method none.
  EXPECT_EQ(small.period_runs, 0);
  EXPECT_GE(large.period_runs, static_cast<long>(2 * frequencies.size()));
}

// The tweezer jaw (netlists/tweezer-jaw.toml: a 25 mm body and a 10 mm tip 80 times softer,
// driven through its circuit at 2.5 kV) at its resonance swings 12.9 % of its length in the small
// network; its soft tip turns by 0.49 rad. With large kinematics (assumed: EA = 640 N, the body's
// E·A for E = 12·EI/t² over its 1.5 mm; an axial holder as stiff as the translational one,
// 5e3 N/m; neither changes the swing by more than 1e-3 of it, measured at EA 64 kN and 5e6 N/m)
// the swing at 16.5 Hz is 14 % smaller (the small one 16.4 % above it) and the peak moves up
// (hardening): 16.6 Hz swings more than 16.5 Hz, where the small network's peak is below 16.5.
// The (w/L)² of the deflection (1.66 %) would have stated a tenth of that difference; the small
// result's geometric error, max((w/L)², ψ²) of its largest deflection and section rotation
// (24.4 %), states more than it.
TEST(LargeKinematicsPeriodic, TweezerJawAtResonanceAgainstTheSmallNetworksStatedError) {
  const std::string path = testing::shipped_scene("tweezer-jaw.toml");
  auto tweezer = [&](const std::string& kinematics) {
    if (kinematics == "small") return read_scene(path);
    Scene scene = read_scene(path, {"beam.kinematics=large", "beam.axial_stiffness=640 N"});
    SpringSpec holder;
    holder.name = "holder_axial";
    holder.kind = SpringKind::axial;
    holder.stiffness = 5e3;
    scene.beam.springs.push_back(holder);
    return scene;
  };
  const std::vector<double> frequencies = {16.5, 16.6};
  const SwitchingSweepResult small = sweep(tweezer("small"), frequencies);
  const SwitchingSweepResult large = sweep(tweezer("large"), frequencies);
  ASSERT_TRUE(small.status.ok()) << small.status.message;
  ASSERT_TRUE(large.status.ok()) << large.status.message;
  const double length = 0.035;
  const double small_swing = small.outputs[0].right[0], large_swing = large.outputs[0].right[0];
  EXPECT_GT(small_swing, 0.12 * length);
  const double difference = std::abs(large_swing - small_swing) / large_swing;
  const double deflection_estimate = std::pow(small_swing / length, 2);
  EXPECT_GT(difference, 5 * deflection_estimate);
  EXPECT_GT(small.validity.geometric_error, difference);
  EXPECT_GT(small.validity.largest_rotation, 0.4);
  EXPECT_GT(large.outputs[0].right[1], large.outputs[0].right[0]);  // the peak moved up
  EXPECT_LT(small.outputs[0].right[1], small.outputs[0].right[0]);
  EXPECT_EQ(large.validity.geometric_error, 0.0);  // large kinematics: none to state
}

}  // namespace
}  // namespace emnet
