// The AC analysis and study never return a non-finite value, and the AC study's JSON (report/
// ac_json.hpp): its keys in order and its values against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>

#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/report/ac_json.hpp"
#include "emnet/studies/ac_study.hpp"
#include "fixtures.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using Complex = std::complex<double>;
using emnet::testing::kTwoPi;

Probe displacement_of(NodeId node, const std::string& name = "x") {
  Probe probe;
  probe.name = name;
  probe.unit = "m";
  probe.description = "displacement of the mass";
  probe.terms = {{node, 1.0}};
  probe.integrations = 1;
  return probe;
}

// A free mass m under a unit AC force: velocity V = F/(jωm), displacement X = −F/(mω²)
// (closed form). At f = 1e-160 Hz, ω² ≈ 4e-319 is subnormal and 1/(mω²) ≈ 1e319 overflows a
// double (max 1.8e308) while V ≈ 8e158 is still finite: the solve succeeds, the probe's
// division by jω gives an infinity. run_ac must fail naming the probe and the frequency, not
// return it. At 1 Hz the same network gives |X| = 1/(m·(2π)²), checked to rounding (1e-12).
TEST(AcNonFinite, OverflowingDisplacementIsAFailedStatusNamingProbeAndFrequency) {
  const double m = 0.2;
  Network network;
  const NodeId v = network.add_node("v", Domain::translational, "free mass");
  network.add<Capacitor>("m", v, ground, m);
  Waveform force = Waveform::constant(0.0);
  force.ac_magnitude = 1.0;
  network.add<CurrentSource>("F", ground, v, force);
  const System system = network.assemble();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.size());

  const AcResult finite = run_ac(system, zero, {1.0}, {displacement_of(v, "free_x")});
  ASSERT_TRUE(finite.status.ok()) << finite.status.message;
  const double exact = 1.0 / (m * kTwoPi * kTwoPi);
  EXPECT_NEAR(std::abs(finite.values[0][0]), exact, 1e-12 * exact);

  const AcResult overflow = run_ac(system, zero, {1.0, 1e-160}, {displacement_of(v, "free_x")});
  ASSERT_FALSE(overflow.status.ok());
  EXPECT_NE(overflow.status.message.find("non-finite"), std::string::npos)
      << overflow.status.message;
  EXPECT_NE(overflow.status.message.find("'free_x'"), std::string::npos) << overflow.status.message;
  EXPECT_NE(overflow.status.message.find("1e-160 Hz"), std::string::npos)
      << overflow.status.message;
}

// A probe coefficient that is NaN (a corrupt output definition) gives a NaN at the first
// frequency, the static limit f = 0 included: a failed Status, never a NaN in the result.
TEST(AcNonFinite, NanProbeCoefficientIsAFailedStatusAtZeroAndAboveZero) {
  const testing::OneMass one = testing::one_mass_spring_damper(0.2, 50.0, 0.3);
  const System system = one.network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok()) << rest.status.message;
  Probe probe = displacement_of(one.velocity, "bad");
  probe.terms = {{one.velocity, std::nan("")}};
  for (double f : {0.0, 2.5}) {
    const AcResult ac = run_ac(system, rest.operating_point, {f}, {probe});
    ASSERT_FALSE(ac.status.ok()) << f << " Hz";
    EXPECT_NE(ac.status.message.find("'bad'"), std::string::npos) << ac.status.message;
  }
}

// The JSON of an AC study of one mass m on a spring k and damper c to ground under a unit
// force: magnitude |X| = 1/|k − mω² + jωc| and phase −atan2(ωc, k − mω²) [deg] (closed form).
// Tolerance 1e-12 relative on |X| and 1e-9 deg on the phase: one 3×3 complex LU, rounding only.
TEST(AcJson, KeysInOrderAndValuesMatchTheClosedForm) {
  const double m = 0.2, k = 50.0, c = 0.3;
  const testing::OneMass one = testing::one_mass_spring_damper(m, k, c);
  const System system = one.network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok()) << rest.status.message;
  const std::vector<Probe> probes{displacement_of(one.velocity)};
  AcStudyResult study;
  study.ac = run_ac(system, rest.operating_point, frequency_grid(0.5, 5.0, 7, true), probes);
  ASSERT_TRUE(study.ac.status.ok()) << study.ac.status.message;
  study.resonances_hz = {std::sqrt(k / m) / kTwoPi};
  Model model;
  model.scene.name = "one mass";
  model.scene.beam.segments = 3;
  model.beam.segment_lengths.assign(3, 0.1);  // the mesh built: what "segments" reports

  const Json json = to_json(study, model, probes, "a unit force", 1.5);
  std::vector<std::string> keys;
  for (const auto& item : json.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"scene", "automatic_choices", "segments", "input",
                                            "notes", "frequencies_hz", "probes", "resonances_hz",
                                            "accuracy", "cost", "validity"}));
  EXPECT_EQ(json["scene"], "one mass");
  EXPECT_EQ(json["segments"], 3);
  EXPECT_EQ(json["input"], "a unit force");
  EXPECT_EQ(json["cost"]["total_seconds"], 1.5);
  EXPECT_EQ(json["resonances_hz"][0].get<double>(), std::sqrt(k / m) / kTwoPi);
  ASSERT_EQ(json["probes"].size(), 1u);
  const Json& probe = json["probes"][0];
  EXPECT_EQ(probe["name"], "x");
  EXPECT_EQ(probe["unit"], "m");
  const auto frequencies = json["frequencies_hz"].get<std::vector<double>>();
  const auto magnitude = probe["magnitude"].get<std::vector<double>>();
  const auto phase = probe["phase_deg"].get<std::vector<double>>();
  ASSERT_EQ(frequencies.size(), 7u);
  ASSERT_EQ(magnitude.size(), 7u);
  ASSERT_EQ(phase.size(), 7u);
  for (size_t i = 0; i < frequencies.size(); ++i) {
    const double w = kTwoPi * frequencies[i];
    const Complex exact = 1.0 / Complex(k - m * w * w, w * c);
    ASSERT_TRUE(std::isfinite(magnitude[i]) && std::isfinite(phase[i]));
    EXPECT_NEAR(magnitude[i], std::abs(exact), 1e-12 * std::abs(exact)) << frequencies[i];
    EXPECT_NEAR(phase[i], std::arg(exact) * 180.0 / M_PI, 1e-9) << frequencies[i];
  }
  const double residual = json["accuracy"]["max_relative_residual"].get<double>();
  EXPECT_TRUE(std::isfinite(residual));
  EXPECT_LT(residual, 1e-12);
  EXPECT_FALSE(json.contains("reduction"));
}

// A scene with nothing exciting it (drive.kind = "none", no load) is an InputError naming the
// scene's key drive.kind and saying why, before any sweep.
TEST(AcStudy, NoAcInputIsAnInputErrorNamingDriveKind) {
  Scene scene = testing::cantilever_scene(4);
  scene.probes = {testing::beam_probe("tip", ProbeQuantity::deflection, 0.5)};
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  AcStudyOptions options;
  options.probes = model.probes;
  try {
    run_ac_study(model, system, Eigen::VectorXd::Zero(system.size()), options);
    FAIL() << "no InputError";
  } catch (const InputError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("drive.kind"), std::string::npos) << what;
    EXPECT_NE(what.find("and no [[load]]"), std::string::npos) << what;
  }
}

// Each drive kind without a small-signal part says why in its own terms: a switched drive at
// 0 V names itself and its voltage (its reason was once left empty).
TEST(AcStudy, NoAcInputReasonNamesEveryDriveKind) {
  Scene scene = testing::cantilever_scene(4);
  scene.drive.voltage = 0.0;
  for (const DriveKind kind : {DriveKind::antagonistic, DriveKind::switched}) {
    scene.drive.kind = kind;
    const std::string why = no_ac_input_reason(scene);
    EXPECT_NE(
        why.find("the " + std::string(drive_kind_name(kind)) + " drive at drive.voltage = 0 V"),
        std::string::npos)
        << why;
  }
  scene.drive.kind = DriveKind::single;
  EXPECT_NE(no_ac_input_reason(scene).find("drive.bias"), std::string::npos);
  scene.drive.kind = DriveKind::none;
  EXPECT_NE(no_ac_input_reason(scene).find("drive.kind = \"none\""), std::string::npos);
}

// The study of a cantilever (L = 0.5 m, EI = 2 N·m², ρA = 0.3 kg/m, 20 segments) under a tip
// force: its resonances in the band are the modes run_modes finds there (an independent
// computation of the same network), and the tip's peak |deflection| is the largest |value|.
TEST(AcStudy, ResonancesInBandAreTheModesAndPeaksTheLargestResponse) {
  Scene scene = testing::cantilever_scene(20);
  scene.loads = {testing::load(LoadKind::force, 0.5, 1.0)};
  scene.probes = {testing::beam_probe("tip", ProbeQuantity::deflection, 0.5)};
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok()) << rest.status.message;
  AcStudyOptions options;
  options.probes = model.probes;
  options.sweep.from = 1.0;
  options.sweep.to = 100.0;
  options.sweep.points = 50;
  options.sweep.log = true;
  const AcStudyResult result = run_ac_study(model, system, rest.operating_point, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ModalOptions modal_options;
  modal_options.keep_vectors = false;
  const ModalResult modes = run_modes(system, rest.operating_point, modal_options);
  ASSERT_TRUE(modes.status.ok()) << modes.status.message;
  std::vector<double> expected;
  for (const auto& mode : modes.modes)
    if (mode.frequency_hz >= 1.0 && mode.frequency_hz <= 100.0)
      expected.push_back(mode.frequency_hz);
  ASSERT_FALSE(expected.empty());
  // The markers ask for the 3 lowest (10 when all 3 lie in the band) without error bounds, the
  // reference for the default 10: other Krylov subspaces, the same poles to rounding (1e-9).
  ASSERT_EQ(result.resonances_hz.size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k)
    EXPECT_NEAR(result.resonances_hz[k], expected[k], 1e-9 * expected[k]);
  ASSERT_EQ(result.peaks.size(), 1u);
  double largest = 0.0;
  for (const auto& v : result.ac.values[0]) largest = std::max(largest, std::abs(v));
  EXPECT_EQ(result.peaks[0].peak, largest);
  EXPECT_EQ(result.failed_stage, AcStudyStage::none);
}

}  // namespace
}  // namespace emnet
