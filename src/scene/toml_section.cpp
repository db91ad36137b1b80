// Reading the values of one TOML table of a scene; see toml_section.hpp.
#include "toml_section.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "emnet/scene/scene_reader.hpp"
#include "parameter_relations.hpp"
#include "scene_text.hpp"

namespace emnet {

using scene_text::did_you_mean;
using scene_text::format_number;
using scene_text::is_identifier;
using scene_text::quoted_list;

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

std::string Locator::where(const toml::node* node) const {
  if (node == nullptr) return display_name_;
  const toml::source_region& source = node->source();
  if (source.path && *source.path == display_name_ && source.begin.line > 0) {
    return display_name_ + ":" + std::to_string(source.begin.line);
  }
  return kOverrideWhere;
}

void Section::reject_unknown_keys(const std::vector<std::string>& allowed) const {
  if (table_ == nullptr) return;
  for (auto&& [table_key, node] : *table_) {
    const std::string name(table_key.str());
    if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) continue;
    std::vector<std::string> candidates;
    for (const std::string& candidate : allowed) candidates.push_back(key(candidate));
    locator_.fail(&node, key(name), "unknown key" + did_you_mean(key(name), candidates));
  }
}

double Section::node_quantity(const toml::node& node, const std::string& name,
                              const Dimension& dimension, const std::string& what) const {
  const std::string subject = what.empty() ? "" : what + " ";
  double value = 0.0;
  if (const auto* integer = node.as_integer()) {
    value = static_cast<double>(integer->get());
  } else if (const auto* floating = node.as_floating_point()) {
    value = floating->get();
    if (!std::isfinite(value)) fail(name, subject + "must be finite, got " + format_number(value));
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
  if (const std::string subnormal = subnormal_violation(value, dimension); !subnormal.empty())
    fail(name, subject + subnormal);
  return value;
}

std::optional<double> Section::optional_quantity(const ParameterInfo& info,
                                                 bool check_range_now) const {
  return optional_quantity(info, info.dimension, check_range_now);
}

std::optional<double> Section::optional_quantity(const ParameterInfo& info,
                                                 const Dimension& dimension,
                                                 bool check_range_now) const {
  const toml::node* node = find(info.name);
  if (node == nullptr) return std::nullopt;
  const double value = node_quantity(*node, info.name, dimension);
  if (check_range_now) {
    const std::string outside =
        parameter_range_violation(info, value, shown_parameter_value(info, value, dimension));
    if (!outside.empty()) fail(info.name, outside);
  }
  return value;
}

double Section::quantity(const ParameterInfo& info) const {
  return quantity(info, info.dimension);
}

double Section::quantity(const ParameterInfo& info, const Dimension& dimension) const {
  const std::optional<double> value = optional_quantity(info, dimension);
  if (value) return *value;
  if (info.required) fail_missing(info.name);
  const std::optional<double> default_value = parameter_default(info);
  if (!default_value) throw std::logic_error(info.key() + " has no plain default");
  return *default_value;
}

void Section::check_range(const ParameterInfo& info, double value) const {
  const std::string outside =
      parameter_range_violation(info, value, shown_parameter_value(info, value, info.dimension));
  if (!outside.empty()) fail(info.name, outside);
}

std::optional<long long> Section::optional_integer(const std::string& name) const {
  const toml::node* node = find(name);
  if (node == nullptr) return std::nullopt;
  const auto* integer = node->as_integer();
  if (integer == nullptr) fail(name, "must be an integer, got " + describe_node(*node));
  return static_cast<long long>(integer->get());
}

std::optional<long long> Section::optional_integer(const ParameterInfo& info) const {
  const std::optional<long long> value = optional_integer(info.name);
  if (value) check_integer_range(info, *value);
  return value;
}

void Section::check_integer_range(const ParameterInfo& info, long long value) const {
  const std::string outside =
      parameter_range_violation(info, static_cast<double>(value), std::to_string(value));
  if (!outside.empty()) fail(info.name, outside);
}

std::optional<std::string> Section::optional_string(const std::string& name) const {
  const toml::node* node = find(name);
  if (node == nullptr) return std::nullopt;
  const auto* text = node->as_string();
  if (text == nullptr) fail(name, "must be a string, got " + describe_node(*node));
  return text->get();
}

std::string Section::string(const std::string& name) const {
  const std::optional<std::string> text = optional_string(name);
  if (!text) fail_missing(name);
  return *text;
}

std::string Section::identifier(const std::string& name) const {
  const std::string text = string(name);
  if (!is_identifier(text)) {
    fail(name,
         "must be a non-empty name of letters, digits and '_' only (names are used in "
         "SPICE decks), got '" +
             text + "'");
  }
  if (text.size() > scene_limits::name_bytes) {
    fail(name, "is " + std::to_string(text.size()) + " characters long; a name may have at most " +
                   std::to_string(scene_limits::name_bytes));
  }
  return text;
}

std::optional<bool> Section::optional_boolean(const std::string& name) const {
  const toml::node* node = find(name);
  if (node == nullptr) return std::nullopt;
  const auto* boolean = node->as_boolean();
  if (boolean == nullptr) fail(name, "must be true or false, got " + describe_node(*node));
  return boolean->get();
}

std::size_t Section::choice_index(const ParameterInfo& info, const std::string& text) const {
  for (std::size_t index = 0; index < info.choices.size(); ++index)
    if (info.choices[index] == text) return index;
  fail(info.name, "must be one of " + quoted_list(info.choices) + ", got '" + text + "'" +
                      did_you_mean(text, info.choices));
}

double Section::position_on_beam(const ParameterInfo& info, double beam_length) const {
  const std::optional<double> position = optional_quantity(info);
  if (!position) fail_missing(info.name);
  const std::string off_the_beam = beam_position_violation(*position, beam_length);
  if (!off_the_beam.empty()) fail(info.name, off_the_beam);
  return std::clamp(*position, 0.0, beam_length);
}

void Section::reject_if_unused(const ParameterInfo& info, const Scene& scene,
                               std::size_t entry) const {
  if (!has(info.name)) return;
  const std::string reason = parameter_unused_reason(info, scene, entry);
  if (!reason.empty()) fail(info.name, reason);
}

}  // namespace emnet
