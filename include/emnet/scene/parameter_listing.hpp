// The parameter table (emnet/scene/parameters.hpp) as text for people: one row per key with its
// unit, default, range, users and meaning, as a wrapped plain-text table or a Markdown table
// (`emnet schema`, `emnet schema --markdown`).
#pragma once

#include <string>
#include <vector>

namespace emnet {

/// One key of the parameter table, as the listings show it.
struct ParameterListingRow {
  std::string key;           ///< "beam.length", "dea[].lever_arm", "provenance.*"
  std::string kind;          ///< parameter_kind_name
  std::string unit;          ///< "m", "" for dimensionless and non-quantities
  std::string default_text;  ///< parameter_default_text: "required", "0 m", "unset", ...
  std::string range;         ///< parameter_range_text: the range and the constraint
  std::string used_by;       ///< "beam", "DEA", "drive kinds 'antagonistic', 'switched'"
  std::string meaning;       ///< one line
  bool required = false;     ///< the scene must give it where it is used
  bool sensitivity = false;  ///< a parameter of `emnet sensitivity`
};

/// Every key of the table, in its order.
std::vector<ParameterListingRow> parameter_listing();
/// Columns key, unit, default, range, used by, meaning, each wrapped at word boundaries to a
/// fixed width; a blank line between the scene's tables.
std::string parameter_listing_text();
/// | key | unit | default | range | used by | meaning |, '|' in cells escaped.
std::string parameter_listing_markdown();

}  // namespace emnet
