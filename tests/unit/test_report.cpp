// The reporting layer (emnet/report/): CSV quoting and writing, JSON of results.
//
// References: RFC 4180 (a field with a comma, quote or line break is enclosed in quotes, a quote
// in it doubled); %.12g formatting (C printf); the keys the program's --json prints (the
// command line's tests check the same keys end to end).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "emnet/report/csv.hpp"
#include "emnet/report/describe.hpp"
#include "emnet/report/identify_json.hpp"
#include "emnet/report/json.hpp"
#include "emnet/report/mismatch_json.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "fixtures.hpp"
#include "test_directory.hpp"

namespace emnet {
namespace {

class ReportTest : public testing::TestDirectory {
 protected:
  ReportTest() : TestDirectory("emnet_report_") {}
};

TEST(Csv, FieldsAreQuotedOnlyWhenRfc4180AsksForIt) {
  EXPECT_EQ(csv_field("frequency_hz"), "frequency_hz");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field("cr\r"), "\"cr\r\"");
  EXPECT_EQ(csv_field(""), "");
}

TEST_F(ReportTest, CsvIsTheQuotedHeaderThenRowsAtTwelveSignificantDigits) {
  const Status status =
      write_csv(path("table.csv"), {"mode", "x,y"}, {{1.0, 1.0 / 3.0}, {2.0, -2.5e-300}});
  ASSERT_TRUE(status.ok()) << status.message;
  // 1/3 at %.12g is 0.333333333333 (12 significant digits).
  EXPECT_EQ(contents("table.csv"), "mode,\"x,y\"\n1,0.333333333333\n2,-2.5e-300\n");
}

TEST_F(ReportTest, CsvRowsAreFilledOneByOne) {
  const Status status =
      write_csv_rows(path("rows.csv"), {"i", "square"}, 3, [](size_t i, std::vector<double>& row) {
        EXPECT_TRUE(row.empty());  // cleared for each row
        row = {double(i), double(i * i)};
      });
  ASSERT_TRUE(status.ok()) << status.message;
  EXPECT_EQ(contents("rows.csv"), "i,square\n0,0\n1,1\n2,4\n");
}

TEST_F(ReportTest, CsvToAnUnwritablePathIsAFailedStatusNamingItAndLeavesNoFile) {
  const std::string missing = path("no_such_directory/table.csv");
  const Status status = write_csv(missing, {"a"}, {{1.0}});
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message.find(missing), std::string::npos) << status.message;
  EXPECT_FALSE(std::filesystem::exists(missing));
}

// Every number in `json` is finite (nlohmann writes a NaN as null, which would hide it).
void expect_finite_numbers(const Json& json, const std::string& where) {
  if (json.is_number()) {
    EXPECT_TRUE(std::isfinite(json.get<double>())) << where;
  } else if (json.is_null()) {
    ADD_FAILURE() << "null (a NaN?) at " << where;
  } else if (json.is_structured()) {
    for (auto it = json.begin(); it != json.end(); ++it)
      expect_finite_numbers(*it, where + "/" + (json.is_object() ? it.key() : std::string("[]")));
  }
}

TEST(Json, ModesStudyHasTheProgramsKeysAndFiniteNumbers) {
  ModesStudyOptions options;
  options.count = 2;
  options.shapes = true;
  const ModesStudyResult result = run_modes_study(testing::cantilever_scene(6), options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  const Json json = to_json(result, {}, 0.25);
  std::vector<std::string> keys;
  for (auto it = json.begin(); it != json.end(); ++it) keys.push_back(it.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"scene", "automatic_choices", "segments", "modes",
                                            "real_poles", "mode_rule", "overdamped_pairs",
                                            "rigid_body_modes", "method", "complete", "pencil_size",
                                            "cost"}));
  ASSERT_EQ(json["modes"].size(), 2u);
  for (const char* key :
       {"frequency_hz", "damping_ratio", "natural_frequency_hz", "pole", "relative_residual",
        "error_bounded", "pole_error_bound", "frequency_error_bound_hz",
        "damping_ratio_error_bound", "discretisation_error_estimate", "shape"})
    EXPECT_TRUE(json["modes"][0].contains(key)) << key;
  EXPECT_EQ(json["modes"][0]["shape"].size(), 7u);  // N + 1 nodes
  EXPECT_EQ(json["segments"], 6);
  EXPECT_EQ(json["cost"]["total_seconds"], 0.25);
  expect_finite_numbers(json, "");
  // Indented by 2, as the program prints it.
  EXPECT_EQ(json_text(Json{{"a", 1}}), "{\n  \"a\": 1\n}");
}

TEST(Json, ValidityAndAutomaticChoicesHaveTheProgramsKeys) {
  Validity validity;
  validity.summary = "deflection 1% of its limit";
  validity.deflection_fraction = 0.01;
  const Json json = to_json(validity);
  EXPECT_EQ(json["status"], "within");
  EXPECT_EQ(json["violations"].size(), 0u);
  EXPECT_EQ(json["deflection_fraction_of_limit"], 0.01);
  AutomaticChoice choice;
  choice.key = "beam.segments";
  choice.value = "38";
  choice.band_from_hz = 0.0;
  choice.band_to_hz = 60.0;
  const Json choices = to_json(std::vector<AutomaticChoice>{choice});
  ASSERT_EQ(choices.size(), 1u);
  EXPECT_EQ(choices[0]["key"], "beam.segments");
  EXPECT_EQ(choices[0]["band_hz"], Json::array({0.0, 60.0}));
  expect_finite_numbers(json, "validity");
  expect_finite_numbers(choices, "automatic_choices");
}

// The keys of `json`'s object in their order.
std::vector<std::string> keys_of(const Json& json) {
  std::vector<std::string> keys;
  for (auto it = json.begin(); it != json.end(); ++it) keys.push_back(it.key());
  return keys;
}

TEST(Json, IdentifyAndMismatchHaveTheProgramsKeysInOrder) {
  IdentifyResult identified;
  identified.parameter = {"beam.bending_stiffness", "N*m^2", 2.4e-3};
  identified.achieved_hz = 5.0;
  IdentifyOptions options;
  options.target_hz = 5.0;
  const Json fit = to_json(identified, options, {{}, "emnet identify fin.toml", 0.5});
  EXPECT_EQ(keys_of(fit),
            (std::vector<std::string>{"automatic_choices", "parameter", "value", "unit", "mode",
                                      "target_hz", "achieved_hz", "iterations", "accuracy", "cost",
                                      "command", "total_seconds"}));
  options.peak = PeakTarget{"P4", 9.3e-3, 4e3};
  identified.validity = Validity{};
  const std::vector<std::string> peak_keys = keys_of(to_json(identified, options, {}));
  EXPECT_EQ(std::vector<std::string>(peak_keys.begin() + 12, peak_keys.end()),
            (std::vector<std::string>{"loss_factor", "peak_probe", "target_peak_m",
                                      "achieved_peak_m", "peak_rounds", "validity"}));
  MismatchResult mismatch;
  mismatch.rows.push_back(
      {"electrode area of A", "dea.A.electrode_width", -0.05, -1e-3, 1e-3, 0.0, 0.0});
  const Json table = to_json(mismatch, {}, 0.1);
  EXPECT_EQ(keys_of(table),
            (std::vector<std::string>{"automatic_choices", "output", "frequency_hz", "method",
                                      "nominal", "cases", "total_seconds", "validity"}));
  EXPECT_EQ(keys_of(table["nominal"]),
            (std::vector<std::string>{"left_m", "right_m", "asymmetry"}));
  EXPECT_EQ(keys_of(table["cases"][0]),
            (std::vector<std::string>{"label", "key", "change", "left_m", "right_m", "asymmetry",
                                      "asymmetry_per_unit_change"}));
}

// Sensitivity of a cantilever's f1 to EI: f ∝ √EI, so the normalised sensitivity is exactly
// 1/2 (the lumped chain's frequencies scale with √EI too, for every N); 1e-6 allows the
// matrices' central difference (relative step 1e-6, error O(1e-12)) and rounding.
TEST(Json, SensitivityHasTheProgramsKeysAndFiniteNumbers) {
  SensitivityOptions options;
  options.modes = 2;
  options.check = true;
  const Scene scene = testing::cantilever_scene(6);
  const SensitivityResult result = run_sensitivity(scene, {"beam.bending_stiffness"}, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  const Json json = to_json(result, scene, true, 0.5);
  std::vector<std::string> keys;
  for (auto it = json.begin(); it != json.end(); ++it) keys.push_back(it.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"scene", "automatic_choices", "segments", "modes",
                                            "parameters", "left_vector_residual", "cost"}));
  ASSERT_EQ(json["parameters"].size(), 1u);
  EXPECT_EQ(json["parameters"][0]["key"], "beam.bending_stiffness");
  ASSERT_EQ(json["parameters"][0]["modes"].size(), 2u);
  EXPECT_NEAR(json["parameters"][0]["modes"][0]["normalised"].get<double>(), 0.5, 1e-6);
  EXPECT_TRUE(json["parameters"][0]["modes"][0].contains("check_difference"));
  expect_finite_numbers(json, "");
  // Without the check its fields are left out.
  EXPECT_FALSE(
      to_json(result, scene, false, 0.5)["parameters"][0]["modes"][0].contains("check_difference"));
}

// The static JSON of a cantilever under a tip force F: the tip deflection is F·L³/(3·EI) (exact
// at the nodes for any N, Hermite statics; 1e-9 relative allows the solve's rounding).
TEST(Json, StaticHasTheProgramsKeysAndTheTipDeflection) {
  Scene scene = testing::cantilever_scene(4);
  scene.loads.push_back(testing::load(LoadKind::force, scene.beam.length, 0.01));
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok()) << rest.status.message;
  std::vector<std::vector<double>> nodes;
  for (double x : model.beam.x) {
    const Probe w = model.make_probe({"w", ProbeQuantity::deflection, x, ""});
    const Probe phi = model.make_probe({"phi", ProbeQuantity::rotation, x, ""});
    nodes.push_back(
        {x, static_probe_value(system, rest, w), static_probe_value(system, rest, phi)});
  }
  const Json json = to_json(model, rest, nodes, {}, {}, Validity{}, 0.125);
  std::vector<std::string> keys;
  for (auto it = json.begin(); it != json.end(); ++it) keys.push_back(it.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"scene", "automatic_choices", "segments", "nodes",
                                            "probes", "accuracy", "cost", "validity"}));
  ASSERT_EQ(json["nodes"].size(), 5u);
  const double tip = 0.01 * std::pow(scene.beam.length, 3) / (3 * scene.beam.bending_stiffness);
  EXPECT_NEAR(std::abs(json["nodes"][4]["deflection_m"].get<double>()), tip, 1e-9 * tip);
  expect_finite_numbers(json, "");
}

TEST(Describe, DriveInWords) {
  Scene scene = testing::cantilever_scene(4);
  EXPECT_EQ(drive_summary(scene), "drive none");
  EXPECT_EQ(ac_input_description(scene, 10.0),
            "AC input: the scene's loads, each with its value as amplitude.");
  // A circuit's sources are named: the gripper finger's amplifier drives it.
  const Scene finger = read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/gripper-finger.toml");
  EXPECT_EQ(drive_summary(finger), "drive none, circuit source(s) amp");
  // The plot titles' short form of the AC input.
  EXPECT_EQ(ac_input_summary(finger), "ac 1 V of circuit source amp");
  EXPECT_EQ(ac_input_summary(read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml")),
            "the antagonistic drive's force level k_F*V^2/2 as a sinusoid (V = 4000 V, DEAs A and "
            "B in antiphase)");
}

}  // namespace
}  // namespace emnet
