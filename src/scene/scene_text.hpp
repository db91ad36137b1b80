// Small text helpers of the scene layer's messages: trimming, "did you mean", quoted lists, the
// name rule of scene names, and the reader's number format.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace emnet {
namespace scene_text {

std::string trim(const std::string& text);

// Optimal-string-alignment edit distance (a transposition counts as one edit).
std::size_t edit_distance(const std::string& first, const std::string& second);

// " (did you mean 'beam.length'?)" for the closest candidate within a few edits, else "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates);

// "'a', 'b', 'c'"
std::string quoted_list(const std::vector<std::string>& words);

// A name that reaches SPICE decks: letters, digits and '_', not empty.
bool is_identifier(const std::string& name);
bool is_all_digits(const std::string& text);

// "%.10g": how the reader's messages print a plain number.
std::string format_number(double value);

}  // namespace scene_text
}  // namespace emnet
