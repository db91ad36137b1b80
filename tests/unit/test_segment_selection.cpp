// The resolve step: beam.segments = "auto" (emnet/studies/segment_selection.hpp),
// drive.electrical_dynamics = "auto" (emnet/studies/resolve.hpp) and the [model] table's reader.
// References: the continuum cantilever's closed form, Richardson-converged frequencies from
// N = 1000 and 2000, and the full RC model's periodic steady state.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/model/mesh.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using emnet::testing::kCantilever;
using emnet::testing::kFishfin;
using emnet::testing::kPi;

const AutomaticChoice* find_choice(const Model& model, const std::string& key) {
  for (const auto& choice : model.automatic_choices)
    if (choice.key == key) return &choice;
  return nullptr;
}

double worst_relative_error(const std::vector<double>& values,
                            const std::vector<double>& references) {
  double worst = 0.0;
  for (size_t k = 0; k < references.size(); ++k)
    worst = std::max(worst, std::abs(values.at(k) - references[k]) / references[k]);
  return worst;
}

TEST(SegmentSelection, RichardsonErrorRemovesTheLeadingTerm) {
  // f_N = 1 − 1/N²: f∞ = 1 exactly from N = 10 and 20, so the error of N = 10 is 1/100
  // (up to rounding).
  EXPECT_NEAR(richardson_error(1.0 - 1.0 / 100, 1.0 - 1.0 / 400), 0.01, 1e-14);
  const std::vector<double> errors = richardson_errors({0.99, 2.0}, {0.9975, 2.0, 5.0});
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_DOUBLE_EQ(errors[1], 0.0);
}

// Reference: the continuum clamped-free beam, f_n = (β_nL)²/(2πL²)·√(EI/ρA), β_nL = 1.875104,
// 4.694091, 7.854757 (netlists/cantilever.toml: 5.7794, 36.219, 101.41 Hz); band 0-110 Hz holds
// these three. Tolerance: the chosen N's modes lie within model.tolerance of the closed form
// (the Richardson estimate is asymptotically exact; its own error is O(N⁻⁴), far below the
// tolerance here), checked for two tolerances. Minimality: the search's granularity is one
// segment, so N − 1 was tried and its estimate failed the tolerance; against the closed form
// N − 1 fails too (its true error is (N/(N−1))² times N's, about 1 + 2/N above the estimate).
TEST(SegmentSelection, CantileverAutoMeetsTheClosedFormAndIsMinimal) {
  const double beta_l[] = {1.875104, 4.694091, 7.854757};
  for (const double tolerance : {1e-2, 1e-3}) {
    const Scene scene =
        read_scene(kCantilever, {"beam.segments=auto", "model.band=[\"0 Hz\", \"110 Hz\"]",
                                 "model.tolerance=" + std::to_string(tolerance)});
    ASSERT_TRUE(scene.beam.auto_segments);
    const Model model = prepare_model(scene);
    const AutomaticChoice* choice = find_choice(model, "beam.segments");
    ASSERT_NE(choice, nullptr);
    const int n = model.scene.beam.segments;
    EXPECT_EQ(choice->value, std::to_string(n));
    EXPECT_LE(choice->estimated_error, tolerance);
    std::vector<double> closed;
    const BeamSpec& beam = scene.beam;
    for (double b : beta_l)
      closed.push_back(b * b / (2 * kPi * beam.length * beam.length) *
                       std::sqrt(beam.bending_stiffness / beam.mass_per_length));
    const double error_n = worst_relative_error(beam_frequencies(beam, n, 4), closed);
    const double error_below = worst_relative_error(beam_frequencies(beam, n - 1, 4), closed);
    EXPECT_LE(error_n, tolerance) << "N = " << n;
    EXPECT_GT(error_below, tolerance) << "N - 1 = " << n - 1;
    // The estimate against the true error: within 10 % (O(N⁻²) relative to it at N ≥ 12).
    EXPECT_NEAR(choice->estimated_error, error_n, 0.1 * error_n);
    // The search itself tried N − 1 and saw it fail.
    const SegmentSelection selection = select_segments(beam, 0.0, 110.0, tolerance);
    EXPECT_EQ(selection.segments, n);
    bool below_tried = false;
    for (const auto& [segments, error] : selection.tried)
      if (segments == n - 1) {
        below_tried = true;
        EXPECT_GT(error, tolerance);
      }
    EXPECT_TRUE(below_tried);
  }
}

// Reference: the bare fin beam's frequencies converged by Richardson from N = 1000 and 2000
// (their own error ~1e-7 of the first mode, O(N⁻²) × the third mode's constant, 1000x below the
// tightest tolerance). Band: fishfin.toml has no [model]; the default is 0 to 10 x drive.frequency
// = 50 Hz (two modes). Tolerance: the chosen N's band modes within model.tolerance of it, for
// two tolerances; a tighter tolerance needs more segments.
TEST(SegmentSelection, FishfinAutoWithinToleranceOfConvergedAnswer) {
  const BeamSpec fin = read_scene(kFishfin).beam;
  const std::vector<double> coarse = beam_frequencies(fin, 1000, 3);
  const std::vector<double> fine = beam_frequencies(fin, 2000, 3);
  std::vector<double> converged;
  for (size_t k = 0; k < 3; ++k) converged.push_back(richardson_extrapolate(coarse[k], fine[k]));
  int previous = 0;
  for (const double tolerance : {1e-2, 1e-3}) {
    const Scene scene = read_scene(
        kFishfin, {"beam.segments=auto", "model.tolerance=" + std::to_string(tolerance)});
    const Model model = prepare_model(scene);
    const AutomaticChoice* choice = find_choice(model, "beam.segments");
    ASSERT_NE(choice, nullptr);
    EXPECT_DOUBLE_EQ(choice->band_to_hz, 50.0);
    const int n = model.scene.beam.segments;
    std::vector<double> in_band;
    for (double f : converged)
      if (f <= 50.0) in_band.push_back(f);
    ASSERT_EQ(in_band.size(), 2u);
    // The chain as the selection and the model mesh it: a node at each DEA end.
    EXPECT_LE(
        worst_relative_error(beam_frequencies(fin, n, 3, scene_attachment_points(scene)), in_band),
        tolerance)
        << "N = " << n;
    EXPECT_GT(n, previous);
    previous = n;
    // The full model (damped, with the DEAs) has the same first resonance to the tolerance.
    const System system = model.network.assemble();
    ModalOptions options;
    options.keep_vectors = false;
    const StaticResult rest = solve_static(system);
    ASSERT_TRUE(rest.status.ok()) << rest.status.message;
    const ModalResult modes = run_modes(system, rest.operating_point, options);
    ASSERT_TRUE(modes.status.ok()) << modes.status.message;
    EXPECT_NEAR(modes.modes.front().natural_frequency_hz, converged[0], tolerance * converged[0]);
  }
}

// --segments N (an integer override) still wins over "auto".
TEST(SegmentSelection, IntegerOverrideWins) {
  const Scene scene = read_scene(kFishfin, {"beam.segments=auto", "beam.segments=12"});
  EXPECT_FALSE(scene.beam.auto_segments);
  const Model model = prepare_model(scene);
  EXPECT_EQ(model.scene.beam.segments, 12);
  EXPECT_EQ(find_choice(model, "beam.segments"), nullptr);
}

// The criterion's numbers for the fish fin: C0 = ε0·εr·w·l/d = 8.854e-12·2.8·25 mm·70 mm/51 µm
// = 0.8507 nF, τ = 1 MΩ·C0 = 0.8507 ms. At f_high = 130 Hz, (2π·130 Hz·τ)²/2 = 0.241 > 1e-3:
// the RC lag matters there, the dynamics are kept. Ideal only below
// f = √(2·tol)/(2πτ) = 8.37 Hz (tol 1e-3): at 8 Hz the estimate is 9.1e-4. Tolerances: 1e-12
// against the same formula (rounding only), 0.001 on 0.241 (the three digits quoted here).
TEST(ElectricalDynamicsAuto, CriterionNumbersForTheFishfin) {
  const double tau = 1e6 * 8.8541878128e-12 * 2.8 * 0.025 * 0.070 / 51e-6;
  {
    const Model model = prepare_model(
        read_scene(kFishfin, {"drive.electrical_dynamics=auto", "model.band=\"130 Hz\""}));
    const AutomaticChoice* choice = find_choice(model, "drive.electrical_dynamics");
    ASSERT_NE(choice, nullptr);
    EXPECT_EQ(choice->value, "true");
    EXPECT_NEAR(choice->estimated_error, std::pow(2 * kPi * 130 * tau, 2) / 2, 1e-12);
    EXPECT_NEAR(choice->estimated_error, 0.241, 0.001);
    EXPECT_TRUE(model.scene.drive.electrical_dynamics);
  }
  {
    const Model model = prepare_model(
        read_scene(kFishfin, {"drive.electrical_dynamics=auto", "model.band=\"8 Hz\""}));
    const AutomaticChoice* choice = find_choice(model, "drive.electrical_dynamics");
    ASSERT_NE(choice, nullptr);
    EXPECT_EQ(choice->value, "false");
    EXPECT_NEAR(choice->estimated_error, std::pow(2 * kPi * 8 * tau, 2) / 2, 1e-12);
    EXPECT_FALSE(model.scene.drive.electrical_dynamics);
    EXPECT_FALSE(model.network.assemble().is_nonlinear());
  }
  {  // a looser tolerance moves the threshold to √(2·1e-2)/(2πτ) = 26.5 Hz
    const Model model =
        prepare_model(read_scene(kFishfin, {"drive.electrical_dynamics=auto",
                                            "model.band=\"25 Hz\"", "model.tolerance=1e-2"}));
    EXPECT_EQ(find_choice(model, "drive.electrical_dynamics")->value, "false");
  }
}

TEST(ElectricalDynamicsAuto, KeptWhenAProbeAsksForAnElectricalQuantity) {
  Scene scene = read_scene(kFishfin, {"drive.electrical_dynamics=auto", "model.band=\"8 Hz\""});
  EXPECT_EQ(find_choice(prepare_model(scene, {true}), "drive.electrical_dynamics")->value, "true");
  ProbeSpec current;
  current.name = "iA";
  current.quantity = ProbeQuantity::dea_current;
  current.dea = "A";
  scene.probes.push_back(current);
  const Model model = prepare_model(scene);
  EXPECT_EQ(find_choice(model, "drive.electrical_dynamics")->value, "true");
  EXPECT_TRUE(model.network.assemble().is_nonlinear());
}

// Reference: the full RC model's periodic steady state at 5 Hz (Newton shooting with IDA,
// rtol 1e-10, its error ~1e-8 of the peak). Band 0-25 Hz, tolerance 1e-2: the square wave's
// fundamental and its 3rd and 5th harmonics lie in the band, and the criterion chooses the
// ideal drive with the estimate (2π·25 Hz·τ)²/2 = 8.9e-3. Tolerance: the ideal model's peak
// deflections (P4, tip) differ from the RC model's by no more than that estimate, relative to
// the peak (measured, bench 5a: 8.3e-4 over P2-P4 and the tip). With a band ending below the 3rd
// harmonic the harmonics the estimate leaves out matter: at 8 Hz the estimate, 9.1e-4, is only 10 %
// above the measured difference, at 6 Hz (5.1e-4) below it; the note says so for such bands.
TEST(ElectricalDynamicsAuto, IdealDifferenceWithinTheStatedEstimate) {
  const Scene scene = read_scene(
      kFishfin, {"drive.electrical_dynamics=auto", "model.band=\"25 Hz\"", "model.tolerance=1e-2"});
  const Model ideal = prepare_model(scene);
  const AutomaticChoice* choice = find_choice(ideal, "drive.electrical_dynamics");
  ASSERT_NE(choice, nullptr);
  ASSERT_EQ(choice->value, "false");
  Scene full_scene = scene;
  full_scene.drive.electrical_dynamics_auto = false;
  full_scene.drive.electrical_dynamics = true;
  const Model full = prepare_model(full_scene);
  const double period = 1.0 / scene.drive.frequency;
  const System ideal_system = ideal.network.assemble();
  const System full_system = full.network.assemble();
  std::vector<Probe> ideal_probes, full_probes;
  for (const char* name : {"P4", "tip"}) {
    ideal_probes.push_back(ideal.parse_probe(name));
    full_probes.push_back(full.parse_probe(name));
  }
  PeriodicSolver solver(ideal_system);
  const PeriodicResult a = solver.solve(ideal_system, ideal_probes, period);
  const PeriodicResult b = run_periodic_shooting(full_system, full_probes, period, 1e-10);
  ASSERT_TRUE(a.status.ok()) << a.status.message;
  ASSERT_TRUE(b.status.ok()) << b.status.message;
  for (size_t p = 0; p < ideal_probes.size(); ++p) {
    const double peak = std::max(std::abs(b.maximum[p]), std::abs(b.minimum[p]));
    const double difference =
        std::max(std::abs(a.maximum[p] - b.maximum[p]), std::abs(a.minimum[p] - b.minimum[p]));
    EXPECT_LE(difference, choice->estimated_error * peak) << ideal_probes[p].name;
  }
}

// Notes: one line per automatic choice and one back-coupling line, not one per DEA.
TEST(ElectricalDynamicsAuto, NotesSayWhatWasChosenAndWhy) {
  const Model model = prepare_model(read_scene(
      kFishfin, {"beam.segments=auto", "drive.electrical_dynamics=auto", "model.band=\"8 Hz\""}));
  int back_coupling = 0, segments = 0, electrical = 0;
  for (const auto& note : model.notes) {
    if (note.find("back-coupling left out") != std::string::npos) ++back_coupling;
    if (note.find("beam.segments = \"auto\"") != std::string::npos) ++segments;
    if (note.find("tau = R_e*C0") != std::string::npos) ++electrical;
  }
  EXPECT_EQ(back_coupling, 1);
  EXPECT_EQ(segments, 1);
  EXPECT_EQ(electrical, 1);
}

// The command line: the choices in --json ("automatic_choices") and in the text notes;
// --segments N overrides "auto"; a --probe for a DEA current keeps the RC dynamics.
TEST(AutomaticChoicesCli, JsonNotesAndOverrides) {
  using Json = nlohmann::json;
  const std::string scene = kFishfin +
                            " --set beam.segments=auto --set drive.electrical_dynamics=auto"
                            " --set 'model.band=\"25 Hz\"' --set model.tolerance=1e-2";
  const auto json_run = testing::run_emnet("modes " + scene + " --count 2 --json");
  ASSERT_EQ(json_run.status, 0) << json_run.err;
  const Json out = Json::parse(json_run.out);
  ASSERT_EQ(out["automatic_choices"].size(), 2u);
  EXPECT_EQ(out["automatic_choices"][0]["key"], "beam.segments");
  EXPECT_EQ(out["automatic_choices"][0]["value"], std::to_string(out["segments"].get<int>()));
  EXPECT_LE(out["automatic_choices"][0]["estimated_error"].get<double>(), 1e-2);
  EXPECT_EQ(out["automatic_choices"][1]["key"], "drive.electrical_dynamics");
  EXPECT_EQ(out["automatic_choices"][1]["value"], "false");
  const auto text = testing::run_emnet("modes " + scene + " --count 2");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("note: beam.segments = \"auto\": N = "), std::string::npos);
  const auto fixed = testing::run_emnet("modes " + scene + " --segments 9 --count 2 --json");
  ASSERT_EQ(fixed.status, 0) << fixed.err;
  EXPECT_EQ(Json::parse(fixed.out)["segments"], 9);
  const auto current = testing::run_emnet("static " + scene + " --probe dea_current:A --json");
  ASSERT_EQ(current.status, 0) << current.err;
  EXPECT_EQ(Json::parse(current.out)["automatic_choices"][1]["value"], "true");
}

// Reader errors name the file, the key and what is wrong.
std::string reader_error(const std::string& scene, const std::vector<std::string>& overrides) {
  try {
    read_scene(scene, overrides);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(ModelTableReader, RejectsBadInput) {
  struct Case {
    std::vector<std::string> overrides;
    std::string key, says;
  };
  const std::vector<Case> cases = {
      {{"model.band=[\"130 Hz\", \"10 Hz\"]"}, "model.band", "below the upper end"},
      {{"model.band=[\"10 Hz\"]"}, "model.band", "two frequencies"},
      {{"model.band=\"-5 Hz\""}, "model.band", "must be > 0"},
      {{"model.band=\"10 m\""}, "model.band", "upper end"},
      {{"model.band=[\"-1 Hz\", \"10 Hz\"]"}, "model.band", ">= 0"},
      {{"model.band=inf"}, "model.band", "finite"},
      {{"model.tolerance=0"}, "model.tolerance", "(0, 0.5)"},
      {{"model.tolerance=0.5"}, "model.tolerance", "(0, 0.5)"},
      {{"model.tolerance=\"1 Hz\""}, "model.tolerance", ""},
      {{"model.accuracy=1e-3"}, "model.accuracy", "unknown key"},
      {{"beam.segments=foo"}, "beam.segments", "\"auto\""},
      {{"beam.segments=1.5"}, "beam.segments", "integer"},
      {{"drive.electrical_dynamics=maybe"}, "drive.electrical_dynamics", "\"auto\""},
  };
  for (const Case& c : cases) {
    const std::string message = reader_error(kFishfin, c.overrides);
    EXPECT_NE(message.find("key '" + c.key + "'"), std::string::npos)
        << c.overrides.front() << ": " << message;
    EXPECT_NE(message.find(c.says), std::string::npos) << c.overrides.front() << ": " << message;
  }
  // "auto" without a band: the cantilever without its [ac] table has no load frequency.
  const std::string text = R"([scene]
name = "c"

[beam]
length = 0.5
segments = "auto"
bending_stiffness = 2.0
mass_per_length = 0.3
)";
  try {
    read_scene_text(text, "c.toml", {});
    ADD_FAILURE() << "accepted segments = \"auto\" without a band";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "beam.segments");
    EXPECT_EQ(error.where(), "c.toml:6");
    EXPECT_NE(std::string(error.what()).find("needs a frequency band"), std::string::npos);
  }
  EXPECT_NO_THROW(read_scene_text(text + "\n[model]\nband = \"100 Hz\"\n", "c.toml", {}));
  // The file's line for a bad band.
  try {
    read_scene_text(text + "\n[model]\nband = [\"100 Hz\", \"1 Hz\"]\n", "c.toml", {});
    ADD_FAILURE() << "accepted a reversed band";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "model.band");
    EXPECT_EQ(error.where(), "c.toml:11");
  }
}

}  // namespace
}  // namespace emnet
