// The switching frequency of a circuit-driven scene (emnet/model/drive.hpp
// set_switching_frequency) and the switching sweep over the circuit's periodic sources
// (emnet/studies/switching_sweep.hpp), on netlists/tweezer-jaw.toml: two 8 Hz square sources,
// the bottom one inverted, each behind 4.7 MOhm and its DEA's RC loop (a nonlinear network whose
// only nonlinearity is the DEAs' force: the exact cascade, or shooting when asked).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/model/drive.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/switching_sweep.hpp"
#include "emnet/studies/transient_study.hpp"

namespace emnet {
namespace {

Scene tweezer(std::vector<std::string> overrides = {}) {
  return read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/tweezer-jaw.toml", overrides);
}

const CircuitSpec& element(const Scene& scene, const std::string& name) {
  return *std::find_if(scene.circuit.begin(), scene.circuit.end(),
                       [&](const CircuitSpec& c) { return c.name == name; });
}

// Reference: the definition (every periodic source at F, levels, duty and rise kept, the delay
// the same fraction of the period). Exact arithmetic on a few doubles: tolerance 1e-15 relative.
TEST(CircuitSweep, SwitchingFrequencySetsEverySourceKeepingItsShape) {
  Scene scene = tweezer({"circuit.src_B.delay=31.25 ms"});  // a quarter of the 8 Hz period
  set_switching_frequency(scene, 20.0);
  EXPECT_EQ(scene.drive.frequency, 20.0);
  const WaveformSpec& a = element(scene, "src_A").waveform;
  const WaveformSpec& b = element(scene, "src_B").waveform;
  EXPECT_EQ(a.frequency, 20.0);
  EXPECT_EQ(b.frequency, 20.0);
  EXPECT_EQ(b.low, 2500.0);  // inverted source stays inverted
  EXPECT_EQ(b.high, 0.0);
  EXPECT_EQ(a.duty, 0.5);
  EXPECT_NEAR(b.delay, 0.25 / 20.0, 1e-15 * 0.0125);  // a quarter of the 20 Hz period

  Scene only_a = tweezer();
  set_switching_frequency(only_a, 20.0, {"src_A"});
  EXPECT_EQ(element(only_a, "src_A").waveform.frequency, 20.0);
  EXPECT_EQ(element(only_a, "src_B").waveform.frequency, 8.0);
}

// A named element that is no source, or a scene with nothing that switches, is refused by the
// scene key "circuit" (no silent run).
TEST(CircuitSweep, ANamedNonSourceIsRefusedByTheCircuitKey) {
  const Scene scene = tweezer();
  EXPECT_NO_THROW(check_swept_drive(scene));
  try {
    check_swept_drive(scene, {"R_A"});
    FAIL() << "accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("circuit"), std::string::npos) << error.what();
  }
}

// The transient's switching_hz switches the circuit's sources: the tran at 20 Hz equals, to
// rounding, the tran of the scene with its sources and drive set to 20 Hz by overrides (an
// independent route through the scene reader). Before, the sources kept 8 Hz.
TEST(CircuitSweep, TransientSwitchingSetsTheCircuitSources) {
  TransientStudyOptions options;
  options.periods = 2.0;
  options.points_per_period = 50;
  options.switching_hz = 20.0;
  const TransientStudyResult switched = run_transient_study(tweezer(), options);
  options.switching_hz.reset();
  const TransientStudyResult set =
      run_transient_study(tweezer({"drive.frequency=20 Hz", "circuit.src_A.frequency=20 Hz",
                                   "circuit.src_B.frequency=20 Hz"}),
                          options);
  ASSERT_TRUE(switched.status.ok() && set.status.ok());
  ASSERT_EQ(switched.result.values.size(), set.result.values.size());
  for (size_t p = 0; p < set.result.values.size(); ++p)
    for (size_t k = 0; k < set.result.values[p].size(); ++k)
      EXPECT_EQ(switched.result.values[p][k], set.result.values[p][k]);
}

// Shooting's Jacobian costs one IDA period per state (35 segments: 50 s per frequency); the
// sweep's route through the scene is the same on 8 segments.
const char* const kCoarse = "beam.segments=8";

// The sweep at 12 Hz, by the automatic choice (the exact cascade) and by shooting, against the
// periodic state of the scene whose sources and drive were set to 12 Hz by overrides (the
// independent route, through the scene reader), solved by the same method on its own model
// (the cascade itself is checked against shooting and a settled transient in
// PeriodicCascade.*). Tolerance 1e-9 of the peak-to-peak: the same computation on the same
// network, to its rounding (shooting's Newton iteration stops at its noise); a source left at
// 8 Hz changes the extremes by far more.
TEST(CircuitSweep, SweepMatchesThePeriodicStateOfTheSetScene) {
  const SweptModel swept =
      prepare_swept_model(tweezer({kCoarse}), SwitchingSweepMethod::automatic, {"tip"}, {}, 12.0);
  SwitchingSweepOptions sweep;
  sweep.frequencies = {12.0};
  sweep.outputs = switching_sweep_outputs(swept.model, {"tip"});
  sweep.first_mode = false;
  const SwitchingSweepResult result = run_switching_sweep(swept.model, swept.scene, sweep);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.method, Method::exact);  // the automatic choice: the DEAs' force, a cascade
  sweep.method = SwitchingSweepMethod::shooting;
  const SwitchingSweepResult shot = run_switching_sweep(swept.model, swept.scene, sweep);
  ASSERT_TRUE(shot.status.ok()) << shot.status.message;
  EXPECT_EQ(shot.method, Method::shooting);

  const Model set =
      prepare_model(tweezer({kCoarse, "drive.frequency=12 Hz", "circuit.src_A.frequency=12 Hz",
                             "circuit.src_B.frequency=12 Hz"}));
  const System set_system = set.network.assemble();
  const PeriodicResult exact =
      PeriodicSolver(set_system).solve(set_system, sweep.outputs, 1.0 / 12.0, 64);
  ASSERT_TRUE(exact.status.ok()) << exact.status.message;
  const PeriodicResult reference =
      run_periodic_shooting(set_system, sweep.outputs, 1.0 / 12.0, sweep.rtol, 256);
  ASSERT_TRUE(reference.status.ok()) << reference.status.message;
  const double swing = reference.maximum[0] - reference.minimum[0];
  ASSERT_GT(swing, 0.0);
  EXPECT_NEAR(result.outputs[0].left[0], exact.minimum[0], 1e-9 * swing);
  EXPECT_NEAR(result.outputs[0].right[0], exact.maximum[0], 1e-9 * swing);
  EXPECT_NEAR(shot.outputs[0].left[0], reference.minimum[0], 1e-9 * swing);
  EXPECT_NEAR(shot.outputs[0].right[0], reference.maximum[0], 1e-9 * swing);

  const Model unswitched = prepare_model(tweezer({kCoarse}));
  const PeriodicResult at_8_hz =
      run_periodic_shooting(unswitched.network.assemble(), sweep.outputs, 1.0 / 8.0, 1e-9, 256);
  EXPECT_GT(std::abs(at_8_hz.maximum[0] - reference.maximum[0]), 1e-3 * swing)
      << "the 12 Hz sources make a difference the test can see";
}

// The device as a user writes it, through the commands: `sweep-switching` chose the exact
// cascade and switched both sources (it refused drive.kind = "none" before), and `study` sweeps
// a variant the same way (its 12 Hz state, the nominal resistance, equals the single sweep's:
// the same computation, 1e-12 relative).
TEST(CliCircuitSweep, TweezerSweepAndStudyRunThroughTheCircuitSources) {
  const std::string scene = std::string(EMNET_SOURCE_DIR) + "/netlists/tweezer-jaw.toml";
  const auto sweep = testing::run_emnet("sweep-switching " + scene +
                                        " --segments 8 --from 12 --to 12 --step 1 --json");
  ASSERT_EQ(sweep.status, 0) << sweep.err;
  const nlohmann::json json = nlohmann::json::parse(sweep.out);
  EXPECT_EQ(json["method"], "exact");
  bool switched_note = false;
  for (const auto& note : json["notes"])
    switched_note |=
        note.get<std::string>().find("circuit's periodic sources") != std::string::npos;
  EXPECT_TRUE(switched_note) << json["notes"].dump();

  const std::string table = ::testing::TempDir() + "tweezer_study.json";
  const auto study = testing::run_emnet(
      "study " + scene +
      " --segments 8 --vary circuit.R_A.value=4.7MOhm --analysis sweep-switching --from 12 "
      "--to 12 --step 1 --at 12 --threads 1 --quiet -o " +
      table);
  ASSERT_EQ(study.status, 0) << study.err;
  std::ifstream file(table);
  const nlohmann::json rows = nlohmann::json::parse(file);
  ASSERT_TRUE(rows.contains("rows")) << rows.dump().substr(0, 400);
  ASSERT_EQ(rows["rows"].size(), 1u);
  const double nominal_right = json["outputs"][0]["right"][0];
  bool found = false;
  for (const auto& [column, value] : rows["rows"][0]["results"].items())
    if (column.find("tip.max_at_12Hz") != std::string::npos) {
      found = true;
      EXPECT_NEAR(value.get<double>(), nominal_right, 1e-12 * std::abs(nominal_right));
    }
  EXPECT_TRUE(found) << rows["rows"][0].dump();
}

}  // namespace
}  // namespace emnet
