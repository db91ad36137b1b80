// The scene's parameter table (emnet/scene/parameters.hpp), one table of a scene file at a time:
// each *_table_keys() function below gives one table and its keys, in the order the reader's
// messages list them, and lives in the file of the component it describes (beam_keys.cpp,
// dea_keys.cpp, ...). src/scene/parameters.cpp lists them in the order of scene_tables().
//
// Defaults are not written here: a key's default is its field's value in a default-constructed
// Scene (emnet/scene/scene.hpp), read through the entry's accessor, so that the Scene type and the
// table cannot disagree. Entries whose default depends on other keys (the fluid's density) say so
// in default_note.
//
// The builders shared by the tables: ranges with the reader's messages, the entry constructors,
// and accessors that read and write a key's field of a Scene.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"  // scene_limits

namespace emnet {
namespace scene_keys {

using Limit = ParameterRange::Limit;

// ---- a table and its keys ---------------------------------------------------------------

// One table of a scene file and its keys in order. add() appends a key (marked as a key of each
// entry when the table is an array of tables) and gives it back to be finished.
struct SceneTableKeys {
  SceneTableInfo table;
  std::vector<ParameterInfo> keys;

  ParameterInfo& add(ParameterInfo info);
  ParameterInfo& back() { return keys.back(); }
};

// A plain table: [beam].
SceneTableKeys plain_table(const char* name, const char* meaning);
// An array of tables of at most `maximum_entries` entries: [[dea]].
SceneTableKeys entries_table(const char* name, std::size_t maximum_entries, const char* meaning);

// The constraint of an entry's name key (dea[].name, mass[].name, ...), which the reader checks.
inline constexpr const char* kEntryNameConstraint =
    "letters, digits and '_', at most 64 characters, unique";

// ---- ranges, with the reader's messages -------------------------------------------------

ParameterRange unbounded();
ParameterRange positive();      // "must be > 0, got {}"
ParameterRange non_negative();  // "must be >= 0, got {}"
// Both limits with one message for a value outside either.
ParameterRange interval(Limit lower, double lower_value, Limit upper, double upper_value,
                        const std::string& message);
// beam.segments, section[].segments: [1, 100000].
ParameterRange segment_count_range();

// ---- entries ----------------------------------------------------------------------------

// A key of `table` (its name, "beam") of `kind`, used by `used_by` (a component, "DEA").
ParameterInfo key(const char* table, const char* name, ParameterKind kind, const char* used_by,
                  const char* meaning);
// A quantity key: a number in the unit of `dimension` within `range`.
ParameterInfo quantity(const char* table, const char* name, const Dimension& dimension,
                       ParameterRange range, bool required, const char* used_by,
                       const char* meaning);
// A choice key: one word of `choices`.
ParameterInfo choice(const char* table, const char* name, std::vector<std::string> choices,
                     bool required, const char* used_by, const char* meaning);
// A [drive] key used by the drive kinds `kinds` only; its used_by names them.
ParameterInfo used_by_kinds(ParameterInfo info, std::vector<DriveKind> kinds);

// "true", "false": how a scene file writes a boolean.
std::string bool_text(bool value);

// ---- accessors --------------------------------------------------------------------------

// A field of a plain table (beam.length: &Scene::beam, &BeamSpec::length).
template <typename Spec>
void plain_field(ParameterInfo& info, Spec Scene::*table, double Spec::*member) {
  info.get = [table, member](const Scene& scene, std::size_t) -> std::optional<double> {
    return scene.*table.*member;
  };
  info.set = [table, member](Scene& scene, std::size_t, double value) {
    (scene.*table).*member = value;
  };
}

// An optional field of a plain table: nullopt while it is unset.
template <typename Spec>
void plain_field(ParameterInfo& info, Spec Scene::*table, std::optional<double> Spec::*member) {
  info.get = [table, member](const Scene& scene, std::size_t) { return scene.*table.*member; };
  info.set = [table, member](Scene& scene, std::size_t, double value) {
    (scene.*table).*member = value;
  };
}

// A field of each entry of an array of tables held in the Scene (dea[].lever_arm).
template <typename Spec>
void entry_field(ParameterInfo& info, std::vector<Spec> Scene::*entries, double Spec::*member) {
  info.get = [entries, member](const Scene& scene, std::size_t entry) -> std::optional<double> {
    return (scene.*entries)[entry].*member;
  };
  info.set = [entries, member](Scene& scene, std::size_t entry, double value) {
    (scene.*entries)[entry].*member = value;
  };
}

// A field of the beam's [[section]], [[mass]] or [[spring]] entries (held in BeamSpec).
template <typename Spec, typename Field>
void beam_entry_field(ParameterInfo& info, std::vector<Spec> BeamSpec::*entries,
                      Field Spec::*member) {
  info.get = [entries, member](const Scene& scene, std::size_t entry) -> std::optional<double> {
    return (scene.beam.*entries)[entry].*member;
  };
  info.set = [entries, member](Scene& scene, std::size_t entry, double value) {
    (scene.beam.*entries)[entry].*member = value;
  };
}

// ---- the tables, in the order of scene_tables() -----------------------------------------

SceneTableKeys scene_table_keys();        // [scene]          document_keys.cpp
SceneTableKeys beam_table_keys();         // [beam]           beam_keys.cpp
SceneTableKeys section_table_keys();      // [[section]]      beam_keys.cpp
SceneTableKeys mass_table_keys();         // [[mass]]         mass_keys.cpp
SceneTableKeys spring_table_keys();       // [[spring]]       spring_keys.cpp
SceneTableKeys damping_table_keys();      // [damping]        beam_keys.cpp
SceneTableKeys dea_table_keys();          // [[dea]]          dea_keys.cpp
SceneTableKeys drive_table_keys();        // [drive]          drive_keys.cpp
SceneTableKeys load_table_keys();         // [[load]]         load_keys.cpp
SceneTableKeys probe_table_keys();        // [[probe]]        probe_keys.cpp
SceneTableKeys circuit_table_keys();      // [[circuit]]      circuit_keys.cpp
SceneTableKeys ac_table_keys();           // [ac]             settings_keys.cpp
SceneTableKeys environment_table_keys();  // [environment]    environment_keys.cpp
SceneTableKeys model_table_keys();        // [model]          settings_keys.cpp
SceneTableKeys provenance_table_keys();   // [provenance]     document_keys.cpp

}  // namespace scene_keys
}  // namespace emnet
