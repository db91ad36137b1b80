// Reading the values of one TOML table of a scene: the types, units and ranges of its keys
// (from the parameter table, emnet/scene/parameters.hpp), and every problem as an InputError that
// names the file and line (or "override" for a value an override wrote), the dotted key and what
// was expected.
#pragma once

#include <toml++/toml.h>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "emnet/core/errors.hpp"
#include "emnet/core/units.hpp"
#include "emnet/scene/parameters.hpp"

namespace emnet {

inline constexpr const char* kOverrideWhere = "override";

// "a string ('abc')", "an integer (3)", "a table": what a node is, for "got ..." messages.
std::string describe_node(const toml::node& node);

// TOML parsing that works whether toml++ reports errors by exception or by result.
struct TomlParseOutcome {
  std::optional<toml::table> table;
  std::string description;
  std::size_t line = 0;
};
TomlParseOutcome parse_toml(std::string_view text, std::string_view source_path);

class Locator {
 public:
  explicit Locator(std::string display_name) : display_name_(std::move(display_name)) {}

  const std::string& display_name() const { return display_name_; }

  // "file:line" for a node read from the file, "override" for one written by an override, "file"
  // when there is no node (a missing key).
  std::string where(const toml::node* node) const;

  [[noreturn]] void fail(const toml::node* node, const std::string& key,
                         const std::string& message) const {
    throw InputError(where(node), key, message);
  }

 private:
  std::string display_name_;
};

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

  void reject_unknown_keys(const std::vector<std::string>& allowed) const;

  // `node` (the value of key `name`, or an element of it that `what` names: "the upper end") as
  // a quantity of `dimension`: a number, or a string "number unit".
  double node_quantity(const toml::node& node, const std::string& name, const Dimension& dimension,
                       const std::string& what = "") const;

  // A quantity key of the parameter table, in `dimension` (parameter_dimension; the entry's
  // own by default), its range checked when `check_range`; nullopt when absent.
  std::optional<double> optional_quantity(const ParameterInfo& info, bool check_range = true) const;
  std::optional<double> optional_quantity(const ParameterInfo& info, const Dimension& dimension,
                                          bool check_range = true) const;
  // The same, and when absent: "missing (required)" for a required key, else its default (a key
  // without a plain default, such as environment.density, is read with optional_quantity).
  double quantity(const ParameterInfo& info) const;
  double quantity(const ParameterInfo& info, const Dimension& dimension) const;
  // The table's range of `info` for a value read earlier (a check the reader makes later).
  void check_range(const ParameterInfo& info, double value) const;
  // An integer key, its range checked (the value shown as it was written).
  std::optional<long long> optional_integer(const ParameterInfo& info) const;
  void check_integer_range(const ParameterInfo& info, long long value) const;

  std::optional<long long> optional_integer(const std::string& name) const;
  std::optional<std::string> optional_string(const std::string& name) const;
  std::string string(const std::string& name) const;
  // A name that reaches SPICE decks: letters, digits and '_', at most scene_limits::name_bytes.
  std::string identifier(const std::string& name) const;
  std::optional<bool> optional_boolean(const std::string& name) const;

  // A choice key of the parameter table: one of info.choices, mapped to `values` (in the same
  // order); nullopt when absent.
  template <typename Enum>
  std::optional<Enum> optional_choice(const ParameterInfo& info,
                                      const std::vector<Enum>& values) const {
    const std::optional<std::string> text = optional_string(info.name);
    if (!text) return std::nullopt;
    const std::size_t index = choice_index(info, *text);
    return values[index];
  }
  template <typename Enum>
  Enum choice(const ParameterInfo& info, const std::vector<Enum>& values) const {
    const std::optional<Enum> value = optional_choice(info, values);
    if (!value) fail_missing(info.name);
    return *value;
  }

  // A position along the beam, 0 <= x <= L (values a hair outside are snapped to the end).
  double position_on_beam(const ParameterInfo& info, double beam_length) const;

  // Fails with parameter_unused_reason's message when the key is given but the scene (its entry
  // `entry`) cannot take it.
  void reject_if_unused(const ParameterInfo& info, const Scene& scene, std::size_t entry) const;

 private:
  // The index of `text` in info.choices; fails with the list (and "did you mean") otherwise.
  std::size_t choice_index(const ParameterInfo& info, const std::string& text) const;

  const Locator& locator_;
  const toml::table* table_;
  std::string prefix_;
};

}  // namespace emnet
