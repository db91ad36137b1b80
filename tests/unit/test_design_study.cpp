// Design studies (emnet/studies/design_study.hpp): variation specs, grids and Monte Carlo draws,
// CSV lists, failed variants as rows, and results independent of the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/report/design_study.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/design_study.hpp"
#include "emnet/studies/resolve.hpp"
#include "fixtures.hpp"
#include "test_directory.hpp"

namespace emnet {
namespace {

class DesignStudyFiles : public testing::TestDirectory {
 protected:
  DesignStudyFiles() : TestDirectory("emnet_design_study_") {}
};

Scene cantilever_with_load() {
  Scene scene = testing::cantilever_scene(10);
  scene.loads.push_back(testing::load(LoadKind::force, 0.5, 1.0));
  scene.probes.push_back(testing::beam_probe("tip", ProbeQuantity::deflection, 0.5));
  return scene;
}

TEST(DesignStudy, ValuesUnitsAndPercentages) {
  const Scene scene = cantilever_with_load();
  const Variation list = parse_variation(scene, "beam.bending_stiffness=1, 2 N*m^2, 150%");
  EXPECT_EQ(list.key, "beam.bending_stiffness");
  EXPECT_EQ(list.values, (std::vector<double>{1.0, 2.0, 3.0}));  // 150 % of 2 N*m^2
  const Variation grid = parse_variation(scene, "beam.length=linspace(0.4,0.6,3)");
  ASSERT_EQ(grid.values.size(), 3u);
  EXPECT_DOUBLE_EQ(grid.values[1], 0.5);
  EXPECT_EQ(grid.values[2], 0.6);  // the end is the end, not a sum of steps
  const Variation log = parse_variation(scene, "beam.mass_per_length=logspace(0.1,10,3)");
  EXPECT_NEAR(log.values[1], 1.0, 1e-15);
  const Variation normal = parse_variation(scene, "beam.bending_stiffness=normal(100%,5%)");
  EXPECT_EQ(normal.kind, VariationKind::normal);
  EXPECT_EQ(normal.first, 2.0);
  EXPECT_DOUBLE_EQ(normal.second, 0.1);
  const Variation millimetres = parse_variation(scene, "beam.length=uniform(400 mm,0.6)");
  EXPECT_DOUBLE_EQ(millimetres.first, 0.4);
}

TEST(DesignStudy, BadSpecsNameTheKey) {
  const Scene scene = cantilever_with_load();
  for (const char* text : {"beam.bending_stiffness=gauss(1,2)", "beam.bending_stiffness=",
                           "beam.bending_stiffness=uniform(2,1)", "beam.length=3 V",
                           "beam.nothing=1", "beam.left=1", "beam.length=linspace(1,2,0)"}) {
    try {
      parse_variation(scene, text);
      ADD_FAILURE() << text << " was accepted";
    } catch (const OptionError& error) {
      EXPECT_EQ(error.field(), "variations") << text;
      EXPECT_EQ(error.where(), "variations") << text;
      EXPECT_NE(std::string(error.what()).find("beam."), std::string::npos) << error.what();
    }
  }
}

TEST(DesignStudy, GridIsCartesianLastKeyFastest) {
  const Scene scene = cantilever_with_load();
  const VariantTable table =
      make_variants({parse_variation(scene, "beam.bending_stiffness=1,2"),
                     parse_variation(scene, "beam.mass_per_length=0.1,0.2,0.3")},
                    0, 1);
  ASSERT_EQ(table.rows.size(), 6u);
  EXPECT_EQ(table.rows[0], (std::vector<double>{1.0, 0.1}));
  EXPECT_EQ(table.rows[2], (std::vector<double>{1.0, 0.3}));
  EXPECT_EQ(table.rows[3], (std::vector<double>{2.0, 0.1}));
}

TEST(DesignStudy, MonteCarloFollowsItsSeedAndItsDistribution) {
  const Scene scene = cantilever_with_load();
  const std::vector<Variation> vary{
      parse_variation(scene, "beam.bending_stiffness=normal(2,0.1)"),
      parse_variation(scene, "beam.mass_per_length=uniform(0.2,0.4)")};
  const VariantTable a = make_variants(vary, 4000, 42), b = make_variants(vary, 4000, 42),
                     c = make_variants(vary, 4000, 43);
  EXPECT_EQ(a.rows, b.rows);
  EXPECT_NE(a.rows, c.rows);
  double sum = 0.0, squares = 0.0;
  for (const auto& row : a.rows) {
    sum += row[0];
    squares += row[0] * row[0];
    EXPECT_GE(row[1], 0.2);
    EXPECT_LE(row[1], 0.4);
  }
  const double mean = sum / 4000.0, sd = std::sqrt(squares / 4000.0 - mean * mean);
  // Sample mean and sd of 4000 normal draws: within 5 standard errors (0.1/sqrt(4000) for the
  // mean, 0.1/sqrt(2*4000) for the sd) of the distribution's.
  EXPECT_NEAR(mean, 2.0, 5 * 0.1 / std::sqrt(4000.0));
  EXPECT_NEAR(sd, 0.1, 5 * 0.1 / std::sqrt(8000.0));
  try {
    make_variants(vary, 0, 1);  // random without samples
    ADD_FAILURE() << "random variations without samples were accepted";
  } catch (const OptionError& error) {
    EXPECT_EQ(error.field(), "samples");
    EXPECT_STREQ(error.what(),
                 "samples: key 'samples': a random variation (uniform, normal, lognormal) needs "
                 "samples N");
    EXPECT_EQ(error.message_with([](const std::string& field) { return "--" + field; }),
              "--samples: key '--samples': a random variation (uniform, normal, lognormal) "
              "needs --samples N");
  }
  EXPECT_THROW(make_variants({parse_variation(scene, "beam.length=0.4,0.5")}, 3, 1),
               InputError);  // samples without a random variation
}

TEST(DesignStudy, LinkedKeysChangeByTheSameRatio) {
  Scene scene = cantilever_with_load();
  scene.beam.rotary_inertia_per_length = 1e-4;
  const Variation linked =
      parse_variation(scene, "beam.mass_per_length+beam.rotary_inertia_per_length=0.6");
  const VariantTable table = make_variants({linked}, 0, 1);
  ASSERT_EQ(table.keys.size(), 2u);
  EXPECT_EQ(table.keys[1], "beam.rotary_inertia_per_length");
  EXPECT_DOUBLE_EQ(table.rows[0][1], 2e-4);  // the mass per length doubled: so does ρI
}

TEST_F(DesignStudyFiles, VariantsFromCsv) {
  const Scene scene = cantilever_with_load();
  const std::string file = path("variants.csv");
  std::ofstream(file) << "# a comment\nbeam.bending_stiffness;beam.length\n1;0.5\n3 N*m^2;90%\n";
  const VariantTable table = read_variants_csv(scene, file);
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.rows[1][0], 3.0);
  EXPECT_DOUBLE_EQ(table.rows[1][1], 0.45);
  std::ofstream(file) << "beam.bending_stiffness,beam.length\n1,0.5\n2\n";
  try {
    read_variants_csv(scene, file);
    ADD_FAILURE() << "a short line was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(error.where().find("variants.csv:3"), std::string::npos) << error.what();
  }
}

// Reference: the same analysis run on a scene changed by set_parameter, and the closed form
// F·L³/(3·EI) of the static tip deflection (nodal statics are exact for any N: rounding only).
TEST(DesignStudy, RowsAreTheAnalysesOfEachVariantWhateverTheThreads) {
  const Scene scene = cantilever_with_load();
  const VariantTable table =
      make_variants({parse_variation(scene, "beam.bending_stiffness=uniform(1,3)")}, 24, 5);
  DesignStudyOptions options;
  options.analyses = {StudyAnalysis::modes, StudyAnalysis::static_state};
  options.mode_count = 2;
  options.threads = 1;
  const DesignStudyResult one = run_design_study(scene, table, options);
  options.threads = 3;
  const DesignStudyResult three = run_design_study(scene, table, options);
  ASSERT_EQ(one.columns, (std::vector<std::string>{"f1_hz", "zeta1", "f1_error_hz", "f2_hz",
                                                   "zeta2", "f2_error_hz", "static.tip_m"}));
  ASSERT_EQ(one.rows.size(), 24u);
  for (size_t i = 0; i < one.rows.size(); ++i) {
    ASSERT_TRUE(one.rows[i].status.ok()) << one.rows[i].status.message;
    EXPECT_EQ(one.rows[i].values, three.rows[i].values);  // bit for bit
    const double stiffness = table.rows[i][0];
    EXPECT_NEAR(one.rows[i].values[6], 0.125 / (3 * stiffness), 1e-14);
    Scene variant = scene;
    set_parameter(variant, "beam.bending_stiffness", stiffness);
    const Model model = prepare_model(variant);
    const System system = model.network.assemble();
    ModalOptions modal;
    modal.count = 2;
    const ModalResult modes =
        run_modes(system, operating_point(system).rest.operating_point, modal);
    EXPECT_EQ(one.rows[i].values[0], modes.modes[0].frequency_hz);
    EXPECT_EQ(one.rows[i].values[3], modes.modes[1].frequency_hz);
  }
  EXPECT_EQ(one.failed, 0u);
}

// The cantilever's tip deflection under 1 N, F·L³/(3EI): 20.8 mm at EI = 2 N·m² (4.2 % of the
// 0.5 m beam, within the 10 % default limit), 83.3 mm at EI = 0.5 (16.7 %, outside).
TEST(DesignStudy, AVariantOutsideTheModelsValidityIsFlagged) {
  const Scene scene = cantilever_with_load();
  VariantTable table;
  table.keys = {"beam.bending_stiffness"};
  table.rows = {{2.0}, {0.5}};
  DesignStudyOptions options;
  options.analyses = {StudyAnalysis::static_state};
  const DesignStudyResult result = run_design_study(scene, table, options);
  ASSERT_TRUE(result.rows[0].status.ok() && result.rows[1].status.ok());
  EXPECT_TRUE(result.rows[0].validity.within());
  EXPECT_FALSE(result.rows[1].validity.within());
  EXPECT_EQ(result.outside_validity, 1u);
  EXPECT_EQ(validity_text(result.rows[0]), "within");
  EXPECT_EQ(validity_text(result.rows[1]).rfind("OUTSIDE: ", 0), 0u);
  EXPECT_NE(validity_text(result.rows[1]).find("model.deflection_limit"), std::string::npos)
      << validity_text(result.rows[1]);
}

TEST_F(DesignStudyFiles, AFailingVariantIsARowWithItsReason) {
  const Scene scene = cantilever_with_load();
  VariantTable table;
  table.keys = {"beam.bending_stiffness"};
  table.rows = {{2.0}, {-1.0}, {3.0}};
  DesignStudyOptions options;
  const DesignStudyResult result = run_design_study(scene, table, options);
  ASSERT_EQ(result.rows.size(), 3u);
  EXPECT_TRUE(result.rows[0].status.ok());
  EXPECT_FALSE(result.rows[1].status.ok());
  EXPECT_NE(result.rows[1].status.message.find("beam.bending_stiffness"), std::string::npos);
  EXPECT_TRUE(result.rows[1].values.empty());
  EXPECT_TRUE(result.rows[2].status.ok());
  EXPECT_EQ(result.failed, 1u);
  // The CSV: the failed row's results empty, its reason quoted when it holds a comma.
  const std::string file = path("study.csv");
  ASSERT_TRUE(write_design_study_csv(file, result).ok());
  std::ifstream in(file);
  std::string header, first, second;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(header, "variant,beam.bending_stiffness,status,validity,f1_hz,zeta1,f1_error_hz");
  EXPECT_NE(first.find(",ok,within,"), std::string::npos) << first;
  EXPECT_EQ(second.substr(0, 9), "1,-1,\"fai");
  EXPECT_EQ(second.substr(second.size() - 4), ",,,,");  // no validity, no results
}

// A key no variant can set was a study of failed rows with exit 0 (the tweezer jaw's
// beam.bending_stiffness, which its [[section]]s set): refused before the run, naming the key and
// the reason.
TEST(DesignStudy, AKeyNoVariantCanSetIsRefusedBeforeTheRun) {
  const Scene tweezer = read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/tweezer-jaw.toml");
  VariantTable table;
  table.keys = {"beam.bending_stiffness"};
  table.rows = {{1e-3}, {2e-3}};
  try {
    run_design_study(tweezer, table, DesignStudyOptions{});
    FAIL() << "accepted";
  } catch (const OptionError& error) {
    EXPECT_EQ(error.field(), "variations");
    EXPECT_EQ(error.key(), "beam.bending_stiffness");
    EXPECT_NE(std::string(error.what()).find("section[].bending_stiffness"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace emnet
