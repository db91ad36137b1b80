// Correctly rounded "%.<p>e" and "%.<p>f" output by double arithmetic, for the values where it
// is exact: append_number's table rows (thousands of numbers per command) at a fifth of
// std::to_chars' cost, the same characters.
#pragma once

#include <cstddef>

namespace emnet {

// Writes `value` as printf's "%.<precision>e" (conversion 'e') or "%.<precision>f" ('f') does
// in the C locale, into `out` (at least 48 characters), and returns the length; 0 where this
// path does not apply (a non-finite or zero value, a precision above 15, a magnitude whose
// scaled value is not below 2⁵², or 'e' of a value outside [10^(precision−22),
// 10^(precision+1))) — then std::to_chars must. The digits are round(value·10^k) to even: the
// product rounded, then corrected by the signs of the exact value·10^k − (r ± ½), which one fused
// multiply-add gives exactly (10^k is exact in a double for k ≤ 22).
std::size_t fixed_precision_digits(double value, char conversion, int precision, char* out);

}  // namespace emnet
