// The beam's deformed shape (emnet/model/deformed_shape.hpp) from the switching sweep's periodic
// state at its peak, and `sweep-switching --shape` (CSV, picture, animation).
//
// References: the periodic state's own tip probe at the same instants (the shape carries the
// right node at the right instant); with large kinematics each chord keeps its length to its
// axial strain (the co-rotational segment's definition), so the shape's polyline is as long as
// the beam.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/switching_sweep.hpp"
#include "emnet/studies/transient_study.hpp"
#include "file_contents.hpp"
#include "gnuplot_on_path.hpp"
#include "shipped_scenes.hpp"
#include "test_directory.hpp"

namespace emnet {
namespace {

SwitchingSweepResult fin_sweep_with_shape(const std::vector<std::string>& overrides, int instants) {
  const SweptModel swept =
      prepare_swept_model(read_scene(testing::kFishfin, overrides), SwitchingSweepMethod::automatic,
                          {}, PrepareOptions{}, 6.5);
  SwitchingSweepOptions options;
  options.frequencies = {6.3, 6.4, 6.5};
  options.outputs = switching_sweep_outputs(swept.model, {"tip"});
  options.first_mode = false;
  options.shape_instants = instants;
  return run_switching_sweep(swept.model, swept.scene, options);
}

// Small kinematics: x stays the undeformed position, y at the tip is the periodic state's tip
// deflection at each instant t = T·s/16 (the exact method, the same solve: to rounding).
TEST(DeformedShape, SmallKinematicsIsEachNodesDeflectionOverThePeriodAtTheSweepPeak) {
  const std::vector<std::string> overrides = {"drive.electrical_dynamics=false"};
  const SwitchingSweepResult sweep = fin_sweep_with_shape(overrides, 16);
  ASSERT_TRUE(sweep.status.ok()) << sweep.status.message;
  ASSERT_TRUE(sweep.shape.has_value());
  const DeformedShape& shape = *sweep.shape;
  EXPECT_DOUBLE_EQ(shape.frequency, 6.4);
  ASSERT_EQ(shape.times.size(), 16u);
  ASSERT_EQ(shape.reference_x.size(), 8u);  // 7 segments
  const Model model = prepare_model(
      read_scene(testing::kFishfin, {"drive.electrical_dynamics=false", "drive.frequency=6.4 Hz"}));
  const System system = model.network.assemble();
  const PeriodicResult tip =
      PeriodicSolver(system).solve(system, switching_sweep_outputs(model, {"tip"}), 1.0 / 6.4, 16);
  ASSERT_TRUE(tip.status.ok()) << tip.status.message;
  double largest = 0.0;
  for (size_t t = 0; t < 16; ++t) {
    EXPECT_EQ(shape.x[t], shape.reference_x);
    EXPECT_EQ(shape.y[t][0], 0.0);  // the clamp
    EXPECT_NEAR(shape.y[t].back(), tip.values[0][t], 1e-12 * std::abs(sweep.peak_right));
    largest = std::max(largest, std::abs(shape.y[t].back()));
  }
  EXPECT_LE(largest, sweep.peak_right * (1 + 1e-12));
  EXPECT_GT(largest, 0.9 * sweep.peak_right);
}

// Large kinematics: the tip moves toward the clamp as it swings (13 mm of 122.5 mm), and every
// chord keeps its length l to its axial strain (EA = 200 kN: below 1e-6).
TEST(DeformedShape, LargeKinematicsChordsKeepTheirLength) {
  const SwitchingSweepResult sweep = fin_sweep_with_shape(
      {"drive.electrical_dynamics=false", "beam.kinematics=large", "beam.axial_stiffness=200 kN"},
      8);
  ASSERT_TRUE(sweep.status.ok()) << sweep.status.message;
  ASSERT_TRUE(sweep.shape.has_value());
  const DeformedShape& shape = *sweep.shape;
  double shortest_tip_x = shape.reference_x.back();
  for (size_t t = 0; t < shape.times.size(); ++t) {
    for (size_t k = 1; k < shape.reference_x.size(); ++k) {
      const double l = shape.reference_x[k] - shape.reference_x[k - 1];
      const double chord =
          std::hypot(shape.x[t][k] - shape.x[t][k - 1], shape.y[t][k] - shape.y[t][k - 1]);
      EXPECT_NEAR(chord, l, 1e-6 * l) << "instant " << t << ", segment " << k;
    }
    shortest_tip_x = std::min(shortest_tip_x, shape.x[t].back());
  }
  EXPECT_LT(shortest_tip_x, shape.reference_x.back() - 1e-4);
}

// tran: the shape at 4 of the last period's 16 output times; the tip's y there is the transient's
// own tip output at those times (the same run).
TEST(DeformedShape, TransientShapeIsTheLastPeriodsOutputs) {
  TransientStudyOptions options;
  options.periods = 2;
  options.points_per_period = 16;
  options.method = TransientMethod::exact;
  options.outputs = {"tip"};
  options.shape_instants = 4;
  const TransientStudyResult study = run_transient_study(
      read_scene(testing::kFishfin, {"drive.electrical_dynamics=false"}), options);
  ASSERT_TRUE(study.status.ok()) << study.status.message;
  ASSERT_TRUE(study.shape.has_value());
  const DeformedShape& shape = *study.shape;
  ASSERT_EQ(shape.times.size(), 4u);
  ASSERT_EQ(study.result.values.size(), 1u);  // the shape's probes are not among the outputs
  const double period = 1.0 / study.frequency_hz;
  for (size_t t = 0; t < 4; ++t) {
    EXPECT_GT(shape.times[t], study.end_time - period);
    EXPECT_LE(shape.times[t], study.end_time);
    const auto at = std::find(study.result.times.begin(), study.result.times.end(), shape.times[t]);
    ASSERT_NE(at, study.result.times.end());
    EXPECT_EQ(shape.y[t].back(), study.result.values[0][at - study.result.times.begin()]);
  }
  options.shape_instants = 17;
  EXPECT_THROW(options.validate(), OptionError);
}

class CliShape : public testing::TestDirectory {
 protected:
  CliShape() : TestDirectory("emnet_shape_") {}
};

// --shape writes a CSV (one row per instant and node), a picture and an animation; it is in the
// JSON; a wrong extension and --shape-instants alone are refused naming the option.
TEST_F(CliShape, WritesTheShapeAsCsvPictureAndAnimation) {
  const std::string sweep = "sweep-switching " + testing::kFishfin + " --from 6.4 --to 6.4 ";
  const auto csv = testing::run_emnet(sweep + "--shape " + path("s.csv") + " --shape-instants 4");
  ASSERT_EQ(csv.status, 5) << csv.err;  // the small model's fin is outside its validity
  EXPECT_NE(csv.out.find("shape written to"), std::string::npos) << csv.out;
  const std::string table = testing::file_contents(path("s.csv"));
  EXPECT_EQ(table.rfind("time_s,node,reference_x_m,x_m,y_m\n", 0), 0u) << table;
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 1 + 4 * 8);
  const auto json = testing::run_emnet(sweep + "--json --shape " + path("j.csv"));
  ASSERT_EQ(json.status, 5) << json.err;
  const nlohmann::json parsed = nlohmann::json::parse(json.out);
  EXPECT_EQ(parsed["shape"]["times_s"].size(), 8u);
  EXPECT_EQ(parsed["shape"]["y_m"][0].size(), 8u);
  const auto wrong = testing::run_emnet(sweep + "--shape " + path("s.txt"));
  EXPECT_EQ(wrong.status, 2);
  EXPECT_NE(wrong.err.find("--shape"), std::string::npos) << wrong.err;
  const auto tran = testing::run_emnet("tran " + testing::kFishfin + " --periods 1 --shape " +
                                       path("t.csv") + " --shape-instants 4");
  ASSERT_EQ(tran.status, 0) << tran.err;
  const std::string tran_table = testing::file_contents(path("t.csv"));
  EXPECT_EQ(std::count(tran_table.begin(), tran_table.end(), '\n'), 1 + 4 * 8);
  const auto too_many = testing::run_emnet("tran " + testing::kFishfin + " --periods 1 --shape " +
                                           path("t.csv") + " --shape-instants 500");
  EXPECT_EQ(too_many.status, 2);
  EXPECT_NE(too_many.err.find("--shape-instants"), std::string::npos) << too_many.err;
  const auto alone = testing::run_emnet(sweep + "--shape-instants 5");
  EXPECT_EQ(alone.status, 2);
  EXPECT_NE(alone.err.find("--shape"), std::string::npos) << alone.err;
  if (!testing::gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const auto gif = testing::run_emnet(sweep + "--shape " + path("s.gif"));
  ASSERT_EQ(gif.status, 5) << gif.err;
  EXPECT_EQ(testing::file_contents(path("s.gif")).rfind("GIF89a", 0), 0u);
  const auto png = testing::run_emnet(sweep + "--shape " + path("s.png"));
  ASSERT_EQ(png.status, 5) << png.err;
  EXPECT_TRUE(std::filesystem::file_size(path("s.png")) > 1000);
}

}  // namespace
}  // namespace emnet
