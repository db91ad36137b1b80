// Dotted scene keys as --set and set_parameter take them: "beam.length", "dea.A.lever_arm",
// "dea[A].lever_arm", "dea.0.lever_arm", "provenance.beam.length". The split and its messages are
// shared by the reader's overrides (on the TOML tree) and set_parameter (on a Scene).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "emnet/scene/parameters.hpp"

namespace emnet {

struct ParameterKeyParts {
  const SceneTableInfo* table = nullptr;
  std::string selector;  // an array-of-tables entry's name or index; "" for a plain table
  std::string name;      // the key within its table (a free-form table: all after its name)
  std::string prefix;    // the key up to the name: "dea.A.", "dea[0]."
};

// Splits `key`; throws InputError(where, key, the reader's message) when it names a table, no
// table or no key of its table, or an entry without saying which.
ParameterKeyParts split_parameter_key(const std::string& key, const std::string& where);

// The entry `selector` names: the first entry of that name (names: one per entry, nullopt for an
// entry without one), else the index it spells (digits only, fewer than 9 of them).
std::optional<std::size_t> select_entry(const std::vector<std::optional<std::string>>& names,
                                        const std::string& selector);

// "no [[dea]] entry 'C'; the scene has 2 [[dea]] entries named 'A', 'B'"
std::string missing_entry_message(const std::string& table, const std::string& selector,
                                  std::size_t count,
                                  const std::vector<std::optional<std::string>>& names);

}  // namespace emnet
