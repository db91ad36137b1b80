// A scan of TOML text before toml++ parses it: refuses what the parser cannot take safely, so
// that reading a scene never crashes, never reaches undefined behaviour and stays bounded in
// time and memory whatever the bytes are.
//
// What toml++ 3.3 (the Debian package) does with such input, and what the scan refuses for it:
//   - Deeply nested documents overflow the stack: the parser and the tree's destructor recurse
//     once per level, so a header of 50 000 dotted parts crashes. Refused: a nesting depth
//     (header parts + key parts + open arrays and inline tables) above
//     scene_limits::nesting_depth.
//   - Many tables are quadratic: each dotted key and each table header searches lists of all
//     implicitly created tables and arrays of tables linearly (100 000 dotted keys: 10 s).
//     Refused: more than scene_limits::tables_and_dotted_keys headers and dotted keys together.
//   - is_non_ascii_horizontal_whitespace() reaches __builtin_unreachable for most code points in
//     U+00A1..U+0499, U+2C5E..U+3057 and U+FB26..U+FEFE, and the parser asks it about every
//     character outside strings (a number, boolean or date up to its terminator, whatever
//     quotes it holds), and in multi-line basic strings about the character after a backslash
//     and the first one after a line-ending backslash. Refused: any non-ASCII character in
//     those places (none of them is valid TOML there, except the last one).
//   - parse_key() assumes (an assertion; with clang in Release, an optimiser hint) that a table
//     header starts with a key character or a quote; "[=]" breaks that. Refused: a header or a
//     key after '.' that does not start with one. parse_date_time() assumes a digit after a
//     date's 'T': "1979-05-27T:07" breaks that. Refused: a date-time without one.
//     parse_value() assumes that a value does not start with a terminator; in an array "[}"
//     breaks that. Refused: '}' where an array element belongs. Its scan of "YYYY-MM-DD H"
//     assumes that no terminator follows the H: "1979-05-27 3#" breaks that. Refused.
// It also refuses invalid UTF-8, control characters other than tab, line feed and carriage
// return, lines longer than scene_limits::line_bytes and keys longer than
// scene_limits::key_bytes, and text longer than scene_limits::file_bytes. Everything it
// refuses is invalid TOML or over a limit, except a non-ASCII character right after a
// line-ending backslash in a multi-line basic string.
//
// The scan follows TOML's lexical structure (strings, comments, keys, values, brackets) exactly
// for valid TOML; on invalid TOML it may refuse where toml++ would report another error, but
// must not let through what toml++ would read unsafely before its own first error: fuzz_scene
// (tests/fuzz) checks that with toml++'s assertions and the sanitizers on.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace emnet {

struct TomlInputProblem {
  std::size_t line = 0;  // 1-based; 0 for the text as a whole (its size)
  std::string message;   // "not a valid TOML file: ..." or what limit is exceeded
};

// The first problem of `text`, or nothing when toml++ may parse it.
std::optional<TomlInputProblem> find_toml_input_problem(std::string_view text);

}  // namespace emnet
