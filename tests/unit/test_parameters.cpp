// Tests of the scene's parameter table (emnet/scene/parameters.hpp) and of set_parameter /
// get_parameter.
//
// References: the shipped scenes (every key they hold is in the table); the scene reader with
// `--set KEY=VALUE` (set_parameter must give the same field value, or refuse with the same
// message, as reading the scene with that override: "%.17g" round-trips a double exactly, so the
// values are compared exactly); a default-constructed Scene (the defaults the table lists).
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using emnet::testing::kFishfin;

std::string number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

// The outcome of reading the fish fin with overrides: the scene, or the error's key and message
// (without its "where", which is "override" for the reader and "set_parameter" for set_parameter).
struct Outcome {
  std::optional<Scene> scene;
  std::string key, message;
};

std::string without_where(const InputError& error) {
  const std::string text = error.what();
  const std::string start = error.where() + ": ";
  return text.rfind(start, 0) == 0 ? text.substr(start.size()) : text;
}

Outcome read_with(const std::vector<std::string>& overrides) {
  Outcome outcome;
  try {
    outcome.scene = read_scene(kFishfin, overrides);
  } catch (const InputError& error) {
    outcome.key = error.key();
    outcome.message = without_where(error);
  }
  return outcome;
}

// ---- the table covers the scenes ----------------------------------------------------------

// Every key of every shipped scene (tables, entries of arrays of tables) is in the table, and
// every table it uses is one of scene_tables().
TEST(ParameterTable, EveryKeyOfTheShippedScenesIsInTheTable) {
  int files = 0, keys = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(EMNET_SOURCE_DIR) / "netlists")) {
    if (entry.path().extension() != ".toml") continue;
    ++files;
    const toml::table root = toml::parse_file(entry.path().string());
    for (auto&& [table_key, node] : root) {
      const std::string table_name(table_key.str());
      const SceneTableInfo* table = find_scene_table(table_name);
      ASSERT_NE(table, nullptr) << entry.path() << ": [" << table_name << "]";
      if (table->free_form) {
        EXPECT_NE(find_parameter_info(table_name, "*"), nullptr);
        continue;
      }
      std::vector<const toml::table*> tables;
      if (table->entries) {
        ASSERT_TRUE(node.is_array()) << table_name;
        for (const toml::node& element : *node.as_array()) tables.push_back(element.as_table());
      } else {
        tables.push_back(node.as_table());
      }
      for (const toml::table* each : tables) {
        ASSERT_NE(each, nullptr) << table_name;
        for (auto&& [key, value] : *each) {
          ++keys;
          const ParameterInfo* info = find_parameter_info(table_name, std::string(key.str()));
          EXPECT_NE(info, nullptr) << entry.path() << ": " << table_name << "." << key.str();
          if (info != nullptr) EXPECT_EQ(info->in_entries, table->entries) << info->key();
        }
      }
    }
  }
  EXPECT_GE(files, 4);
  EXPECT_GE(keys, 100);
}

// What each table key gives when --set on the fish fin (netlists/fishfin.toml: an antagonistic
// drive, a loss factor, two DEAs A and B, deflection probes P1..P4 and tip, no loads, no fluid):
// accepted, or refused with the reader's message for the reason stated. Every key of the table
// must be listed here, so a new key comes with its case.
struct SetCase {
  std::string assignment;          // "beam.length=0.2"
  std::optional<double> expected;  // a numeric key's SI value after reading
  std::string refused;             // "" if accepted; else a fragment of the message
};

std::map<std::string, SetCase> fishfin_set_cases() {
  return {
      {"scene.name", {"scene.name=fin", {}, ""}},
      {"scene.title", {"scene.title=a fin", {}, ""}},
      {"scene.description", {"scene.description=text", {}, ""}},
      {"beam.length", {"beam.length=0.2", 0.2, ""}},
      {"beam.segments", {"beam.segments=12", 12.0, ""}},
      {"beam.bending_stiffness", {"beam.bending_stiffness=2e-3 N*m^2", 2e-3, ""}},
      {"beam.mass_per_length", {"beam.mass_per_length=80 g/m", 0.08, ""}},
      {"beam.rotary_inertia_per_length", {"beam.rotary_inertia_per_length=1e-9 kg*m", 1e-9, ""}},
      {"beam.left", {"beam.left=pinned", {}, ""}},
      {"beam.right", {"beam.right=sliding", {}, ""}},
      // Timoshenko needs a shear stiffness, which the fin (Euler-Bernoulli) does not give.
      {"beam.theory", {"beam.theory=timoshenko", {}, "needs the shear stiffness"}},
      {"beam.shear_stiffness",
       {"beam.shear_stiffness=100 N", {}, "is only used with beam.theory = \"timoshenko\""}},
      // The fin at large deflection is read (no analysis runs here); its EA is unused with
      // the small kinematics it has.
      {"beam.kinematics", {"beam.kinematics=large", {}, ""}},
      {"beam.axial_stiffness",
       {"beam.axial_stiffness=1 kN", {}, "is only used with beam.kinematics = \"large\""}},
      {"section[].axial_stiffness",
       {"section.0.axial_stiffness=1 kN", {}, "no [[section]] entry '0'"}},
      // The fin is one uniform beam: no [[section]], [[mass]] or [[spring]] entries.
      {"section[].length", {"section.0.length=0.1", {}, "no [[section]] entry '0'"}},
      {"section[].bending_stiffness",
       {"section.0.bending_stiffness=1", {}, "no [[section]] entry '0'"}},
      {"section[].mass_per_length",
       {"section.0.mass_per_length=1", {}, "no [[section]] entry '0'"}},
      {"section[].rotary_inertia_per_length",
       {"section.0.rotary_inertia_per_length=0", {}, "no [[section]] entry '0'"}},
      {"section[].shear_stiffness",
       {"section.0.shear_stiffness=1 N", {}, "no [[section]] entry '0'"}},
      {"section[].viscous_per_length",
       {"section.0.viscous_per_length=0", {}, "no [[section]] entry '0'"}},
      {"section[].kelvin_voigt_time",
       {"section.0.kelvin_voigt_time=0", {}, "no [[section]] entry '0'"}},
      {"section[].segments", {"section.0.segments=3", {}, "no [[section]] entry '0'"}},
      {"mass[].name", {"mass.0.name=sensor", {}, "no [[mass]] entry '0'"}},
      {"mass[].at", {"mass.0.at=0.1", {}, "no [[mass]] entry '0'"}},
      {"mass[].mass", {"mass.0.mass=1 g", {}, "no [[mass]] entry '0'"}},
      {"mass[].rotary_inertia", {"mass.0.rotary_inertia=0", {}, "no [[mass]] entry '0'"}},
      {"spring[].name", {"spring.0.name=clamp", {}, "no [[spring]] entry '0'"}},
      {"spring[].at", {"spring.0.at=0", {}, "no [[spring]] entry '0'"}},
      {"spring[].kind", {"spring.0.kind=rotational", {}, "no [[spring]] entry '0'"}},
      {"spring[].stiffness", {"spring.0.stiffness=1 N/m", {}, "no [[spring]] entry '0'"}},
      {"spring[].damping", {"spring.0.damping=0", {}, "no [[spring]] entry '0'"}},
      {"spring[].to", {"spring.0.to=0.1", {}, "no [[spring]] entry '0'"}},
      {"damping.viscous_per_length", {"damping.viscous_per_length=0.1", 0.1, ""}},
      // The fin's damping is a loss factor: a Kelvin-Voigt time beside it is refused.
      {"damping.kelvin_voigt_time",
       {"damping.kelvin_voigt_time=1ms", {}, "give either damping.kelvin_voigt_time"}},
      {"damping.loss_factor", {"damping.loss_factor=0.05", 0.05, ""}},
      {"damping.loss_factor_frequency", {"damping.loss_factor_frequency=5 Hz", 5.0, ""}},
      // drive.deas names DEA B: renaming it leaves the drive without it.
      {"dea[].name", {"dea.B.name=C", {}, "unknown DEA 'B'"}},
      {"dea[].from", {"dea.A.from=10 mm", 0.01, ""}},
      {"dea[].to", {"dea.A.to=60 mm", 0.06, ""}},
      {"dea[].face", {"dea.A.face=bottom", {}, ""}},
      {"dea[].lever_arm", {"dea[A].lever_arm=2 mm", 2e-3, ""}},
      {"dea[].relative_permittivity", {"dea.0.relative_permittivity=3", 3.0, ""}},
      {"dea[].dielectric_thickness", {"dea[1].dielectric_thickness=60 um", 60e-6, ""}},
      {"dea[].force_thickness", {"dea.B.force_thickness=60 um", 60e-6, ""}},
      {"dea[].electrode_width", {"dea.A.electrode_width=20 mm", 0.02, ""}},
      {"dea[].electrode_resistance", {"dea.A.electrode_resistance=2 MOhm", 2e6, ""}},
      {"dea[].back_coupling", {"dea.A.back_coupling=true", {}, ""}},
      {"dea[].breakdown_field", {"dea.A.breakdown_field=100 V/um", 100e6, ""}},
      // A switched drive drives one DEA; the fin names two.
      {"drive.kind", {"drive.kind=switched", {}, "needs exactly 1 DEA name, got 2"}},
      {"drive.deas", {"drive.deas=[\"B\", \"A\"]", {}, ""}},
      {"drive.voltage", {"drive.voltage=3 kV", 3000.0, ""}},
      // The sine drives' levels are not the antagonistic drive's.
      {"drive.bias", {"drive.bias=1 kV", {}, "is not used by drive kind 'antagonistic'"}},
      {"drive.amplitude", {"drive.amplitude=1 kV", {}, "is not used by drive kind 'antagonistic'"}},
      {"drive.frequency", {"drive.frequency=6 Hz", 6.0, ""}},
      {"drive.duty", {"drive.duty=0.4", 0.4, ""}},
      {"drive.rise_time", {"drive.rise_time=1 ms", 1e-3, ""}},
      {"drive.overlap", {"drive.overlap=2 ms", 2e-3, ""}},
      {"drive.electrical_dynamics", {"drive.electrical_dynamics=false", {}, ""}},
      // The fin has no [[load]] entries.
      {"load[].kind", {"load.0.kind=force", {}, "no [[load]] entry '0'"}},
      {"load[].at", {"load.0.at=0.1", {}, "no [[load]] entry '0'"}},
      {"load[].value", {"load.0.value=1 N", {}, "no [[load]] entry '0'"}},
      {"probe[].name", {"probe.tip.name=end", {}, ""}},
      {"probe[].quantity", {"probe.tip.quantity=velocity", {}, ""}},
      {"probe[].at", {"probe.P4.at=60 mm", 0.06, ""}},
      // The fin's probes are deflections, which name no DEA.
      {"probe[].dea",
       {"probe.tip.dea=A",
        {},
        "is only used by probe quantities 'dea_voltage', 'dea_current' and 'dea_force'"}},
      // Nor a spring, a face or a distance from the neutral plane.
      {"probe[].spring",
       {"probe.tip.spring=k", {}, "is only used by probe quantity 'spring_force'"}},
      {"probe[].face", {"probe.tip.face=top", {}, "is only used by probe quantity 'strain'"}},
      {"probe[].distance",
       {"probe.tip.distance=1 mm", {}, "is only used by probe quantity 'strain'"}},
      // The fin has no [[circuit]] entries.
      {"circuit[].name", {"circuit.0.name=x", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].kind", {"circuit.0.kind=resistor", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].from", {"circuit.0.from=a", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].to", {"circuit.0.to=b", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].value", {"circuit.0.value=1 kOhm", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].waveform", {"circuit.0.waveform=sine", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].low", {"circuit.0.low=0", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].high", {"circuit.0.high=1", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].frequency", {"circuit.0.frequency=1 Hz", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].duty", {"circuit.0.duty=0.5", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].rise", {"circuit.0.rise=0", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].fall", {"circuit.0.fall=0", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].delay", {"circuit.0.delay=0", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].width", {"circuit.0.width=1 ms", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].period", {"circuit.0.period=0", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].offset", {"circuit.0.offset=0", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].amplitude", {"circuit.0.amplitude=1", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].phase", {"circuit.0.phase=0", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].points", {"circuit.0.points=[]", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].file", {"circuit.0.file=x.csv", {}, "no [[circuit]] entry '0'"}},
      {"circuit[].ac", {"circuit.0.ac=1", {}, "no [[circuit]] entry '0'"}},
      {"ac.from", {"ac.from=1 Hz", 1.0, ""}},
      {"ac.to", {"ac.to=20 Hz", 20.0, ""}},
      {"ac.points", {"ac.points=50", 50.0, ""}},
      // The fin's sweep starts at 0 Hz, which has no logarithm.
      {"ac.scale", {"ac.scale=log", {}, "must be > 0 for a log scale"}},
      // A fluid needs the plate's width, which the fin does not give.
      {"environment.fluid", {"environment.fluid=water", {}, "missing (required)"}},
      // The fin is in no fluid: the fluid's properties are refused.
      {"environment.density",
       {"environment.density=1000 kg/m^3", {}, "is only used with environment.fluid"}},
      {"environment.dynamic_viscosity",
       {"environment.dynamic_viscosity=1e-3 Pa*s", {}, "is only used with environment.fluid"}},
      {"environment.width", {"environment.width=25 mm", {}, "is only used with environment.fluid"}},
      {"environment.frequency",
       {"environment.frequency=5 Hz", {}, "is only used with environment.fluid"}},
      {"model.band", {"model.band=130 Hz", {}, ""}},
      {"model.tolerance", {"model.tolerance=1e-2", 1e-2, ""}},
      {"model.deflection_limit", {"model.deflection_limit=0.2", 0.2, ""}},
      {"provenance.*", {"provenance.beam.length=paper: Sect. 2.4", {}, ""}},
  };
}

TEST(ParameterTable, EveryKeyCanBeSetOnTheFishFinOrIsRefusedForAStatedReason) {
  const std::map<std::string, SetCase> cases = fishfin_set_cases();
  for (const ParameterInfo& info : parameter_table()) {
    const auto found = cases.find(info.key());
    if (found == cases.end()) {
      ADD_FAILURE() << info.key() << ": no --set case for this key";
      continue;
    }
    const SetCase& set = found->second;
    const Outcome outcome = read_with({set.assignment});
    if (!set.refused.empty()) {
      EXPECT_FALSE(outcome.scene.has_value()) << set.assignment << ": accepted";
      EXPECT_NE(outcome.message.find(set.refused), std::string::npos)
          << set.assignment << ": " << outcome.message;
      continue;
    }
    ASSERT_TRUE(outcome.scene.has_value()) << set.assignment << ": " << outcome.message;
    if (set.expected) {
      ASSERT_TRUE(info.numeric()) << info.key();
      const std::string key = set.assignment.substr(0, set.assignment.find('='));
      EXPECT_DOUBLE_EQ(get_parameter(*outcome.scene, key), *set.expected) << set.assignment;
    }
  }
  EXPECT_EQ(cases.size(), parameter_table().size()) << "a case for a key the table lacks";
}

// ---- defaults and listings --------------------------------------------------------------

// The reader's defaults are the table's: a scene with only the required keys reads to them.
TEST(ParameterTable, AMinimalSceneReadsToTheTablesDefaults) {
  const Scene scene = read_scene_text(
      "[scene]\nname = \"m\"\n[beam]\nlength = 0.1\nsegments = 4\nbending_stiffness = 1\n"
      "mass_per_length = 1\n",
      "m.toml");
  int checked = 0;
  for (const SceneParameterAddress& address : scene_numeric_parameters(scene)) {
    const std::optional<double> default_value = parameter_default(*address.info);
    if (!default_value) continue;
    EXPECT_EQ(get_parameter(scene, address.key), *default_value) << address.key;
    ++checked;
  }
  EXPECT_GE(checked, 8);  // rho*I, the dampings, the drive's timing, ac and model
  EXPECT_EQ(parameter_default_text(parameter_info("beam", "left")), "clamped");
  EXPECT_EQ(parameter_default_text(parameter_info("dea", "breakdown_field")), "80000000 V/m");
  EXPECT_EQ(parameter_default_text(parameter_info("beam", "length")), "required");
  EXPECT_EQ(parameter_range_text(parameter_info("drive", "duty")), "(0, 1)");
  EXPECT_EQ(parameter_info("beam", "bending_stiffness").unit(), "N*m^2");
  EXPECT_EQ(parameter_info("dea", "lever_arm").key(), "dea[].lever_arm");
}

// Every unit the table lists is one the unit parser reads, in the key's dimension.
TEST(ParameterTable, UnitsAreSpelledAsTheUnitParserReadsThem) {
  for (const ParameterInfo& info : parameter_table()) {
    if (info.kind != ParameterKind::quantity || !info.unit_note.empty()) continue;
    const std::string unit = info.unit();
    EXPECT_EQ(parse_quantity(unit.empty() ? "1" : "1 " + unit, info.dimension), 1.0) << info.key();
  }
}

// ---- set_parameter and get_parameter ------------------------------------------------------

// For every numeric key the fish fin uses, set_parameter(value) gives the same field as reading
// the scene with --set KEY=%.17g, or refuses with the same key and message: larger, smaller and
// negative values (within the range, past a relation such as a probe off a shorter beam, outside
// the range).
TEST(SetParameter, AgreesWithTheReadersOverrideForEveryNumericKey) {
  const Scene fin = read_scene(kFishfin);
  int compared = 0, refused = 0;
  for (const SceneParameterAddress& address : scene_numeric_parameters(fin)) {
    const double value = get_parameter(fin, address.key);
    const bool integer = address.info->kind == ParameterKind::integer;
    const std::vector<double> trials =
        integer ? std::vector<double>{value + 1.0, -value, 1e6}
                : std::vector<double>{value * 1.1, value * 0.9, -value - 1.0};
    for (double trial : trials) {
      const Outcome reader = read_with({address.key + "=" + number(trial)});
      Scene scene = fin;
      try {
        set_parameter(scene, address.key, trial);
        ASSERT_TRUE(reader.scene.has_value())
            << address.key << " = " << trial << ": the reader refused: " << reader.message;
        EXPECT_EQ(get_parameter(scene, address.key), get_parameter(*reader.scene, address.key))
            << address.key << " = " << trial;
      } catch (const InputError& error) {
        EXPECT_FALSE(reader.scene.has_value())
            << address.key << " = " << trial << ": set_parameter refused: " << error.what();
        EXPECT_EQ(error.where(), "set_parameter");
        EXPECT_EQ(error.key(), reader.key) << trial;
        EXPECT_EQ(without_where(error), reader.message);
        // A refused value leaves the scene as it was.
        EXPECT_EQ(get_parameter(scene, address.key), value) << address.key;
        ++refused;
      }
      ++compared;
    }
  }
  EXPECT_GE(compared, 3 * 25);
  EXPECT_GE(refused, 25);  // every negative value, and the shorter beam's probes
}

TEST(SetParameter, SetsTheFieldDirectly) {
  Scene scene = read_scene(kFishfin);
  set_parameter(scene, "beam.bending_stiffness", 1.5e-3);
  EXPECT_EQ(scene.beam.bending_stiffness, 1.5e-3);
  set_parameter(scene, "dea.B.lever_arm", 2e-3);
  EXPECT_EQ(scene.deas[1].lever_arm, 2e-3);
  EXPECT_EQ(get_parameter(scene, "dea[B].lever_arm"), 2e-3);
  EXPECT_EQ(get_parameter(scene, "dea.1.lever_arm"), 2e-3);
  set_parameter(scene, "damping.loss_factor", 0.03);
  EXPECT_EQ(*scene.damping.loss_factor, 0.03);
  // beam.segments by value clears "auto", as --set beam.segments=N does.
  scene.beam.auto_segments = true;
  set_parameter(scene, "beam.segments", 9);
  EXPECT_EQ(scene.beam.segments, 9);
  EXPECT_FALSE(scene.beam.auto_segments);
}

TEST(SetParameter, RefusalsNameTheKeyAndTheReason) {
  Scene scene = read_scene(kFishfin);
  auto message_of = [&](const std::string& key, double value) {
    try {
      set_parameter(scene, key, value);
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message_of("beam.lenght", 1.0),
            "set_parameter: key 'beam.lenght': unknown key (did you mean 'beam.length'?)");
  EXPECT_EQ(message_of("dea.C.lever_arm", 1e-3),
            "set_parameter: key 'dea.C.lever_arm': no [[dea]] entry 'C'; the scene has 2 [[dea]] "
            "entries named 'A', 'B'");
  EXPECT_EQ(message_of("beam.left", 1.0),
            "set_parameter: key 'beam.left': is not a number but a choice key; set_parameter "
            "takes numeric keys");
  EXPECT_EQ(message_of("beam.segments", 7.5),
            "set_parameter: key 'beam.segments': must be an integer, got 7.5");
  EXPECT_EQ(message_of("beam.length", std::nan("")),
            "set_parameter: key 'beam.length': must be finite, got nan");
  EXPECT_EQ(message_of("drive.duty", 1.0),
            "set_parameter: key 'drive.duty': must be between 0 and 1 (exclusive), got 1");
  EXPECT_EQ(message_of("drive.rise_time", 0.2),
            "set_parameter: key 'drive.rise_time': must be shorter than half a period (0.1 s at "
            "5 Hz), got 0.2 s");
  EXPECT_EQ(message_of("drive.bias", 1.0).find("is not used by drive kind 'antagonistic'"),
            std::string("set_parameter: key 'drive.bias': ").size());
  try {
    (void)get_parameter(scene, "environment.frequency");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(),
                 "get_parameter: key 'environment.frequency': is only used with "
                 "environment.fluid = \"air\" or \"water\"");
  }
}

// ---- emnet schema -----------------------------------------------------------------------

TEST(SchemaCli, PrintsEveryKeyAsTextMarkdownAndJson) {
  const auto text = testing::run_emnet("schema");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_EQ(text.out.rfind("KEY", 0), 0u) << text.out;
  const auto markdown = testing::run_emnet("schema --markdown");
  ASSERT_EQ(markdown.status, 0) << markdown.err;
  EXPECT_EQ(markdown.out.rfind("| key | unit | default | range | used by | meaning |\n", 0), 0u);
  for (const ParameterInfo& info : parameter_table()) {
    EXPECT_NE(text.out.find("\n" + info.key() + " "), std::string::npos) << info.key();
    EXPECT_NE(markdown.out.find("| `" + info.key() + "` | " + info.unit() + " |"),
              std::string::npos)
        << info.key();
  }
  EXPECT_NE(markdown.out.find("| `beam.length` | m | required | > 0 | beam |"), std::string::npos);
  const auto json = testing::run_emnet("schema --json");
  ASSERT_EQ(json.status, 0) << json.err;
  const nlohmann::json parsed = nlohmann::json::parse(json.out);
  ASSERT_EQ(parsed["keys"].size(), parameter_table().size());
  EXPECT_EQ(parsed["keys"][3]["key"], "beam.length");
  EXPECT_EQ(parsed["keys"][3]["unit"], "m");
  EXPECT_EQ(parsed["keys"][3]["sensitivity"], true);
  const auto both = testing::run_emnet("schema --markdown --json");
  EXPECT_EQ(both.status, 2) << both.out;
}

// docs/scene-reference.md is the preamble of tools/scene-reference and then exactly what
// `emnet schema --markdown` prints: the checked-in file cannot fall behind the parameter
// table (and so behind the reader, EveryKeyOfTheShippedScenesIsInTheTable). Run
// tools/scene-reference after changing a key.
TEST(SceneReference, CheckedInFileIsWhatTheCommandWrites) {
  std::ifstream file(std::string(EMNET_SOURCE_DIR) + "/docs/scene-reference.md");
  ASSERT_TRUE(file) << "docs/scene-reference.md is missing: run tools/scene-reference";
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const size_t table = text.find("\n| key | unit | default | range | used by | meaning |\n");
  ASSERT_NE(table, std::string::npos) << "no key table in docs/scene-reference.md";
  const auto markdown = testing::run_emnet("schema --markdown");
  ASSERT_EQ(markdown.status, 0) << markdown.err;
  EXPECT_EQ(text.substr(table + 1), markdown.out)
      << "docs/scene-reference.md differs from `emnet schema --markdown`: run "
         "tools/scene-reference";
}

}  // namespace
}  // namespace emnet
