// Text from outside the program (scene names and titles, probe and DEA names, file names,
// override values, ngspice's and gnuplot's messages) made safe to show on a terminal.
//
// Such text may hold control characters: an escape sequence (ESC [ ...) can move the cursor,
// rewrite earlier output or retitle the window, a carriage return or newline can forge a line of
// output. Each control character is shown as a visible escape instead: \n, \r, \t, \e (ESC),
// \xNN for the other C0 bytes and DEL, \u{NNNN} for the C1 controls (U+0080..U+009F, which some
// terminals also obey) and the bidirectional overrides and isolates (U+202A..U+202E,
// U+2066..U+2069, which reorder what is shown). A byte that is not part of valid UTF-8 is
// shown as \xNN. Everything else, the backslash and printable UTF-8 such as "µm" or "N·m²"
// included, is kept as it is, so ordinary text reads unchanged.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace emnet {

/// `text` on one line: every control character escaped, newlines included.
std::string terminal_text(std::string_view text);

/// terminal_text of the first `max_bytes` bytes of `text`, with " [... N more bytes]" when there
/// were more: for quoting a piece of untrusted input in a message.
std::string terminal_excerpt(std::string_view text, std::size_t max_bytes);

/// `text` keeping its line structure: newlines stay, every other control character is escaped.
/// For messages that are several lines by design (a tool's output tail).
std::string terminal_lines(std::string_view text);

}  // namespace emnet
