// [[circuit]] elements and source waveforms in scene files (emnet/scene/scene.hpp,
// emnet/model/circuit.hpp): a DEA charged through a resistor against the closed-form exponential,
// a pure RC circuit on the exact method, the reader's messages, pwl points from a CSV file equal
// to the same points inline, the SPICE deck's circuit lines and the cross-check against ngspice.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/model/circuit.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/studies/resolve.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

std::string source_path(const std::string& relative) {
  return std::string(EMNET_SOURCE_DIR) + "/" + relative;
}

// A measured error for the test's XML record (--gtest_output=xml), in %.3g.
std::string measured(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

// A small cantilever, with two DEAs (A on top, B below, 0..30 mm) when `deas`, and the [drive]
// `drive`, then the circuit text `circuit`.
std::string scene_text(const std::string& drive, const std::string& circuit, bool deas = true) {
  std::string text =
      "[scene]\nname = \"circuit_test\"\n"
      "[beam]\nlength = \"50 mm\"\nsegments = 4\nbending_stiffness = \"2e-3 N*m^2\"\n"
      "mass_per_length = \"50 g/m\"\n";
  for (const char* dea : {"A", "B"})
    if (deas)
      text += std::string("[[dea]]\nname = \"") + dea +
              "\"\nfrom = \"0 mm\"\nto = \"30 mm\"\nface = \"" +
              (std::string(dea) == "A" ? "top" : "bottom") +
              "\"\nlever_arm = \"1.55 mm\"\nrelative_permittivity = 2.8\n"
              "dielectric_thickness = \"51 um\"\nforce_thickness = \"51 um\"\n"
              "electrode_width = \"20 mm\"\nelectrode_resistance = \"1 MOhm\"\n";
  return text + "[drive]\n" + drive + "\n" + circuit;
}

const char* kNoDrive = "kind = \"none\"\nelectrical_dynamics = true";

// An element as TOML: [[circuit]] with the given lines.
std::string element(const std::string& lines) {
  return "[[circuit]]\n" + lines + "\n";
}

// The amplifier of netlists/rc-dea.toml: a voltage source "amp" on node out, R_amp to dea.A.
std::string amplifier(const std::string& waveform_lines) {
  return element("name = \"amp\"\nkind = \"voltage_source\"\nfrom = \"out\"\nto = \"ground\"\n" +
                 waveform_lines) +
         element(
             "name = \"R_amp\"\nkind = \"resistor\"\nfrom = \"out\"\nto = \"dea.A\"\n"
             "value = \"10 MOhm\"");
}

struct Refusal {
  std::string where, key, message;
};

// The InputError reading `text` gives (an empty refusal when it reads).
Refusal refusal_of(const std::string& text, const std::string& file = "circuit.toml") {
  try {
    (void)read_scene_text(text, file);
  } catch (const InputError& error) {
    return {error.where(), error.key(), error.what()};
  }
  return {};
}

// ---- the acceptance test: a DEA charged through a resistor -------------------------------

// A 0 -> V step (a square wave's rising edge at `delay`, rise 0) behind R = 10 MOhm charges DEA
// A (not driven by the [drive]) through its electrode resistance R_e = 1 MOhm. Without
// back-coupling the DEA's film is a plain capacitor C0 to the electrical side (its force acts on
// the beam only), so the capacitor voltage is u(t) = V*(1 - exp(-(t - delay)/tau)),
// tau = (R + R_e)*C0, C0 = dea_capacitance of the DEA's geometry. Reference: this closed form.
// The network is nonlinear (the DEA's force k_F*u^2), which the exact method refuses, so the
// transient is IDA at rtol 1e-10 (stopping at the edge, a breakpoint); its local error control
// keeps the global error of this smooth first-order decay below the tolerance (measured 8.6e-12
// of V). 1e-9 of V, ten times the tolerance, leaves room for other compilers' step choices.
TEST(Circuit, SourceBehindAResistorChargesADeaAsTheClosedFormExponential) {
  const double voltage = 3000.0, delay = 1e-3;
  const Scene scene = read_scene_text(
      scene_text(kNoDrive, amplifier("waveform = \"square\"\nlow = \"0 V\"\nhigh = \"3 kV\"\n"
                                     "frequency = \"1 Hz\"\ndelay = \"1 ms\"")) +
          "[[probe]]\nname = \"u_A\"\nquantity = \"dea_voltage\"\ndea = \"A\"\n",
      "rc-step.toml");
  const Model model = build_model(scene);
  ASSERT_NE(model.circuit_nodes.find("out"), model.circuit_nodes.end());
  const double capacitance = dea_capacitance(2.8, 51e-6, 0.02, 0.03);
  const double tau = (10e6 + 1e6) * capacitance;
  const System system = model.network.assemble();
  ASSERT_TRUE(system.is_nonlinear());
  TransientOptions options;
  options.end_time = delay + 10 * tau;
  for (int k = 0; k <= 400; ++k) options.output_times.push_back(options.end_time * k / 400);
  options.relative_tolerance = 1e-10;
  const TransientResult result = run_transient_ida(system, model.probes, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.times.size(), options.output_times.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < result.times.size(); ++k) {
    const double t = result.times[k];
    const double expected = t <= delay ? 0.0 : voltage * (1 - std::exp(-(t - delay) / tau));
    worst = std::max(worst, std::abs(result.values[0][k] - expected));
  }
  EXPECT_LT(worst, 1e-9 * voltage);
  RecordProperty("ida_error_of_V", measured(worst / voltage));
}

// The same circuit with a capacitor element in place of the DEA, in a scene without DEAs (a
// linear network), on the exact method: u(t) = V*(1 - exp(-(t - delay)/(R*C))) on the
// capacitor's node. Reference: the closed form. The exact method's error is the rounding of the
// matrix exponential per interval (a few eps of V; measured below); 1e-12 of V is rounding with
// a wide margin.
TEST(Circuit, PureRcCircuitOnTheExactMethodMatchesTheClosedForm) {
  const double voltage = 3000.0, delay = 1e-3, resistance = 10e6, capacitance = 300e-12;
  const double tau = resistance * capacitance;
  const Scene scene = read_scene_text(
      scene_text(kNoDrive,
                 element("name = \"amp\"\nkind = \"voltage_source\"\nfrom = \"out\"\n"
                         "to = \"0\"\nwaveform = \"square\"\nlow = 0\nhigh = \"3 kV\"\n"
                         "frequency = \"1 Hz\"\ndelay = \"1 ms\"") +
                     element("name = \"R\"\nkind = \"resistor\"\nfrom = \"out\"\nto = \"c\"\n"
                             "value = \"10 MOhm\"") +
                     element("name = \"C\"\nkind = \"capacitor\"\nfrom = \"c\"\nto = "
                             "\"ground\"\nvalue = \"300 pF\""),
                 false),
      "rc.toml");
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  ASSERT_FALSE(system.is_nonlinear());
  Probe capacitor_voltage;
  capacitor_voltage.name = "u_C";
  capacitor_voltage.terms = {{model.circuit_nodes.at("c"), 1.0}};
  TransientOptions options;
  options.end_time = delay + 10 * tau;
  for (int k = 0; k <= 400; ++k) options.output_times.push_back(options.end_time * k / 400);
  const TransientResult result = run_transient_exact(system, {capacitor_voltage}, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  double worst = 0.0;
  for (std::size_t k = 0; k < result.times.size(); ++k) {
    const double t = result.times[k];
    const double expected = t <= delay ? 0.0 : voltage * (1 - std::exp(-(t - delay) / tau));
    worst = std::max(worst, std::abs(result.values[0][k] - expected));
  }
  EXPECT_LT(worst, 1e-12 * voltage);
  RecordProperty("exact_error_of_V", measured(worst / voltage));
}

// "auto" electrical dynamics keep the RC loops for a scene with a circuit, and say why.
TEST(Circuit, AutoElectricalDynamicsAreKeptForACircuit) {
  const Scene scene = read_scene_text(
      scene_text("kind = \"none\"\nelectrical_dynamics = \"auto\"", amplifier("value = \"1 kV\"")) +
          "[model]\nband = \"100 Hz\"\n",
      "auto.toml");
  const ResolvedScene resolved = resolve_scene(scene);
  EXPECT_TRUE(resolved.scene.drive.electrical_dynamics);
  ASSERT_FALSE(resolved.scene.automatic_choices.empty());
  EXPECT_NE(resolved.scene.automatic_choices.back().reason.find("[[circuit]]"), std::string::npos)
      << resolved.scene.automatic_choices.back().reason;
  EXPECT_NO_THROW(build_model(resolved.scene));
}

// ---- the reader's messages ---------------------------------------------------------------

TEST(CircuitReader, RefusesBadElementsNamingTheKey) {
  struct Case {
    std::string what, text, key, fragment;
  };
  const std::string resistor =
      "name = \"R1\"\nkind = \"resistor\"\nfrom = \"out\"\nto = \"dea.A\"\n";
  const std::vector<Case> cases = {
      {"unknown kind",
       scene_text(kNoDrive, element("name = \"D1\"\nkind = \"diode\"\nfrom = \"a\"\nto = \"0\"")),
       "circuit[D1].kind", "'diode'"},
      {"missing value",
       scene_text(kNoDrive, amplifier("value = \"1 kV\"") +
                                element("name = \"R1\"\nkind = \"resistor\"\nfrom = "
                                        "\"out\"\nto = \"dea.A\"")),
       "circuit[R1].value", "missing (required)"},
      {"negative resistance",
       scene_text(kNoDrive, amplifier("value = \"1 kV\"") + element(resistor + "value = -1")),
       "circuit[R1].value", "must be > 0 for a resistor"},
      {"a waveform key the waveform does not use",
       scene_text(kNoDrive, amplifier("waveform = \"square\"\nlow = 0\nhigh = 1\nfrequency = 1\n"
                                      "width = \"1 ms\"")),
       "circuit[amp].width", "is not used by waveform 'square'"},
      {"a waveform on a resistor",
       scene_text(kNoDrive, amplifier("value = 1") + element(resistor + "value = 1\nwaveform = "
                                                                        "\"sine\"")),
       "circuit[R1].waveform", "is only used by sources"},
      {"a source's value beside its waveform",
       scene_text(kNoDrive, amplifier("waveform = \"sine\"\namplitude = 1\nfrequency = 1\n"
                                      "value = 2")),
       "circuit[amp].value", "is not used by waveform 'sine'"},
      {"unknown DEA",
       scene_text(kNoDrive, element("name = \"V1\"\nkind = \"voltage_source\"\n"
                                    "from = \"dea.C\"\nto = \"0\"\nvalue = 1")),
       "circuit[V1].from", "names DEA 'C', which the scene does not have"},
      {"dangling node",
       scene_text(kNoDrive, element("name = \"V1\"\nkind = \"voltage_source\"\nfrom = "
                                    "\"dea.A\"\nto = \"0\"\nvalue = 1") +
                                element("name = \"R1\"\nkind = \"resistor\"\nfrom = "
                                        "\"loose\"\nto = \"dea.A\"\nvalue = 1")),
       "circuit[R1].from", "node 'loose' is touched by this element only"},
      {"a DEA driven by the drive and a circuit",
       scene_text("kind = \"switched\"\ndeas = [\"A\"]\nvoltage = \"1 kV\"\nfrequency = \"1 Hz\"",
                  amplifier("value = \"1 kV\"")),
       "circuit[R_amp].to", "drive.deas"},
      {"no DC path to ground",
       scene_text(kNoDrive, amplifier("value = \"1 kV\"") +
                                element("name = \"C1\"\nkind = \"capacitor\"\nfrom = \"dea.B\"\n"
                                        "to = \"float\"\nvalue = \"1 nF\"") +
                                element("name = \"C2\"\nkind = \"capacitor\"\nfrom = "
                                        "\"float\"\nto = \"0\"\nvalue = \"1 nF\"")),
       "circuit[C1].from", "node 'dea.B' has no DC path to ground"},
      {"a loop of voltage sources",
       scene_text(kNoDrive, amplifier("value = \"1 kV\"") +
                                element("name = \"V2\"\nkind = \"voltage_source\"\nfrom = "
                                        "\"out\"\nto = \"ground\"\nvalue = 2")),
       "circuit[V2].to", "closes a loop of voltage sources and inductors"},
      {"electrical dynamics off",
       scene_text("kind = \"none\"\nelectrical_dynamics = false", amplifier("value = 1")),
       "drive.electrical_dynamics", "[[circuit]]"},
      {"an element on one node",
       scene_text(kNoDrive,
                  element(resistor.substr(0, resistor.find("to =")) + "to = \"out\"\nvalue = 1")),
       "circuit[R1].to", "between a node and itself"},
      {"a square wave's rise longer than its high part",
       scene_text(kNoDrive, amplifier("waveform = \"square\"\nlow = 0\nhigh = 1\nfrequency = "
                                      "\"1 kHz\"\nrise = \"0.6 ms\"")),
       "circuit[amp].rise", "must fit the high part of the period"},
      {"pwl times not increasing",
       scene_text(kNoDrive, amplifier("waveform = \"pwl\"\npoints = [[\"1 ms\", \"0 V\"], "
                                      "[\"1 ms\", \"1 V\"]]")),
       "circuit[amp].points", "point 2's time"},
  };
  for (const Case& c : cases) {
    const Refusal refused = refusal_of(c.text);
    EXPECT_EQ(refused.key, c.key) << c.what << ": " << refused.message;
    EXPECT_NE(refused.message.find(c.fragment), std::string::npos)
        << c.what << ": " << refused.message;
    EXPECT_EQ(refused.where.rfind("circuit.toml", 0), 0u) << c.what << ": " << refused.where;
  }
}

// ---- pwl points from a CSV file --------------------------------------------------------------

struct TemporaryDirectory {
  std::filesystem::path path;
  TemporaryDirectory() {
    path = std::filesystem::path(::testing::TempDir()) /
           ("emnet_circuit_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(path);
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
};

const char* kPwlInline =
    "waveform = \"pwl\"\npoints = [[\"0 s\", \"0 V\"], [\"1 ms\", \"3 kV\"], [\"5 ms\", \"3 kV\"], "
    "[\"6.5 ms\", \"1 kV\"]]";

// The same points in a CSV file (a header line, a comment, commas and spaces) read to the same
// doubles as inline; the waveform and the model's transient agree bit for bit.
TEST(CircuitReader, PwlFromCsvEqualsTheSamePwlInline) {
  const TemporaryDirectory directory;
  directory.write("drive.csv",
                  "time [s], voltage [V]\n# the amplifier\n0, 0\n1e-3, 3000\n"
                  "5e-3 3000\n\n6.5e-3,1000\n");
  const std::string from_file = directory.write(
      "file.toml", scene_text(kNoDrive, amplifier("waveform = \"pwl\"\nfile = \"drive.csv\"")));
  const std::string inline_points =
      directory.write("inline.toml", scene_text(kNoDrive, amplifier(kPwlInline)));
  const Scene file_scene = read_scene(from_file), inline_scene = read_scene(inline_points);
  const WaveformSpec& a = file_scene.circuit[0].waveform;
  const WaveformSpec& b = inline_scene.circuit[0].waveform;
  ASSERT_EQ(a.points.size(), 4u);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.file, "drive.csv");
  const Waveform wa = circuit_waveform(file_scene.circuit[0]);
  const Waveform wb = circuit_waveform(inline_scene.circuit[0]);
  for (double t : {0.0, 0.5e-3, 1e-3, 3e-3, 6e-3, 1.0}) EXPECT_EQ(wa.value(t), wb.value(t)) << t;
  EXPECT_DOUBLE_EQ(wa.value(5.75e-3), 2000.0);
}

// The files a scene read, as data (scene_files: what a pickled Python scene carries): read back
// with the scene's text in place of the file, they give the same points bit for bit, even after
// the file changed or went (a worker in another directory), with values that have no short
// decimal form (1/3, 0.1 + 0.2).
TEST(CircuitReader, PwlFilesAsDataRebuildTheSamePoints) {
  const TemporaryDirectory directory;
  char csv[128];
  std::snprintf(csv, sizeof csv, "0,0\n%.17g,%.17g\n%.17g,3000\n", 1.0 / 3.0 * 1e-3, 0.1 + 0.2,
                7e-3 / 3.0);
  directory.write("drive.csv", csv);
  const std::string text =
      scene_text(kNoDrive, amplifier("waveform = \"pwl\"\nfile = \"drive.csv\""));
  const std::string path = directory.write("file.toml", text);
  const Scene read = read_scene(path);
  const SceneFiles files = scene_files(read);
  ASSERT_EQ(files.size(), 1u);
  ASSERT_EQ(files.count("drive.csv"), 1u);
  std::filesystem::remove(directory.path / "drive.csv");
  const Scene rebuilt = read_scene_text(text, path, {}, files);
  ASSERT_EQ(rebuilt.circuit[0].waveform.points.size(), 3u);
  EXPECT_EQ(rebuilt.circuit[0].waveform.points, read.circuit[0].waveform.points);
  EXPECT_EQ(scene_files(rebuilt), files);
  // Without the data the missing file is an error, as before.
  EXPECT_THROW(read_scene_text(text, path), InputError);
}

TEST(CircuitReader, CsvPwlErrorsNameTheFileAndLine) {
  const TemporaryDirectory directory;
  const std::string missing = directory.write(
      "missing.toml", scene_text(kNoDrive, amplifier("waveform = \"pwl\"\nfile = \"none.csv\"")));
  const Refusal no_file = refusal_of(read_scene_file(missing), missing);
  EXPECT_EQ(no_file.key, "circuit[amp].file");
  EXPECT_NE(no_file.where.find("none.csv"), std::string::npos) << no_file.where;
  EXPECT_NE(no_file.message.find("no such file"), std::string::npos) << no_file.message;

  directory.write("bad.csv", "t,v\n0,0\n1e-3,3 kV\n");
  const std::string bad = directory.write(
      "bad.toml", scene_text(kNoDrive, amplifier("waveform = \"pwl\"\nfile = \"bad.csv\"")));
  const Refusal bad_line = refusal_of(read_scene_file(bad), bad);
  EXPECT_EQ(bad_line.key, "circuit[amp].file");
  EXPECT_EQ(bad_line.where, (directory.path / "bad.csv").string() + ":3");
  EXPECT_NE(bad_line.message.find("expected two numbers"), std::string::npos) << bad_line.message;

  directory.write("backwards.csv", "0,0\n2e-3,1\n1e-3,2\n");
  const std::string backwards = directory.write(
      "backwards.toml",
      scene_text(kNoDrive, amplifier("waveform = \"pwl\"\nfile = \"backwards.csv\"")));
  const Refusal not_increasing = refusal_of(read_scene_file(backwards), backwards);
  EXPECT_EQ(not_increasing.where, (directory.path / "backwards.csv").string() + ":3");
  EXPECT_NE(not_increasing.message.find("times must increase"), std::string::npos)
      << not_increasing.message;
}

// ---- the parameter table: --set and set_parameter on circuit keys -------------------------

TEST(CircuitReader, CircuitKeysAreSetByName) {
  const Scene scene = read_scene(source_path("netlists/rc-dea.toml"),
                                 {"circuit.R_amp.value=20 MOhm", "circuit[amp].high=2 kV"});
  EXPECT_DOUBLE_EQ(get_parameter(scene, "circuit[R_amp].value"), 20e6);
  EXPECT_DOUBLE_EQ(get_parameter(scene, "circuit.amp.high"), 2000.0);
  Scene changed = scene;
  set_parameter(changed, "circuit.R_amp.value", 5e6);
  EXPECT_DOUBLE_EQ(changed.circuit[1].value, 5e6);
  EXPECT_THROW(set_parameter(changed, "circuit.R_amp.value", -1.0), InputError);
  EXPECT_THROW(set_parameter(changed, "circuit.amp.width", 1e-3), InputError);  // square: unused
  // The source's levels are volts: a current is refused.
  try {
    (void)read_scene(source_path("netlists/rc-dea.toml"), {"circuit.amp.high=1 A"});
    ADD_FAILURE() << "a current accepted as a voltage source's level";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "circuit[amp].high");
  }
}

// ---- the SPICE deck and the cross-check ----------------------------------------------------

TEST(CircuitSpice, DeckHoldsTheCircuitElements) {
  const Model model = build_model(read_scene(source_path("netlists/rc-dea.toml")));
  SpiceDeckOptions options;
  options.analysis = SpiceAnalysis::tran;
  options.end_time = 0.2;
  options.output_step = 1e-4;
  const SpiceDeck deck = write_spice_deck(model, options);
  for (const char* line : {"circuit ([[circuit]] entries)", "\nR_R_amp out s_A 10000000\n",
                           "\nV_amp out 0 PULSE(", "driven by the circuit at its terminal s_A"})
    EXPECT_NE(deck.text.find(line), std::string::npos) << line << "\n" << deck.text;
  // DEA A's terminal has no source of the drive: the circuit drives it.
  EXPECT_EQ(deck.text.find("V_V_A "), std::string::npos) << deck.text;
}

using emnet::testing::ngspice_available;

// The whole cross-check (op, ac, modal, tran) of the shipped circuit example against ngspice,
// with the tolerances include/emnet/verification/crosscheck.hpp justifies.
TEST(CircuitSpice, CrosscheckOfTheCircuitExamplePasses) {
  if (!ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  const auto run = emnet::testing::run_emnet(
      "crosscheck " + source_path("netlists/rc-dea.toml") + " --timeout 60", "timeout 120 ");
  EXPECT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("crosscheck passed"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace emnet
