// Text from another program (ngspice's messages, the names in a rawfile) made safe to print on
// a terminal: every control character becomes a visible escape, so no escape sequence,
// carriage return, backspace or bell from that program reaches the user's terminal.
//
//   * C0 controls (bytes 0x00-0x1f) except tab, and DEL (0x7f): "\x1b", "\x0d", "\x7f";
//   * C1 controls written in UTF-8 (U+0080-U+009F; some terminals obey U+009B like "ESC ["):
//     "\u009b";
//   * bytes that are not part of well-formed UTF-8 (a terminal in an 8-bit mode reads
//     0x80-0x9f as C1 controls): "\xff".
//
// Tab and well-formed UTF-8 are kept as they are, and so is a backslash: the result contains
// no control character, so applying the function again changes nothing.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace emnet {

std::string printable_text(std::string_view text);

// printable_text of the first `max_bytes` bytes of `text`, with " [... N more bytes]" when
// there were more: for quoting a piece of untrusted input in a message.
std::string printable_excerpt(std::string_view text, std::size_t max_bytes);

}  // namespace emnet
