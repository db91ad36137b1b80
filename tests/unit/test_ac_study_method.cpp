// The AC study's choice of method (AcSweepMethod, studies/ac_study.hpp): the automatic method
// reduces a large network's long sweep only where its check against the full model meets the
// tolerance, and says so; the full model otherwise. Reference throughout: the same study on the
// full model (run_ac at every frequency, its residuals ~1e-12).
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/model/model.hpp"
#include "emnet/report/ac_json.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/ac_study.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

// The fish fin at N = 400: 2406 unknowns, above kAcReductionUnknowns.
struct LargeFin {
  Model model;
  System system;
  Eigen::VectorXd rest;
};

LargeFin large_fin() {
  LargeFin fin{build_model(read_scene(testing::kFishfin, {"beam.segments=400"})), {}, {}};
  fin.system = fin.model.network.assemble();
  const StaticResult rest = solve_static(fin.system);
  EXPECT_TRUE(rest.status.ok()) << rest.status.message;
  fin.rest = rest.operating_point;
  return fin;
}

AcStudyOptions sweep_of(const Model& model, int points, AcSweepMethod method) {
  AcStudyOptions options;
  options.sweep = model.scene.ac;
  options.sweep.points = points;
  options.probes = model.probes;
  options.method = method;
  return options;
}

bool has_note(const AcStudyResult& result, const std::string& part) {
  return std::any_of(result.notes.begin(), result.notes.end(),
                     [&](const std::string& note) { return note.find(part) != std::string::npos; });
}

// 2406 unknowns and 500 frequencies: the automatic method reduces, says so, and its sweep is the
// full model's to the tolerance (1e-3 of each probe's peak, the scene's model.tolerance) at
// every frequency, not only at the check frequencies it measured.
TEST(AcStudyMethod, AutomaticReducesALargeLongSweepWithinItsTolerance) {
  ASSERT_GT(2406, kAcReductionUnknowns);
  const LargeFin fin = large_fin();
  const AcStudyResult automatic =
      run_ac_study(fin.model, fin.system, fin.rest,
                   sweep_of(fin.model, kAcReductionPoints, AcSweepMethod::automatic));
  ASSERT_TRUE(automatic.status.ok()) << automatic.status.message;
  ASSERT_TRUE(automatic.reduction.has_value());
  EXPECT_EQ(automatic.ac.method, Method::reduced);
  EXPECT_TRUE(has_note(automatic, "chosen automatically")) << automatic.notes.size();
  const AcStudyResult full =
      run_ac_study(fin.model, fin.system, fin.rest,
                   sweep_of(fin.model, kAcReductionPoints, AcSweepMethod::full));
  ASSERT_TRUE(full.status.ok()) << full.status.message;
  EXPECT_FALSE(full.reduction.has_value());
  const std::vector<double> errors = errors_relative_to_peak(automatic.ac.values, full.ac.values);
  const double tolerance = fin.model.scene.model.tolerance;
  for (size_t p = 0; p < errors.size(); ++p)
    EXPECT_LE(errors[p], tolerance) << fin.model.probes[p].name;
  // The JSON's accuracy is the measured error, not a residual the reduced sweep does not have.
  const Json json = to_json(automatic, fin.model, fin.model.probes, "input", 0.0);
  EXPECT_EQ(json["accuracy"]["method"], "reduced");
  EXPECT_LE(json["accuracy"]["measured_error"].get<double>(), tolerance);
  EXPECT_FALSE(json["accuracy"].contains("max_relative_residual"));
}

// A tolerance the reduction cannot meet (1e-12: it measures ~5e-10): the automatic method
// solves every frequency on the full model and says why; the values are the full sweep's.
TEST(AcStudyMethod, AutomaticFallsBackToTheFullModelWhenTheCheckMissesTheTolerance) {
  const LargeFin fin = large_fin();
  AcStudyOptions options = sweep_of(fin.model, kAcReductionPoints, AcSweepMethod::automatic);
  ReductionOptions reduction;
  reduction.tolerance = 1e-12;
  options.reduction = reduction;
  const AcStudyResult automatic = run_ac_study(fin.model, fin.system, fin.rest, options);
  ASSERT_TRUE(automatic.status.ok()) << automatic.status.message;
  EXPECT_FALSE(automatic.reduction.has_value());
  EXPECT_NE(automatic.ac.method, Method::reduced);
  EXPECT_TRUE(has_note(automatic, "every frequency was solved on the full model"));
  EXPECT_TRUE(has_note(automatic, "above its tolerance 1e-12"));
  const AcStudyResult full =
      run_ac_study(fin.model, fin.system, fin.rest,
                   sweep_of(fin.model, kAcReductionPoints, AcSweepMethod::full));
  ASSERT_TRUE(full.status.ok());
  EXPECT_EQ(automatic.ac.values, full.ac.values);
  // Asked for, the reduction is kept whatever its check finds (and reported as not met).
  options.method = AcSweepMethod::reduced;
  const AcStudyResult reduced = run_ac_study(fin.model, fin.system, fin.rest, options);
  ASSERT_TRUE(reduced.status.ok()) << reduced.status.message;
  ASSERT_TRUE(reduced.reduction.has_value());
  EXPECT_FALSE(reduced.reduction->tolerance_met);
}

// Below either threshold the automatic method is the full model's: 499 frequencies of the large
// network, or the 48-unknown fin's long sweep.
TEST(AcStudyMethod, AutomaticIsTheFullModelBelowEitherThreshold) {
  const LargeFin fin = large_fin();
  const AcStudyResult short_sweep =
      run_ac_study(fin.model, fin.system, fin.rest,
                   sweep_of(fin.model, kAcReductionPoints - 1, AcSweepMethod::automatic));
  ASSERT_TRUE(short_sweep.status.ok()) << short_sweep.status.message;
  EXPECT_FALSE(short_sweep.reduction.has_value());
  EXPECT_FALSE(has_note(short_sweep, "modal reduction"));

  const Model small = build_model(read_scene(testing::kFishfin));
  const System system = small.network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok());
  const AcStudyResult small_sweep = run_ac_study(small, system, rest.operating_point,
                                                 sweep_of(small, 2000, AcSweepMethod::automatic));
  ASSERT_TRUE(small_sweep.status.ok()) << small_sweep.status.message;
  EXPECT_FALSE(small_sweep.reduction.has_value());
}

// The command's words: --method full with reduction options, or --reduce beside --method full,
// are input errors naming the option; --method reduced is --reduce.
TEST(AcStudyMethod, CommandRefusesContradictoryMethodOptions) {
  const auto tolerance =
      testing::run_emnet("ac " + testing::kFishfin + " --method full --tolerance 1e-4 --points 3");
  EXPECT_EQ(tolerance.status, 2) << tolerance.out;
  EXPECT_NE(tolerance.err.find("--method full"), std::string::npos) << tolerance.err;
  const auto both =
      testing::run_emnet("ac " + testing::kFishfin + " --method full --reduce --points 3");
  EXPECT_EQ(both.status, 2) << both.out;
  EXPECT_NE(both.err.find("--reduce"), std::string::npos) << both.err;
  const auto reduced = testing::run_emnet("ac " + testing::kFishfin +
                                          " --method reduced --points 20 --json --quiet");
  ASSERT_EQ(reduced.status, 0) << reduced.err;
  EXPECT_NE(reduced.out.find("\"reduction\""), std::string::npos);
}

}  // namespace
}  // namespace emnet
