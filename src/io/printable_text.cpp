// Control characters made visible; see printable_text.hpp.
#include "printable_text.hpp"

#include <cstdint>
#include <cstdio>

namespace emnet {

namespace {

void append_escape(std::string& text, const char* format, unsigned value) {
  char escape[8];
  std::snprintf(escape, sizeof escape, format, value);
  text += escape;
}

// The length of the well-formed UTF-8 sequence (RFC 3629: no overlong forms, no surrogates,
// at most U+10FFFF) that starts at `at`, 0 when there is none.
std::size_t utf8_sequence_length(std::string_view text, std::size_t at) {
  const auto byte = [&](std::size_t k) { return static_cast<std::uint8_t>(text[at + k]); };
  const auto continuation = [&](std::size_t k, std::uint8_t low = 0x80, std::uint8_t high = 0xbf) {
    return at + k < text.size() && byte(k) >= low && byte(k) <= high;
  };
  const std::uint8_t lead = byte(0);
  if (lead >= 0xc2 && lead <= 0xdf) return continuation(1) ? 2 : 0;
  if (lead >= 0xe0 && lead <= 0xef) {
    const std::uint8_t low = lead == 0xe0 ? 0xa0 : 0x80, high = lead == 0xed ? 0x9f : 0xbf;
    return continuation(1, low, high) && continuation(2) ? 3 : 0;
  }
  if (lead >= 0xf0 && lead <= 0xf4) {
    const std::uint8_t low = lead == 0xf0 ? 0x90 : 0x80, high = lead == 0xf4 ? 0x8f : 0xbf;
    return continuation(1, low, high) && continuation(2) && continuation(3) ? 4 : 0;
  }
  return 0;
}

}  // namespace

std::string printable_text(std::string_view text) {
  std::string printable;
  printable.reserve(text.size());
  for (std::size_t at = 0; at < text.size();) {
    const auto byte = static_cast<std::uint8_t>(text[at]);
    if (byte < 0x80) {
      if ((byte < 0x20 && byte != '\t') || byte == 0x7f)
        append_escape(printable, "\\x%02x", byte);
      else
        printable += static_cast<char>(byte);
      ++at;
      continue;
    }
    const std::size_t length = utf8_sequence_length(text, at);
    if (length == 0) {
      append_escape(printable, "\\x%02x", byte);
      ++at;
    } else if (length == 2 && byte == 0xc2 && static_cast<std::uint8_t>(text[at + 1]) <= 0x9f) {
      append_escape(printable, "\\u%04x", static_cast<std::uint8_t>(text[at + 1]));
      at += 2;
    } else {
      printable.append(text.substr(at, length));
      at += length;
    }
  }
  return printable;
}

std::string printable_excerpt(std::string_view text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return printable_text(text);
  return printable_text(text.substr(0, max_bytes)) + " [... " +
         std::to_string(text.size() - max_bytes) + " more bytes]";
}

}  // namespace emnet
