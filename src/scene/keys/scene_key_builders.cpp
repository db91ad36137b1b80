// The builders the scene's key tables share (scene_key_tables.hpp): tables, ranges and entries.
#include "scene/scene_text.hpp"
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

ParameterInfo& SceneTableKeys::add(ParameterInfo info) {
  info.in_entries = table.entries;
  keys.push_back(std::move(info));
  return keys.back();
}

SceneTableKeys plain_table(const char* name, const char* meaning) {
  SceneTableKeys table;
  table.table.name = name;
  table.table.meaning = meaning;
  return table;
}

SceneTableKeys entries_table(const char* name, std::size_t maximum_entries, const char* meaning) {
  SceneTableKeys table = plain_table(name, meaning);
  table.table.entries = true;
  table.table.maximum_entries = maximum_entries;
  return table;
}

ParameterRange unbounded() {
  return {};
}

ParameterRange positive() {
  return {Limit::exclusive, 0.0, Limit::none, 0.0, "must be > 0, got {}", ""};
}

ParameterRange non_negative() {
  return {Limit::inclusive, 0.0, Limit::none, 0.0, "must be >= 0, got {}", ""};
}

ParameterRange interval(Limit lower, double lower_value, Limit upper, double upper_value,
                        const std::string& message) {
  return {lower, lower_value, upper, upper_value, message, message};
}

ParameterRange segment_count_range() {
  return {Limit::inclusive,       1.0,
          Limit::inclusive,       100000.0,
          "must be >= 1, got {}", "{} segments is absurdly large (at most 100000)"};
}

ParameterInfo key(const char* table, const char* name, ParameterKind kind, const char* used_by,
                  const char* meaning) {
  ParameterInfo info;
  info.table = table;
  info.name = name;
  info.kind = kind;
  info.used_by = used_by;
  info.meaning = meaning;
  return info;
}

ParameterInfo quantity(const char* table, const char* name, const Dimension& dimension,
                       ParameterRange range, bool required, const char* used_by,
                       const char* meaning) {
  ParameterInfo info = key(table, name, ParameterKind::quantity, used_by, meaning);
  info.dimension = dimension;
  info.range = std::move(range);
  info.required = required;
  return info;
}

ParameterInfo choice(const char* table, const char* name, std::vector<std::string> choices,
                     bool required, const char* used_by, const char* meaning) {
  ParameterInfo info = key(table, name, ParameterKind::choice, used_by, meaning);
  info.choices = std::move(choices);
  info.required = required;
  return info;
}

namespace {

std::string drive_kinds_text(const std::vector<DriveKind>& kinds) {
  if (kinds.empty()) return "every drive kind";
  std::vector<std::string> names;
  for (DriveKind kind : kinds) names.push_back(drive_kind_name(kind));
  return std::string("drive kind") + (names.size() == 1 ? " " : "s ") +
         scene_text::quoted_list(names);
}

}  // namespace

ParameterInfo used_by_kinds(ParameterInfo info, std::vector<DriveKind> kinds) {
  info.drive_kinds = std::move(kinds);
  info.used_by = drive_kinds_text(info.drive_kinds);
  return info;
}

std::string bool_text(bool value) {
  return value ? "true" : "false";
}

}  // namespace scene_keys
}  // namespace emnet
