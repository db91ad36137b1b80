// Correctly rounded fixed-precision output: see fixed_precision.hpp.
#include "fixed_precision.hpp"

#include <cmath>
#include <cstdint>

namespace emnet {

namespace {

constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                   1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                   1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// r = round(|value|·10^k), ties to even, of the exact product; false where |value|·10^k is not
// below 2⁵² (r ± ½ would not be exact). The rounded product is within half an ulp of the exact
// one, so r from it is off by at most one, where the exact product lies within that of a half.
bool scaled_integer(double value, int k, double& r) {
  const double scale = kPowersOfTen[k];
  const double magnitude = std::fabs(value);
  const double product = magnitude * scale;
  if (!(product < 0x1p52)) return false;
  r = std::nearbyint(product);
  for (int correction = 0; correction < 2; ++correction) {
    const bool even = (static_cast<std::int64_t>(r) & 1) == 0;    // r < 2⁵²: an exact integer
    const double below = std::fma(magnitude, scale, -(r - 0.5));  // sign of P − (r − ½)
    const double above = std::fma(magnitude, scale, -(r + 0.5));  // sign of P − (r + ½)
    if (below < 0.0 || (below == 0.0 && !even)) {
      r -= 1.0;
    } else if (above > 0.0 || (above == 0.0 && !even)) {
      r += 1.0;
    } else {
      return true;
    }
  }
  return false;
}

// The decimal digits of n, exactly `count` of them (leading zeros), at out; returns out + count.
char* write_digits(std::uint64_t n, int count, char* out) {
  for (int i = count - 1; i >= 0; --i) {
    out[i] = static_cast<char>('0' + n % 10);
    n /= 10;
  }
  return out + count;
}

int digit_count(std::uint64_t n) {
  int count = 1;
  while (n >= 10) n /= 10, ++count;
  return count;
}

std::size_t fixed(double value, int precision, char* out) {
  double r = 0.0;
  if (!scaled_integer(value, precision, r)) return 0;
  const auto n = static_cast<std::uint64_t>(r);
  const std::uint64_t unit = static_cast<std::uint64_t>(kPowersOfTen[precision]);
  char* p = out;
  if (std::signbit(value)) *p++ = '-';
  const std::uint64_t whole = n / unit;
  p = write_digits(whole, digit_count(whole), p);
  if (precision > 0) {
    *p++ = '.';
    p = write_digits(n % unit, precision, p);
  }
  return static_cast<std::size_t>(p - out);
}

std::size_t scientific(double value, int precision, char* out) {
  if (value == 0.0) return 0;
  // ⌊log₁₀|value|⌋ from the binary exponent (⌊e₂·log₁₀2⌋, at most one below it), corrected
  // below, as is a rounding that carries to one more digit.
  int exponent = static_cast<int>(std::floor(std::ilogb(value) * 0.30102999566398120));
  double r = 0.0;
  const double lowest = kPowersOfTen[precision], highest = kPowersOfTen[precision + 1];
  for (int attempt = 0;; ++attempt) {
    const int k = precision - exponent;
    if (attempt == 3 || k < 0 || k > 22 || !scaled_integer(value, k, r)) return 0;
    if (r >= highest)
      ++exponent;
    else if (r < lowest)
      --exponent;
    else
      break;
  }
  const auto n = static_cast<std::uint64_t>(r);
  char* p = out;
  if (std::signbit(value)) *p++ = '-';
  char digits[24];
  write_digits(n, precision + 1, digits);
  *p++ = digits[0];
  if (precision > 0) {
    *p++ = '.';
    for (int i = 1; i <= precision; ++i) *p++ = digits[i];
  }
  *p++ = 'e';
  *p++ = exponent < 0 ? '-' : '+';
  const int shown = exponent < 0 ? -exponent : exponent;
  p = write_digits(static_cast<std::uint64_t>(shown), shown < 10 ? 2 : digit_count(shown), p);
  return static_cast<std::size_t>(p - out);
}

}  // namespace

std::size_t fixed_precision_digits(double value, char conversion, int precision, char* out) {
  if (!std::isfinite(value) || precision < 0 || precision > 15) return 0;
  if (conversion == 'f') return fixed(value, precision, out);
  if (conversion == 'e') return scientific(value, precision, out);
  return 0;
}

}  // namespace emnet
