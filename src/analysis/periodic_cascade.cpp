// The exact cascade's stages: see periodic_cascade.hpp.
#include "periodic_cascade.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "emnet/core/units.hpp"

namespace emnet {

namespace {

using Complex = std::complex<double>;

// An exponent closer than this (times 1/T) to a pole it forces is refused: the particular
// state's 1/(μ − λ) would leave eps/(|μ − λ|·T) ≈ 1e-9 of the response to rounding.
constexpr double kResonanceGap = 1e-7;
// A forcing of a mode below this fraction of the largest one is the stages' rounding (the
// voltages' poles seen by the beam's modes, ~1e-16): left out where it meets its own pole.
constexpr double kNegligibleForcing = 1e-10;
// The poles a voltage carries: above this fraction of its scale in some interval.
constexpr double kKeptPole = 1e-12;

}  // namespace

Status cascade_sources(const System& system, const DisplacementForm& form,
                       std::vector<SquaredSource>& sources) {
  sources.clear();
  for (const auto& element : system.nonlinear_elements) {
    LinearTerms voltage, direction;
    if (!element->squared_source(voltage, direction))
      return not_a_squared_source(*element, "the exact cascade");
    SquaredSource source;
    source.name = element->name();
    source.voltage = squared_voltage_probe(element->name(), voltage);
    for (const auto& [node, coefficient] : voltage)
      if (form.mechanical(node))
        return Status::failure("element '" + element->name() +
                               "' squares a mechanical quantity: the exact cascade squares "
                               "voltages only");
    source.direction = Eigen::VectorXd::Zero(form.size());
    for (const auto& [row, value] : direction) source.direction[row] += value;
    sources.push_back(std::move(source));
  }
  return Status::success();
}

Status not_a_squared_source(const Element& element, const std::string& method) {
  return Status::failure("element '" + element.name() + "' (" + element.kind() +
                         ") is nonlinear otherwise than by a DEA's force k_F·u² without "
                         "back-coupling (dea[].back_coupling; beam.kinematics = \"large\"), the "
                         "only nonlinearity " +
                         method + " takes");
}

Probe squared_voltage_probe(const std::string& element_name, const LinearTerms& voltage) {
  Probe probe;
  probe.name = "\x01u(" + element_name + ")";  // not a name a scene can give
  probe.quantity = ProbeQuantity::dea_voltage;
  probe.unit = "V";
  for (const auto& [node, coefficient] : voltage) probe.terms.emplace_back(node, coefficient);
  return probe;
}

bool same_cascade(const std::vector<std::shared_ptr<const Element>>& a,
                  const std::vector<std::shared_ptr<const Element>>& b) {
  if (a.size() != b.size()) return false;
  for (size_t e = 0; e < a.size(); ++e) {
    if (a[e] == b[e]) continue;
    LinearTerms a_voltage, a_direction, b_voltage, b_direction;
    if (!a[e]->squared_source(a_voltage, a_direction) ||
        !b[e]->squared_source(b_voltage, b_direction) || a_voltage != b_voltage ||
        a_direction != b_direction)
      return false;
  }
  return true;
}

SquareExponents square_exponents(const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
                                 const std::vector<ExponentialSeries>& voltages) {
  std::vector<bool> carried(static_cast<size_t>(lambda.size()), false);
  for (const ExponentialSeries& v : voltages) {
    double scale = 0.0;
    for (size_t i = 0; i < v.offset.size(); ++i)
      scale = std::max(
          scale, std::abs(v.offset[i]) +
                     (v.slope.empty() ? 0.0 : std::abs(v.slope[i])) * (edges[i + 1] - edges[i]) +
                     moduli(v.coefficient[i]).sum());
    for (const Eigen::VectorXcd& a : v.coefficient)
      for (Eigen::Index k = 0; k < a.size(); ++k)
        if (std::norm(a[k]) > kKeptPole * kKeptPole * scale * scale)
          carried[static_cast<size_t>(k)] = true;
  }
  SquareExponents exponents;
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
    if (carried[static_cast<size_t>(k)]) exponents.kept.push_back(k);
  const auto kept = static_cast<Eigen::Index>(exponents.kept.size());
  exponents.mu.resize(1 + kept + kept * (kept + 1) / 2);
  Eigen::Index m = 0;
  exponents.mu[m++] = 0.0;
  for (Eigen::Index k : exponents.kept) exponents.mu[m++] = lambda[k];
  for (Eigen::Index p = 0; p < kept; ++p)
    for (Eigen::Index q = p; q < kept; ++q)
      exponents.mu[m++] = lambda[exponents.kept[static_cast<size_t>(p)]] +
                          lambda[exponents.kept[static_cast<size_t>(q)]];
  return exponents;
}

std::vector<ExponentialSeries::ForcedTerms> squared_terms(const ExponentialSeries& voltage,
                                                          const SquareExponents& exponents) {
  const auto kept = static_cast<Eigen::Index>(exponents.kept.size());
  std::vector<ExponentialSeries::ForcedTerms> terms;
  for (size_t i = 0; i < voltage.offset.size(); ++i) {
    const double o = voltage.offset[i], s = voltage.slope.empty() ? 0.0 : voltage.slope[i];
    ExponentialSeries::ForcedTerms t = ExponentialSeries::ForcedTerms::Zero(exponents.mu.size(), 3);
    t.row(0) << o * o, 2.0 * o * s, s * s;
    Eigen::VectorXcd a(kept);
    for (Eigen::Index p = 0; p < kept; ++p)
      a[p] = voltage.coefficient[i][exponents.kept[static_cast<size_t>(p)]];
    for (Eigen::Index p = 0; p < kept; ++p) {
      t(1 + p, 0) = 2.0 * o * a[p];
      t(1 + p, 1) = 2.0 * s * a[p];
    }
    Eigen::Index m = 1 + kept;
    for (Eigen::Index p = 0; p < kept; ++p)
      for (Eigen::Index q = p; q < kept; ++q) t(m++, 0) = (p == q ? 1.0 : 2.0) * a[p] * a[q];
    terms.push_back(std::move(t));
  }
  return terms;
}

namespace {

// The forcing Σ_j m_kj·P_jm of every mode k on interval i: state_size × 3M, columns as
// ForcedModalResponse::coefficients.
Eigen::MatrixXcd modal_forcing_on(
    size_t i, const Eigen::MatrixXcd& modal_forcing,
    const std::vector<std::vector<ExponentialSeries::ForcedTerms>>& squares, Eigen::Index terms) {
  Eigen::MatrixXcd stacked(static_cast<Eigen::Index>(squares.size()), 3 * terms);
  for (size_t j = 0; j < squares.size(); ++j)
    for (Eigen::Index m = 0; m < terms; ++m)
      for (int d = 0; d < 3; ++d)
        stacked(static_cast<Eigen::Index>(j), 3 * m + d) = squares[j][i](m, d);
  return modal_forcing * stacked;
}

}  // namespace

Status forced_modal_response(
    const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
    const SquareExponents& exponents, const Eigen::MatrixXcd& modal_forcing,
    const std::vector<std::vector<ExponentialSeries::ForcedTerms>>& squares,
    const std::vector<bool>& fixed_at_zero, bool free_body, ForcedModalResponse& response) {
  const Eigen::Index n = lambda.size(), terms = exponents.mu.size();
  const size_t intervals = edges.size() - 1;
  const double period = edges.back();
  std::vector<Eigen::MatrixXcd> forcing;
  double largest = 0.0;
  for (size_t i = 0; i < intervals; ++i) {
    forcing.push_back(squares.empty() ? Eigen::MatrixXcd::Zero(n, 3 * terms)
                                      : modal_forcing_on(i, modal_forcing, squares, terms));
    largest = std::max(largest, std::sqrt(forcing.back().cwiseAbs2().maxCoeff()));
  }
  const double negligible = kNegligibleForcing * largest;
  response = {};
  for (size_t i = 0; i < intervals; ++i) {
    const double h = edges[i + 1] - edges[i];
    const Eigen::MatrixXcd& f = forcing[i];
    Eigen::MatrixXcd q = Eigen::MatrixXcd::Zero(n, 3 * terms);
    Eigen::VectorXcd start = Eigen::VectorXcd::Zero(n), end = Eigen::VectorXcd::Zero(n);
    const Eigen::VectorXcd growth = (exponents.mu * h).array().exp();  // e^{μ_m h}, once
    for (Eigen::Index k = 0; k < n; ++k) {
      const bool invariant =
          static_cast<size_t>(k) < fixed_at_zero.size() && fixed_at_zero[static_cast<size_t>(k)];
      for (Eigen::Index m = 0; m < terms; ++m) {
        const Complex f0 = f(k, 3 * m), f1 = f(k, 3 * m + 1), f2 = f(k, 3 * m + 2);
        auto size = [&] { return std::max({modulus(f0), modulus(f1), modulus(f2)}); };
        if (invariant) {
          if (free_body && size() > 1e-9 * largest)
            return Status::failure(
                "the network has a pole at s = 0 that the DEAs' force excites (a free body): no "
                "periodic state");
          continue;
        }
        const Complex gap = exponents.mu[m] - lambda[k];
        if (std::norm(gap) * period * period < kResonanceGap * kResonanceGap) {
          if (size() <= negligible) continue;
          return Status::failure(
              "a pole of the network (s = " + format_number("%.6g", lambda[k].real()) +
              (lambda[k].imag() < 0 ? " - " : " + ") +
              format_number("%.6g", std::abs(lambda[k].imag())) +
              "j 1/s) coincides with an exponent of the DEAs' squared voltages: the exact "
              "cascade would lose its accuracy to rounding there; the shooting method serves it");
        }
        // (μ − λ)·Q + Q' = F, from the top coefficient down.
        const Complex inverse = std::conj(gap) / std::norm(gap);
        const Complex q2 = f2 * inverse, q1 = (f1 - 2.0 * q2) * inverse, q0 = (f0 - q1) * inverse;
        q(k, 3 * m) = q0;
        q(k, 3 * m + 1) = q1;
        q(k, 3 * m + 2) = q2;
        start[k] += q0;
        end[k] += (q0 + h * (q1 + h * q2)) * growth[m];
      }
    }
    response.coefficients.push_back(std::move(q));
    response.start.push_back(std::move(start));
    response.end.push_back(std::move(end));
  }
  return Status::success();
}

}  // namespace emnet
