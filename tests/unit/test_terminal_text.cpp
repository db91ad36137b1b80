// Text from outside shown on a terminal: every control character becomes a visible escape,
// printable text (ASCII and UTF-8) is unchanged. Reference: the escapes the header documents.
#include <gtest/gtest.h>

#include "emnet/core/terminal_text.hpp"

namespace {

using emnet::terminal_lines;
using emnet::terminal_text;

TEST(TerminalText, PrintableTextIsUnchanged) {
  EXPECT_EQ(terminal_text("fish fin (P4 = 70 mm), \\ and 'quotes'"),
            "fish fin (P4 = 70 mm), \\ and 'quotes'");
  EXPECT_EQ(terminal_text("51 \xc2\xb5m, N\xc2\xb7m\xc2\xb2, \xe2\x80\x93"),
            "51 \xc2\xb5m, N\xc2\xb7m\xc2\xb2, \xe2\x80\x93");  // µ · ² en dash
}

TEST(TerminalText, ControlCharactersAreEscaped) {
  EXPECT_EQ(terminal_text("a\x1b[2Jb"), "a\\e[2Jb");
  EXPECT_EQ(terminal_text("line\nforged\rback\ttab"), "line\\nforged\\rback\\ttab");
  EXPECT_EQ(terminal_text(std::string("nul\0bel\x07 del\x7f", 13)), "nul\\x00bel\\x07 del\\x7F");
  // C1 controls (the 8-bit CSI U+009B) and bidirectional overrides, as code points.
  EXPECT_EQ(terminal_text("x\xc2\x9b"
                          "31m"),
            "x\\u{009B}31m");
  EXPECT_EQ(terminal_text("\xe2\x80\xae"
                          "evil"),
            "\\u{202E}evil");
  EXPECT_EQ(terminal_text("\xe2\x81\xa6"
                          "iso"),
            "\\u{2066}iso");
}

TEST(TerminalText, InvalidUtf8BytesAreEscaped) {
  EXPECT_EQ(terminal_text("a\xff"
                          "b"),
            "a\\xFFb");
  EXPECT_EQ(terminal_text("\xc0\xaf"), "\\xC0\\xAF");           // overlong '/'
  EXPECT_EQ(terminal_text("\xed\xa0\x80"), "\\xED\\xA0\\x80");  // a surrogate
  EXPECT_EQ(terminal_text("cut \xe2\x80"), "cut \\xE2\\x80");   // a truncated sequence
}

TEST(TerminalText, LinesKeepNewlinesOnly) {
  EXPECT_EQ(terminal_lines("one\ntwo\x1b]0;title\x07"), "one\ntwo\\e]0;title\\x07");
  EXPECT_EQ(terminal_lines("cr\r\n"), "cr\\r\n");
}

}  // namespace
