// Tests of the unit parser (emnet/core/units.hpp): SI prefixes, compound units, Unicode spellings,
// exact decimal conversion, and the error messages for wrong, missing or unknown units and for
// NaN, infinity and text that is not a number.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/fixed_precision.hpp"
#include "emnet/core/units.hpp"

namespace emnet {
namespace {

// The message of the std::invalid_argument that parse_quantity throws, or "" if none.
std::string parse_error_message(const std::string& text, const Dimension& expected) {
  try {
    parse_quantity(text, expected);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(Units, PlainNumbersAreDimensionless) {
  EXPECT_DOUBLE_EQ(parse_quantity("0.5", dim::none), 0.5);
  EXPECT_DOUBLE_EQ(parse_quantity("  2.8 ", dim::none), 2.8);
  EXPECT_DOUBLE_EQ(parse_quantity("-3e2", dim::none), -300.0);
  EXPECT_DOUBLE_EQ(parse_quantity("0.1 rad", dim::none), 0.1);
}

TEST(Units, BaseUnitsWithoutPrefix) {
  EXPECT_DOUBLE_EQ(parse_quantity("2 m", dim::length), 2.0);
  EXPECT_DOUBLE_EQ(parse_quantity("5 Hz", dim::frequency), 5.0);
  EXPECT_DOUBLE_EQ(parse_quantity("1e-3 s", dim::time), 1e-3);
  EXPECT_DOUBLE_EQ(parse_quantity("1 N", dim::force), 1.0);
  EXPECT_DOUBLE_EQ(parse_quantity("3 A", dim::current), 3.0);
  EXPECT_DOUBLE_EQ(parse_quantity("2 kg", dim::mass), 2.0);
  EXPECT_DOUBLE_EQ(parse_quantity("7 J", dim::moment), 7.0);
}

TEST(Units, SiPrefixes) {
  EXPECT_DOUBLE_EQ(parse_quantity("70 mm", dim::length), 0.07);
  EXPECT_DOUBLE_EQ(parse_quantity("4 kV", dim::voltage), 4000.0);
  EXPECT_DOUBLE_EQ(parse_quantity("51 um", dim::length), 51e-6);
  EXPECT_DOUBLE_EQ(parse_quantity("0.85 nF", dim::capacitance), 0.85e-9);
  EXPECT_DOUBLE_EQ(parse_quantity("3 pF", dim::capacitance), 3e-12);
  EXPECT_DOUBLE_EQ(parse_quantity("1 MOhm", dim::resistance), 1e6);
  EXPECT_DOUBLE_EQ(parse_quantity("2 GHz", dim::frequency), 2e9);
  EXPECT_DOUBLE_EQ(parse_quantity("12 cm", dim::length), 0.12);
  EXPECT_DOUBLE_EQ(parse_quantity("1 ms", dim::time), 1e-3);
  EXPECT_DOUBLE_EQ(parse_quantity("5 g", dim::mass), 5e-3);
  EXPECT_DOUBLE_EQ(parse_quantity("70mm", dim::length), 0.07);
}

TEST(Units, DecimalConversionIsExact) {
  EXPECT_EQ(parse_quantity("122.5 mm", dim::length), 0.1225);
  EXPECT_EQ(parse_quantity("1.55 mm", dim::length), 1.55e-3);
  EXPECT_EQ(parse_quantity("2.2e-3 N*m^2", dim::bending_stiffness), 2.2e-3);
}

TEST(Units, CompoundUnits) {
  EXPECT_DOUBLE_EQ(parse_quantity("73 g/m", dim::mass_per_length), 0.073);
  EXPECT_DOUBLE_EQ(parse_quantity("2.2e-3 N*m^2", dim::bending_stiffness), 2.2e-3);
  EXPECT_DOUBLE_EQ(parse_quantity("0 N*s/m^2", dim::damping_per_length), 0.0);
  EXPECT_DOUBLE_EQ(parse_quantity("1.5 N*s/m^2", dim::damping_per_length), 1.5);
  EXPECT_DOUBLE_EQ(parse_quantity("1e-9 kg*m", dim::rotary_inertia_per_length), 1e-9);
  EXPECT_DOUBLE_EQ(parse_quantity("3 N m", dim::moment), 3.0);
  EXPECT_DOUBLE_EQ(parse_quantity("3 N * m", dim::moment), 3.0);
  EXPECT_DOUBLE_EQ(parse_quantity("2 kg*m^2/s^2", dim::moment), 2.0);
  EXPECT_DOUBLE_EQ(parse_quantity("4 1/s", dim::frequency), 4.0);
  EXPECT_DOUBLE_EQ(parse_quantity("4 s^-1", dim::frequency), 4.0);
  EXPECT_DOUBLE_EQ(parse_quantity("6 V/A", dim::resistance), 6.0);
  EXPECT_DOUBLE_EQ(parse_quantity("1 kPa", dim::pressure), 1000.0);
  EXPECT_DOUBLE_EQ(parse_quantity("2 mW", dim::power), 2e-3);
}

TEST(Units, UnicodeSpellings) {
  EXPECT_DOUBLE_EQ(parse_quantity("2.2e-3 N\u00b7m\u00b2", dim::bending_stiffness), 2.2e-3);
  EXPECT_DOUBLE_EQ(parse_quantity("51 \u00b5m", dim::length), 51e-6);   // micro sign
  EXPECT_DOUBLE_EQ(parse_quantity("51 \u03bcm", dim::length), 51e-6);   // Greek mu
  EXPECT_DOUBLE_EQ(parse_quantity("1 M\u03a9", dim::resistance), 1e6);  // Greek omega
  EXPECT_DOUBLE_EQ(parse_quantity("1 k\u2126", dim::resistance), 1e3);  // ohm sign
  EXPECT_DOUBLE_EQ(parse_quantity("2 m\u00b3", Dimension{0, 3, 0, 0}), 2.0);
  EXPECT_DOUBLE_EQ(parse_quantity("4 s\u207b\u00b9", dim::frequency), 4.0);
}

TEST(Units, DimensionText) {
  EXPECT_EQ(dim::bending_stiffness.text(), "kg*m^3/s^2");
  EXPECT_EQ(dim::frequency.text(), "1/s");
  EXPECT_EQ(dim::none.text(), "1");
  EXPECT_EQ(si_unit_symbol(dim::bending_stiffness), "N*m^2");
  EXPECT_EQ(si_unit_symbol(dim::voltage), "V");
  EXPECT_EQ(describe_dimension(dim::length), "a length (m)");
  EXPECT_EQ(format_quantity(-0.1, dim::length), "-0.1 m");
  EXPECT_EQ(format_quantity(0.5, dim::none), "0.5");
}

TEST(Units, ParseUnitGivesDimensionAndPowerOfTen) {
  const ParsedUnit unit = parse_unit("mm");
  EXPECT_EQ(unit.dimension, dim::length);
  EXPECT_EQ(unit.power_of_ten, -3);
  EXPECT_EQ(parse_unit("kg").power_of_ten, 0);
  EXPECT_EQ(parse_unit("").dimension, dim::none);
}

TEST(Units, DimensionMismatchNamesBoth) {
  EXPECT_EQ(parse_error_message("4 kV", dim::length),
            "unit 'kV' is a voltage, expected a length (m)");
  EXPECT_EQ(parse_error_message("3 m", dim::none),
            "unit 'm' is a length, expected a dimensionless number");
  EXPECT_EQ(parse_error_message("3 kg*s", dim::length),
            "unit 'kg*s' has dimension kg*s, expected a length (m)");
}

TEST(Units, MissingUnitIsRejectedForDimensionalKeys) {
  EXPECT_EQ(parse_error_message("70", dim::length), "missing unit, expected a length (m)");
}

TEST(Units, UnknownUnitIsNamed) {
  EXPECT_EQ(parse_error_message("1 mmm", dim::length), "unknown unit 'mmm'");
  EXPECT_EQ(parse_error_message("1 kg*mmm", dim::length), "unknown unit 'mmm' in 'kg*mmm'");
  EXPECT_NE(parse_error_message("1 m^", dim::length).find("malformed unit"), std::string::npos);
  EXPECT_NE(parse_error_message("1 N**m", dim::moment).find("malformed unit"), std::string::npos);
}

TEST(Units, NanAndInfinityAreRejected) {
  EXPECT_NE(parse_error_message("nan m", dim::length).find("not a finite number"),
            std::string::npos);
  EXPECT_NE(parse_error_message("NaN", dim::none).find("not a finite number"), std::string::npos);
  EXPECT_NE(parse_error_message("inf", dim::none).find("not a finite number"), std::string::npos);
  EXPECT_NE(parse_error_message("-inf V", dim::voltage).find("not a finite number"),
            std::string::npos);
  EXPECT_NE(parse_error_message("1e999 m", dim::length).find("out of range"), std::string::npos);
}

TEST(Units, TextThatIsNotANumberIsRejected) {
  EXPECT_NE(parse_error_message("abc", dim::length).find("not a number: 'abc'"), std::string::npos);
  EXPECT_NE(parse_error_message("mm", dim::length).find("not a number"), std::string::npos);
  EXPECT_NE(parse_error_message("", dim::length).find("empty value"), std::string::npos);
  EXPECT_NE(parse_error_message(".", dim::none).find("not a number"), std::string::npos);
}

// append_number writes what printf writes for the table formats, on values spread over the whole
// double range, signs, zeros, and the specials. Reference: glibc's printf (both round correctly,
// so the texts must be equal, not close).
TEST(Units, AppendNumberWritesWhatPrintfWrites) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  std::vector<double> values = {0.0,      -0.0,   1.0,          -1.0,     0.5,
                                999999.5, 1e-300, 9.9999995e-5, INFINITY, -INFINITY,
                                123456.7, 0.1225, 6.385};
  for (int k = 0; k < 3000; ++k)
    values.push_back(mantissa(random) * std::pow(10.0, exponent(random)));
  for (int k = 0; k < 3000; ++k)
    values.push_back(mantissa(random) * std::pow(10.0, exponent(random) / 30));
  struct Format {
    char conversion;
    int precision, width;
  };
  for (const Format& f :
       {Format{'e', 6, 16}, Format{'f', 3, 11}, Format{'g', 6, 14}, Format{'g', 9, 0}}) {
    const std::string pattern = "%" + std::to_string(f.width) + "." + std::to_string(f.precision) +
                                std::string(1, f.conversion);
    for (double value : values) {
      if (f.conversion == 'f' && std::abs(value) > 1e30) continue;  // not a table's column
      char expected[512];
      std::snprintf(expected, sizeof expected, pattern.c_str(), value);
      std::string written;
      append_number(written, value, f.conversion, f.precision, f.width);
      EXPECT_EQ(written, expected) << pattern << " of " << value;
    }
  }
}

// The exact double-arithmetic path of append_number (core/fixed_precision.hpp) against glibc's
// printf where the rounding is hardest: values within a few ulps of a decimal half-way point
// (the rounded product lands on the wrong side there unless corrected), exact binary ties
// (printf rounds them to even), every precision 0–15, both conversions, both signs. Equal
// texts, not close ones; and the path must apply to the table's values (else nothing is fast).
TEST(Units, FixedPrecisionDigitsRoundLikePrintfAtHalfWayPoints) {
  std::mt19937_64 random(11);
  std::vector<double> values = {0.125, 0.375, 2.5,  3.5, 1234.5, -0.5, 0.0625, -2.5e-5,
                                1e-5,  0.0,   -0.0, 9.5, 99.5,   0.95, 1e15};
  for (int k = 0; k < 4000; ++k) {
    const int decimals = std::uniform_int_distribution<int>(0, 18)(random);
    const double n = std::floor(std::uniform_real_distribution<double>(0.0, 1e7)(random));
    double x = (n + 0.5) / std::pow(10.0, decimals);
    const int ulps = std::uniform_int_distribution<int>(-3, 3)(random);
    for (int u = 0; u < std::abs(ulps); ++u) x = std::nextafter(x, ulps > 0 ? INFINITY : 0.0);
    values.push_back(k % 2 ? x : -x);
  }
  int fast = 0, checked = 0;
  for (const char conversion : {'e', 'f'})
    for (int precision = 0; precision <= 15; ++precision)
      for (double value : values) {
        char digits[64];
        const size_t length = fixed_precision_digits(value, conversion, precision, digits);
        if (length == 0) continue;
        ++fast;
        const std::string pattern = "%." + std::to_string(precision) + conversion;
        char expected[512];
        std::snprintf(expected, sizeof expected, pattern.c_str(), value);
        EXPECT_EQ(std::string(digits, length), expected) << pattern << " of " << value;
        ++checked;
      }
  EXPECT_GT(fast, 50000);  // most of the 128 000 cases take the path
  // The AC table's numbers take it: a deflection magnitude and a phase.
  char digits[64];
  EXPECT_GT(fixed_precision_digits(4.231438e-04, 'e', 6, digits), 0u);
  EXPECT_GT(fixed_precision_digits(-179.99951, 'f', 3, digits), 0u);
  EXPECT_EQ(checked, fast);
}

}  // namespace
}  // namespace emnet
