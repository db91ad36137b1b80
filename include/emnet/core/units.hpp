// Physical units for scene files: parses "number unit" strings such as "70 mm", "4 kV",
// "2.2e-3 N*m^2" or "51 µm" into SI values, checking the dimension against what a key expects.
//
// A dimension is a vector of exponents over the SI base units (kg, m, s, A). Every unit the
// parser knows is a power of ten times a product of base units, so a value is converted by
// shifting its decimal exponent: "122.5 mm" becomes exactly the double nearest to 0.1225.
#pragma once

#include <string>

namespace emnet {

/// Exponents over the SI base units kg, m, s, A.
struct Dimension {
  int kg = 0;  ///< exponent of kg
  int m = 0;   ///< exponent of m
  int s = 0;   ///< exponent of s
  int A = 0;   ///< exponent of A

  bool operator==(const Dimension& other) const;
  bool operator!=(const Dimension& other) const { return !(*this == other); }
  /// The dimension of the product of the two.
  Dimension times(const Dimension& other) const;
  /// The dimension of this one to the power `exponent`.
  Dimension raised_to(int exponent) const;
  /// Base-unit spelling, e.g. "kg*m^3/s^2"; "1" for a dimensionless quantity.
  std::string text() const;
};

/// The dimensions of the quantities emnet reads and writes.
namespace dim {
inline constexpr Dimension none{0, 0, 0, 0};
inline constexpr Dimension length{0, 1, 0, 0};
inline constexpr Dimension area{0, 2, 0, 0};
inline constexpr Dimension mass{1, 0, 0, 0};
inline constexpr Dimension time{0, 0, 1, 0};
inline constexpr Dimension current{0, 0, 0, 1};
inline constexpr Dimension frequency{0, 0, -1, 0};
inline constexpr Dimension velocity{0, 1, -1, 0};
inline constexpr Dimension force{1, 1, -2, 0};                     ///< N
inline constexpr Dimension moment{1, 2, -2, 0};                    ///< N*m (= J)
inline constexpr Dimension power{1, 2, -3, 0};                     ///< W
inline constexpr Dimension pressure{1, -1, -2, 0};                 ///< Pa
inline constexpr Dimension charge{0, 0, 1, 1};                     ///< A*s
inline constexpr Dimension voltage{1, 2, -3, -1};                  ///< V
inline constexpr Dimension electric_field{1, 1, -3, -1};           ///< V/m
inline constexpr Dimension resistance{1, 2, -3, -2};               ///< Ohm
inline constexpr Dimension capacitance{-1, -2, 4, 2};              ///< F
inline constexpr Dimension bending_stiffness{1, 3, -2, 0};         ///< N*m^2
inline constexpr Dimension mass_per_length{1, -1, 0, 0};           ///< kg/m
inline constexpr Dimension rotary_inertia_per_length{1, 1, 0, 0};  ///< kg*m
inline constexpr Dimension damping_per_length{1, -1, -1, 0};       ///< N*s/m^2
inline constexpr Dimension dynamic_viscosity{1, -1, -1, 0};        ///< Pa*s (= N*s/m^2)
inline constexpr Dimension density{1, -3, 0, 0};                   ///< kg/m^3
inline constexpr Dimension stiffness{1, 0, -2, 0};                 ///< N/m
inline constexpr Dimension damping{1, 0, -1, 0};                   ///< N*s/m
inline constexpr Dimension rotational_damping{1, 2, -1, 0};        ///< N*m*s (per rad)
inline constexpr Dimension rotary_inertia{1, 2, 0, 0};             ///< kg*m^2
inline constexpr Dimension inductance{1, 2, -2, -2};               ///< H
}  // namespace dim

/// The conventional SI symbol of a dimension: "m", "V", "N*m^2", "kg/m"; the base-unit text for
/// dimensions without a conventional name; "" for dimensionless.
std::string si_unit_symbol(const Dimension& dimension);

/// What a key expects, for messages: "a length (m)", "a voltage (V)", "a dimensionless number".
std::string describe_dimension(const Dimension& dimension);

/// A parsed unit expression: its dimension and the power of ten that converts it to SI.
struct ParsedUnit {
  Dimension dimension;
  int power_of_ten = 0;  ///< SI value of one unit = 10^power_of_ten
};

/// Parses a unit expression such as "mm", "N*s/m^2", "N·m²", "MΩ" or "1/s"; "" is dimensionless.
/// @throws std::invalid_argument ("unknown unit 'mmm'") on failure
ParsedUnit parse_unit(const std::string& unit_text);

/// Parses "number unit" (or a bare number, accepted only when `expected` is dimensionless) and
/// returns the SI value.
/// @throws std::invalid_argument with a reason: "unknown unit 'mmm'",
/// "unit 'kV' is a voltage, expected a length (m)", "missing unit, expected a length (m)",
/// "not a number: ...", "not a finite number: ..." (NaN and infinity are rejected).
double parse_quantity(const std::string& text, const Dimension& expected);

/// "-0.1 m", "4000 V", "0.5": a value with its SI unit, for messages.
std::string format_quantity(double value, const Dimension& dimension);

/// One number through a printf format ("%.3g", "%.4g Hz"), for messages and notes.
std::string format_number(const char* format, double value);
/// A number as people write it, through a printf "%.<digits>g": "1e-8", "2e6", not printf's
/// "1e-08", "2e+06".
std::string short_number(double value, int digits = 3);
/// Appends `value` to `out` as printf's "%<width>.<precision><conversion>" would (conversion 'e',
/// 'f' or 'g'; right-aligned in `width`), by std::to_chars: the same digits, since both round
/// correctly, at a fraction of printf's cost (no format parsing, no locale) — so that writing a
/// table of thousands of rows does not cost more than computing it.
void append_number(std::string& out, double value, char conversion, int precision, int width = 0);
/// A value with six significant digits and its unit, as results and messages print quantities:
/// "3000 V", "6.385 Hz" (no unit: the number alone).
std::string format_with_unit(double value, const std::string& unit);
/// A duration as it is read: "3.2 ms" below a second, "1.4 s" above.
std::string format_duration(double seconds);

}  // namespace emnet
