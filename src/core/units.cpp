// Unit parsing for scene files: "number unit" strings to SI values, with dimension checking.
//
// Grammar of a unit expression: factors separated by '*', '·', '⋅', '×' or spaces (product)
// or '/' (divides by the next factor only); each factor is an optional SI prefix (p n u µ m c k
// M G) and a unit symbol (m g s A N V Hz F Ohm Ω W J Pa rad, or 1), optionally raised to an
// integer power with '^2', '^-1' or superscripts '²', '³', '⁻¹'. Every unit is a power of ten
// times SI base units, so the conversion is done on the decimal exponent and is exact to the
// last bit: "122.5 mm" reads as the double nearest to 0.1225.
#include "emnet/core/units.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <system_error>

#include "emnet/core/terminal_text.hpp"
#include "fixed_precision.hpp"

namespace emnet {

bool Dimension::operator==(const Dimension& other) const {
  return kg == other.kg && m == other.m && s == other.s && A == other.A;
}

Dimension Dimension::times(const Dimension& other) const {
  return Dimension{kg + other.kg, m + other.m, s + other.s, A + other.A};
}

Dimension Dimension::raised_to(int exponent) const {
  return Dimension{kg * exponent, m * exponent, s * exponent, A * exponent};
}

std::string Dimension::text() const {
  const std::pair<const char*, int> base_units[] = {{"kg", kg}, {"m", m}, {"s", s}, {"A", A}};
  std::string numerator;
  std::string denominator;
  for (const auto& [symbol, exponent] : base_units) {
    if (exponent == 0) continue;
    std::string& side = exponent > 0 ? numerator : denominator;
    if (!side.empty()) side += "*";
    side += symbol;
    const int magnitude = exponent > 0 ? exponent : -exponent;
    if (magnitude != 1) side += "^" + std::to_string(magnitude);
  }
  if (numerator.empty() && denominator.empty()) return "1";
  if (numerator.empty()) numerator = "1";
  return denominator.empty() ? numerator : numerator + "/" + denominator;
}

namespace {

struct NamedDimension {
  Dimension dimension;
  const char* noun;    // "a length"
  const char* symbol;  // "m"
};

// Dimensions with a conventional name; the first entry for a dimension wins (moment before
// energy, frequency before angular velocity).
const NamedDimension kNamedDimensions[] = {
    {dim::length, "a length", "m"},
    {dim::area, "an area", "m^2"},
    {dim::mass, "a mass", "kg"},
    {dim::time, "a time", "s"},
    {dim::current, "a current", "A"},
    {dim::frequency, "a frequency", "Hz"},
    {dim::velocity, "a velocity", "m/s"},
    {dim::force, "a force", "N"},
    {dim::moment, "a moment", "N*m"},
    {dim::power, "a power", "W"},
    {dim::pressure, "a pressure", "Pa"},
    {dim::charge, "a charge", "A*s"},
    {dim::voltage, "a voltage", "V"},
    {dim::electric_field, "an electric field", "V/m"},
    {dim::resistance, "a resistance", "Ohm"},
    {dim::capacitance, "a capacitance", "F"},
    {dim::bending_stiffness, "a bending stiffness", "N*m^2"},
    {dim::mass_per_length, "a mass per length", "kg/m"},
    {dim::rotary_inertia_per_length, "a rotary inertia per length", "kg*m"},
    {dim::damping_per_length, "a damping per length", "N*s/m^2"},
    {dim::density, "a density", "kg/m^3"},
    {dim::stiffness, "a stiffness", "N/m"},
    {dim::damping, "a damping coefficient", "N*s/m"},
    {dim::rotational_damping, "a rotational damping coefficient", "N*m*s"},
    {dim::rotary_inertia, "a rotary inertia", "kg*m^2"},
    {dim::inductance, "an inductance", "H"},
};

const NamedDimension* find_named_dimension(const Dimension& dimension) {
  for (const NamedDimension& named : kNamedDimensions) {
    if (named.dimension == dimension) return &named;
  }
  return nullptr;
}

struct UnitSymbol {
  const char* symbol;
  Dimension dimension;
  int power_of_ten;  // SI value of one unit = 10^power_of_ten (g = 1e-3 kg)
};

const UnitSymbol kUnitSymbols[] = {
    {"m", dim::length, 0},
    {"g", dim::mass, -3},
    {"s", dim::time, 0},
    {"A", dim::current, 0},
    {"N", dim::force, 0},
    {"V", dim::voltage, 0},
    {"Hz", dim::frequency, 0},
    {"F", dim::capacitance, 0},
    {"Ohm", dim::resistance, 0},
    {"ohm", dim::resistance, 0},
    {"\xCE\xA9", dim::resistance, 0},      // Ω, Greek capital omega
    {"\xE2\x84\xA6", dim::resistance, 0},  // Ω, ohm sign
    {"W", dim::power, 0},
    {"J", dim::moment, 0},
    {"Pa", dim::pressure, 0},
    {"rad", dim::none, 0},
    {"H", dim::inductance, 0},
};

struct PrefixSymbol {
  const char* symbol;
  int power_of_ten;
};

const PrefixSymbol kPrefixes[] = {
    {"p", -12},
    {"n", -9},
    {"u", -6},
    {"\xC2\xB5", -6} /* µ micro sign */,
    {"\xCE\xBC", -6} /* μ Greek mu */,
    {"m", -3},
    {"c", -2},
    {"k", 3},
    {"M", 6},
    {"G", 9},
};

const char* const kMultiplicationSigns[] = {"*", "\xC2\xB7" /* · */, "\xE2\x8B\x85" /* ⋅ */,
                                            "\xC3\x97" /* × */};

struct Superscript {
  const char* symbol;
  int digit;  // -1 for the superscript minus
};

const Superscript kSuperscripts[] = {
    {"\xE2\x81\xBB", -1} /* ⁻ */, {"\xE2\x81\xB0", 0} /* ⁰ */, {"\xC2\xB9", 1} /* ¹ */,
    {"\xC2\xB2", 2} /* ² */,      {"\xC2\xB3", 3} /* ³ */,     {"\xE2\x81\xB4", 4},
    {"\xE2\x81\xB5", 5},          {"\xE2\x81\xB6", 6},         {"\xE2\x81\xB7", 7},
    {"\xE2\x81\xB8", 8},          {"\xE2\x81\xB9", 9},
};

constexpr int kMaximumUnitExponent = 12;

bool has_at(const std::string& text, std::size_t position, const char* token) {
  return text.compare(position, std::char_traits<char>::length(token), token) == 0;
}

bool is_space(char character) {
  return character == ' ' || character == '\t' || character == '\n' || character == '\r';
}

void skip_spaces(const std::string& text, std::size_t& position) {
  while (position < text.size() && is_space(text[position])) ++position;
}

std::string trim(const std::string& text) {
  std::size_t begin = 0;
  skip_spaces(text, begin);
  std::size_t end = text.size();
  while (end > begin && is_space(text[end - 1])) --end;
  return text.substr(begin, end - begin);
}

// Length of the multiplication sign at `position`, or 0.
std::size_t multiplication_sign_length(const std::string& text, std::size_t position) {
  for (const char* sign : kMultiplicationSigns) {
    if (has_at(text, position, sign)) return std::char_traits<char>::length(sign);
  }
  return 0;
}

const Superscript* superscript_at(const std::string& text, std::size_t position) {
  for (const Superscript& superscript : kSuperscripts) {
    if (has_at(text, position, superscript.symbol)) return &superscript;
  }
  return nullptr;
}

bool ends_unit_symbol(const std::string& text, std::size_t position) {
  const char character = text[position];
  return is_space(character) || character == '/' || character == '^' ||
         multiplication_sign_length(text, position) > 0 ||
         superscript_at(text, position) != nullptr;
}

const UnitSymbol* find_unit_symbol(const std::string& symbol) {
  for (const UnitSymbol& unit : kUnitSymbols) {
    if (symbol == unit.symbol) return &unit;
  }
  return nullptr;
}

// Resolves "mm", "kV", "MΩ", "1" to a dimension and power of ten; false if unknown.
bool resolve_unit_symbol(const std::string& symbol, ParsedUnit& resolved) {
  if (symbol == "1") {
    resolved = ParsedUnit{};
    return true;
  }
  if (const UnitSymbol* unit = find_unit_symbol(symbol)) {
    resolved = ParsedUnit{unit->dimension, unit->power_of_ten};
    return true;
  }
  for (const PrefixSymbol& prefix : kPrefixes) {
    const std::size_t prefix_length = std::char_traits<char>::length(prefix.symbol);
    if (symbol.size() <= prefix_length || !has_at(symbol, 0, prefix.symbol)) continue;
    if (const UnitSymbol* unit = find_unit_symbol(symbol.substr(prefix_length))) {
      resolved = ParsedUnit{unit->dimension, unit->power_of_ten + prefix.power_of_ten};
      return true;
    }
  }
  return false;
}

// A piece of the input quoted in a message: escaped (a NUL cut the message where it was
// printed) and at most 60 bytes (a 100 000-character value was echoed whole, twice).
std::string quoted(const std::string& text) {
  return terminal_excerpt(text, 60);
}

[[noreturn]] void throw_malformed_unit(const std::string& unit_text, const std::string& why) {
  throw std::invalid_argument("malformed unit '" + quoted(unit_text) + "': " + why);
}

// Reads an optional exponent ("^2", "^-1", "²", "⁻¹") at `position`; 1 if there is none.
int read_unit_exponent(const std::string& unit_text, std::size_t& position) {
  if (position < unit_text.size() && unit_text[position] == '^') {
    ++position;
    int sign = 1;
    if (position < unit_text.size() && (unit_text[position] == '-' || unit_text[position] == '+')) {
      if (unit_text[position] == '-') sign = -1;
      ++position;
    }
    int magnitude = 0;
    const std::size_t digits_begin = position;
    while (position < unit_text.size() &&
           std::isdigit(static_cast<unsigned char>(unit_text[position]))) {
      magnitude = magnitude * 10 + (unit_text[position] - '0');
      if (magnitude > kMaximumUnitExponent) throw_malformed_unit(unit_text, "exponent too large");
      ++position;
    }
    if (position == digits_begin) {
      throw_malformed_unit(unit_text, "expected an integer exponent after '^'");
    }
    return sign * magnitude;
  }
  const Superscript* superscript = superscript_at(unit_text, position);
  if (superscript == nullptr) return 1;
  int sign = 1;
  if (superscript->digit < 0) {
    sign = -1;
    position += std::char_traits<char>::length(superscript->symbol);
    superscript = superscript_at(unit_text, position);
    if (superscript == nullptr || superscript->digit < 0) {
      throw_malformed_unit(unit_text, "expected a superscript digit after '\xE2\x81\xBB'");
    }
  }
  int magnitude = 0;
  while (superscript != nullptr && superscript->digit >= 0) {
    magnitude = magnitude * 10 + superscript->digit;
    if (magnitude > kMaximumUnitExponent) throw_malformed_unit(unit_text, "exponent too large");
    position += std::char_traits<char>::length(superscript->symbol);
    superscript = superscript_at(unit_text, position);
  }
  return sign * magnitude;
}

}  // namespace

std::string si_unit_symbol(const Dimension& dimension) {
  if (dimension == dim::none) return "";
  if (const NamedDimension* named = find_named_dimension(dimension)) return named->symbol;
  return dimension.text();
}

std::string describe_dimension(const Dimension& dimension) {
  if (dimension == dim::none) return "a dimensionless number";
  if (const NamedDimension* named = find_named_dimension(dimension)) {
    return std::string(named->noun) + " (" + named->symbol + ")";
  }
  return "a quantity in " + dimension.text();
}

ParsedUnit parse_unit(const std::string& unit_text) {
  ParsedUnit result;
  std::size_t position = 0;
  bool first_factor = true;
  while (true) {
    skip_spaces(unit_text, position);
    if (position == unit_text.size()) break;
    int direction = 1;  // +1 multiplies, -1 divides
    if (unit_text[position] == '/') {
      if (first_factor) throw_malformed_unit(unit_text, "nothing before '/'");
      direction = -1;
      ++position;
    } else if (const std::size_t sign_length = multiplication_sign_length(unit_text, position)) {
      if (first_factor) throw_malformed_unit(unit_text, "nothing before the product sign");
      position += sign_length;
    }
    skip_spaces(unit_text, position);
    const std::size_t symbol_begin = position;
    while (position < unit_text.size() && !ends_unit_symbol(unit_text, position)) ++position;
    if (position == symbol_begin) throw_malformed_unit(unit_text, "expected a unit symbol");
    const std::string symbol = unit_text.substr(symbol_begin, position - symbol_begin);
    ParsedUnit factor;
    if (!resolve_unit_symbol(symbol, factor)) {
      if (symbol == trim(unit_text))
        throw std::invalid_argument("unknown unit '" + quoted(symbol) + "'");
      throw std::invalid_argument("unknown unit '" + quoted(symbol) + "' in '" +
                                  quoted(trim(unit_text)) + "'");
    }
    const int exponent = direction * read_unit_exponent(unit_text, position);
    result.dimension = result.dimension.times(factor.dimension.raised_to(exponent));
    result.power_of_ten += exponent * factor.power_of_ten;
    first_factor = false;
  }
  return result;
}

double parse_quantity(const std::string& text, const Dimension& expected) {
  const std::string trimmed = trim(text);
  const std::string example = expected == dim::none ? "0.5" : "1 " + si_unit_symbol(expected);
  const std::string expectation =
      "expected " + describe_dimension(expected) + " such as '" + example + "'";
  if (trimmed.empty()) throw std::invalid_argument("empty value, " + expectation);

  // Number: [sign] digits [. digits] [e [sign] digits]
  std::size_t position = 0;
  std::string mantissa;
  if (trimmed[position] == '+' || trimmed[position] == '-') {
    if (trimmed[position] == '-') mantissa += '-';
    ++position;
  }
  std::string word;
  for (std::size_t i = position; i < trimmed.size() && i < position + 3; ++i) {
    word += static_cast<char>(std::tolower(static_cast<unsigned char>(trimmed[i])));
  }
  if (word == "nan" || word == "inf") {
    throw std::invalid_argument("not a finite number: '" + quoted(trimmed) + "'");
  }
  std::size_t digit_count = 0;
  while (position < trimmed.size()) {
    const char character = trimmed[position];
    if (std::isdigit(static_cast<unsigned char>(character))) {
      ++digit_count;
    } else if (character != '.' || mantissa.find('.') != std::string::npos) {
      break;
    }
    mantissa += character;
    ++position;
  }
  if (digit_count == 0) {
    throw std::invalid_argument("not a number: '" + quoted(trimmed) + "', " + expectation);
  }
  long long decimal_exponent = 0;
  if (position < trimmed.size() && (trimmed[position] == 'e' || trimmed[position] == 'E')) {
    std::size_t exponent_position = position + 1;
    int exponent_sign = 1;
    if (exponent_position < trimmed.size() &&
        (trimmed[exponent_position] == '+' || trimmed[exponent_position] == '-')) {
      if (trimmed[exponent_position] == '-') exponent_sign = -1;
      ++exponent_position;
    }
    if (exponent_position < trimmed.size() &&
        std::isdigit(static_cast<unsigned char>(trimmed[exponent_position]))) {
      while (exponent_position < trimmed.size() &&
             std::isdigit(static_cast<unsigned char>(trimmed[exponent_position]))) {
        if (decimal_exponent < 100000) {
          decimal_exponent = decimal_exponent * 10 + (trimmed[exponent_position] - '0');
        }
        ++exponent_position;
      }
      decimal_exponent *= exponent_sign;
      position = exponent_position;
    }
  }

  const std::string unit_text = trim(trimmed.substr(position));
  const ParsedUnit unit = parse_unit(unit_text);
  const std::string scientific =
      mantissa + "e" + std::to_string(decimal_exponent + unit.power_of_ten);
  double value = 0.0;
  const auto [end, error] =
      std::from_chars(scientific.data(), scientific.data() + scientific.size(), value);
  if (error == std::errc::result_out_of_range || !std::isfinite(value)) {
    throw std::invalid_argument("number out of range: '" + quoted(trimmed) + "'");
  }
  if (error != std::errc() || end != scientific.data() + scientific.size()) {
    throw std::invalid_argument("not a number: '" + quoted(trimmed) + "', " + expectation);
  }
  if (unit_text.empty() && expected != dim::none) {
    throw std::invalid_argument("missing unit, expected " + describe_dimension(expected));
  }
  if (unit.dimension != expected) {
    std::string actual;
    if (unit.dimension == dim::none) {
      actual = "is dimensionless";
    } else if (const NamedDimension* named = find_named_dimension(unit.dimension)) {
      actual = std::string("is ") + named->noun;
    } else {
      actual = "has dimension " + unit.dimension.text();
    }
    throw std::invalid_argument("unit '" + quoted(unit_text) + "' " + actual + ", expected " +
                                describe_dimension(expected));
  }

  return value;
}

std::string format_quantity(double value, const Dimension& dimension) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  const std::string unit = si_unit_symbol(dimension);
  return unit.empty() ? std::string(buffer) : std::string(buffer) + " " + unit;
}

std::string format_number(const char* format, double value) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string short_number(double value, int digits) {
  std::string out = format_number(("%." + std::to_string(digits) + "g").c_str(), value);
  const size_t e = out.find('e');
  if (e == std::string::npos) return out;
  size_t exponent = e + 1;
  if (exponent < out.size() && (out[exponent] == '-' || out[exponent] == '+')) ++exponent;
  while (exponent + 1 < out.size() && out[exponent] == '0') out.erase(exponent, 1);
  if (out[e + 1] == '+') out.erase(e + 1, 1);
  return out;
}

void append_number(std::string& out, double value, char conversion, int precision, int width) {
  char buffer[400];  // the longest: "%.<precision>f" of 1e308
  // The table rows' numbers by the exact double-arithmetic path where it applies (its own file
  // says where; the same characters), else by std::to_chars.
  size_t length = fixed_precision_digits(value, conversion, precision, buffer);
  if (length == 0) {
    const std::chars_format format = conversion == 'e'   ? std::chars_format::scientific
                                     : conversion == 'f' ? std::chars_format::fixed
                                                         : std::chars_format::general;
    const std::to_chars_result written =
        std::to_chars(buffer, buffer + sizeof buffer, value, format, precision);
    length = written.ec == std::errc() ? static_cast<size_t>(written.ptr - buffer) : 0;
  }
  if (length == 0) {  // too long for the buffer (never for the formats used): printf's own
    const std::string pattern =
        "%" + std::to_string(width) + "." + std::to_string(precision) + std::string(1, conversion);
    out += format_number(pattern.c_str(), value);
    return;
  }
  if (static_cast<int>(length) < width) out.append(static_cast<size_t>(width) - length, ' ');
  out.append(buffer, length);
}

std::string format_with_unit(double value, const std::string& unit) {
  return format_number("%.6g", value) + (unit.empty() ? "" : " " + unit);
}

std::string format_duration(double seconds) {
  return seconds < 1.0 ? format_number("%.3g ms", seconds * 1e3) : format_number("%.3g s", seconds);
}

}  // namespace emnet
