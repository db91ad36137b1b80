// Control characters in outside text shown as escapes; see include/emnet/core/terminal_text.hpp.
#include "emnet/core/terminal_text.hpp"

#include <cstdio>

namespace emnet {

namespace {

std::string hex_byte(unsigned char byte) {
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "\\x%02X", byte);
  return buffer;
}

std::string code_point_escape(unsigned long code) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "\\u{%04lX}", code);
  return buffer;
}

// Length of the valid UTF-8 sequence starting at text[at] and its code point; 0 if invalid.
size_t utf8_sequence(std::string_view text, size_t at, unsigned long& code) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(at);
  size_t length = 0;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2, code = lead & 0x1F;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3, code = lead & 0x0F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4, code = lead & 0x07;
  } else {
    return 0;
  }
  if (at + length > text.size()) return 0;
  for (size_t k = 1; k < length; ++k) {
    if ((byte(at + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(at + k) & 0x3F);
  }
  // Overlong forms, surrogates and code points beyond U+10FFFF are not valid UTF-8.
  if ((length == 3 && code < 0x800) || (length == 4 && (code < 0x10000 || code > 0x10FFFF)) ||
      (code >= 0xD800 && code <= 0xDFFF))
    return 0;
  return length;
}

std::string escaped(std::string_view text, bool keep_newlines) {
  std::string shown;
  shown.reserve(text.size());
  for (size_t at = 0; at < text.size();) {
    const auto byte = static_cast<unsigned char>(text[at]);
    if (byte >= 0x20 && byte < 0x7F) {
      shown += text[at++];
      continue;
    }
    if (byte < 0x80) {  // C0 controls and DEL
      switch (byte) {
        case '\n':
          shown += keep_newlines ? "\n" : "\\n";
          break;
        case '\r':
          shown += "\\r";
          break;
        case '\t':
          shown += "\\t";
          break;
        case 0x1B:
          shown += "\\e";
          break;
        default:
          shown += hex_byte(byte);
      }
      ++at;
      continue;
    }
    unsigned long code = 0;
    const size_t length = utf8_sequence(text, at, code);
    if (length == 0) {
      shown += hex_byte(byte);
      ++at;
      continue;
    }
    const bool control = (code >= 0x80 && code <= 0x9F) || (code >= 0x202A && code <= 0x202E) ||
                         (code >= 0x2066 && code <= 0x2069);
    if (control) {
      shown += code_point_escape(code);
    } else {
      shown.append(text.substr(at, length));
    }
    at += length;
  }
  return shown;
}

}  // namespace

std::string terminal_text(std::string_view text) {
  return escaped(text, false);
}

std::string terminal_excerpt(std::string_view text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return terminal_text(text);
  return terminal_text(text.substr(0, max_bytes)) + " [... " +
         std::to_string(text.size() - max_bytes) + " more bytes]";
}

std::string terminal_lines(std::string_view text) {
  return escaped(text, true);
}

}  // namespace emnet
