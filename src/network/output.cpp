// Probe values and their linearisation: see include/emnet/network/output.hpp.
#include "emnet/network/output.hpp"

#include <cstdio>
#include <stdexcept>

namespace emnet {

double linear_value(const LinearTerms& terms, const Eigen::VectorXd& y) {
  double sum = 0.0;
  for (const auto& [index, coefficient] : terms) sum += coefficient * y[index];
  return sum;
}

double squares_value(const Probe& probe, const Eigen::VectorXd& y) {
  double sum = 0.0;
  for (const SquaredTerm& square : probe.squares) {
    const double inner = linear_value(square.terms, y);
    sum += square.factor * inner * inner;
  }
  return sum;
}

Probe linearised_probe(const Probe& probe, const Eigen::VectorXd& operating_point) {
  if (is_linear(probe)) return probe;
  Probe linear = probe;
  linear.squares.clear();
  std::string levels;
  for (const SquaredTerm& square : probe.squares) {
    const double level =
        operating_point.size() > 0 ? linear_value(square.terms, operating_point) : 0.0;
    for (const auto& [index, d] : square.terms)
      linear.terms.emplace_back(index, 2.0 * square.factor * level * d);
    char text[48];
    std::snprintf(text, sizeof text, "%s%.6g", levels.empty() ? "" : ", ", level);
    levels += text;
  }
  linear.description +=
      " (small signal: linearised about the operating point, 2*k*u0*U with u0 = " + levels + ")";
  return linear;
}

std::complex<double> probe_phasor(const Probe& probe, const Eigen::VectorXcd& y, double omega) {
  if (!is_linear(probe))
    throw std::invalid_argument("probe_phasor: probe '" + probe.name +
                                "' has squares; take linearised_probe about the operating point");
  std::complex<double> sum = 0.0;
  for (const auto& [index, coefficient] : probe.terms) sum += coefficient * y[index];
  for (int k = 0; k < probe.integrations; ++k) sum /= std::complex<double>(0.0, omega);
  return sum;
}

}  // namespace emnet
