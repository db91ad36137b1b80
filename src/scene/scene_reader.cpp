// Scene reader: TOML scene text plus `--set key=value` overrides into a validated SI Scene.
//
// The file is parsed with toml++ into a document tree; overrides are written into that tree
// (scene_overrides.cpp: a value from an override is checked exactly like one from the file, and
// is recognised by having no source position: its errors say "override"); then the tree is walked
// table by table, rejecting unknown tables and keys, reading each value with its unit and
// checking its range. Which tables and keys exist, and every key's unit, range and default, come
// from the parameter table (emnet/scene/parameters.hpp); the conditions between keys from
// parameter_relations.hpp. The first problem found is thrown as an InputError.
#include "emnet/scene/scene_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "parameter_relations.hpp"
#include "scene_overrides.hpp"
#include "scene_reader_internal.hpp"
#include "scene_text.hpp"
#include "toml_input_guard.hpp"

namespace emnet {
namespace scene_reading {

using scene_text::did_you_mean;
using scene_text::format_number;
using scene_text::is_identifier;
using scene_text::quoted_list;
using scene_text::trim;

std::vector<std::string> table_names() {
  std::vector<std::string> names;
  for (const SceneTableInfo& table : scene_tables()) names.push_back(table.name);
  return names;
}

// The DEA names of the scene read so far, and "the scene defines 'A', 'B'" for messages.
std::vector<std::string> dea_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const DeaSpec& dea : scene.deas) names.push_back(dea.name);
  return names;
}

std::string defined_deas(const std::vector<std::string>& names) {
  return names.empty() ? std::string("the scene defines no DEAs")
                       : "the scene defines " + quoted_list(names);
}

Section SceneReader::section(const toml::table& root, const std::string& table_name) const {
  const SceneTableInfo* table = find_scene_table(table_name);
  Section result(locator_, root.get_as<toml::table>(table_name), table_name);
  if (table != nullptr) result.reject_unknown_keys(table->keys);
  return result;
}

std::vector<SceneReader::Entry> SceneReader::entries(const toml::table& root,
                                                     const SceneTableInfo& table) const {
  std::vector<Entry> result;
  const std::string& table_name = table.name;
  const toml::array* array = root.get_as<toml::array>(table_name);
  if (array == nullptr) return result;
  const std::size_t maximum = table.maximum_entries;
  if (array->size() > maximum) {
    locator_.fail(array, table_name,
                  std::to_string(array->size()) + " [[" + table_name + "]] entries; a scene may " +
                      "have at most " + std::to_string(maximum));
  }
  for (std::size_t index = 0; index < array->size(); ++index) {
    const toml::node& element = (*array)[index];
    const std::string indexed = table_name + "[" + std::to_string(index) + "]";
    const toml::table* entry = element.as_table();
    if (entry == nullptr) {
      locator_.fail(&element, indexed, "must be a table, got " + describe_node(element));
    }
    std::string prefix = indexed;
    if (const auto* name = entry->get_as<std::string>("name")) {
      if (is_identifier(name->get())) prefix = table_name + "[" + name->get() + "]";
    }
    result.push_back(Entry{entry, prefix});
  }
  return result;
}

void SceneReader::check_top_level(const toml::table& root) const {
  for (auto&& [table_key, node] : root) {
    const std::string name(table_key.str());
    const SceneTableInfo* table = find_scene_table(name);
    if (table == nullptr) {
      locator_.fail(&node, name,
                    std::string(node.is_table() ? "unknown table" : "unknown key") +
                        did_you_mean(name, table_names()) + "; a scene has the tables " +
                        quoted_list(table_names()));
    }
    if (table->entries) {
      if (!node.is_array()) {
        locator_.fail(
            &node, name,
            "must be an array of tables, written [[" + name + "]], got " + describe_node(node));
      }
    } else if (!node.is_table()) {
      locator_.fail(&node, name,
                    "must be a table, written [" + name + "], got " + describe_node(node));
    }
  }
  for (const char* required : {"scene", "beam"}) {
    if (!root.contains(required)) {
      locator_.fail(nullptr, required, std::string("missing table [") + required + "] (required)");
    }
  }
}

void SceneReader::read_scene_table(const toml::table& root, Scene& scene) const {
  const Section section_reader = section(root, "scene");
  scene.name = section_reader.string("name");
  if (trim(scene.name).empty()) section_reader.fail("name", "must not be empty");
  scene.title = section_reader.optional_string("title").value_or("");
  section_reader.optional_string("description");
}

void SceneReader::read_beam(const toml::table& root, Scene& scene) const {
  BeamSpec& beam = scene.beam;
  const Section reader = section(root, "beam");
  auto key = [](const char* name) -> const ParameterInfo& { return parameter_info("beam", name); };
  const bool sections = root.contains("section");
  beam.length = reader.quantity(key("length"));
  beam.auto_segments = false;
  if (const toml::node* node = reader.find("segments"); node != nullptr && node->is_string()) {
    const std::string text = node->as_string()->get();
    if (text != "auto")
      reader.fail("segments", "must be an integer >= 1 or \"auto\", got '" + text + "'");
    beam.auto_segments = true;
    beam.segments = 0;  // chosen by the resolve step (emnet/studies/segment_selection.hpp)
  } else {
    const std::optional<long long> segments = reader.optional_integer(key("segments"));
    // With sections that each give their own count, beam.segments is their sum (read_sections).
    if (!segments && !sections) reader.fail_missing("segments");
    beam.segments = static_cast<int>(segments.value_or(0));
  }
  if (sections) {
    // The bending stiffness and mass per length are per section: the beam's are refused.
    beam.sections.emplace_back();  // so that parameter_unused_reason sees a sectioned beam
    for (const char* name : {"bending_stiffness", "mass_per_length", "rotary_inertia_per_length"})
      reader.reject_if_unused(key(name), scene, 0);
    beam.sections.clear();
  } else {
    beam.bending_stiffness = reader.quantity(key("bending_stiffness"));
    beam.mass_per_length = reader.quantity(key("mass_per_length"));
    beam.rotary_inertia_per_length = reader.quantity(key("rotary_inertia_per_length"));
  }
  const std::vector<EndCondition> ends = {EndCondition::clamped, EndCondition::free,
                                          EndCondition::pinned, EndCondition::sliding};
  beam.left = reader.optional_choice(key("left"), ends).value_or(BeamSpec{}.left);
  beam.right = reader.optional_choice(key("right"), ends).value_or(BeamSpec{}.right);
  beam.theory =
      reader
          .optional_choice(key("theory"), std::vector<BeamTheory>{BeamTheory::euler_bernoulli,
                                                                  BeamTheory::timoshenko})
          .value_or(BeamSpec{}.theory);
  reader.reject_if_unused(key("shear_stiffness"), scene, 0);
  beam.shear_stiffness = reader.optional_quantity(key("shear_stiffness")).value_or(0.0);
  // "auto" reads as small until the resolve step chooses (BeamSpec::kinematics_auto).
  beam.kinematics =
      reader
          .optional_choice(key("kinematics"),
                           std::vector<BeamKinematics>{BeamKinematics::small, BeamKinematics::large,
                                                       BeamKinematics::small})
          .value_or(BeamSpec{}.kinematics);
  beam.kinematics_auto = reader.optional_string("kinematics") == std::optional<std::string>("auto");
  reader.reject_if_unused(key("axial_stiffness"), scene, 0);
  beam.axial_stiffness = reader.optional_quantity(key("axial_stiffness")).value_or(0.0);
}

// [[section]]: in order from x = 0, adding up to beam.length; under Timoshenko theory each needs
// a shear stiffness, its own or the beam's.
void SceneReader::read_sections(const toml::table& root, Scene& scene) const {
  const SceneTableInfo& table = *find_scene_table("section");
  auto key = [](const char* name) -> const ParameterInfo& {
    return parameter_info("section", name);
  };
  BeamSpec& beam = scene.beam;
  const std::vector<Entry> list = entries(root, table);
  if (root.contains("section") && list.empty())
    locator_.fail(root.get("section"), "section", "has no entries: give at least one [[section]]");
  int fixed_segments = 0;
  bool every_section_fixed = true;
  for (const Entry& entry : list) {
    const Section reader(locator_, entry.table, entry.prefix);
    reader.reject_unknown_keys(table.keys);
    beam.sections.emplace_back();
    const std::size_t index = beam.sections.size() - 1;
    SectionSpec& section = beam.sections.back();
    section.length = reader.quantity(key("length"));
    section.bending_stiffness = reader.quantity(key("bending_stiffness"));
    section.mass_per_length = reader.quantity(key("mass_per_length"));
    section.rotary_inertia_per_length = reader.quantity(key("rotary_inertia_per_length"));
    reader.reject_if_unused(key("shear_stiffness"), scene, index);
    section.shear_stiffness = reader.optional_quantity(key("shear_stiffness"));
    if (beam.theory == BeamTheory::timoshenko && !section.shear_stiffness &&
        !(beam.shear_stiffness > 0.0))
      reader.fail("shear_stiffness",
                  "missing: beam.theory = \"timoshenko\" needs a shear stiffness kappa*G*A for "
                  "every section (give it here or as beam.shear_stiffness)");
    reader.reject_if_unused(key("axial_stiffness"), scene, index);
    section.axial_stiffness = reader.optional_quantity(key("axial_stiffness"));
    section.viscous_per_length = reader.optional_quantity(key("viscous_per_length"));
    section.kelvin_voigt_time = reader.optional_quantity(key("kelvin_voigt_time"));
    section.segments = 0;
    if (const toml::node* node = reader.find("segments"); node != nullptr && node->is_string()) {
      if (node->as_string()->get() != "auto")
        reader.fail("segments",
                    "must be an integer >= 1 or \"auto\", got '" + node->as_string()->get() + "'");
    } else if (const std::optional<long long> count = reader.optional_integer(key("segments"))) {
      section.segments = static_cast<int>(*count);
    }
    if (section.segments > 0) {
      fixed_segments += section.segments;
      if (beam.auto_segments) {
        const Section owner = this->section(root, "beam");
        owner.fail("segments", "\"auto\" chooses every segment count, but section[" +
                                   std::to_string(index) +
                                   "].segments gives its own: give beam.segments as an "
                                   "integer, or leave the sections' counts out");
      }
    } else {
      every_section_fixed = false;
    }
  }
  if (list.empty()) {
    if (beam.theory == BeamTheory::timoshenko && !(beam.shear_stiffness > 0.0)) {
      const Section owner = section(root, "beam");
      owner.fail("shear_stiffness",
                 "missing: beam.theory = \"timoshenko\" needs the shear stiffness kappa*G*A");
    }
    return;
  }
  const Section owner = section(root, "beam");
  if (!beam.auto_segments && beam.segments == 0) {
    if (!every_section_fixed) owner.fail_missing("segments");
    const ParameterInfo& count = parameter_info("beam", "segments");
    if (!count.range.contains(fixed_segments))
      owner.fail("segments", "the sections' own segment counts add up to " +
                                 std::to_string(fixed_segments) +
                                 ", more than the 100000 a "
                                 "beam may have");
    beam.segments = fixed_segments;
  } else if (!beam.auto_segments && every_section_fixed && fixed_segments != beam.segments) {
    owner.fail("segments", "is " + std::to_string(beam.segments) +
                               ", but every section gives its own segment count, adding up to " +
                               std::to_string(fixed_segments) + " (the mesh they build): leave " +
                               "beam.segments out, or change the sections' counts " +
                               "(section[k].segments)");
  } else if (!beam.auto_segments && fixed_segments > beam.segments) {
    owner.fail("segments", "is the beam's total, " + std::to_string(beam.segments) +
                               ", but the sections' own segment counts add up to " +
                               std::to_string(fixed_segments));
  }
  if (const std::string why = sections_length_violation(beam); !why.empty())
    owner.fail("length", why);
}

// [[mass]] and [[spring]]: attachments at positions on the beam, names unique when given.
void SceneReader::read_masses(const toml::table& root, Scene& scene) const {
  const SceneTableInfo& table = *find_scene_table("mass");
  auto key = [](const char* name) -> const ParameterInfo& { return parameter_info("mass", name); };
  std::set<std::string> names;
  for (const Entry& entry : entries(root, table)) {
    const Section reader(locator_, entry.table, entry.prefix);
    reader.reject_unknown_keys(table.keys);
    MassSpec mass;
    if (reader.has("name")) {
      mass.name = reader.identifier("name");
      if (!names.insert(mass.name).second)
        reader.fail("name", "duplicate mass name '" + mass.name + "'");
    }
    mass.at = reader.position_on_beam(key("at"), scene.beam.length);
    mass.mass = reader.quantity(key("mass"));
    mass.rotary_inertia = reader.quantity(key("rotary_inertia"));
    scene.beam.masses.push_back(mass);
  }
}

void SceneReader::read_springs(const toml::table& root, Scene& scene) const {
  const SceneTableInfo& table = *find_scene_table("spring");
  auto key = [](const char* name) -> const ParameterInfo& {
    return parameter_info("spring", name);
  };
  std::set<std::string> names;
  for (const Entry& entry : entries(root, table)) {
    const Section reader(locator_, entry.table, entry.prefix);
    reader.reject_unknown_keys(table.keys);
    scene.beam.springs.emplace_back();
    const std::size_t index = scene.beam.springs.size() - 1;
    SpringSpec& spring = scene.beam.springs.back();
    if (reader.has("name")) {
      spring.name = reader.identifier("name");
      if (!names.insert(spring.name).second)
        reader.fail("name", "duplicate spring name '" + spring.name + "'");
    }
    spring.at = reader.position_on_beam(key("at"), scene.beam.length);
    spring.kind = reader.choice(
        key("kind"), std::vector<SpringKind>{SpringKind::translational, SpringKind::rotational,
                                             SpringKind::axial});
    if (spring.kind == SpringKind::axial && scene.beam.kinematics != BeamKinematics::large &&
        !scene.beam.kinematics_auto)
      reader.fail("kind",
                  "\"axial\" acts along the beam's x, which only beam.kinematics = \"large\" "
                  "has (small deflections have no axial motion)");
    const ParameterInfo& stiffness = key("stiffness");
    spring.stiffness = reader.quantity(stiffness, parameter_dimension(stiffness, scene, index));
    const ParameterInfo& damping = key("damping");
    spring.damping = reader.quantity(damping, parameter_dimension(damping, scene, index));
    if (reader.has("to")) {
      spring.to = reader.position_on_beam(key("to"), scene.beam.length);
      if (const std::string why = spring_ends_violation(spring, scene.beam.length); !why.empty())
        reader.fail("to", why);
    }
  }
}

void SceneReader::read_damping(const toml::table& root, Scene& scene) const {
  const Section reader = section(root, "damping");
  auto key = [](const char* name) -> const ParameterInfo& {
    return parameter_info("damping", name);
  };
  DampingSpec& damping = scene.damping;
  damping.viscous_per_length = reader.quantity(key("viscous_per_length"));
  damping.kelvin_voigt_time = reader.quantity(key("kelvin_voigt_time"));
  damping.loss_factor = reader.optional_quantity(key("loss_factor"));
  damping.loss_factor_frequency = reader.optional_quantity(key("loss_factor_frequency"));
  // Either the Kelvin-Voigt time or a loss factor with its frequency.
  for (const char* name : {"kelvin_voigt_time", "loss_factor", "loss_factor_frequency"})
    reader.reject_if_unused(key(name), scene, 0);
}

void SceneReader::read_deas(const toml::table& root, Scene& scene) const {
  const SceneTableInfo& table = *find_scene_table("dea");
  auto key = [](const char* name) -> const ParameterInfo& { return parameter_info("dea", name); };
  const double beam_length = scene.beam.length;
  std::set<std::string> names;
  for (const Entry& entry : entries(root, table)) {
    const Section reader(locator_, entry.table, entry.prefix);
    reader.reject_unknown_keys(table.keys);
    DeaSpec dea;
    dea.name = reader.identifier("name");
    if (!names.insert(dea.name).second) {
      reader.fail("name", "duplicate DEA name '" + dea.name + "'");
    }
    dea.from = reader.quantity(key("from"));
    dea.to = reader.quantity(key("to"));
    if (const auto span = dea_span_violation(dea.name, dea.from, dea.to, beam_length))
      reader.fail(span->name, span->message);
    dea.from = std::max(dea.from, 0.0);
    dea.to = std::min(dea.to, beam_length);
    dea.face = reader.choice(key("face"), std::vector<Face>{Face::top, Face::bottom});
    dea.lever_arm = reader.quantity(key("lever_arm"));
    dea.relative_permittivity = reader.quantity(key("relative_permittivity"));
    dea.dielectric_thickness = reader.quantity(key("dielectric_thickness"));
    dea.force_thickness = reader.quantity(key("force_thickness"));
    dea.electrode_width = reader.quantity(key("electrode_width"));
    dea.electrode_resistance = reader.quantity(key("electrode_resistance"));
    dea.back_coupling = reader.optional_boolean("back_coupling").value_or(DeaSpec{}.back_coupling);
    // Default: the paper's film's data-sheet value (kDefaultBreakdownField, emnet/scene/scene.hpp).
    dea.breakdown_field = reader.quantity(key("breakdown_field"));
    scene.deas.push_back(dea);
  }
}

void SceneReader::read_drive(const toml::table& root, Scene& scene) const {
  const Section reader = section(root, "drive");
  auto key = [](const char* name) -> const ParameterInfo& { return parameter_info("drive", name); };
  DriveSpec& drive = scene.drive;
  drive.kind =
      reader
          .optional_choice(
              key("kind"),
              std::vector<DriveKind>{DriveKind::none, DriveKind::antagonistic, DriveKind::switched,
                                     DriveKind::bias_differential, DriveKind::single})
          .value_or(DriveSpec{}.kind);
  const std::string kind_name = drive_kind_name(drive.kind);
  // A key the scene's kind does not use is refused by name, with the kinds that use it.
  for (const std::string& name : find_scene_table("drive")->keys)
    reader.reject_if_unused(key(name.c_str()), scene, 0);

  // drive.deas: names of existing, distinct DEAs.
  const std::vector<std::string> known = dea_names(scene);
  const std::set<std::string> known_deas(known.begin(), known.end());
  std::set<std::string> named_deas;
  if (const toml::node* deas_node = reader.find("deas")) {
    const toml::array* array = deas_node->as_array();
    if (array == nullptr) {
      reader.fail("deas", "must be an array of DEA names such as [\"A\", \"B\"], got " +
                              describe_node(*deas_node));
    }
    for (const toml::node& element : *array) {
      const auto* name = element.as_string();
      if (name == nullptr) {
        locator_.fail(&element, reader.key("deas"),
                      "must list DEA names as strings, got " + describe_node(element));
      }
      const std::string dea_name = name->get();
      if (known_deas.count(dea_name) == 0) {
        locator_.fail(&element, reader.key("deas"),
                      "unknown DEA '" + dea_name + "'" + did_you_mean(dea_name, known) + "; " +
                          defined_deas(known));
      }
      if (!named_deas.insert(dea_name).second) {
        locator_.fail(&element, reader.key("deas"), "names DEA '" + dea_name + "' twice");
      }
      drive.deas.push_back(dea_name);
    }
  }
  std::size_t needed_deas = 0;
  if (drive.kind == DriveKind::antagonistic || drive.kind == DriveKind::bias_differential) {
    needed_deas = 2;
  } else if (drive.kind == DriveKind::single || drive.kind == DriveKind::switched) {
    needed_deas = 1;
  }
  if (drive.kind != DriveKind::none && drive.deas.size() != needed_deas) {
    if (!reader.has("deas")) reader.fail_missing("deas");
    reader.fail("deas", "drive kind '" + kind_name + "' needs exactly " +
                            std::to_string(needed_deas) + " DEA name" +
                            (needed_deas == 1 ? "" : "s") + ", got " +
                            std::to_string(drive.deas.size()));
  }

  // Levels: every key the kind uses is required (none has a default that could be meant).
  for (const char* level : {"voltage", "bias", "amplitude"}) {
    const ParameterInfo& info = key(level);
    if (parameter_unused_reason(info, scene, 0).empty()) info.set(scene, 0, reader.quantity(info));
  }

  const std::optional<double> frequency = reader.optional_quantity(key("frequency"));
  if (drive.kind != DriveKind::none && !frequency) reader.fail_missing("frequency");
  drive.frequency = frequency.value_or(0.0);
  drive.rise_time = reader.quantity(key("rise_time"));
  if (frequency) {
    const std::string too_slow = rise_time_violation(drive.rise_time, *frequency);
    if (!too_slow.empty()) reader.fail("rise_time", too_slow);
  }
  drive.duty = reader.quantity(key("duty"));
  drive.overlap = reader.quantity(key("overlap"));
  if (frequency) {
    const std::string outside =
        overlap_violation(drive.duty, drive.overlap, *frequency, drive.rise_time);
    if (!outside.empty()) reader.fail("overlap", outside);
  }
  drive.electrical_dynamics_auto = false;
  if (const toml::node* node = reader.find("electrical_dynamics");
      node != nullptr && node->is_string()) {
    const std::string text = node->as_string()->get();
    if (text != "auto")
      reader.fail("electrical_dynamics", "must be true, false or \"auto\", got '" + text + "'");
    drive.electrical_dynamics_auto = true;
    drive.electrical_dynamics = true;  // until the resolve step chooses
  } else {
    drive.electrical_dynamics =
        reader.optional_boolean("electrical_dynamics").value_or(DriveSpec{}.electrical_dynamics);
  }
}

void SceneReader::read_loads(const toml::table& root, Scene& scene) const {
  const SceneTableInfo& table = *find_scene_table("load");
  auto key = [](const char* name) -> const ParameterInfo& { return parameter_info("load", name); };
  for (const Entry& entry : entries(root, table)) {
    const Section reader(locator_, entry.table, entry.prefix);
    reader.reject_unknown_keys(table.keys);
    scene.loads.emplace_back();
    const std::size_t index = scene.loads.size() - 1;
    LoadSpec& load = scene.loads.back();
    load.kind =
        reader.choice(key("kind"), std::vector<LoadKind>{LoadKind::force, LoadKind::moment});
    load.at = reader.position_on_beam(key("at"), scene.beam.length);
    const ParameterInfo& value = key("value");
    load.value = reader.quantity(value, parameter_dimension(value, scene, index));
  }
}

void SceneReader::read_probes(const toml::table& root, Scene& scene) const {
  const SceneTableInfo& table = *find_scene_table("probe");
  auto key = [](const char* name) -> const ParameterInfo& { return parameter_info("probe", name); };
  const std::vector<std::string> known = dea_names(scene);
  const std::set<std::string> known_deas(known.begin(), known.end());
  std::set<std::string> names;
  for (const Entry& entry : entries(root, table)) {
    const Section reader(locator_, entry.table, entry.prefix);
    reader.reject_unknown_keys(table.keys);
    ProbeSpec probe;
    probe.name = reader.identifier("name");
    if (!names.insert(probe.name).second) {
      reader.fail("name", "duplicate probe name '" + probe.name + "'");
    }
    probe.quantity = reader.choice(key("quantity"), probe_quantities());
    scene.probes.push_back(probe);
    const std::size_t index = scene.probes.size() - 1;
    // Each key belongs to the quantities that use it (parameter_unused_reason): probe[].at to
    // the beam quantities, probe[].dea to the DEA ones, probe[].spring to spring_force,
    // probe[].face and probe[].distance to strain.
    for (const char* name : {"at", "dea", "spring", "face", "distance"})
      reader.reject_if_unused(key(name), scene, index);
    ProbeSpec& read = scene.probes.back();
    auto used = [&](const char* name) {
      return parameter_unused_reason(key(name), scene, index).empty();
    };
    if (used("dea")) {
      read.dea = reader.string("dea");
      if (known_deas.count(read.dea) == 0) {
        reader.fail("dea", "unknown DEA '" + read.dea + "'" + did_you_mean(read.dea, known) + "; " +
                               defined_deas(known));
      }
    }
    if (used("at")) read.at = reader.position_on_beam(key("at"), scene.beam.length);
    if (used("spring")) read.spring = read_probe_spring(reader, scene);
    if (used("face"))
      read.face = reader.choice(key("face"), std::vector<Face>{Face::top, Face::bottom});
    if (used("distance")) read.distance = reader.quantity(key("distance"));
  }
}

std::string SceneReader::read_probe_spring(const Section& reader, const Scene& scene) const {
  const std::vector<SpringSpec>& springs = scene.beam.springs;
  std::string names;
  for (std::size_t k = 0; k < springs.size(); ++k)
    names += (k == 0 ? "" : ", ") + std::to_string(k) +
             (springs[k].name.empty() ? "" : " ('" + springs[k].name + "')");
  const std::string defined = springs.empty() ? "the scene has no [[spring]]"
                                              : "the scene's springs are, by index: " + names;
  if (!reader.has("spring")) reader.fail_missing("spring");
  const toml::node& node = *reader.find("spring");
  if (const auto* integer = node.as_integer()) {
    const long long k = integer->get();
    if (k < 0 || k >= static_cast<long long>(springs.size()))
      reader.fail("spring", "no spring of index " + std::to_string(k) + "; " + defined);
    return std::to_string(k);
  }
  const std::string name = reader.string("spring");
  for (std::size_t k = 0; k < springs.size(); ++k)
    if (springs[k].name == name) return name;
  // An index written as a string ("0") names the spring of that index too.
  for (std::size_t k = 0; k < springs.size(); ++k)
    if (name == std::to_string(k)) return name;
  reader.fail("spring", "unknown spring '" + name + "'; " + defined);
}

// circuit[].from or .to: "ground" or "0", "dea.X" of a DEA the drive does not drive, or a name.
void SceneReader::read_ac(const toml::table& root, AcSpec& ac) const {
  const Section reader = section(root, "ac");
  auto key = [](const char* name) -> const ParameterInfo& { return parameter_info("ac", name); };
  ac.given = root.contains("ac");
  ac.log =
      reader.optional_choice(key("scale"), std::vector<bool>{false, true}).value_or(AcSpec{}.log);
  // ac.from's own range is checked after the log scale's (> 0), as the stricter one.
  ac.from = reader.optional_quantity(key("from"), false).value_or(*parameter_default(key("from")));
  ac.to = reader.quantity(key("to"));
  if (const std::string why = ac_log_from_violation(ac.log, ac.from); !why.empty())
    reader.fail("from", why);
  reader.check_range(key("from"), ac.from);
  if (const std::string why = ac_to_violation(ac.from, ac.to, !reader.has("to")); !why.empty())
    reader.fail("to", why);
  const ParameterInfo& points = key("points");
  const long long count = reader.optional_integer(points.name)
                              .value_or(static_cast<long long>(*parameter_default(points)));
  reader.check_integer_range(points, count);
  ac.points = static_cast<int>(count);
}

// Without a fluid, the [environment] keys other than fluid are refused; with one, density and
// viscosity default to the fluid's (fluid_properties, emnet/scene/parameters.hpp).
void SceneReader::read_environment(const toml::table& root, Scene& scene) const {
  const Section reader = section(root, "environment");
  auto key = [](const char* name) -> const ParameterInfo& {
    return parameter_info("environment", name);
  };
  EnvironmentSpec& environment = scene.environment;
  environment.fluid =
      reader
          .optional_choice(key("fluid"), std::vector<Fluid>{Fluid::none, Fluid::air, Fluid::water})
          .value_or(EnvironmentSpec{}.fluid);
  for (const std::string& name : find_scene_table("environment")->keys)
    reader.reject_if_unused(key(name.c_str()), scene, 0);
  if (environment.fluid == Fluid::none) return;
  const FluidProperties fluid = fluid_properties(environment.fluid);
  environment.density = reader.optional_quantity(key("density")).value_or(fluid.density);
  environment.dynamic_viscosity =
      reader.optional_quantity(key("dynamic_viscosity")).value_or(fluid.dynamic_viscosity);
  environment.width = reader.quantity(key("width"));
  environment.frequency = reader.optional_quantity(key("frequency"));
}

// [model]: band = "130 Hz" (from 0) or ["0 Hz", "130 Hz"], 0 <= from < to, finite; tolerance and
// deflection_limit in their ranges. The automatic choices need a band: from model.band, else
// from an [ac] table or the drive frequency (band_of_interest in
// emnet/studies/segment_selection.hpp); without any, "auto" is an error here.
void SceneReader::read_model(const toml::table& root, Scene& scene) const {
  const Section reader = section(root, "model");
  auto key = [](const char* name) -> const ParameterInfo& { return parameter_info("model", name); };
  ModelSpec& model = scene.model;
  const ParameterInfo& band_key = key("band");
  auto frequency_of = [&](const toml::node& node, const std::string& what) {
    return reader.node_quantity(node, "band", band_key.dimension, what);
  };
  if (const toml::node* band = reader.find("band")) {
    double from = 0.0, to = 0.0;
    if (const toml::array* array = band->as_array()) {
      if (array->size() != 2)
        reader.fail("band", "must be [from, to] (two frequencies) or one upper frequency, got " +
                                std::to_string(array->size()) + " entries");
      from = frequency_of(*array->get(0), "the lower end");
      to = frequency_of(*array->get(1), "the upper end");
    } else {
      to = frequency_of(*band, "the upper end");
    }
    const Dimension& unit = band_key.dimension;
    if (!band_key.range.contains(from))
      reader.fail("band", "the lower end must be >= 0, got " + format_quantity(from, unit));
    if (!(to > 0.0))
      reader.fail("band", "the upper end must be > 0, got " + format_quantity(to, unit));
    if (!(to > from))
      reader.fail("band", "the lower end (" + format_quantity(from, unit) +
                              ") must be below the upper end (" + format_quantity(to, unit) + ")");
    model.band_from = from;
    model.band_to = to;
  }
  model.tolerance = reader.quantity(key("tolerance"));
  model.deflection_limit = reader.quantity(key("deflection_limit"));
  const bool band_known = model.band_to || scene.ac.given || (scene.drive.kind != DriveKind::none);
  // (drive.electrical_dynamics = "auto" needs a band only with a drive, which brings one.)
  if (!band_known) {
    if (scene.beam.auto_segments) {
      const Section owner = section(root, "beam");
      owner.fail("segments",
                 "\"auto\" needs a frequency band to be accurate in: give [model] band (e.g. "
                 "band = \"130 Hz\"), an [ac] table or a periodic drive");
    }
  }
}

void SceneReader::read_provenance_table(const toml::table& table, const std::string& prefix,
                                        Scene& scene) const {
  static const std::vector<std::string> sources = {
      "paper:", "data sheet:", "assumed:", "identified:"};
  for (auto&& [table_key, node] : table) {
    const std::string entry =
        prefix.empty() ? std::string(table_key.str()) : prefix + "." + std::string(table_key.str());
    const std::string key = "provenance." + entry;
    if (const toml::table* nested = node.as_table()) {
      read_provenance_table(*nested, entry, scene);
      continue;
    }
    const std::string first_segment = entry.substr(0, entry.find_first_of(".["));
    const SceneTableInfo* named = find_scene_table(first_segment);
    if (named == nullptr || named->free_form) {
      std::vector<std::string> candidates;
      for (const SceneTableInfo& candidate : scene_tables()) {
        if (!candidate.free_form) candidates.push_back(candidate.name);
      }
      locator_.fail(&node, key,
                    "names no scene key: '" + first_segment + "' is not a scene table" +
                        did_you_mean(first_segment, candidates));
    }
    // The entry's last part must be one of the table's keys: TABLE.KEY (in an array of tables,
    // every entry's KEY) or TABLE.NAME.KEY, TABLE[NAME].KEY, TABLE.INDEX.KEY.
    const std::string last = entry.substr(entry.find_last_of(".]") + 1);
    if (entry.find_first_of(".[") == std::string::npos ||
        std::find(named->keys.begin(), named->keys.end(), last) == named->keys.end()) {
      locator_.fail(&node, key,
                    "names no scene key: '" + last + "' is not a key of [" + named->name + "]" +
                        did_you_mean(last, named->keys));
    }
    const auto* text = node.as_string();
    if (text == nullptr) {
      locator_.fail(&node, key,
                    "must be a string such as \"paper: Table 1\", got " + describe_node(node));
    }
    const std::string value = text->get();
    const bool known_source = std::any_of(sources.begin(), sources.end(), [&](const auto& start) {
      return value.compare(0, start.size(), start) == 0;
    });
    if (!known_source) {
      locator_.fail(&node, key,
                    "must start with one of " + quoted_list(sources) + ", got '" + value + "'");
    }
    if (scene.provenance.size() >= scene_limits::provenance_entries &&
        scene.provenance.count(entry) == 0) {
      locator_.fail(&node, key,
                    "more than " + std::to_string(scene_limits::provenance_entries) +
                        " [provenance] entries; a scene may have at most " +
                        std::to_string(scene_limits::provenance_entries));
    }
    scene.provenance[entry] = value;
  }
}

void SceneReader::read_provenance(const toml::table& root, Scene& scene) const {
  if (const toml::table* table = root.get_as<toml::table>("provenance")) {
    read_provenance_table(*table, "", scene);
  }
}

Scene SceneReader::read(const toml::table& root) const {
  Scene scene;
  scene.file = locator_.display_name();
  check_top_level(root);
  read_scene_table(root, scene);
  read_beam(root, scene);
  read_sections(root, scene);
  read_masses(root, scene);
  read_springs(root, scene);
  read_damping(root, scene);
  read_deas(root, scene);
  read_drive(root, scene);
  read_loads(root, scene);
  read_probes(root, scene);
  read_circuit(root, scene);
  read_ac(root, scene.ac);
  read_environment(root, scene);
  read_model(root, scene);
  read_provenance(root, scene);
  return scene;
}

}  // namespace scene_reading

using scene_reading::SceneReader;

Scene read_scene_text(const std::string& text, const std::string& display_name,
                      const std::vector<std::string>& overrides, const SceneFiles& files) {
  const std::string name = display_name.empty() ? std::string("<scene>") : display_name;
  if (const std::optional<TomlInputProblem> problem = find_toml_input_problem(text)) {
    throw InputError(problem->line > 0 ? name + ":" + std::to_string(problem->line) : name, "",
                     problem->message);
  }
  if (overrides.size() > scene_limits::overrides) {
    throw InputError(kOverrideWhere, "",
                     std::to_string(overrides.size()) + " overrides; at most " +
                         std::to_string(scene_limits::overrides) + " may be given");
  }
  TomlParseOutcome parsed = parse_toml(text, name);
  if (!parsed.table) {
    const std::string where = parsed.line > 0 ? name + ":" + std::to_string(parsed.line) : name;
    throw InputError(where, "", "not a valid TOML file: " + parsed.description);
  }
  const SceneReader reader(name, &files);
  for (const std::string& assignment : overrides)
    apply_override(*parsed.table, assignment, reader.locator());
  return reader.read(*parsed.table);
}

Scene read_scene(const std::string& path, const std::vector<std::string>& overrides) {
  return read_scene_text(read_scene_file(path), path, overrides);
}

}  // namespace emnet
