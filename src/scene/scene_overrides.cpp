// `--set key=value` overrides into the scene's TOML tree; see scene_overrides.hpp.
#include "scene_overrides.hpp"

#include <optional>

#include "parameter_keys.hpp"
#include "scene_text.hpp"
#include "toml_input_guard.hpp"

namespace emnet {

namespace {

toml::table& table_for_override(toml::table& root, const std::string& table_name,
                                const std::string& key, const Locator& locator) {
  toml::node* node = root.get(table_name);
  if (node == nullptr) {
    root.insert(table_name, toml::table{});
    node = root.get(table_name);
  }
  toml::table* table = node->as_table();
  if (table == nullptr) {
    locator.fail(
        node, table_name,
        "must be a table, written [" + table_name + "] (needed by the override of " + key + ")");
  }
  return *table;
}

}  // namespace

void apply_override(toml::table& root, const std::string& assignment, const Locator& locator) {
  const std::size_t equals = assignment.find('=');
  if (equals == std::string::npos) {
    throw InputError(kOverrideWhere, scene_text::trim(assignment),
                     "expected key=value, e.g. beam.length=70mm, got '" + assignment + "'");
  }
  const std::string key = scene_text::trim(assignment.substr(0, equals));
  const std::string text = scene_text::trim(assignment.substr(equals + 1));
  if (key.empty()) {
    throw InputError(kOverrideWhere, "", "missing key before '=' in '" + assignment + "'");
  }

  const ParameterKeyParts parts = split_parameter_key(key, kOverrideWhere);
  const std::string& table_name = parts.table->name;
  toml::table* target = nullptr;
  if (!parts.table->entries) {
    target = &table_for_override(root, table_name, key, locator);
  } else {
    toml::array* array = root.get_as<toml::array>(table_name);
    std::vector<std::optional<std::string>> names;
    if (array != nullptr) {
      for (toml::node& element : *array) {
        const toml::table* entry = element.as_table();
        const auto* name = entry == nullptr ? nullptr : entry->get_as<std::string>("name");
        names.push_back(name == nullptr ? std::nullopt : std::optional<std::string>(name->get()));
      }
      if (const std::optional<std::size_t> index = select_entry(names, parts.selector))
        target = (*array)[*index].as_table();
    }
    if (target == nullptr) {
      throw InputError(kOverrideWhere, key,
                       missing_entry_message(table_name, parts.selector, names.size(), names));
    }
  }

  // The value: a TOML value if it is one, else the text as a string. Text that the parser
  // cannot read safely (toml_input_guard.hpp: "70 µm" unquoted, say) is not TOML either.
  const std::string& target_key = parts.name;
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

}  // namespace emnet
