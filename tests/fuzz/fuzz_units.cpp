// libFuzzer target: the unit parser (emnet/core/units.hpp) on any bytes. A unit or quantity string
// is parsed or refused with std::invalid_argument; a value that parses is finite. Anything
// else (a crash, another exception, a sanitizer report, a hang) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "emnet/core/units.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const emnet::ParsedUnit unit = emnet::parse_unit(text);
    (void)emnet::describe_dimension(unit.dimension);
    (void)emnet::si_unit_symbol(unit.dimension);
  } catch (const std::invalid_argument&) {
  }
  for (const emnet::Dimension& dimension :
       {emnet::dim::none, emnet::dim::length, emnet::dim::voltage, emnet::dim::bending_stiffness,
        emnet::dim::damping_per_length, emnet::dim::capacitance}) {
    try {
      const double value = emnet::parse_quantity(text, dimension);
      if (!std::isfinite(value)) std::abort();  // parse_quantity promises a finite value
      (void)emnet::format_quantity(value, dimension);
    } catch (const std::invalid_argument&) {
    }
  }
  return 0;
}
