// The scene's parameter table: every key a scene file may hold, in one place.
//
// Each entry says what a key is: its table and name ("beam.length", "dea[].lever_arm" for a key
// of every [[dea]] entry), its kind (a quantity with a unit, an integer, a choice, ...), its unit
// as the unit parser spells it (emnet/core/units.hpp), its allowed range and what the reader
// says when a value is outside it, its default (or that it is required), which drive kinds or
// components use it, and a one-line meaning. Numeric keys also carry an accessor that reads and
// writes their field of a Scene directly.
//
// The scene reader (src/scene/scene_reader.cpp) takes every key's unit, range and default from
// here, and checks `--set` keys against it; `emnet sensitivity` takes its parameters from it;
// set_parameter and get_parameter address a Scene's numeric fields by key without reading any
// TOML; `emnet schema` prints it.
//
// Keys are addressed as `--set` addresses them: "beam.length" for a plain table's key, and for an
// entry of an array of tables its name or index: "dea.A.lever_arm", "dea[A].lever_arm",
// "dea.0.lever_arm", "load.0.value". The canonical form, used in results, is "dea[A].lever_arm"
// (the entry's name where it has one, otherwise its index: "load[0].value").
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "emnet/core/units.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

enum class ParameterKind {
  quantity,   // a number, or a string "number unit" ("70 mm", "4 kV")
  integer,    // an integer (beam.segments also takes "auto")
  boolean,    // true or false (drive.electrical_dynamics also takes "auto")
  choice,     // one word of a list
  text,       // any string
  name,       // a name of letters, digits and '_' (it reaches SPICE decks)
  name_list,  // an array of names (drive.deas)
  band,       // model.band: one frequency, or [from, to]
  free_form,  // [provenance]: any dotted key naming a scene key
};
const char* parameter_kind_name(ParameterKind kind);  // "quantity", "integer", ...

// The interval a numeric value must lie in, and the reader's message for a value outside it.
struct ParameterRange {
  enum class Limit { none, inclusive, exclusive };
  Limit lower = Limit::none;
  double lower_value = 0.0;
  Limit upper = Limit::none;
  double upper_value = 0.0;
  // "must be > 0, got {}": "{}" stands for the value as the message shows it (a quantity with its
  // SI unit, an integer as it was written).
  std::string below_message;
  std::string above_message;

  bool bounded() const { return lower != Limit::none || upper != Limit::none; }
  bool contains(double value) const;  // false for NaN
  std::string text() const;           // "> 0", ">= 0", "(0, 1)", "[1, 100000]", "any"
};

// A table of a scene file: [beam], or an array of tables [[dea]].
struct SceneTableInfo {
  std::string name;
  bool entries = false;             // an array of tables: [[dea]], [[load]], [[probe]]
  bool free_form = false;           // [provenance]: any dotted key
  std::size_t maximum_entries = 0;  // scene_limits, for arrays of tables
  std::vector<std::string> keys;    // its keys, in the parameter table's order
  std::string meaning;
};

using ParameterGetter = std::function<std::optional<double>(const Scene&, std::size_t entry)>;
using ParameterSetter = std::function<void(Scene&, std::size_t entry, double value)>;
using ParameterText = std::function<std::string(const Scene&, std::size_t entry)>;

struct ParameterInfo {
  std::string table;        // "beam", "dea"
  std::string name;         // "length", "lever_arm"; "*" for [provenance]'s free-form keys
  bool in_entries = false;  // a key of each entry of an array of tables
  ParameterKind kind = ParameterKind::quantity;
  Dimension dimension;       // quantity and band keys: what the unit parser expects
  std::string unit_note;     // when the unit is not one: load[].value ("N, N*m for a moment")
  ParameterRange range;      // numeric keys; unbounded when none applies
  std::string constraint;    // what else bounds it, in words ("on the beam: 0 <= x <= beam.length")
  bool required = false;     // where it is used (a drive key by the kinds that use it)
  std::string default_note;  // when the default is not the value of a default Scene
  std::vector<std::string> choices;    // choice keys: the words it takes
  std::vector<DriveKind> drive_kinds;  // [drive] keys used by some kinds only (empty: every kind)
  std::string used_by;                 // "beam", "DEA", "drive kinds 'antagonistic', 'switched'"
  std::string meaning;                 // one line
  // A continuous parameter of the linearised network's matrices G, C and J_g, which `emnet
  // sensitivity` differentiates the poles by.
  bool sensitivity = false;
  // Numeric keys (quantity, integer): the field in a Scene (entry: the index of an array-of-tables
  // entry, 0 for a plain table). get gives nullopt for an optional field that is not set.
  ParameterGetter get;
  ParameterSetter set;
  // Every key: its value as a scene file writes it ("clamped", "auto", "0.1225 m").
  ParameterText text;

  std::string key() const;   // "beam.length", "dea[].lever_arm", "provenance.*"
  std::string unit() const;  // "m", "N*m^2", "" (dimensionless or not a quantity), or unit_note
  bool numeric() const { return static_cast<bool>(get); }
};

// Every key, grouped by table in the order of scene_tables(), each table's keys in the order its
// messages list them.
const std::vector<ParameterInfo>& parameter_table();
// The tables of a scene file, in order: scene, beam, damping, dea, drive, load, probe, ac,
// environment, model, provenance.
const std::vector<SceneTableInfo>& scene_tables();
const SceneTableInfo* find_scene_table(const std::string& name);
const ParameterInfo* find_parameter_info(const std::string& table, const std::string& name);
// The entry of a key the program itself names; throws std::logic_error when there is none (a
// programming error, not bad input).
const ParameterInfo& parameter_info(const std::string& table, const std::string& name);

// A key's default: its value in a default Scene (an entry key's in a default entry); nullopt for
// a required key, one that is unset by default, and one whose default depends on other keys
// (default_note says which: environment.density is the fluid's).
std::optional<double> parameter_default(const ParameterInfo& info);
// For listings: "required", "0 m", "clamped", "unset", or the entry's default_note.
std::string parameter_default_text(const ParameterInfo& info);
// For listings: the range and the constraint together ("> 0", "on the beam ...").
std::string parameter_range_text(const ParameterInfo& info);

// What the unit parser expects of a quantity key in `scene` (its entry `entry`): the entry's
// dimension, except load[].value, a moment (N*m) for a moment load and a force (N) otherwise.
Dimension parameter_dimension(const ParameterInfo& info, const Scene& scene, std::size_t entry);
// The SI unit of a quantity key in `scene` (its entry `entry`) as a scene file writes it:
// "N*m/rad" for a rotational spring's stiffness, "N*m*s/rad" for its damping, "N*m" for a moment
// load's value; "" for a dimensionless key and a key that is not a quantity.
std::string parameter_unit(const ParameterInfo& info, const Scene& scene, std::size_t entry);

// The value as the reader's messages show it: a quantity with its SI unit ("0.07 m"), an integer
// without a decimal point.
std::string shown_parameter_value(const ParameterInfo& info, double value,
                                  const Dimension& dimension);
// The reader's message for `value` (shown as `shown`) outside info.range; "" inside it.
std::string parameter_range_violation(const ParameterInfo& info, double value,
                                      const std::string& shown);

// "" when `scene` (its entry `entry`) uses the key; otherwise what the reader says when a file
// gives it anyway: a [drive] key the drive kind does not use, an [environment] key without a
// fluid, probe[].at of a DEA probe, damping.kelvin_voigt_time beside a loss factor, ...
std::string parameter_unused_reason(const ParameterInfo& info, const Scene& scene,
                                    std::size_t entry);

// Fluid properties at 20 °C and 101.325 kPa, the defaults of environment.density and
// environment.dynamic_viscosity (zero for Fluid::none).
struct FluidProperties {
  double density = 0.0;            // [kg/m³]
  double dynamic_viscosity = 0.0;  // [Pa·s]
};
FluidProperties fluid_properties(Fluid fluid);

// ---- numeric parameters of a Scene, by key ----------------------------------------------

// One key of one scene: the table entry and, for an array-of-tables key, the entry's index.
struct SceneParameterAddress {
  const ParameterInfo* info = nullptr;
  std::size_t entry = 0;
  std::string key;  // canonical: "beam.length", "dea[A].lever_arm", "load[0].value"
};

// The address of `key` (any form --set takes) in `scene`. Throws InputError(where, key, ...)
// with the reader's messages for an unknown key or entry.
SceneParameterAddress find_scene_parameter_address(const Scene& scene, const std::string& key,
                                                   const std::string& where);
// Whether `scene` can take a number for a key: usable, or why not (numeric_use).
enum class NumericUseCode {
  usable,       // a number the scene uses and has a value for
  not_numeric,  // a choice, text or list key
  unused,       // the scene does not use it (parameter_unused_reason)
  not_set,      // an optional key the scene leaves unset (no value to start from)
};
struct NumericUse {
  NumericUseCode code = NumericUseCode::usable;
  std::string reason;  // "" when usable, else as the reader says it ("is not set in scene 'x'")
  bool usable() const { return code == NumericUseCode::usable; }
};
/// Whether the key at `address` (found in `scene`) is a number that `scene` uses and sets, the
/// check get_parameter and set_parameter make, as a code and a reason instead of an exception.
NumericUse numeric_use(const Scene& scene, const SceneParameterAddress& address);

// Every numeric key of `scene` that the scene uses (parameter_unused_reason is ""), table by
// table in the table's order and entry by entry: "dea[A].…" before "dea[B].…".
std::vector<SceneParameterAddress> scene_numeric_parameters(const Scene& scene);

// The value [SI] of a numeric key. Throws InputError ("get_parameter", key, why) for an unknown
// key, a key that is not numeric, one the scene does not use, or an optional one not set.
double get_parameter(const Scene& scene, const std::string& key);
// Sets a numeric key to `value_si` [SI], directly in the Scene, after the checks the reader
// makes: the key's range, an integer for an integer key, a key the scene uses, and what the new
// value does to the keys that depend on it (positions on a shorter beam, the rise time within
// half a period, ac.to above ac.from). Throws InputError("set_parameter", key, the reader's
// message) and leaves the scene as it was. beam.segments clears "auto". Positions are not moved
// with beam.length (sensitivity's with_parameter stretches them).
void set_parameter(Scene& scene, const std::string& key, double value_si);

}  // namespace emnet
