// The analyses' progress hooks (include/emnet/core/progress.hpp): one report per step with the
// right counts, and a cancellation honoured at the next step with the Status "cancelled"; and the
// residual limit: a solve that did not solve its system is a failed Status, not a result.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/sensitivity.hpp"
#include "fixtures.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

// Records every report; cancelled once `cancel_after` reports have come (0: never, < 0: from
// the start).
class RecordingProgress : public Progress {
 public:
  explicit RecordingProgress(long cancel_after = 0) : cancel_after_(cancel_after) {}
  void report(long done, long total, std::string_view what) override {
    reports.push_back({done, total, std::string(what)});
  }
  bool cancelled() const override {
    return cancel_after_ < 0 ||
           (cancel_after_ > 0 && static_cast<long>(reports.size()) >= cancel_after_);
  }
  struct Report {
    long done, total;
    std::string what;
  };
  std::vector<Report> reports;

 private:
  long cancel_after_;
};

using emnet::testing::kFishfin;

TEST(ProgressHooks, AcReportsEveryFrequencyAndStopsWhenCancelled) {
  auto one = testing::one_mass_spring_damper(0.2, 50.0, 0.3);
  const System system = one.network.assemble();
  Probe x{"x", ProbeQuantity::deflection, "m", {{one.velocity, 1.0}}, 1, "x"};
  const std::vector<double> grid = frequency_grid(0.0, 10.0, 50, false);
  RecordingProgress all;
  AcOptions options;
  options.method = AcMethod::direct;  // one solve per frequency, each reported
  options.progress = &all;
  const AcResult full = run_ac(system, Eigen::VectorXd::Zero(system.size()), grid, {x}, options);
  ASSERT_TRUE(full.status.ok()) << full.status.message;
  ASSERT_EQ(all.reports.size(), grid.size() + 1);  // the set-up, then each frequency
  EXPECT_EQ(all.reports[0].total, 0);
  EXPECT_EQ(all.reports[8].done, 7);
  EXPECT_EQ(all.reports[8].total, 50);
  EXPECT_EQ(all.reports[8].what, "AC frequencies");

  RecordingProgress stopping(10);
  options.progress = &stopping;
  const AcResult cut = run_ac(system, Eigen::VectorXd::Zero(system.size()), grid, {x}, options);
  EXPECT_FALSE(cut.status.ok());
  EXPECT_TRUE(cut.status.cancelled()) << cut.status.message;
  EXPECT_EQ(stopping.reports.size(), 10u);  // stopped at the 10th report
  EXPECT_EQ(cut.values[0].size(), 8u);      // after 8 frequencies (one report is the set-up)

  // The pole-residue form is one step (every frequency at once): the set-up, then the poles.
  RecordingProgress modal;
  options.method = AcMethod::pole_residue;
  options.progress = &modal;
  const AcResult fast = run_ac(system, Eigen::VectorXd::Zero(system.size()), grid, {x}, options);
  ASSERT_TRUE(fast.status.ok()) << fast.status.message;
  EXPECT_EQ(fast.method, Method::pole_residue);
  ASSERT_EQ(modal.reports.size(), 2u);
  EXPECT_EQ(modal.reports[1].what, "AC: poles and residues");
  RecordingProgress stop_at_poles(2);
  options.progress = &stop_at_poles;
  const AcResult stopped = run_ac(system, Eigen::VectorXd::Zero(system.size()), grid, {x}, options);
  EXPECT_TRUE(stopped.status.cancelled()) << stopped.status.message;
}

TEST(ProgressHooks, TransientsReportOutputTimesAndStopWhenCancelled) {
  const Scene scene = read_scene(kFishfin, {"drive.electrical_dynamics=false"});
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  TransientOptions options;
  options.end_time = 2 / scene.drive.frequency;
  for (int k = 0; k <= 200; ++k) options.output_times.push_back(options.end_time * k / 200);
  for (const bool exact : {false, true}) {
    RecordingProgress all;
    options.progress = &all;
    const TransientResult full = exact ? run_transient_exact(system, model.probes, options)
                                       : run_transient_ida(system, model.probes, options);
    ASSERT_TRUE(full.status.ok()) << full.status.message;
    ASSERT_FALSE(all.reports.empty());
    EXPECT_EQ(all.reports.back().done, 201) << exact;
    EXPECT_EQ(all.reports.back().total, 201) << exact;
    RecordingProgress stopping(20);
    options.progress = &stopping;
    const TransientResult cut = exact ? run_transient_exact(system, model.probes, options)
                                      : run_transient_ida(system, model.probes, options);
    EXPECT_TRUE(cut.status.cancelled()) << exact << ": " << cut.status.message;
    EXPECT_LT(cut.times.size(), full.times.size()) << exact;
  }
}

TEST(ProgressHooks, ShootingAndSensitivityStopWhenCancelled) {
  const Scene scene = read_scene(kFishfin, {"drive.electrical_dynamics=false"});
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  RecordingProgress cancelled_at_once(-1);  // cancelled() true from the start
  const PeriodicResult shooting =
      run_periodic_shooting(system, model.probes, 0.2, 1e-8, 64, &cancelled_at_once);
  EXPECT_FALSE(shooting.status.ok());
  EXPECT_TRUE(shooting.status.cancelled()) << shooting.status.message;

  RecordingProgress stopping(2);
  SensitivityOptions options;
  options.progress = &stopping;
  const SensitivityResult sensitivity = run_sensitivity(scene, {}, options);
  EXPECT_TRUE(sensitivity.status.cancelled()) << sensitivity.status.message;
  EXPECT_EQ(sensitivity.parameters.size(), 1u);  // the first done, stopped before the second

  RecordingProgress newton(-1);
  StaticOptions static_options;
  static_options.progress = &newton;
  EXPECT_TRUE(solve_static(system, static_options).status.cancelled());
  // A cancellation keeps its code through the steps that add their context to a message (the
  // operating point's "static operating point: "), so that no front-end compares messages.
  OperatingPointOptions point_options;
  point_options.static_options.progress = &newton;
  const OperatingPoint point = operating_point(system, point_options);
  EXPECT_TRUE(point.status.cancelled()) << point.status.message;
  EXPECT_EQ(point.status.message, "static operating point: cancelled");
}

// The residual limit is inclusive: 1e-8 passes, anything above or not finite fails and says so.
TEST(ResidualLimit, AboveOrNotFiniteIsAFailure) {
  EXPECT_TRUE(check_residual(0.0, "x").ok());
  EXPECT_TRUE(check_residual(1e-8, "x").ok());
  const Status above = check_residual(2e-8, "the AC solve");
  EXPECT_FALSE(above.ok());
  EXPECT_NE(above.message.find("the AC solve: relative residual 2e-08"), std::string::npos)
      << above.message;
  EXPECT_NE(above.message.find("at most 1e-8"), std::string::npos) << above.message;
  // An integrator's result is held to its own limit (shooting: 1000 times its rtol).
  EXPECT_TRUE(check_residual(2e-8, "shooting", 1e-6).ok());
  const Status above_own = check_residual(2e-6, "shooting", 1e-6);
  EXPECT_FALSE(above_own.ok());
  EXPECT_NE(above_own.message.find("at most 1e-6"), std::string::npos) << above_own.message;
  EXPECT_FALSE(check_residual(std::numeric_limits<double>::infinity(), "x").ok());
  EXPECT_FALSE(check_residual(std::numeric_limits<double>::quiet_NaN(), "x").ok());
}

// A static solve whose residual is not small (a bending stiffness of 1e-308 N·m²: the system
// is beyond double precision) is a failed Status; it was a result with "relative residual inf".
TEST(ResidualLimit, StaticSolveBeyondDoublePrecisionFails) {
  const Scene scene = read_scene(kFishfin, {"beam.bending_stiffness=1e-300"});  // normal, overflows
  const Model model = build_model(scene);  // the System refers to the model's elements
  const StaticResult rest = solve_static(model.network.assemble());
  EXPECT_FALSE(rest.status.ok());
  EXPECT_NE(rest.status.message.find("relative residual"), std::string::npos)
      << rest.status.message;
}

}  // namespace
}  // namespace emnet
