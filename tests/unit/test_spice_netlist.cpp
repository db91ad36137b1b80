// SPICE export (include/emnet/spice/spice_netlist.hpp): deck structure, safety against scene text,
// freshness of the decks checked in under netlists/, and ngspice (run as a subprocess) on the
// exported decks against emnet's own static and AC results.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/studies/resolve.hpp"
#include "fixtures.hpp"
#include "shipped_scenes.hpp"

namespace {

using namespace emnet;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::string source_path(const std::string& relative) {
  return std::string(EMNET_SOURCE_DIR) + "/" + relative;
}

Model scene_model(const std::string& relative, const std::vector<std::string>& overrides = {}) {
  return prepare_model(read_scene(source_path(relative), overrides));
}

// Element lines: not comments, not dot commands, not continuation lines.
std::vector<std::string> element_lines(const std::string& deck) {
  std::vector<std::string> elements;
  for (const auto& line : lines_of(deck))
    if (!line.empty() && line[0] != '*' && line[0] != '.' && line[0] != '+')
      elements.push_back(line);
  return elements;
}

TEST(SpiceNetlist, FishFinDeckHasEveryNodeSegmentAndDeaCommented) {
  const Model model = scene_model("netlists/fishfin.toml");
  SpiceDeckOptions options;
  options.analysis = SpiceAnalysis::tran;
  options.end_time = 1.0;
  options.output_step = 2e-3;
  const SpiceDeck deck = write_spice_deck(model, options);
  const auto lines = lines_of(deck.text);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.front()[0], '*') << "the first line (SPICE's title) is a comment";
  EXPECT_EQ(lines.back(), ".end");
  for (const Node& node : model.network.nodes())
    EXPECT_NE(deck.text.find("\n* " + node.name + ": " + node.meaning + "\n"), std::string::npos)
        << "node " << node.name << " has no comment with its meaning";
  for (int k = 0; k < model.scene.beam.segments; ++k)
    EXPECT_NE(deck.text.find("\n* ---- segment " + std::to_string(k) + ": "), std::string::npos)
        << "segment " << k;
  for (const char* dea : {"A", "B"})
    EXPECT_NE(deck.text.find(std::string("\n* ---- DEA ") + dea + ": "), std::string::npos)
        << "DEA " << dea;
  // Only elements LTspice also reads; names unique without regard to case.
  std::set<std::string> names;
  for (const auto& line : element_lines(deck.text)) {
    EXPECT_NE(std::string("RLCVIEFGB").find(line[0]), std::string::npos) << line;
    const std::string name = lower(line.substr(0, line.find(' ')));
    EXPECT_TRUE(names.insert(name).second) << "duplicate element " << name;
    for (char c : name) EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  }
  for (const auto& line : lines) {
    EXPECT_FALSE(starts_with(lower(line), ".control")) << "no control block unless asked";
    EXPECT_LE(line.size(), 100u) << line;
  }
  // The mapping: every node has its vector, every inductor and source its branch.
  const System system = model.network.assemble();
  ASSERT_EQ(deck.unknowns.size(), system.unknowns.size());
  for (size_t k = 0; k < system.unknowns.size(); ++k)
    EXPECT_FALSE(deck.unknowns[k].vector.empty()) << system.unknowns[k].name;
  EXPECT_EQ(deck.unknowns[static_cast<size_t>(system.branch_index("nT0"))].vector, "l_nt0#branch");
  EXPECT_EQ(deck.unknowns[static_cast<size_t>(system.branch_index("lever3"))].vector,
            "v_lever3#branch");
  // dx2..dx4 as `emnet tran` prints them, beside P1..P4 and the tip.
  std::set<std::string> outputs;
  for (const auto& o : deck.outputs) outputs.insert(o.vector);
  for (const char* name : {"out_p1", "out_p4", "out_tip", "out_dx2", "out_dx4", "out_u_a"})
    EXPECT_EQ(outputs.count(name), 1u) << name;
}

TEST(SpiceNetlist, ZeroConductanceIsAnOpenNotADivisionByZero) {
  Model model = build_model(emnet::testing::cantilever_scene(2));
  model.network.add<Conductance>("open_damper", model.beam.velocity[1], ground, 0.0);
  SpiceDeckOptions options;
  options.analysis = SpiceAnalysis::ac;  // the op deck leaves every damper out anyway
  const SpiceDeck deck = write_spice_deck(model, options);
  EXPECT_EQ(deck.text.find("R_open_damper"), std::string::npos);
  EXPECT_NE(deck.text.find("open_damper: conductance 0"), std::string::npos);
  for (const char* bad : {"inf", "nan"})
    for (const auto& line : element_lines(deck.text))
      EXPECT_EQ(lower(line).find(bad), std::string::npos) << line;
}

// Scene text tries to add lines, a control block and a shell command to the deck.
const std::string injection = "x\n.control\nshell touch /tmp/pwned\n.endc\r\nshell rm -rf /\n*#";

void expect_no_injected_lines(const std::string& text, bool control_block) {
  int control_lines = 0, end_control_lines = 0;
  for (const auto& raw : lines_of(text)) {
    std::string line = lower(raw);
    line.erase(0, line.find_first_not_of(" \t"));
    EXPECT_FALSE(starts_with(line, "shell")) << raw;
    EXPECT_FALSE(starts_with(line, "*#")) << raw;
    EXPECT_EQ(raw.find('\r'), std::string::npos);
    control_lines += starts_with(line, ".control");
    end_control_lines += starts_with(line, ".endc");
  }
  EXPECT_EQ(control_lines, control_block ? 1 : 0);
  EXPECT_EQ(end_control_lines, control_block ? 1 : 0);
}

TEST(SpiceNetlist, SceneTextCannotAddLinesOrCommands) {
  Scene scene = emnet::testing::cantilever_scene(3);
  scene.name = "name" + injection;
  scene.title = "title" + injection;
  scene.file = "dir/scene" + injection + ".toml";
  scene.drive.deas = {"A" + injection};
  scene.loads.push_back(emnet::testing::load(LoadKind::force, 0.5, 1.0));
  scene.probes.push_back(
      emnet::testing::beam_probe("tip" + injection, ProbeQuantity::deflection, 0.5));
  const Model model = build_model(scene);
  for (SpiceAnalysis analysis : {SpiceAnalysis::op, SpiceAnalysis::ac, SpiceAnalysis::tran})
    for (bool control : {false, true}) {
      SpiceDeckOptions options;
      options.analysis = analysis;
      options.end_time = 1.0;
      options.output_step = 0.01;
      options.control = control;
      options.overrides = {"scene.title=" + injection};
      const SpiceDeck deck = write_spice_deck(model, options);
      SCOPED_TRACE(std::string(spice_analysis_name(analysis)) + (control ? " +control" : ""));
      expect_no_injected_lines(deck.text, control);
      for (const auto& o : deck.outputs)
        for (char c : o.vector)
          EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) || c == '_');
    }
}

TEST(SpiceNetlist, SceneTextFromAFileCannotAddLines) {
  // The same through the scene reader: TOML strings may hold newlines.
  const std::string text =
      "[scene]\nname = \"fin\\n.control\\nshell touch /tmp/pwned\\n.endc\"\n"
      "title = \"t\\r\\nshell ls\\n.endc\"\n"
      "description = \"d\\n.control\"\n"
      "[beam]\nlength = 0.5\nsegments = 2\nbending_stiffness = 2.0\nmass_per_length = 0.3\n"
      "[[load]]\nkind = \"force\"\nat = 0.5\nvalue = 1.0\n"
      "[provenance]\n\"beam.length\" = \"assumed:\\n.control\\nshell ls\"\n";
  const Model model = build_model(read_scene_text(text, "inline.toml"));
  for (bool control : {false, true}) {
    SpiceDeckOptions options;
    options.control = control;
    expect_no_injected_lines(write_spice_deck(model, options).text, control);
  }
}

TEST(SpiceNetlist, ADeaNameThatIsNotANameIsRefusedNamingTheKey) {
  Scene scene = emnet::testing::cantilever_scene(2);
  DeaSpec dea;
  dea.name = "A\n.control";
  dea.to = 0.25;
  dea.lever_arm = 1e-3;
  dea.relative_permittivity = 2.8;
  dea.dielectric_thickness = 51e-6;
  dea.force_thickness = 51e-6;
  dea.electrode_width = 0.025;
  dea.electrode_resistance = 1e6;
  scene.deas.push_back(dea);
  const Model model = build_model(scene);
  try {
    write_spice_deck(model, {});
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "dea[0].name");
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

TEST(SpiceNetlist, NamesAreSafeAndUniqueWithoutRegardToCase) {
  Scene scene = emnet::testing::cantilever_scene(2);
  scene.probes.push_back(emnet::testing::beam_probe("Tip", ProbeQuantity::deflection, 0.5));
  scene.probes.push_back(emnet::testing::beam_probe("tip", ProbeQuantity::deflection, 0.5));
  scene.probes.push_back(emnet::testing::beam_probe("gnd", ProbeQuantity::deflection, 0.25));
  const Model model = build_model(scene);
  SpiceDeckOptions options;
  options.outputs = model.probes;
  options.outputs.push_back(model.parse_probe("deflection@0.1"));
  const SpiceDeck deck = write_spice_deck(model, options);
  std::set<std::string> vectors;
  for (const auto& o : deck.outputs) {
    EXPECT_TRUE(vectors.insert(o.vector).second) << o.vector;
    EXPECT_NE(o.vector, "0");
    EXPECT_NE(o.vector, "gnd");
    for (char c : o.vector) EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  }
  EXPECT_EQ(deck.outputs.back().vector, "out_deflection_0_1");
}

// ---- freshness of the checked-in decks ----------------------------------------------------
//
// Regenerate them from the repository root with exactly:
//   build/emnet netlist netlists/fishfin.toml --analysis ac -o netlists/fishfin-ac.cir
//   build/emnet netlist netlists/fishfin.toml --analysis tran -o netlists/fishfin-tran.cir
//   build/emnet netlist netlists/cantilever.toml --analysis ac -o netlists/cantilever-ac.cir
//   build/emnet netlist netlists/cantilever.toml --analysis tran --switching 5 --reltol 1e-4
//       -o netlists/cantilever-tran.cir
// (the options below are what those commands set; the CLI test further down checks one of
// them through the program itself).
struct CheckedInDeck {
  std::string file;
  std::string scene;
  SpiceAnalysis analysis;
  std::vector<std::string> overrides;
  double switching_hz;  // tran: the period's frequency (0: the scene's drive.frequency)
  double reltol;
};

std::vector<CheckedInDeck> checked_in_decks() {
  return {
      {"netlists/fishfin-ac.cir", "netlists/fishfin.toml", SpiceAnalysis::ac, {}, 0.0, 1e-6},
      {"netlists/fishfin-tran.cir", "netlists/fishfin.toml", SpiceAnalysis::tran, {}, 0.0, 1e-6},
      {"netlists/cantilever-ac.cir", "netlists/cantilever.toml", SpiceAnalysis::ac, {}, 0.0, 1e-6},
      {"netlists/cantilever-tran.cir",
       "netlists/cantilever.toml",
       SpiceAnalysis::tran,
       {"drive.frequency=5"},
       5.0,
       1e-4}};
}

// What `emnet netlist` writes with its default options (10 periods, 100 points per period,
// max step = output step, start at rest, the scene's [ac] sweep).
std::string regenerate(const CheckedInDeck& d) {
  const Model model = scene_model(d.scene, d.overrides);
  SpiceDeckOptions options;
  options.analysis = d.analysis;
  options.overrides = d.overrides;
  if (d.analysis == SpiceAnalysis::tran) {
    const double period = 1.0 / model.scene.drive.frequency;
    options.end_time = 10.0 * period;
    options.output_step = period / 100;
    options.relative_tolerance = d.reltol;
  }
  return write_spice_deck(model, options).text;
}

// The tran deck from the static state takes that state from its caller (the writer runs no
// analysis). Reference: emnet's static solve of the same network, whose probe values the .ic
// lines hold (printed with the deck's 12 digits); without a state the writer refuses, a failed
// one is the OptionError naming the field "start" (the command line's --start).
TEST(SpiceNetlist, StaticStartTakesTheCallersStaticState) {
  const Model model = scene_model("netlists/fishfin.toml");
  SpiceDeckOptions options;
  options.analysis = SpiceAnalysis::tran;
  options.end_time = 0.4;
  options.output_step = 2e-3;
  options.start = StartState::static_;
  EXPECT_THROW(write_spice_deck(model, options), std::invalid_argument);
  const System system = model.network.assemble();
  options.static_state = solve_static(system);
  ASSERT_TRUE(options.static_state->status.ok());
  const SpiceDeck deck = write_spice_deck(model, options);
  const Probe tip = model.parse_probe("tip");
  char expected[96];
  std::snprintf(expected, sizeof expected, ".ic V(out_tip)=%.12g\n",
                static_probe_value(system, *options.static_state, tip));
  EXPECT_NE(deck.text.find(expected), std::string::npos) << expected;
  options.static_state->status = Status::failure("singular");
  try {
    write_spice_deck(model, options);
    ADD_FAILURE() << "a failed static state was written";
  } catch (const OptionError& error) {
    EXPECT_EQ(error.field(), "start");
    EXPECT_EQ(error.key(), "start");
    EXPECT_NE(std::string(error.what()).find("no static state (singular)"), std::string::npos);
  }
}

TEST(SpiceNetlist, CheckedInDecksAreFresh) {
  for (const auto& d : checked_in_decks()) {
    const std::string expected = regenerate(d);
    const std::string actual = read_file(source_path(d.file));
    if (actual == expected) continue;
    const auto a = lines_of(actual), e = lines_of(expected);
    size_t k = 0;
    while (k < a.size() && k < e.size() && a[k] == e[k]) ++k;
    ADD_FAILURE() << d.file << " is out of date (regenerate it: see the comment above this test)"
                  << "; first difference at line " << k + 1
                  << ":\n  checked in: " << (k < a.size() ? a[k] : "<end of file>")
                  << "\n  regenerated: " << (k < e.size() ? e[k] : "<end of file>");
  }
}

TEST(SpiceNetlist, CommandLineWritesTheSameDeckAsTheLibrary) {
  const auto run = emnet::testing::run_emnet("netlist " + source_path("netlists/fishfin.toml") +
                                             " --analysis ac");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.out, regenerate(checked_in_decks()[0]));
  const auto bad = emnet::testing::run_emnet("netlist " + source_path("netlists/fishfin.toml") +
                                             " --analysis tran --periods -1");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("--periods"), std::string::npos) << bad.err;
}

// ---- ngspice on the exported decks -------------------------------------------------------

// ngspice's vectors from an ASCII rawfile, by lower-case plain name ("v3", "out_tip",
// "v_lever0#branch"): the rawfile's "v(x)" and "i(x)" renamed.
struct RawFile {
  std::map<std::string, std::vector<std::complex<double>>> vectors;
};

using emnet::testing::ngspice_available;

RawFile run_ngspice(const std::string& deck, const std::string& tag) {
  const std::string base =
      ::testing::TempDir() + "emnet_spice_" + tag + "_" + std::to_string(getpid());
  {
    std::ofstream out(base + ".cir");
    out << deck;
  }
  const std::string command = "cd " + ::testing::TempDir() +
                              " && SPICE_ASCIIRAWFILE=1 timeout 60 ngspice -b -r " + base +
                              ".raw " + base + ".cir > " + base + ".log 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_EQ(status, 0) << "ngspice failed: " << read_file(base + ".log");
  const std::string log = lower(read_file(base + ".log"));
  for (const char* word : {"singular", "warning", "error"})
    EXPECT_EQ(log.find(word), std::string::npos) << "ngspice: " << read_file(base + ".log");
  RawFile raw;
  std::istringstream in(read_file(base + ".raw"));
  std::string line;
  int variables = 0, points = 0;
  bool is_complex = false;
  std::vector<std::string> names;
  while (std::getline(in, line)) {
    if (starts_with(line, "Flags:")) is_complex = line.find("complex") != std::string::npos;
    if (starts_with(line, "No. Variables:")) variables = std::stoi(line.substr(14));
    if (starts_with(line, "No. Points:")) points = std::stoi(line.substr(11));
    if (line == "Variables:")
      for (int k = 0; k < variables && std::getline(in, line); ++k) {
        std::istringstream fields(line);
        std::string index, name;
        fields >> index >> name;
        name = lower(name);
        if (starts_with(name, "v(") || starts_with(name, "i("))
          name = starts_with(name, "i(") ? name.substr(2, name.size() - 3) + "#branch"
                                         : name.substr(2, name.size() - 3);
        names.push_back(name);
      }
    if (line == "Values:") break;
  }
  std::string token;
  for (int p = 0; p < points; ++p) {
    in >> token;  // point index
    for (const auto& name : names) {
      in >> token;
      const auto comma = token.find(',');
      raw.vectors[name].push_back(
          comma == std::string::npos
              ? std::complex<double>(std::stod(token), 0.0)
              : std::complex<double>(std::stod(token.substr(0, comma)),
                                     is_complex ? std::stod(token.substr(comma + 1)) : 0.0));
    }
  }
  for (const char* extension : {".cir", ".raw", ".log"}) std::remove((base + extension).c_str());
  return raw;
}

// Tolerance of the op and ac comparisons: 1e-6 relative. Reference: emnet's own solve of the
// same network (and, for the cantilever tip, the closed form F·L³/(3EI)). Both solve the same
// linear(ised) equations by LU in double precision; the deck carries 12 significant digits
// and the ASCII rawfile 16, so rounding differences are ~1e-12 times the condition of the
// network. 1e-6 leaves that margin and still catches any wrong weight, sign or element value
// (those change results at the percent level). The op deck runs at reltol 1e-9 so that
// ngspice's Newton test does not stop earlier.
constexpr double same_network_tolerance = 1e-6;

TEST(SpiceNetlist, NgspiceOpDeckOfTheCantileverGivesTheClosedFormAndEmnetsStaticState) {
  if (!ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  const Model model = scene_model("netlists/cantilever.toml");  // 1 N at the tip
  const SpiceDeck deck = write_spice_deck(model, {});
  const RawFile raw = run_ngspice(deck.text, "cantilever_op");
  const auto value = [&](const std::string& vector) {
    const auto at = raw.vectors.find(vector);
    EXPECT_NE(at, raw.vectors.end()) << vector;
    return at == raw.vectors.end() ? NAN : at->second.at(0).real();
  };
  const BeamSpec& beam = model.scene.beam;
  const double closed_form =
      1.0 * std::pow(beam.length, 3) / (3.0 * beam.bending_stiffness);  // F·L³/(3EI)
  double tip = NAN;
  for (const auto& o : deck.outputs)
    if (o.probe == "tip") tip = value(o.vector);
  EXPECT_NEAR(tip, closed_form, same_network_tolerance * closed_form);

  // Every node against emnet's static state z (displacements and rotations), each relative to
  // the largest value of its domain (a node near the clamp has a small value of its own).
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok()) << rest.status.message;
  std::map<Domain, double> scale;
  const auto& nodes = model.network.nodes();
  for (size_t k = 0; k < nodes.size(); ++k)
    scale[nodes[k].domain] = std::max(scale[nodes[k].domain], std::abs(rest.state[k]));
  for (size_t k = 0; k < nodes.size(); ++k) {
    SCOPED_TRACE(nodes[k].name);
    EXPECT_NEAR(deck.unknowns[k].sign * value(deck.unknowns[k].vector), rest.state[k],
                same_network_tolerance * scale[nodes[k].domain]);
  }
  // Lever forces (branch currents of their sense sources) against emnet's static forces.
  const int lever = system.branch_index("lever0");
  EXPECT_NEAR(deck.unknowns[static_cast<size_t>(lever)].sign *
                  value(deck.unknowns[static_cast<size_t>(lever)].vector),
              rest.state[lever], same_network_tolerance * std::abs(rest.state[lever]));
}

TEST(SpiceNetlist, NgspiceOpDeckOfTheFishFinGivesEmnetsStaticProbes) {
  // The DEA force as a B source on the capacitor voltage (DEA A at 4 kV, the first half-period).
  if (!ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  const Model model = scene_model("netlists/fishfin.toml");
  const SpiceDeck deck = write_spice_deck(model, {});
  const RawFile raw = run_ngspice(deck.text, "fishfin_op");
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok()) << rest.status.message;
  const auto probes = spice_output_probes(model);
  ASSERT_EQ(probes.size(), deck.outputs.size());
  const double tip = std::abs(static_probe_value(system, rest, model.parse_probe("tip")));
  for (size_t k = 0; k < probes.size(); ++k) {
    SCOPED_TRACE(probes[k].name);
    const double expected = static_probe_value(system, rest, probes[k]);
    // Deflections relative to the tip's, voltages to 4 kV, currents absolute (0 at rest).
    const double scale = probes[k].unit == "m" ? tip : probes[k].unit == "V" ? 4000.0 : 1e-12;
    EXPECT_NEAR(raw.vectors.at(deck.outputs[k].vector).at(0).real(), expected,
                same_network_tolerance * scale);
  }
}

TEST(SpiceNetlist, NgspiceAcDeckOfTheFishFinGivesEmnetsResponseAndResonance) {
  if (!ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  const Model model = scene_model("netlists/fishfin.toml");
  SpiceDeckOptions options;
  options.analysis = SpiceAnalysis::ac;
  const SpiceDeck deck = write_spice_deck(model, options);
  const RawFile raw = run_ngspice(deck.text, "fishfin_ac");
  const auto& frequency = raw.vectors.at("frequency");
  std::vector<double> grid;
  for (const auto& f : frequency) grid.push_back(f.real());
  const auto& ac = model.scene.ac;
  const auto emnet_grid = frequency_grid(ac.from, ac.to, ac.points, ac.log);
  ASSERT_EQ(grid.size(), emnet_grid.size());
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  const auto probes = spice_output_probes(model);
  const AcResult result = run_ac(system, rest.operating_point, grid, probes);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  for (size_t p = 0; p < probes.size(); ++p) {
    if (probes[p].unit != "m") continue;  // the deflections; u and i of the DEAs have no AC
    const auto& spice = raw.vectors.at(deck.outputs[p].vector);
    double peak = 0.0;
    for (const auto& v : result.values[p]) peak = std::max(peak, std::abs(v));
    if (peak == 0.0) continue;  // P1 at the clamp
    size_t emnet_peak = 0, spice_peak = 0;
    // From the first frequency above 0: at f = 0 an integrator output is 0 (see the header).
    for (size_t f = 1; f < grid.size(); ++f) {
      EXPECT_LE(std::abs(spice[f] - result.values[p][f]), same_network_tolerance * peak)
          << probes[p].name << " at " << grid[f] << " Hz";
      if (std::abs(result.values[p][f]) > std::abs(result.values[p][emnet_peak])) emnet_peak = f;
      if (std::abs(spice[f]) > std::abs(spice[spice_peak])) spice_peak = f;
    }
    EXPECT_EQ(spice_peak, emnet_peak) << probes[p].name;
    // emnet's f1 = 6.385 Hz: the peak is the grid point next to it (spacing 0.01 Hz).
    EXPECT_NEAR(grid[spice_peak], 6.385, 0.01) << probes[p].name;
  }
}

}  // namespace
