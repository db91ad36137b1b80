// Circuit-driven DEAs are DEAs for the validity checks (emnet/model/validity.hpp): a DEA that a
// [[circuit]] drives through its terminal "dea.X" has its field judged against a voltage bound
// proved from the circuit (emnet/model/circuit.hpp, circuit_voltage_bound), and where no bound
// is known the summary says "field not checked" and why instead of "no DEA driven".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/model/circuit.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/transient_study.hpp"

namespace emnet {
namespace {

using testing::run_emnet;

const std::string kTweezer = std::string(EMNET_SOURCE_DIR) + "/netlists/tweezer-jaw.toml";

// Reference: the maximum principle of RC networks driven by grounded voltage sources (no node
// exceeds the sources' levels and 0). In the tweezer each DEA sits behind 4.7 MOhm from its own
// square source (0 V .. high, src_B inverted), joined to the other only through ground, so each
// DEA's bound is its own source's level: exactly 2500 V over the waveform (the levels are read
// from the scene file; the comparison is exact because no arithmetic is done on them).
TEST(CircuitValidity, EachDeaIsBoundedByTheSourcesOfItsOwnPart) {
  const Scene scene = read_scene(kTweezer);
  EXPECT_EQ(circuit_driven_deas(scene), (std::vector<std::string>{"A", "B"}));
  const Scene raised = read_scene(kTweezer, {"circuit.src_A.high=6kV"});
  const CircuitVoltageBound a = circuit_voltage_bound(raised, "A");
  const CircuitVoltageBound b = circuit_voltage_bound(raised, "B");
  ASSERT_TRUE(a.bounded) << a.reason;
  ASSERT_TRUE(b.bounded) << b.reason;
  EXPECT_EQ(a.peak, 6000.0);  // src_A's raised high level
  EXPECT_EQ(b.peak, 2500.0);  // src_B untouched: src_A reaches B only through ground
}

// 6 kV on 37 um is 162 V/um, 203 % of the 80 V/um breakdown field: a violation naming DEA A
// (6000/37e-6/80e6 = 2.027, the closed form of the field fraction, to 1e-12 relative).
TEST(CircuitValidity, BreakdownFieldOfACircuitDrivenDeaIsAViolation) {
  const Scene scene = read_scene(kTweezer, {"circuit.src_A.high=6kV"});
  const Validity validity = check_validity(scene, {}, drive_peak_voltages(scene));
  ASSERT_FALSE(validity.within());
  EXPECT_EQ(validity.violations[0].subject, "A");
  EXPECT_NEAR(validity.field_fraction, 6000.0 / 37e-6 / 80e6, 1e-12 * 2.03);
  EXPECT_EQ(validity.summary.find("no DEA driven"), std::string::npos) << validity.summary;
  EXPECT_NE(validity.summary.find("bound:"), std::string::npos) << validity.summary;
}

// An inductor in the DEA's part of the circuit leaves the RC class: no bound, and the summary
// says so, naming the element, rather than "no DEA driven".
TEST(CircuitValidity, NoKnownBoundSaysFieldNotChecked) {
  std::string text = read_scene_file(kTweezer);
  const std::string resistor =
      "kind = \"resistor\"\nfrom = \"in_A\"\nto = \"dea.A\"\nvalue = \"4.7 MOhm\"";
  const std::size_t at = text.find(resistor);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, resistor.size(),
               "kind = \"inductor\"\nfrom = \"in_A\"\nto = \"dea.A\"\nvalue = \"1 H\"");
  const Scene scene = read_scene_text(text, kTweezer);
  const CircuitVoltageBound a = circuit_voltage_bound(scene, "A");
  EXPECT_FALSE(a.bounded);
  EXPECT_NE(a.reason.find("circuit[R_A]"), std::string::npos) << a.reason;
  const Validity validity = check_validity(scene, {}, drive_peak_voltages(scene));
  EXPECT_NE(validity.summary.find("field not checked for circuit-driven DEA A"), std::string::npos)
      << validity.summary;
  EXPECT_EQ(validity.summary.find("no DEA driven"), std::string::npos) << validity.summary;
}

// The program: at 6 kV / 37 um the tweezer warns and exits 5 (kExitOutsideValidity) in static;
// the shipped 2.5 kV says its field fraction (2500/37e-6/80e6 = 84.5 %) and exits 0.
TEST(CliCircuitValidity, TweezerAtSixKilovoltsExitsOutsideValidity) {
  const std::string raised = " --set circuit.src_A.high=6kV --set dea.A.dielectric_thickness=37um";
  const auto run = run_emnet("static " + kTweezer + raised);
  EXPECT_EQ(run.status, kExitOutsideValidity) << run.out << run.err;
  EXPECT_NE(run.out.find("WARNING"), std::string::npos) << run.out;
  const auto shipped = run_emnet("static " + kTweezer);
  EXPECT_EQ(shipped.status, 0) << shipped.out << shipped.err;
  EXPECT_NE(shipped.out.find("84.5 % of its breakdown field"), std::string::npos) << shipped.out;
  EXPECT_EQ(shipped.out.find("no DEA driven"), std::string::npos) << shipped.out;
}

// The tweezer with a 1000 H inductor after a 1 kOhm R_A: no bound (an inductor), so the field
// was "not checked"; the transient now judges the voltage it computed. Reference: the series
// RLC's step response (back-coupling off, so the DEA's loop is a pure RLC: C its capacitance, R
// the 1 kOhm plus its 0.5 MOhm electrode), peak V·(1 + exp(−ζπ/√(1 − ζ²))) at t = π/ω_d,
// 4309 V here, 146 % of the 2960 V breakdown. Tolerance 1e-3: the largest of the output samples
// (every 6.25 us, a phase step of 0.015 rad: 5e-5 low) at IDA's rtol 1e-8.
TEST(CircuitValidity, TransientJudgesTheComputedVoltageWhereNoBoundIsKnown) {
  std::ifstream file(kTweezer);
  std::string text((std::istreambuf_iterator<char>(file)), {});
  const std::string series = "to = \"dea.A\"\nvalue = \"4.7 MOhm\"";
  ASSERT_NE(text.find(series), std::string::npos);
  text.replace(text.find(series), series.size(),
               "to = \"mid_A\"\nvalue = \"1 kOhm\"\n\n[[circuit]]\nname = \"L_A\"\nkind = "
               "\"inductor\"\nfrom = \"mid_A\"\nto = \"dea.A\"\nvalue = \"1000 H\"");
  const std::string path = ::testing::TempDir() + "tweezer_inductor.toml";
  std::ofstream(path) << text;
  const Scene scene = read_scene(path, {"beam.segments=8"});
  TransientStudyOptions options;
  options.periods = 0.05;  // 6.25 ms: the first peak at 1.29 ms
  options.points_per_period = 20000;
  options.rtol = 1e-8;
  const TransientStudyResult run = run_transient_study(scene, options);
  ASSERT_TRUE(run.status.ok()) << run.status.message;
  const DeaLayout& dea = run.model.deas[0];
  ASSERT_EQ(dea.name, "A");
  const double r = 1e3 + dea.electrode_resistance, c = dea.capacitance, l = 1000.0;
  const double zeta = 0.5 * r * std::sqrt(c / l);
  const double peak = 2500.0 * (1.0 + std::exp(-zeta * M_PI / std::sqrt(1.0 - zeta * zeta)));
  ASSERT_FALSE(run.validity.within()) << run.validity.summary;
  const double breakdown = 80e6 * 37e-6;
  EXPECT_NEAR(run.validity.field_fraction * breakdown, peak, 1e-3 * peak) << run.validity.summary;
  EXPECT_NE(run.validity.summary.find("computed at the output times"), std::string::npos)
      << run.validity.summary;
}

// The inverted source is at 0 V at t = 0, so its DEA's k_F·V² force has no part linear in an AC
// input there: an AC input on src_B alone moved nothing and said nothing (an all-zero Bode
// plot, exit 0). Now a note names the DEA (the shipped scene, its input on src_A, has it too:
// B adds nothing to the response), and where every output is exactly zero the command
// refuses, naming circuit.
TEST(CliAcInput, AnInputAboutZeroVoltsIsSaidAndAnAllZeroResponseRefused) {
  const std::string on_b =
      "ac " + kTweezer + " --segments 8 --set circuit.src_A.ac=0 --set circuit.src_B.ac=1V";
  const auto noted = run_emnet(on_b);
  EXPECT_EQ(noted.status, 0) << noted.err;
  EXPECT_NE(noted.out.find("note: DEA B is at 0 V at the operating point"), std::string::npos)
      << noted.out;
  const auto refused = run_emnet(on_b + " --probe tip");
  EXPECT_EQ(refused.status, 2) << refused.out;
  EXPECT_NE(refused.err.find("key 'circuit'"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("every response is exactly zero"), std::string::npos) << refused.err;
  const auto shipped = run_emnet("ac " + kTweezer + " --segments 8 --probe tip");
  EXPECT_EQ(shipped.status, 0) << shipped.err;
  EXPECT_EQ(shipped.out.find("DEA A is at 0 V"), std::string::npos) << shipped.out;
}

}  // namespace
}  // namespace emnet
