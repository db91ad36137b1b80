// Lookups, ranges, defaults and listing text of the scene's parameter table
// (emnet/scene/parameters.hpp); the table itself is in src/scene/keys/, one file per component.
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "emnet/scene/parameters.hpp"
#include "scene_text.hpp"

namespace emnet {

using Limit = ParameterRange::Limit;

const char* parameter_kind_name(ParameterKind kind) {
  switch (kind) {
    case ParameterKind::quantity:
      return "quantity";
    case ParameterKind::integer:
      return "integer";
    case ParameterKind::boolean:
      return "boolean";
    case ParameterKind::choice:
      return "choice";
    case ParameterKind::text:
      return "text";
    case ParameterKind::name:
      return "name";
    case ParameterKind::name_list:
      return "name list";
    case ParameterKind::band:
      return "band";
    case ParameterKind::free_form:
      return "free form";
  }
  return "?";
}

const SceneTableInfo* find_scene_table(const std::string& name) {
  for (const SceneTableInfo& table : scene_tables())
    if (table.name == name) return &table;
  return nullptr;
}

const ParameterInfo* find_parameter_info(const std::string& table, const std::string& name) {
  for (const ParameterInfo& info : parameter_table())
    if (info.table == table && info.name == name) return &info;
  return nullptr;
}

const ParameterInfo& parameter_info(const std::string& table, const std::string& name) {
  if (const ParameterInfo* info = find_parameter_info(table, name)) return *info;
  throw std::logic_error("the parameter table has no key " + table + "." + name);
}

std::string ParameterInfo::key() const {
  return table + (in_entries ? "[]." : ".") + name;
}

std::string ParameterInfo::unit() const {
  if (!unit_note.empty()) return unit_note;
  if (kind != ParameterKind::quantity && kind != ParameterKind::band) return "";
  return si_unit_symbol(dimension);
}

bool ParameterRange::contains(double value) const {
  if (std::isnan(value)) return false;
  if (lower == Limit::inclusive && !(value >= lower_value)) return false;
  if (lower == Limit::exclusive && !(value > lower_value)) return false;
  if (upper == Limit::inclusive && !(value <= upper_value)) return false;
  if (upper == Limit::exclusive && !(value < upper_value)) return false;
  return true;
}

std::string ParameterRange::text() const {
  const std::string low = scene_text::format_number(lower_value);
  const std::string high = scene_text::format_number(upper_value);
  if (lower == Limit::none && upper == Limit::none) return "any";
  if (upper == Limit::none) return (lower == Limit::inclusive ? ">= " : "> ") + low;
  if (lower == Limit::none) return (upper == Limit::inclusive ? "<= " : "< ") + high;
  return (lower == Limit::inclusive ? "[" : "(") + low + ", " + high +
         (upper == Limit::inclusive ? "]" : ")");
}

namespace {

// A default Scene with one default entry in every array of tables, for entry keys' defaults.
const Scene& default_scene() {
  static const Scene scene = [] {
    Scene defaults;
    defaults.deas.resize(1);
    defaults.loads.resize(1);
    defaults.probes.resize(1);
    defaults.circuit.resize(1);
    defaults.beam.sections.resize(1);
    defaults.beam.masses.resize(1);
    defaults.beam.springs.resize(1);
    return defaults;
  }();
  return scene;
}

}  // namespace

std::optional<double> parameter_default(const ParameterInfo& info) {
  if (info.required || !info.numeric() || !info.default_note.empty()) return std::nullopt;
  return info.get(default_scene(), 0);
}

std::string parameter_default_text(const ParameterInfo& info) {
  if (!info.default_note.empty()) return info.default_note;
  if (info.required) return "required";
  if (info.numeric()) {
    const std::optional<double> value = parameter_default(info);
    if (!value) return "unset";
    return shown_parameter_value(info, *value, info.dimension);
  }
  if (info.text) {
    const std::string text = info.text(default_scene(), 0);
    return text.empty() ? "\"\"" : text;
  }
  return "";
}

std::string parameter_range_text(const ParameterInfo& info) {
  std::string text;
  if (!info.choices.empty()) {
    for (const std::string& choice : info.choices) text += (text.empty() ? "" : " | ") + choice;
  } else if (info.range.bounded()) {
    text = info.range.text();
  }
  if (!info.constraint.empty()) text += (text.empty() ? "" : "; ") + info.constraint;
  return text.empty() ? "any" : text;
}

std::string shown_parameter_value(const ParameterInfo& info, double value,
                                  const Dimension& dimension) {
  if (info.kind == ParameterKind::integer) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.0f", value);
    return buffer;
  }
  return format_quantity(value, dimension);
}

std::string parameter_range_violation(const ParameterInfo& info, double value,
                                      const std::string& shown) {
  const ParameterRange& range = info.range;
  if (range.contains(value)) return "";
  const bool below = std::isnan(value) ||
                     (range.lower == Limit::inclusive && !(value >= range.lower_value)) ||
                     (range.lower == Limit::exclusive && !(value > range.lower_value));
  std::string message = below ? range.below_message : range.above_message;
  const std::size_t slot = message.find("{}");
  if (slot != std::string::npos) message.replace(slot, 2, shown);
  return message;
}

}  // namespace emnet
