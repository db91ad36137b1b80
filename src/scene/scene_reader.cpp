// Scene reader: TOML scene text plus `--set key=value` overrides into a validated SI Scene.
//
// The file is parsed with toml++ into a document tree; overrides are written into that tree
// (so a value from an override is checked exactly like one from the file, and is recognised by
// having no source position: its errors say "--set"); then the tree is walked table by table,
// rejecting unknown tables and keys, reading each value with its unit and checking its range.
// The first problem found is thrown as an InputError.
#include "emnet/scene/scene_reader.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "emnet/core/units.hpp"
#include "toml_input_guard.hpp"

namespace emnet {
namespace {

constexpr const char* kOverrideWhere = "--set";
constexpr long long kMaximumSegments = 100000;
constexpr long long kMinimumAcPoints = 2;
constexpr long long kMaximumAcPoints = 1000000;
// Positions within this fraction of the beam length outside [0, L] are taken as the beam end.
constexpr double kBeamEndTolerance = 1e-9;

// ---------------------------------------------------------------------------------------------
// Schema: which tables and keys a scene may contain.

struct TableSchema {
  std::string name;
  bool is_array_of_tables;
  bool is_free_form;  // [provenance]: any dotted key
  std::vector<std::string> keys;
};

const std::vector<TableSchema>& scene_schema() {
  static const std::vector<TableSchema> schema = {
      {"scene", false, false, {"name", "title", "description"}},
      {"beam",
       false,
       false,
       {"length", "segments", "bending_stiffness", "mass_per_length", "rotary_inertia_per_length",
        "left", "right"}},
      {"damping",
       false,
       false,
       {"viscous_per_length", "kelvin_voigt_time", "loss_factor", "loss_factor_frequency"}},
      {"dea",
       true,
       false,
       {"name", "from", "to", "face", "lever_arm", "relative_permittivity", "dielectric_thickness",
        "force_thickness", "electrode_width", "electrode_resistance", "back_coupling",
        "breakdown_field"}},
      {"drive",
       false,
       false,
       {"kind", "deas", "voltage", "bias", "amplitude", "frequency", "rise_time", "duty", "overlap",
        "electrical_dynamics"}},
      {"load", true, false, {"kind", "at", "value"}},
      {"probe", true, false, {"name", "quantity", "at", "dea"}},
      {"ac", false, false, {"from", "to", "points", "scale"}},
      {"environment",
       false,
       false,
       {"fluid", "density", "dynamic_viscosity", "width", "frequency"}},
      {"model", false, false, {"band", "tolerance", "deflection_limit"}},
      {"provenance", false, true, {}},
  };
  return schema;
}

const TableSchema* find_table_schema(const std::string& name) {
  for (const TableSchema& table : scene_schema()) {
    if (table.name == name) return &table;
  }
  return nullptr;
}

// The most entries an array of tables may have (scene_limits); 0 for a plain table.
std::size_t maximum_entries(const std::string& table_name) {
  if (table_name == "dea") return scene_limits::deas;
  if (table_name == "load") return scene_limits::loads;
  if (table_name == "probe") return scene_limits::probes;
  return 0;
}

bool schema_has_key(const TableSchema& table, const std::string& key) {
  return std::find(table.keys.begin(), table.keys.end(), key) != table.keys.end();
}

std::vector<std::string> table_names() {
  std::vector<std::string> names;
  for (const TableSchema& table : scene_schema()) names.push_back(table.name);
  return names;
}

// ---------------------------------------------------------------------------------------------
// Small text helpers.

std::string trim(const std::string& text) {
  const char* const spaces = " \t\r\n";
  const std::size_t begin = text.find_first_not_of(spaces);
  if (begin == std::string::npos) return "";
  const std::size_t end = text.find_last_not_of(spaces);
  return text.substr(begin, end - begin + 1);
}

// Optimal-string-alignment edit distance (a transposition counts as one edit).
std::size_t edit_distance(const std::string& first, const std::string& second) {
  const std::size_t rows = first.size() + 1;
  const std::size_t columns = second.size() + 1;
  std::vector<std::size_t> distance(rows * columns, 0);
  auto at = [columns, &distance](std::size_t row, std::size_t column) -> std::size_t& {
    return distance[row * columns + column];
  };
  for (std::size_t row = 0; row < rows; ++row) at(row, 0) = row;
  for (std::size_t column = 0; column < columns; ++column) at(0, column) = column;
  for (std::size_t row = 1; row < rows; ++row) {
    for (std::size_t column = 1; column < columns; ++column) {
      const std::size_t substitution = first[row - 1] == second[column - 1] ? 0 : 1;
      std::size_t best = std::min({at(row - 1, column) + 1, at(row, column - 1) + 1,
                                   at(row - 1, column - 1) + substitution});
      if (row > 1 && column > 1 && first[row - 1] == second[column - 2] &&
          first[row - 2] == second[column - 1]) {
        best = std::min(best, at(row - 2, column - 2) + 1);
      }
      at(row, column) = best;
    }
  }
  return at(rows - 1, columns - 1);
}

// " (did you mean 'beam.length'?)" for the closest candidate within a few edits, else "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates) {
  // Very short words are never "close" to anything: 'C' is one edit from every one-letter name.
  if (word.size() <= 2) return "";
  const std::size_t allowed = word.size() <= 4 ? 1 : (word.size() <= 12 ? 2 : 3);
  std::string best;
  std::size_t best_distance = allowed + 1;
  for (const std::string& candidate : candidates) {
    // The distance is at least the difference in length: skip those too far to be close (and
    // keep the cost of a long word linear).
    const std::size_t length_difference = word.size() > candidate.size()
                                              ? word.size() - candidate.size()
                                              : candidate.size() - word.size();
    if (length_difference > allowed) continue;
    const std::size_t distance = edit_distance(word, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

std::string quoted_list(const std::vector<std::string>& words) {
  std::string list;
  for (const std::string& word : words) {
    if (!list.empty()) list += ", ";
    list += "'" + word + "'";
  }
  return list;
}

bool is_identifier(const std::string& name) {
  if (name.empty()) return false;
  return std::all_of(name.begin(), name.end(), [](char character) {
    return (character >= 'A' && character <= 'Z') || (character >= 'a' && character <= 'z') ||
           (character >= '0' && character <= '9') || character == '_';
  });
}

bool is_all_digits(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char character) {
    return character >= '0' && character <= '9';
  });
}

std::string format_number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

// "a string ('abc')", "an integer (3)", "a table": what a node is, for "got ..." messages.
std::string describe_node(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return "a string ('" + std::string(node.as_string()->get()) + "')";
    case toml::node_type::integer:
      return "an integer (" + std::to_string(node.as_integer()->get()) + ")";
    case toml::node_type::floating_point:
      return "a floating-point number (" + format_number(node.as_floating_point()->get()) + ")";
    case toml::node_type::boolean:
      return std::string("a boolean (") + (node.as_boolean()->get() ? "true" : "false") + ")";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

// ---------------------------------------------------------------------------------------------
// TOML parsing that works whether toml++ reports errors by exception or by result.

struct TomlParseOutcome {
  std::optional<toml::table> table;
  std::string description;
  std::size_t line = 0;
};

TomlParseOutcome parse_toml(std::string_view text, std::string_view source_path) {
  TomlParseOutcome outcome;
#if TOML_EXCEPTIONS
  try {
    outcome.table = toml::parse(text, source_path);
  } catch (const toml::parse_error& error) {
    outcome.description = std::string(error.description());
    outcome.line = static_cast<std::size_t>(error.source().begin.line);
  }
#else
  toml::parse_result result = toml::parse(text, source_path);
  if (result) {
    outcome.table = std::move(result).table();
  } else {
    outcome.description = std::string(result.error().description());
    outcome.line = static_cast<std::size_t>(result.error().source().begin.line);
  }
#endif
  return outcome;
}

// ---------------------------------------------------------------------------------------------
// Locating errors.

class Locator {
 public:
  explicit Locator(std::string display_name) : display_name_(std::move(display_name)) {}

  const std::string& display_name() const { return display_name_; }

  // "file:line" for a node read from the file, "--set" for one written by an override, "file"
  // when there is no node (a missing key).
  std::string where(const toml::node* node) const {
    if (node == nullptr) return display_name_;
    const toml::source_region& source = node->source();
    if (source.path && *source.path == display_name_ && source.begin.line > 0) {
      return display_name_ + ":" + std::to_string(source.begin.line);
    }
    return kOverrideWhere;
  }

  [[noreturn]] void fail(const toml::node* node, const std::string& key,
                         const std::string& message) const {
    throw InputError(where(node), key, message);
  }

 private:
  std::string display_name_;
};

enum class Bound { any, non_negative, positive };

// One table of the scene (or one entry of an array of tables), read key by key; keys are named
// "<prefix>.<key>" in messages.
class Section {
 public:
  Section(const Locator& locator, const toml::table* table, std::string prefix)
      : locator_(locator), table_(table), prefix_(std::move(prefix)) {}

  std::string key(const std::string& name) const { return prefix_ + "." + name; }
  const toml::node* find(const std::string& name) const {
    return table_ == nullptr ? nullptr : table_->get(name);
  }
  bool has(const std::string& name) const { return find(name) != nullptr; }

  [[noreturn]] void fail(const std::string& name, const std::string& message) const {
    locator_.fail(find(name), key(name), message);
  }
  [[noreturn]] void fail_missing(const std::string& name) const {
    locator_.fail(nullptr, key(name), "missing (required)");
  }

  void reject_unknown_keys(const std::vector<std::string>& allowed) const {
    if (table_ == nullptr) return;
    for (auto&& [table_key, node] : *table_) {
      const std::string name(table_key.str());
      if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) continue;
      std::vector<std::string> candidates;
      for (const std::string& candidate : allowed) candidates.push_back(key(candidate));
      locator_.fail(&node, key(name), "unknown key" + did_you_mean(key(name), candidates));
    }
  }

  // `node` (the value of key `name`, or an element of it that `what` names: "the upper end") as
  // a quantity of `dimension`: a number, or a string "number unit".
  double node_quantity(const toml::node& node, const std::string& name, const Dimension& dimension,
                       const std::string& what = "") const {
    const std::string subject = what.empty() ? "" : what + " ";
    double value = 0.0;
    if (const auto* integer = node.as_integer()) {
      value = static_cast<double>(integer->get());
    } else if (const auto* floating = node.as_floating_point()) {
      value = floating->get();
      if (!std::isfinite(value))
        fail(name, subject + "must be finite, got " + format_number(value));
    } else if (const auto* text = node.as_string()) {
      try {
        value = parse_quantity(text->get(), dimension);
      } catch (const std::invalid_argument& error) {
        fail(name, (what.empty() ? "" : what + ": ") + error.what());
      }
    } else {
      const std::string example = dimension == dim::none ? "0.5" : "1 " + si_unit_symbol(dimension);
      fail(name, subject + "must be a number or a string like '" + example + "', got " +
                     describe_node(node));
    }
    // A subnormal value has lost its precision, and a length of one cut into segments
    // underflows to zero.
    if (value != 0.0 && std::abs(value) < std::numeric_limits<double>::min()) {
      fail(name, subject + "must be 0 or at least " +
                     format_quantity(std::numeric_limits<double>::min(), dimension) +
                     " in magnitude (a normal floating-point number), got " +
                     format_quantity(value, dimension));
    }
    return value;
  }

  std::optional<double> optional_quantity(const std::string& name, const Dimension& dimension,
                                          Bound bound) const {
    const toml::node* node = find(name);
    if (node == nullptr) return std::nullopt;
    const double value = node_quantity(*node, name, dimension);
    if (bound == Bound::positive && !(value > 0.0)) {
      fail(name, "must be > 0, got " + format_quantity(value, dimension));
    }
    if (bound == Bound::non_negative && !(value >= 0.0)) {
      fail(name, "must be >= 0, got " + format_quantity(value, dimension));
    }
    return value;
  }

  double quantity(const std::string& name, const Dimension& dimension, Bound bound) const {
    const std::optional<double> value = optional_quantity(name, dimension, bound);
    if (!value) fail_missing(name);
    return *value;
  }

  double quantity_or(const std::string& name, const Dimension& dimension, Bound bound,
                     double default_value) const {
    return optional_quantity(name, dimension, bound).value_or(default_value);
  }

  std::optional<long long> optional_integer(const std::string& name) const {
    const toml::node* node = find(name);
    if (node == nullptr) return std::nullopt;
    const auto* integer = node->as_integer();
    if (integer == nullptr) fail(name, "must be an integer, got " + describe_node(*node));
    return static_cast<long long>(integer->get());
  }

  std::optional<std::string> optional_string(const std::string& name) const {
    const toml::node* node = find(name);
    if (node == nullptr) return std::nullopt;
    const auto* text = node->as_string();
    if (text == nullptr) fail(name, "must be a string, got " + describe_node(*node));
    return text->get();
  }

  std::string string(const std::string& name) const {
    const std::optional<std::string> text = optional_string(name);
    if (!text) fail_missing(name);
    return *text;
  }

  // A name that reaches SPICE decks: letters, digits and '_', at most scene_limits::name_bytes.
  std::string identifier(const std::string& name) const {
    const std::string text = string(name);
    if (!is_identifier(text)) {
      fail(name,
           "must be a non-empty name of letters, digits and '_' only (names are used in "
           "SPICE decks), got '" +
               text + "'");
    }
    if (text.size() > scene_limits::name_bytes) {
      fail(name, "is " + std::to_string(text.size()) +
                     " characters long; a name may have at most " +
                     std::to_string(scene_limits::name_bytes));
    }
    return text;
  }

  std::optional<bool> optional_boolean(const std::string& name) const {
    const toml::node* node = find(name);
    if (node == nullptr) return std::nullopt;
    const auto* boolean = node->as_boolean();
    if (boolean == nullptr) fail(name, "must be true or false, got " + describe_node(*node));
    return boolean->get();
  }

  template <typename Enum>
  std::optional<Enum> optional_choice(
      const std::string& name, const std::vector<std::pair<std::string, Enum>>& choices) const {
    const std::optional<std::string> text = optional_string(name);
    if (!text) return std::nullopt;
    std::vector<std::string> names;
    for (const auto& [choice_name, value] : choices) {
      if (*text == choice_name) return value;
      names.push_back(choice_name);
    }
    fail(name, "must be one of " + quoted_list(names) + ", got '" + *text + "'" +
                   did_you_mean(*text, names));
  }

  template <typename Enum>
  Enum choice(const std::string& name,
              const std::vector<std::pair<std::string, Enum>>& choices) const {
    const std::optional<Enum> value = optional_choice(name, choices);
    if (!value) fail_missing(name);
    return *value;
  }

  // A position along the beam, 0 <= x <= L (values a hair outside are snapped to the end).
  double position_on_beam(const std::string& name, double beam_length) const {
    const double position = quantity(name, dim::length, Bound::any);
    const double tolerance = kBeamEndTolerance * beam_length;
    if (position < -tolerance || position > beam_length + tolerance) {
      fail(name, "must lie on the beam [0, " + format_quantity(beam_length, dim::length) +
                     "], got " + format_quantity(position, dim::length));
    }
    return std::clamp(position, 0.0, beam_length);
  }

 private:
  const Locator& locator_;
  const toml::table* table_;
  std::string prefix_;
};

// ---------------------------------------------------------------------------------------------
// Reading the document tree into a Scene.

class SceneReader {
 public:
  explicit SceneReader(const std::string& display_name) : locator_(display_name) {}

  void apply_override(toml::table& root, const std::string& assignment) const;
  Scene read(const toml::table& root) const;

 private:
  // The entries of an array of tables, each with the prefix its keys are named by.
  struct Entry {
    const toml::table* table;
    std::string prefix;  // "dea[A]" or "load[0]"
  };
  std::vector<Entry> entries(const toml::table& root, const std::string& table_name) const;
  Section section(const toml::table& root, const std::string& table_name) const;
  toml::table& table_for_override(toml::table& root, const std::string& table_name,
                                  const std::string& key) const;

  void check_top_level(const toml::table& root) const;
  void read_scene_table(const toml::table& root, Scene& scene) const;
  void read_beam(const toml::table& root, BeamSpec& beam) const;
  void read_damping(const toml::table& root, DampingSpec& damping) const;
  void read_deas(const toml::table& root, Scene& scene) const;
  void read_drive(const toml::table& root, Scene& scene) const;
  void read_loads(const toml::table& root, Scene& scene) const;
  void read_probes(const toml::table& root, Scene& scene) const;
  void read_ac(const toml::table& root, AcSpec& ac) const;
  void read_environment(const toml::table& root, EnvironmentSpec& environment) const;
  void read_model(const toml::table& root, Scene& scene) const;
  void read_provenance(const toml::table& root, Scene& scene) const;
  void read_provenance_table(const toml::table& table, const std::string& prefix,
                             Scene& scene) const;

  Locator locator_;
};

Section SceneReader::section(const toml::table& root, const std::string& table_name) const {
  const TableSchema* schema = find_table_schema(table_name);
  Section result(locator_, root.get_as<toml::table>(table_name), table_name);
  if (schema != nullptr) result.reject_unknown_keys(schema->keys);
  return result;
}

std::vector<SceneReader::Entry> SceneReader::entries(const toml::table& root,
                                                     const std::string& table_name) const {
  std::vector<Entry> result;
  const toml::array* array = root.get_as<toml::array>(table_name);
  if (array == nullptr) return result;
  const std::size_t maximum = maximum_entries(table_name);
  if (array->size() > maximum) {
    locator_.fail(array, table_name,
                  std::to_string(array->size()) + " [[" + table_name + "]] entries; a scene may " +
                      "have at most " + std::to_string(maximum));
  }
  for (std::size_t index = 0; index < array->size(); ++index) {
    const toml::node& element = (*array)[index];
    const std::string indexed = table_name + "[" + std::to_string(index) + "]";
    const toml::table* table = element.as_table();
    if (table == nullptr) {
      locator_.fail(&element, indexed, "must be a table, got " + describe_node(element));
    }
    std::string prefix = indexed;
    if (const auto* name = table->get_as<std::string>("name")) {
      if (is_identifier(name->get())) prefix = table_name + "[" + name->get() + "]";
    }
    result.push_back(Entry{table, prefix});
  }
  return result;
}

void SceneReader::check_top_level(const toml::table& root) const {
  for (auto&& [table_key, node] : root) {
    const std::string name(table_key.str());
    const TableSchema* schema = find_table_schema(name);
    if (schema == nullptr) {
      locator_.fail(&node, name,
                    std::string(node.is_table() ? "unknown table" : "unknown key") +
                        did_you_mean(name, table_names()) + "; a scene has the tables " +
                        quoted_list(table_names()));
    }
    if (schema->is_array_of_tables) {
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

void SceneReader::read_beam(const toml::table& root, BeamSpec& beam) const {
  const Section reader = section(root, "beam");
  beam.length = reader.quantity("length", dim::length, Bound::positive);
  beam.auto_segments = false;
  if (const toml::node* node = reader.find("segments"); node != nullptr && node->is_string()) {
    const std::string text = node->as_string()->get();
    if (text != "auto")
      reader.fail("segments", "must be an integer >= 1 or \"auto\", got '" + text + "'");
    beam.auto_segments = true;
    beam.segments = 0;  // chosen by the resolve step (emnet/studies/segment_selection.hpp)
  }
  const std::optional<long long> segments =
      beam.auto_segments ? std::optional<long long>(1) : reader.optional_integer("segments");
  if (!segments) reader.fail_missing("segments");
  if (*segments < 1) reader.fail("segments", "must be >= 1, got " + std::to_string(*segments));
  if (*segments > kMaximumSegments) {
    reader.fail("segments", std::to_string(*segments) + " segments is absurdly large (at most " +
                                std::to_string(kMaximumSegments) + ")");
  }
  if (!beam.auto_segments) beam.segments = static_cast<int>(*segments);
  beam.bending_stiffness =
      reader.quantity("bending_stiffness", dim::bending_stiffness, Bound::positive);
  beam.mass_per_length = reader.quantity("mass_per_length", dim::mass_per_length, Bound::positive);
  beam.rotary_inertia_per_length = reader.quantity_or(
      "rotary_inertia_per_length", dim::rotary_inertia_per_length, Bound::non_negative, 0.0);
  const std::vector<std::pair<std::string, EndCondition>> ends = {
      {"clamped", EndCondition::clamped},
      {"free", EndCondition::free},
      {"pinned", EndCondition::pinned},
      {"sliding", EndCondition::sliding}};
  beam.left = reader.optional_choice("left", ends).value_or(EndCondition::clamped);
  beam.right = reader.optional_choice("right", ends).value_or(EndCondition::free);
}

void SceneReader::read_damping(const toml::table& root, DampingSpec& damping) const {
  const Section reader = section(root, "damping");
  damping.viscous_per_length =
      reader.quantity_or("viscous_per_length", dim::damping_per_length, Bound::non_negative, 0.0);
  damping.kelvin_voigt_time =
      reader.quantity_or("kelvin_voigt_time", dim::time, Bound::non_negative, 0.0);
  damping.loss_factor = reader.optional_quantity("loss_factor", dim::none, Bound::non_negative);
  damping.loss_factor_frequency =
      reader.optional_quantity("loss_factor_frequency", dim::frequency, Bound::positive);
  if (damping.loss_factor && reader.has("kelvin_voigt_time")) {
    reader.fail("kelvin_voigt_time",
                "give either damping.kelvin_voigt_time or damping.loss_factor (with "
                "damping.loss_factor_frequency), not both");
  }
  if (damping.loss_factor && !damping.loss_factor_frequency) {
    reader.fail("loss_factor",
                "needs damping.loss_factor_frequency (Hz), the frequency at which it holds");
  }
  if (damping.loss_factor_frequency && !damping.loss_factor) {
    reader.fail("loss_factor_frequency", "is only used with damping.loss_factor, which is missing");
  }
}

void SceneReader::read_deas(const toml::table& root, Scene& scene) const {
  const TableSchema& schema = *find_table_schema("dea");
  const double beam_length = scene.beam.length;
  std::set<std::string> names;
  for (const Entry& entry : entries(root, "dea")) {
    const Section reader(locator_, entry.table, entry.prefix);
    reader.reject_unknown_keys(schema.keys);
    DeaSpec dea;
    dea.name = reader.identifier("name");
    if (!names.insert(dea.name).second) {
      reader.fail("name", "duplicate DEA name '" + dea.name + "'");
    }
    dea.from = reader.quantity("from", dim::length, Bound::any);
    dea.to = reader.quantity("to", dim::length, Bound::any);
    const double tolerance = kBeamEndTolerance * beam_length;
    const std::string span = "DEA '" + dea.name + "' spans [" +
                             format_quantity(dea.from, dim::length) + ", " +
                             format_quantity(dea.to, dim::length) + "]";
    const std::string beam_span = "the beam [0, " + format_quantity(beam_length, dim::length) + "]";
    if (dea.from < -tolerance) reader.fail("from", span + ", outside " + beam_span);
    if (dea.to > beam_length + tolerance) reader.fail("to", span + ", outside " + beam_span);
    if (!(dea.from < dea.to)) reader.fail("to", span + ": 'to' must be greater than 'from'");
    dea.from = std::max(dea.from, 0.0);
    dea.to = std::min(dea.to, beam_length);
    dea.face = reader.choice("face", std::vector<std::pair<std::string, Face>>{
                                         {"top", Face::top}, {"bottom", Face::bottom}});
    dea.lever_arm = reader.quantity("lever_arm", dim::length, Bound::positive);
    dea.relative_permittivity =
        reader.quantity("relative_permittivity", dim::none, Bound::positive);
    dea.dielectric_thickness =
        reader.quantity("dielectric_thickness", dim::length, Bound::positive);
    dea.force_thickness = reader.quantity("force_thickness", dim::length, Bound::positive);
    dea.electrode_width = reader.quantity("electrode_width", dim::length, Bound::positive);
    dea.electrode_resistance =
        reader.quantity("electrode_resistance", dim::resistance, Bound::positive);
    dea.back_coupling = reader.optional_boolean("back_coupling").value_or(false);
    // Default: the paper's film's data-sheet value (kDefaultBreakdownField, emnet/scene/scene.hpp).
    dea.breakdown_field = reader.quantity_or("breakdown_field", dim::electric_field,
                                             Bound::positive, kDefaultBreakdownField);
    scene.deas.push_back(dea);
  }
}

// Which drive kinds use which [drive] key (drive.kind and drive.electrical_dynamics: all of
// them); a key the scene's kind does not use is refused by name, with the kinds that use it.
struct DriveKeyUse {
  const char* key;
  std::vector<DriveKind> kinds;
};

const std::vector<DriveKeyUse>& drive_key_uses() {
  using K = DriveKind;
  static const std::vector<DriveKeyUse> uses = {
      {"deas", {K::antagonistic, K::switched, K::bias_differential, K::single}},
      {"voltage", {K::antagonistic, K::switched}},
      {"bias", {K::bias_differential, K::single}},
      {"amplitude", {K::bias_differential, K::single}},
      {"frequency", {K::none, K::antagonistic, K::switched, K::bias_differential, K::single}},
      {"duty", {K::antagonistic, K::switched}},
      {"rise_time", {K::antagonistic, K::switched}},
      {"overlap", {K::antagonistic}},
  };
  return uses;
}

// "the 0/V square wave on DEA A, then on DEA B": what each kind is, for messages.
const char* drive_kind_meaning(DriveKind kind) {
  switch (kind) {
    case DriveKind::none:
      return "no DEA driven, the scene's loads only";
    case DriveKind::antagonistic:
      return "a 0/V square wave on DEA A, then on DEA B";
    case DriveKind::switched:
      return "a 0/V square wave on one DEA";
    case DriveKind::bias_differential:
      return "V_A,B = V0 +/- v*sin(2*pi*f*t)";
    case DriveKind::single:
      return "the sine V = V0 + v*sin(2*pi*f*t) on one DEA";
  }
  return "?";
}

void SceneReader::read_drive(const toml::table& root, Scene& scene) const {
  const Section reader = section(root, "drive");
  DriveSpec& drive = scene.drive;
  const std::vector<std::pair<std::string, DriveKind>> kinds = {
      {"none", DriveKind::none},
      {"antagonistic", DriveKind::antagonistic},
      {"switched", DriveKind::switched},
      {"bias_differential", DriveKind::bias_differential},
      {"single", DriveKind::single}};
  drive.kind = reader.optional_choice("kind", kinds).value_or(DriveKind::none);
  const std::string kind_name = drive_kind_name(drive.kind);
  for (const DriveKeyUse& use : drive_key_uses()) {
    if (!reader.has(use.key) ||
        std::find(use.kinds.begin(), use.kinds.end(), drive.kind) != use.kinds.end())
      continue;
    std::vector<std::string> users;
    for (DriveKind kind : use.kinds) users.push_back(drive_kind_name(kind));
    std::string hint;
    if (drive.kind == DriveKind::single && std::string(use.key) == "voltage")
      hint = "; a 0/V square wave on one DEA is drive.kind = \"switched\"";
    reader.fail(use.key, std::string("is not used by drive kind '") + kind_name + "' (" +
                             drive_kind_meaning(drive.kind) + "); it is used by drive kind" +
                             (users.size() == 1 ? " " : "s ") + quoted_list(users) + hint);
  }

  // drive.deas: names of existing, distinct DEAs.
  std::vector<std::string> dea_names;
  for (const DeaSpec& dea : scene.deas) dea_names.push_back(dea.name);
  const std::set<std::string> known_deas(dea_names.begin(), dea_names.end());
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
        const std::string defined = dea_names.empty()
                                        ? std::string("the scene defines no DEAs")
                                        : "the scene defines " + quoted_list(dea_names);
        locator_.fail(
            &element, reader.key("deas"),
            "unknown DEA '" + dea_name + "'" + did_you_mean(dea_name, dea_names) + "; " + defined);
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
  const bool square_wave =
      drive.kind == DriveKind::antagonistic || drive.kind == DriveKind::switched;
  const bool sine = drive.kind == DriveKind::bias_differential || drive.kind == DriveKind::single;
  if (square_wave) drive.voltage = reader.quantity("voltage", dim::voltage, Bound::non_negative);
  if (sine) {
    drive.bias = reader.quantity("bias", dim::voltage, Bound::non_negative);
    drive.amplitude = reader.quantity("amplitude", dim::voltage, Bound::non_negative);
  }

  const std::optional<double> frequency =
      reader.optional_quantity("frequency", dim::frequency, Bound::positive);
  if (drive.kind != DriveKind::none && !frequency) reader.fail_missing("frequency");
  drive.frequency = frequency.value_or(0.0);
  drive.rise_time = reader.quantity_or("rise_time", dim::time, Bound::non_negative, 0.0);
  if (frequency && !(drive.rise_time < 0.5 / *frequency)) {
    reader.fail("rise_time", "must be shorter than half a period (" +
                                 format_quantity(0.5 / *frequency, dim::time) + " at " +
                                 format_quantity(*frequency, dim::frequency) + "), got " +
                                 format_quantity(drive.rise_time, dim::time));
  }
  drive.duty = reader.quantity_or("duty", dim::none, Bound::any, 0.5);
  if (!(drive.duty > 0.0 && drive.duty < 1.0)) {
    reader.fail("duty", "must be between 0 and 1 (exclusive), got " + format_number(drive.duty));
  }
  drive.overlap = reader.quantity_or("overlap", dim::time, Bound::any, 0.0);
  if (frequency && drive.overlap != 0.0) {
    // A's on-time (duty·T + overlap) must stay inside (rise time, T − rise time).
    const double period = 1.0 / *frequency;
    const double on_time = drive.duty * period + drive.overlap;
    if (!(on_time > 2.0 * drive.rise_time && on_time < period - 2.0 * drive.rise_time))
      reader.fail("overlap", "makes DEA A's on-time " + format_quantity(on_time, dim::time) +
                                 " leave the period " + format_quantity(period, dim::time) +
                                 " (with the rise time at both edges)");
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
    drive.electrical_dynamics = reader.optional_boolean("electrical_dynamics").value_or(true);
  }
}

void SceneReader::read_loads(const toml::table& root, Scene& scene) const {
  const TableSchema& schema = *find_table_schema("load");
  for (const Entry& entry : entries(root, "load")) {
    const Section reader(locator_, entry.table, entry.prefix);
    reader.reject_unknown_keys(schema.keys);
    LoadSpec load;
    load.kind =
        reader.choice("kind", std::vector<std::pair<std::string, LoadKind>>{
                                  {"force", LoadKind::force}, {"moment", LoadKind::moment}});
    load.at = reader.position_on_beam("at", scene.beam.length);
    load.value = reader.quantity("value", load.kind == LoadKind::force ? dim::force : dim::moment,
                                 Bound::any);
    scene.loads.push_back(load);
  }
}

void SceneReader::read_probes(const toml::table& root, Scene& scene) const {
  const TableSchema& schema = *find_table_schema("probe");
  std::vector<std::string> dea_names;
  for (const DeaSpec& dea : scene.deas) dea_names.push_back(dea.name);
  const std::set<std::string> known_deas(dea_names.begin(), dea_names.end());
  std::set<std::string> names;
  for (const Entry& entry : entries(root, "probe")) {
    const Section reader(locator_, entry.table, entry.prefix);
    reader.reject_unknown_keys(schema.keys);
    ProbeSpec probe;
    probe.name = reader.identifier("name");
    if (!names.insert(probe.name).second) {
      reader.fail("name", "duplicate probe name '" + probe.name + "'");
    }
    probe.quantity =
        reader.choice("quantity", std::vector<std::pair<std::string, ProbeQuantity>>{
                                      {"deflection", ProbeQuantity::deflection},
                                      {"velocity", ProbeQuantity::velocity},
                                      {"rotation", ProbeQuantity::rotation},
                                      {"angular_velocity", ProbeQuantity::angular_velocity},
                                      {"dea_voltage", ProbeQuantity::dea_voltage},
                                      {"dea_current", ProbeQuantity::dea_current}});
    const std::string quantity_name = probe_quantity_name(probe.quantity);
    const bool on_dea = probe.quantity == ProbeQuantity::dea_voltage ||
                        probe.quantity == ProbeQuantity::dea_current;
    if (on_dea) {
      if (reader.has("at")) {
        reader.fail("at", "is not used by probe quantity '" + quantity_name + "' (it names a DEA)");
      }
      probe.dea = reader.string("dea");
      if (known_deas.count(probe.dea) == 0) {
        const std::string defined = dea_names.empty()
                                        ? std::string("the scene defines no DEAs")
                                        : "the scene defines " + quoted_list(dea_names);
        reader.fail("dea", "unknown DEA '" + probe.dea + "'" + did_you_mean(probe.dea, dea_names) +
                               "; " + defined);
      }
    } else {
      if (reader.has("dea")) {
        reader.fail("dea",
                    "is only used by probe quantities 'dea_voltage' and 'dea_current', "
                    "not '" +
                        quantity_name + "'");
      }
      probe.at = reader.position_on_beam("at", scene.beam.length);
    }
    scene.probes.push_back(probe);
  }
}

void SceneReader::read_ac(const toml::table& root, AcSpec& ac) const {
  const Section reader = section(root, "ac");
  ac.given = root.contains("ac");
  ac.log = reader
               .optional_choice("scale", std::vector<std::pair<std::string, bool>>{{"lin", false},
                                                                                   {"log", true}})
               .value_or(false);
  ac.from = reader.quantity_or("from", dim::frequency, Bound::any, ac.from);
  ac.to = reader.quantity_or("to", dim::frequency, Bound::any, ac.to);
  if (ac.log && !(ac.from > 0.0)) {
    reader.fail("from",
                "must be > 0 for a log scale, got " + format_quantity(ac.from, dim::frequency));
  }
  if (!(ac.from >= 0.0)) {
    reader.fail("from", "must be >= 0, got " + format_quantity(ac.from, dim::frequency));
  }
  if (!(ac.to > ac.from)) {
    reader.fail("to", "must be greater than ac.from (" + format_quantity(ac.from, dim::frequency) +
                          "), got " + format_quantity(ac.to, dim::frequency) +
                          (reader.has("to") ? "" : " (the default)"));
  }
  const long long points = reader.optional_integer("points").value_or(ac.points);
  if (points < kMinimumAcPoints || points > kMaximumAcPoints) {
    reader.fail("points", "must be between " + std::to_string(kMinimumAcPoints) + " and " +
                              std::to_string(kMaximumAcPoints) + ", got " + std::to_string(points));
  }
  ac.points = static_cast<int>(points);
}

// Fluid properties at 20 °C and 101.325 kPa: water ρ = 998.2 kg/m³ (CRC Handbook of Chemistry
// and Physics, density of water), η = 1.002e-3 Pa·s (ISO/TR 3666:1998, the viscosity of water
// at 20 °C); dry air ρ = 1.204 kg/m³ (ideal gas, M = 28.96 g/mol), η = 1.81e-5 Pa·s (CRC
// Handbook, viscosity of air).
void SceneReader::read_environment(const toml::table& root, EnvironmentSpec& environment) const {
  const Section reader = section(root, "environment");
  environment.fluid =
      reader
          .optional_choice("fluid",
                           std::vector<std::pair<std::string, Fluid>>{
                               {"none", Fluid::none}, {"air", Fluid::air}, {"water", Fluid::water}})
          .value_or(Fluid::none);
  if (environment.fluid == Fluid::none) {
    for (const char* key : {"density", "dynamic_viscosity", "width", "frequency"})
      if (reader.has(key))
        reader.fail(key, "is only used with environment.fluid = \"air\" or \"water\"");
    return;
  }
  const bool water = environment.fluid == Fluid::water;
  environment.density =
      reader.quantity_or("density", dim::density, Bound::positive, water ? 998.2 : 1.204);
  environment.dynamic_viscosity = reader.quantity_or("dynamic_viscosity", dim::dynamic_viscosity,
                                                     Bound::positive, water ? 1.002e-3 : 1.81e-5);
  environment.width = reader.quantity("width", dim::length, Bound::positive);
  environment.frequency = reader.optional_quantity("frequency", dim::frequency, Bound::positive);
}

// [model]: band = "130 Hz" (from 0) or ["0 Hz", "130 Hz"], 0 <= from < to, finite;
// tolerance in (0, 0.5) (a relative error of one half is no accuracy at all); deflection_limit
// in (0, 1], a fraction of the beam length (default 0.1). The automatic
// choices need a band: from model.band, else from an [ac] table or the drive frequency
// (band_of_interest in emnet/studies/segment_selection.hpp); without any, "auto" is an error here.
void SceneReader::read_model(const toml::table& root, Scene& scene) const {
  const Section reader = section(root, "model");
  ModelSpec& model = scene.model;
  auto frequency_of = [&](const toml::node& node, const std::string& what) {
    return reader.node_quantity(node, "band", dim::frequency, what);
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
    if (!(from >= 0.0))
      reader.fail("band",
                  "the lower end must be >= 0, got " + format_quantity(from, dim::frequency));
    if (!(to > 0.0))
      reader.fail("band", "the upper end must be > 0, got " + format_quantity(to, dim::frequency));
    if (!(to > from))
      reader.fail("band", "the lower end (" + format_quantity(from, dim::frequency) +
                              ") must be below the upper end (" +
                              format_quantity(to, dim::frequency) + ")");
    model.band_from = from;
    model.band_to = to;
  }
  model.tolerance = reader.quantity_or("tolerance", dim::none, Bound::any, 1e-3);
  if (!(model.tolerance > 0.0 && model.tolerance < 0.5))
    reader.fail("tolerance",
                "must lie in (0, 0.5) (a relative error), got " + format_number(model.tolerance));
  model.deflection_limit = reader.quantity_or("deflection_limit", dim::none, Bound::any, 0.1);
  if (!(model.deflection_limit > 0.0 && model.deflection_limit <= 1.0))
    reader.fail("deflection_limit", "must be > 0 and at most 1 (a fraction of beam.length), got " +
                                        format_number(model.deflection_limit));
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
    const TableSchema* schema = find_table_schema(first_segment);
    if (schema == nullptr || schema->is_free_form) {
      std::vector<std::string> candidates;
      for (const TableSchema& candidate : scene_schema()) {
        if (!candidate.is_free_form) candidates.push_back(candidate.name);
      }
      locator_.fail(&node, key,
                    "names no scene key: '" + first_segment + "' is not a scene table" +
                        did_you_mean(first_segment, candidates));
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
  read_beam(root, scene.beam);
  read_damping(root, scene.damping);
  read_deas(root, scene);
  read_drive(root, scene);
  read_loads(root, scene);
  read_probes(root, scene);
  read_ac(root, scene.ac);
  read_environment(root, scene.environment);
  read_model(root, scene);
  read_provenance(root, scene);
  return scene;
}

// ---------------------------------------------------------------------------------------------
// Overrides.

toml::table& SceneReader::table_for_override(toml::table& root, const std::string& table_name,
                                             const std::string& key) const {
  toml::node* node = root.get(table_name);
  if (node == nullptr) {
    root.insert(table_name, toml::table{});
    node = root.get(table_name);
  }
  toml::table* table = node->as_table();
  if (table == nullptr) {
    locator_.fail(node, table_name,
                  "must be a table, written [" + table_name + "] (needed by --set " + key + ")");
  }
  return *table;
}

void SceneReader::apply_override(toml::table& root, const std::string& assignment) const {
  const std::size_t equals = assignment.find('=');
  if (equals == std::string::npos) {
    throw InputError(kOverrideWhere, trim(assignment),
                     "expected key=value, e.g. beam.length=70mm, got '" + assignment + "'");
  }
  const std::string key = trim(assignment.substr(0, equals));
  const std::string text = trim(assignment.substr(equals + 1));
  if (key.empty()) {
    throw InputError(kOverrideWhere, "", "missing key before '=' in '" + assignment + "'");
  }

  // Candidates for "did you mean": every plain key.
  std::vector<std::string> candidates;
  for (const TableSchema& schema : scene_schema()) {
    for (const std::string& name : schema.keys) {
      candidates.push_back(schema.is_array_of_tables ? schema.name + ".<name>." + name
                                                     : schema.name + "." + name);
    }
  }
  auto unknown_key = [&](const std::vector<std::string>& extra_candidates) {
    std::vector<std::string> all = candidates;
    all.insert(all.end(), extra_candidates.begin(), extra_candidates.end());
    return InputError(kOverrideWhere, key, "unknown key" + did_you_mean(key, all));
  };

  const std::size_t split = key.find_first_of(".[");
  const std::string table_name = key.substr(0, split);
  const TableSchema* schema = find_table_schema(table_name);
  if (schema != nullptr && split == std::string::npos) {
    throw InputError(kOverrideWhere, key,
                     "names a table, not a key; override one of its keys, e.g. " +
                         (schema->keys.empty()         ? key + ".beam.length"
                          : schema->is_array_of_tables ? key + ".0." + schema->keys.front()
                                                       : key + "." + schema->keys.front()));
  }
  if (schema == nullptr || split == std::string::npos || split + 1 >= key.size()) {
    throw unknown_key({});
  }

  toml::table* target = nullptr;
  std::string target_key;
  if (schema->is_free_form) {
    if (key[split] != '.') throw unknown_key({});
    target = &table_for_override(root, table_name, key);
    target_key = key.substr(split + 1);
  } else if (!schema->is_array_of_tables) {
    target_key = key.substr(split + 1);
    if (key[split] != '.' || !schema_has_key(*schema, target_key)) throw unknown_key({});
    target = &table_for_override(root, table_name, key);
  } else {
    // dea.A.lever_arm, dea[A].lever_arm, dea.0.lever_arm or dea[0].lever_arm
    std::string selector;
    std::size_t after_selector = std::string::npos;
    if (key[split] == '[') {
      const std::size_t close = key.find(']', split);
      if (close != std::string::npos && close + 1 < key.size() && key[close + 1] == '.') {
        selector = key.substr(split + 1, close - split - 1);
        after_selector = close + 2;
      }
    } else {
      const std::size_t dot = key.find('.', split + 1);
      if (dot != std::string::npos) {
        selector = key.substr(split + 1, dot - split - 1);
        after_selector = dot + 1;
      }
    }
    if (selector.empty() || after_selector == std::string::npos) {
      throw InputError(kOverrideWhere, key,
                       "an entry of [[" + table_name + "]] is addressed as " + table_name +
                           ".<name or index>.<key>, e.g. " + table_name + ".0." +
                           schema->keys.front());
    }
    target_key = key.substr(after_selector);
    if (!schema_has_key(*schema, target_key)) {
      std::vector<std::string> extra;
      for (const std::string& name : schema->keys) {
        extra.push_back(key.substr(0, after_selector) + name);
      }
      throw unknown_key(extra);
    }
    toml::array* array = root.get_as<toml::array>(table_name);
    std::vector<std::string> names;
    if (array != nullptr) {
      for (toml::node& element : *array) {
        toml::table* entry = element.as_table();
        if (entry == nullptr) continue;
        if (const auto* name = entry->get_as<std::string>("name")) {
          names.push_back(name->get());
          if (name->get() == selector && target == nullptr) target = entry;
        }
      }
      if (target == nullptr && is_all_digits(selector) && selector.size() < 9) {
        const std::size_t index = std::stoul(selector);
        if (index < array->size()) target = (*array)[index].as_table();
      }
    }
    if (target == nullptr) {
      const std::size_t count = array == nullptr ? 0 : array->size();
      std::string known = "the scene has " + std::to_string(count) + " [[" + table_name +
                          "]] entr" + (count == 1 ? "y" : "ies");
      if (!names.empty()) known += " named " + quoted_list(names);
      throw InputError(kOverrideWhere, key,
                       "no [[" + table_name + "]] entry '" + selector + "'; " + known);
    }
  }

  // The value: a TOML value if it is one, else the text as a string. Text that the parser
  // cannot read safely (toml_input_guard.hpp: "70 µm" unquoted, say) is not TOML either.
  const std::string document = "value = " + text;
  if (find_toml_input_problem(document)) {
    target->insert_or_assign(target_key, text);
    return;
  }
  const TomlParseOutcome parsed = parse_toml(document, kOverrideWhere);
  if (parsed.table && parsed.table->size() == 1 && parsed.table->contains("value")) {
    parsed.table->get("value")->visit(
        [&](const auto& value_node) { target->insert_or_assign(target_key, value_node); });
  } else {
    target->insert_or_assign(target_key, text);
  }
}

}  // namespace

Scene read_scene_text(const std::string& text, const std::string& display_name,
                      const std::vector<std::string>& overrides) {
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
  const SceneReader reader(name);
  for (const std::string& assignment : overrides) reader.apply_override(*parsed.table, assignment);
  return reader.read(*parsed.table);
}

Scene read_scene(const std::string& path, const std::vector<std::string>& overrides) {
  return read_scene_text(read_scene_file(path), path, overrides);
}

std::string read_scene_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  const char* kind = nullptr;
  switch (status.type()) {
    case fs::file_type::not_found:
      throw InputError(path, "", "cannot open file");
    case fs::file_type::directory:
      throw InputError(path, "", "cannot open file (it is a directory)");
    case fs::file_type::character:
      kind = "a character device";
      break;
    case fs::file_type::block:
      kind = "a block device";
      break;
    case fs::file_type::fifo:
      kind = "a pipe";
      break;
    case fs::file_type::socket:
      kind = "a socket";
      break;
    default:
      break;
  }
  if (kind != nullptr) {
    throw InputError(
        path, "",
        std::string("not a regular file (") + kind + "); a scene is read from a " + "regular file");
  }
  const std::string limit = "a scene file may have at most " +
                            std::to_string(scene_limits::file_bytes) + " bytes (4 MiB)";
  const std::uintmax_t size = fs::file_size(path, error);
  if (!error && size > scene_limits::file_bytes) {
    throw InputError(path, "", "the file is " + std::to_string(size) + " bytes; " + limit);
  }
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw InputError(path, "", "cannot open file");
  // Read at most one byte past the limit, whatever the size said (the file may have grown).
  std::string contents;
  char buffer[65536];
  while (contents.size() <= scene_limits::file_bytes) {
    stream.read(buffer, sizeof buffer);
    contents.append(buffer, static_cast<std::size_t>(stream.gcount()));
    if (!stream) break;
  }
  if (stream.bad()) throw InputError(path, "", "cannot read file");
  if (contents.size() > scene_limits::file_bytes) {
    throw InputError(
        path, "",
        "the file is larger than " + std::to_string(scene_limits::file_bytes) + " bytes; " + limit);
  }
  return contents;
}

}  // namespace emnet
