// Identification (emnet identify): bending stiffness to a resonance, and with --peak the loss
// factor to a periodic peak deflection.
//
// References: (1) synthetic targets — a scene with known EI and loss factor gives f1 (`modes`)
// and the periodic peak of dx4 (`sweep-switching`, exact periodic state); identify, started
// from other values, must give them back. The fit's own tolerances are 1e-10 on the frequency
// and a bisection to 1e-12 in log η inside a fixed point converged to 1e-9, and the targets are
// printed with 17 digits, so 1e-6 relative leaves a margin for the targets' rounding; (2) the
// two scenes in netlists/ that come from identify, re-identified from perturbed starts: their
// values are written with 7 significant digits, so they come back within 1e-6 relative; (3) --fit
// of an elastic clamp's rotational stiffness: the target is f1 at k = 4 N*m/rad (`modes`,
// printed with 17 digits), the fit starts from 40 N*m/rad and must print k = 4.000000e+00 (7
// digits; the study's tolerance, test_identify_study.cpp, is far finer).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_json.hpp"
#include "cli_run.hpp"
#include "emnet/scene/scene_reader.hpp"

namespace {

using emnet::testing::run_emnet;
using emnet::testing::run_json;
using Json = nlohmann::json;

std::string scene(const std::string& name) {
  return std::string(EMNET_SOURCE_DIR) + "/netlists/" + name;
}

std::string number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

TEST(Identify, RecoversKnownStiffnessAndLossFactorFromSyntheticTargets) {
  const double stiffness = 1.7e-3, loss_factor = 0.03;
  const std::string known = " --set beam.bending_stiffness=" + number(stiffness) +
                            " --set damping.loss_factor=" + number(loss_factor);
  const Json modes = run_json("modes " + scene("fishfin.toml") + known + " --count 1");
  ASSERT_FALSE(modes.is_null());
  const double f1 = modes["modes"][0]["frequency_hz"].get<double>();
  // At its resonance this softer fin swings its tip by 21 % of its length, past the default
  // validity limit (10 %); the test is of the fit, so the limit is raised for the sweep.
  const Json sweep =
      run_json("sweep-switching " + scene("fishfin.toml") + known + " --from " + number(f1) +
               " --to " + number(f1) + " --step 1 --set model.deflection_limit=0.3");
  ASSERT_FALSE(sweep.is_null());
  double peak = 0.0;
  for (const auto& output : sweep["outputs"])
    if (output["name"] == "dx4")
      peak = std::max(std::abs(output["left"][0].get<double>()),
                      std::abs(output["right"][0].get<double>()));
  ASSERT_GT(peak, 0.0);
  // Started from the scene's own values (EI 2.18e-3, loss factor 0.04).
  const Json fit = run_json("identify " + scene("fishfin.toml") + " --resonance " + number(f1) +
                            " --peak dx4=" + number(peak) + "m");
  ASSERT_FALSE(fit.is_null());
  EXPECT_NEAR(fit["value"].get<double>() / stiffness, 1.0, 1e-6);
  EXPECT_NEAR(fit["loss_factor"].get<double>() / loss_factor, 1.0, 1e-6);
}

TEST(Identify, MeasuredFinSceneComesBackFromAPerturbedStart) {
  const Json fit = run_json("identify " + scene("fishfin-measured.toml") +
                            " --resonance 5.0 --peak P4=9.3mm@4kV"
                            " --set beam.bending_stiffness=2e-3 --set damping.loss_factor=0.02");
  ASSERT_FALSE(fit.is_null());
  const emnet::Scene written = emnet::read_scene(scene("fishfin-measured.toml"));
  ASSERT_TRUE(written.damping.loss_factor.has_value());
  EXPECT_NEAR(fit["value"].get<double>() / written.beam.bending_stiffness, 1.0, 1e-6);
  EXPECT_NEAR(fit["loss_factor"].get<double>() / *written.damping.loss_factor, 1.0, 1e-6);
  EXPECT_NEAR(fit["achieved_peak_m"].get<double>(), 9.3e-3, 1e-9);
}

TEST(Identify, NetworkSceneComesBackFromAPerturbedStart) {
  const Json fit = run_json("identify " + scene("fishfin.toml") +
                            " --resonance 6.385 --set beam.bending_stiffness=1e-3");
  ASSERT_FALSE(fit.is_null());
  const emnet::Scene written = emnet::read_scene(scene("fishfin.toml"));
  EXPECT_NEAR(fit["value"].get<double>() / written.beam.bending_stiffness, 1.0, 1e-6);
}

TEST(Identify, BadPeakTargetsAreInputErrors) {
  for (const char* peak : {"P4", "P4=9.3", "P4=9.3kV", "nowhere=9.3mm", "P4=9.3mm@4mm"}) {
    const auto run =
        run_emnet("identify " + scene("fishfin.toml") + " --resonance 5 --peak " + peak);
    EXPECT_EQ(run.status, 2) << peak << ": " << run.err;
    EXPECT_NE(run.err.find("--peak"), std::string::npos) << peak << ": " << run.err;
  }
}

// A value the scene takes from the paper or a data sheet is a given: identify refuses to fit it
// and names the provenance key.
TEST(Identify, GivenValuesAreNotFitted) {
  std::ifstream source(scene("fishfin.toml"));
  std::stringstream text;
  text << source.rdbuf();
  std::string scene_text = text.str();
  const std::string from = "\"beam.bending_stiffness\" = \"identified:";
  const auto at = scene_text.find(from);
  ASSERT_NE(at, std::string::npos);
  scene_text.replace(at, from.size(), "\"beam.bending_stiffness\" = \"paper:");
  const std::string path =
      ::testing::TempDir() + "emnet_given_stiffness_" + std::to_string(getpid()) + ".toml";
  std::ofstream(path) << scene_text;
  const auto run = run_emnet("identify " + path + " --resonance 6");
  std::remove(path.c_str());
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("provenance.beam.bending_stiffness"), std::string::npos) << run.err;
}

TEST(Identify, FitsAnElasticClampStiffnessAndPrintsWhereItsLineGoes) {
  const std::string path =
      ::testing::TempDir() + "emnet_elastic_clamp_" + std::to_string(getpid()) + ".toml";
  std::ofstream(path) << "[scene]\nname = \"elastic_clamp\"\n[beam]\nlength = 0.5\n"
                         "segments = 10\nbending_stiffness = 2.0\nmass_per_length = 0.3\n"
                         "left = \"pinned\"\n[[spring]]\nname = \"clamp\"\nat = 0\n"
                         "kind = \"rotational\"\nstiffness = 40\n";
  const Json modes = run_json("modes " + path + " --set spring.clamp.stiffness=4 --count 1");
  ASSERT_FALSE(modes.is_null());
  const std::string f1 = number(modes["modes"][0]["frequency_hz"].get<double>());
  const std::string arguments =
      "identify " + path + " --resonance " + f1 + " --fit spring.clamp.stiffness";
  const auto run = run_emnet(arguments);
  const Json fit = run_json(arguments);
  std::remove(path.c_str());
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("identified spring[clamp].stiffness = 4.000000e+00 N*m/rad: mode 1 at "),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("scene lines (in the [[spring]] entry name = \"clamp\"):\n"
                         "  stiffness = \"4.000000e+00 N*m/rad\"\n"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("\"spring[clamp].stiffness\" = \"identified: emnet identify " + path +
                         " --resonance "),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find(" --fit spring.clamp.stiffness\"\n"), std::string::npos) << run.out;
  ASSERT_FALSE(fit.is_null());
  EXPECT_EQ(fit["parameter"], "spring[clamp].stiffness");
  EXPECT_EQ(fit["unit"], "N*m/rad");
  EXPECT_NEAR(fit["value"].get<double>(), 4.0, 4.0 * 1e-6);
}

TEST(Identify, DefaultOutputNamesTheBendingStiffnessAsBefore) {
  const auto run = run_emnet("identify " + scene("fishfin.toml") + " --resonance 6.385");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.out.rfind("identified beam.bending_stiffness = ", 0), 0u) << run.out;
  EXPECT_NE(run.out.find(" N*m^2: mode 1 at "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("scene lines:\n  bending_stiffness = \""), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("provenance:\n  \"beam.bending_stiffness\" = \"identified: emnet "
                         "identify " +
                         scene("fishfin.toml") + " --resonance 6.385\"\n"),
            std::string::npos)
      << run.out;
}

// identify has no --method: its refusals do not advise one (they said "use --method
// shooting").
TEST(Identify, RefusalAtScaleAdvisesNoOptionItLacks) {
  const auto run = run_emnet("identify " + scene("fishfin.toml") +
                             " --resonance 5 --peak P4=9.3mm --segments 800");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("--segments"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("--method"), std::string::npos) << run.err;
}

// The tweezer with its pad mass given by a table-wide entry ("mass.mass", every [[mass]]'s
// mass) from a paper: identify --fit mass.pad.mass fitted it (only "mass[pad].mass" counted);
// now refused, naming the entry. A misspelt key is refused by the reader with a suggestion
// (it was accepted silently).
TEST(Provenance, TableWideEntriesProtectEveryEntryAndMisspeltKeysAreRefused) {
  std::ifstream file(scene("tweezer-jaw.toml"));
  std::stringstream buffer;
  buffer << file.rdbuf();
  std::string text = buffer.str();
  const std::string assumed = "\"mass.mass\" = \"assumed:";
  ASSERT_NE(text.find(assumed), std::string::npos);
  std::string given = text;
  given.replace(given.find(assumed), assumed.size(), "\"mass.mass\" = \"paper:");
  const std::string given_path =
      ::testing::TempDir() + "tweezer_given_" + std::to_string(getpid()) + ".toml";
  std::ofstream(given_path) << given;
  const auto fitted =
      run_emnet("identify " + given_path + " --segments 8 --resonance 15 --fit mass.pad.mass");
  EXPECT_EQ(fitted.status, 2) << fitted.out;
  EXPECT_NE(fitted.err.find("provenance.mass.mass"), std::string::npos) << fitted.err;

  std::string misspelt = text;
  misspelt.replace(misspelt.find(assumed), assumed.size(), "\"mass.mas\" = \"assumed:");
  const std::string misspelt_path =
      ::testing::TempDir() + "tweezer_misspelt_" + std::to_string(getpid()) + ".toml";
  std::ofstream(misspelt_path) << misspelt;
  const auto refused = run_emnet("static " + misspelt_path);
  EXPECT_EQ(refused.status, 2) << refused.out;
  EXPECT_NE(refused.err.find("provenance.mass.mas"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("did you mean"), std::string::npos) << refused.err;
  std::remove(given_path.c_str());
  std::remove(misspelt_path.c_str());
}

TEST(Identify, UnknownFitKeyExitsTwoNamingIt) {
  const auto run = run_emnet("identify " + scene("fishfin.toml") +
                             " --resonance 6 --fit spring.clamp.stiffness");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("spring.clamp.stiffness"), std::string::npos) << run.err;
}

}  // namespace
