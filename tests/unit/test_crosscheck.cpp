// `emnet crosscheck` (include/emnet/verification/crosscheck.hpp): both checked-in scenes pass
// against ngspice with the tolerances the header justifies; a perturbed ngspice vector fails the
// report; ngspice missing gives exit status 3 with a clear message; the peak fit is exact for an
// isolated mode.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/verification/crosscheck.hpp"
#include "shipped_scenes.hpp"

namespace {

using namespace emnet;

std::string source_path(const std::string& relative) {
  return std::string(EMNET_SOURCE_DIR) + "/" + relative;
}

using emnet::testing::ngspice_available;

// The whole cross-check of the fish fin (op, ac, modal, tran at the defaults).
TEST(Crosscheck, FishFinPassesAgainstNgspice) {
  if (!ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  const auto run = emnet::testing::run_emnet(
      "crosscheck " + source_path("netlists/fishfin.toml") + " --timeout 60", "timeout 120 ");
  EXPECT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("crosscheck passed"), std::string::npos) << run.out;
  for (const char* analysis : {"\nop ", "\nac ", "\nmodal ", "\ntran "})
    EXPECT_NE(run.out.find(analysis), std::string::npos) << analysis << "\n" << run.out;
}

// The switched drive (a 0/V square wave on DEA A alone; B undriven) in every deck: op (A on),
// ac (its force level), tran (its PULSE source), all within the tolerances above.
// The gripper finger (netlists/gripper-finger.toml): two sections, an elastic clamp of two
// springs, a tip mass, and a DEA charged through an amplifier's 10 MOhm by a 0/3 kV square wave
// ([[circuit]]): every analysis within the same tolerances (its tran against IDA, the network
// being nonlinear; ngspice's max step from its 14.9 Hz first mode, not the 2 Hz switching).
TEST(Crosscheck, GripperFingerPassesAgainstNgspice) {
  if (!ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  const auto run = emnet::testing::run_emnet(
      "crosscheck " + source_path("netlists/gripper-finger.toml") + " --timeout 60",
      "timeout 120 ");
  EXPECT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("crosscheck passed"), std::string::npos) << run.out;
  for (const char* analysis : {"\nop ", "\nac ", "\nmodal ", "\ntran "})
    EXPECT_NE(run.out.find(analysis), std::string::npos) << analysis << "\n" << run.out;
}

TEST(Crosscheck, SwitchedDrivePassesAgainstNgspice) {
  if (!ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  const auto run = emnet::testing::run_emnet(
      "crosscheck " + source_path("netlists/fishfin.toml") +
          " --set drive.kind=switched --set 'drive.deas=[\"A\"]' --timeout 60",
      "timeout 120 ");
  EXPECT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("drive switched 0/4000 V square wave at 5 Hz on DEA A"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("crosscheck passed"), std::string::npos) << run.out;
  for (const char* analysis : {"\nop ", "\nac ", "\nmodal ", "\ntran "})
    EXPECT_NE(run.out.find(analysis), std::string::npos) << analysis << "\n" << run.out;
}

// The cantilever's step load from rest: ngspice stops with "timestep too small" at max steps
// below ~T/1000 (docs/commands.md, "Cross-check"), so the default run (T/2000) must retry at max
// step T/200 and say so; ngspice's own steps are far smaller there (its error control at reltol
// 1e-6 binds).
TEST(Crosscheck, CantileverPassesAgainstNgspice) {
  if (!ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  const auto run = emnet::testing::run_emnet(
      "crosscheck " + source_path("netlists/cantilever.toml") + " --timeout 60", "timeout 120 ");
  EXPECT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("crosscheck passed"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("\nmodal  f2"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("retried with T/200"), std::string::npos) << run.out;
}

// A deliberately perturbed ngspice vector (one output 1e-5 relative off, ten times the
// tolerance) must fail its row, and only its analysis.
TEST(Crosscheck, PerturbedNgspiceVectorFailsTheReport) {
  if (!ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  const Model model = build_model(read_scene(source_path("netlists/fishfin.toml")));
  CrosscheckOptions options;
  options.analyses = {CrosscheckAnalysis::op, CrosscheckAnalysis::ac};
  const CrosscheckReport clean = run_crosscheck(model, options);
  ASSERT_TRUE(clean.status.ok()) << clean.status.message;
  EXPECT_TRUE(clean.all_pass());
  options.inspect_ngspice_result = [](CrosscheckAnalysis analysis, NgspiceResult& result) {
    if (analysis != CrosscheckAnalysis::ac) return;
    for (auto& vector : result.vectors)
      if (vector.name == "out_tip")
        for (auto& value : vector.complex_values) value *= 1.0 + 1e-5;
  };
  const CrosscheckReport perturbed = run_crosscheck(model, options);
  ASSERT_TRUE(perturbed.status.ok()) << perturbed.status.message;
  EXPECT_FALSE(perturbed.all_pass());
  bool ac_magnitude_failed = false;
  for (const auto& row : perturbed.rows) {
    if (row.analysis == CrosscheckAnalysis::op) EXPECT_TRUE(row.pass) << row.quantity;
    if (row.analysis == CrosscheckAnalysis::ac && row.quantity == "outputs |Y|") {
      ac_magnitude_failed = !row.pass;
      EXPECT_NEAR(row.largest_difference, 1e-5, 1e-7);
      EXPECT_NE(row.where.find("tip"), std::string::npos) << row.where;
    }
  }
  EXPECT_TRUE(ac_magnitude_failed);
}

TEST(Crosscheck, MissingNgspiceProgramExitsThreeWithAClearMessage) {
  const auto run = emnet::testing::run_emnet(
      "crosscheck " + source_path("netlists/fishfin.toml") +
          " --backend program --ngspice-program /nonexistent/ngspice --analysis op",
      "timeout 60 ");
  EXPECT_EQ(run.status, 3) << run.out << run.err;
  EXPECT_NE(run.err.find("ngspice"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("/nonexistent/ngspice"), std::string::npos) << run.err;
}

TEST(Crosscheck, BadAnalysisNameIsBadInput) {
  EXPECT_THROW(parse_crosscheck_analyses("op,pz"), OptionError);
  EXPECT_EQ(parse_crosscheck_analyses("all").size(), 4u);
  const auto run = emnet::testing::run_emnet("crosscheck " + source_path("netlists/fishfin.toml") +
                                             " --analysis op,pz");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("pz"), std::string::npos) << run.err;
}

// --keep-decks into a directory that does not exist yet: made (with its parents), the op deck
// written there; it failed with "cannot open" before. A path under a regular file cannot be
// made: exit 2 naming --keep-decks and the reason.
TEST(Crosscheck, KeepDecksMakesItsDirectory) {
  const std::string base = ::testing::TempDir() + "emnet_keep_decks_" + std::to_string(getpid());
  const std::string directory = base + "/new/decks";
  const auto run = emnet::testing::run_emnet("crosscheck " + source_path("netlists/fishfin.toml") +
                                             " --analysis op --keep-decks " + directory);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(std::filesystem::exists(directory + "/fishfin-crosscheck-op.cir")) << run.out;
  const std::string file = base + "/file";
  std::ofstream(file) << "x";
  const auto refused =
      emnet::testing::run_emnet("crosscheck " + source_path("netlists/fishfin.toml") +
                                " --analysis op --keep-decks " + file + "/decks");
  EXPECT_EQ(refused.status, 2) << refused.err;
  EXPECT_NE(refused.err.find("--keep-decks"), std::string::npos) << refused.err;
  std::filesystem::remove_all(base);
}

// 1/|H|² of an isolated mode's displacement response is quadratic in f²: the three-point fit
// finds f_n·sqrt(1 − 2ζ²) to rounding, on any grid around it, damped or not.
TEST(Crosscheck, ParabolicPeakIsExactForAnIsolatedMode) {
  for (const double zeta : {0.0, 0.02, 0.12}) {
    const double natural = 6.385;
    const double expected = natural * std::sqrt(1.0 - 2.0 * zeta * zeta);
    std::vector<double> frequencies, magnitudes;
    for (int k = 0; k < 200; ++k) {
      const double f = expected * (0.97 + 0.06 * (k + 0.5) / 200.0);
      const std::complex<double> denominator(natural * natural - f * f, 2.0 * zeta * natural * f);
      frequencies.push_back(f);
      magnitudes.push_back(1.0 / std::abs(denominator));
    }
    double peak = 0.0;
    ASSERT_TRUE(parabolic_peak_frequency(frequencies, magnitudes, peak)) << zeta;
    EXPECT_NEAR(peak, expected, 1e-9 * expected) << zeta;
  }
  // A monotone response has no peak inside the grid.
  double peak = 0.0;
  EXPECT_FALSE(parabolic_peak_frequency({1.0, 2.0, 3.0, 4.0}, {1.0, 2.0, 3.0, 4.0}, peak));
}

TEST(Crosscheck, LargestRelativeDifference) {
  const auto largest = largest_relative_difference({1.0, 2.0, 3.0}, {1.0, 2.5, 3.1}, 2.0);
  EXPECT_EQ(largest.index, 1u);
  EXPECT_DOUBLE_EQ(largest.value, 0.25);
}

}  // namespace
