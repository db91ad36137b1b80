// libFuzzer target: the ngspice rawfile reader (parse_ngspice_rawfile,
// src/spice/ngspice_rawfile.cpp) on any bytes, binary or ASCII. It returns false with a reason
// or true with plots that keep its promises: each plot has its scale first and every vector
// has as many points as the others, real or complex as the plot's flags say; a complex plot's
// scale has no imaginary part. Anything else (a crash, an exception, a sanitizer report, a
// hang, an allocation beyond -rss_limit_mb) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "emnet/spice/ngspice_runner.hpp"
#include "spice/ngspice_rawfile.hpp"

namespace {

void check_plot(const emnet::NgspiceRawPlot& plot) {
  if (plot.vectors.empty() || !plot.vectors.front().is_scale) std::abort();
  const emnet::NgspiceVector& scale = plot.vectors.front();
  const std::size_t points =
      scale.is_complex ? scale.complex_values.size() : scale.real_values.size();
  for (std::size_t k = 0; k < plot.vectors.size(); ++k) {
    const emnet::NgspiceVector& vector = plot.vectors[k];
    if (vector.is_scale != (k == 0) || vector.is_complex != scale.is_complex) std::abort();
    const std::size_t size =
        vector.is_complex ? vector.complex_values.size() : vector.real_values.size();
    const std::size_t other =
        vector.is_complex ? vector.real_values.size() : vector.complex_values.size();
    if (size != points || other != 0) std::abort();
    (void)emnet::vector_name_from_rawfile(vector.name);
  }
  if (scale.is_complex)
    for (const auto& value : scale.complex_values)
      if (value.imag() != 0.0) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  std::vector<emnet::NgspiceRawPlot> plots;
  std::string why;
  if (emnet::parse_ngspice_rawfile(bytes, plots, why)) {
    for (const emnet::NgspiceRawPlot& plot : plots) check_plot(plot);
  } else if (why.empty()) {
    std::abort();  // a refusal always says why
  }
  return 0;
}
