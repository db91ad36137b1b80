// `--set key=value` overrides, written into a scene's TOML tree before the reader walks it, so
// that a value from an override is checked exactly like one from the file.
#pragma once

#include <toml++/toml.h>

#include <string>

#include "toml_section.hpp"

namespace emnet {

// Writes one "dotted.key=value" into `root`: the key is checked against the parameter table
// (an unknown key, a table, an entry of [[dea]] that does not exist are InputErrors whose where
// is "override"); the value is a TOML value if it parses as one (0.2, true, "70 mm", ["A", "B"])
// and the text as a string otherwise (70mm, 70 mm, log). `locator` names the scene in messages.
void apply_override(toml::table& root, const std::string& assignment, const Locator& locator);

}  // namespace emnet
