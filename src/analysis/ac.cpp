// AC analysis: (G + J_g + jω·C)·Y = B_ac at every frequency; KLU (SuiteSparse's LU for
// circuit matrices) with the symbolic analysis done once for the sweep.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "complex_klu.hpp"
#include "core/timed.hpp"
#include "emnet/analysis/analysis.hpp"
#include "equilibration.hpp"

namespace emnet {

namespace {
constexpr double two_pi = 6.283185307179586476925286766559;

std::string hz(double f) {
  char text[40];
  std::snprintf(text, sizeof text, "%.9g Hz", f);
  return text;
}

// A failed Status when a probe's response is not finite (an overflow, a NaN in a coefficient):
// the AC result never carries one.
Status check_finite_response(const std::complex<double>& value, const Probe& probe, double f) {
  if (std::isfinite(value.real()) && std::isfinite(value.imag())) return Status::success();
  return Status::failure("non-finite result for an AC response: probe '" + probe.name +
                         "' at f = " + hz(f));
}
}  // namespace

std::vector<double> frequency_grid(double from, double to, int points, bool log) {
  std::vector<double> grid;
  if (points < 1) return grid;
  if (points == 1) return {from};
  for (int k = 0; k < points; ++k) {
    const double t = static_cast<double>(k) / (points - 1);
    grid.push_back(log ? from * std::pow(to / from, t) : from + (to - from) * t);
  }
  return grid;
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

AcResult run_ac(const System& system, const Eigen::VectorXd& operating_point,
                const std::vector<double>& frequencies, const std::vector<Probe>& given_probes,
                const AcOptions& options) {
  // The small-signal part of each probe (a square 2·k·u₀·U, emnet/network/output.hpp).
  std::vector<Probe> probes;
  for (const Probe& probe : given_probes)
    probes.push_back(linearised_probe(probe, operating_point));
  Timed<AcResult> timed;
  AcResult& result = timed.result;
  result.frequencies = frequencies;
  result.values.assign(probes.size(), {});
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  using ComplexMatrix = Eigen::SparseMatrix<std::complex<double>>;
  if (!keep_going(options.progress, 0, 0, "AC matrices: equilibration and KLU's symbolic analysis"))
    return finish(cancelled_status());
  const Eigen::SparseMatrix<double> g_matrix = linearised_g(system, operating_point);
  const Eigen::VectorXcd rhs = system.b_ac();
  const double rhs_norm = rhs.norm();
  if (rhs_norm == 0.0)
    return finish(Status::failure(
        "the scene has no AC excitation (no drive and no load): every response would be zero"));

  // The pattern of G + C, with explicit zeros where only one of them has an entry.
  const ComplexMatrix pattern_g = g_matrix.cast<std::complex<double>>();
  const ComplexMatrix pattern_c = system.C.cast<std::complex<double>>();
  // G and C on the common pattern (explicit zeros kept), so that each frequency only
  // rewrites the values: A(ω) = G + jω·C entry by entry.
  // Both equilibrated once for the sweep (rows R, columns D, equilibration.hpp): the solve is
  // R·A·D·ŷ = R·b, y = D·ŷ. Unscaled, KLU's answer near the fish fin's resonance at N = 2000
  // changed by 1.5 % between two pivot orders of equal residual.
  const DiagonalScaling scaling = equilibrate_pencil(g_matrix, system.C);
  ComplexMatrix g_aligned =
      scaled(g_matrix, scaling).cast<std::complex<double>>() + 0.0 * pattern_c;
  ComplexMatrix c_aligned =
      0.0 * pattern_g + scaled(system.C, scaling).cast<std::complex<double>>();
  const Eigen::VectorXcd scaled_rhs = scaling.row.cast<std::complex<double>>().cwiseProduct(rhs);
  const double scaled_rhs_norm = scaled_rhs.norm();
  g_aligned.makeCompressed();
  c_aligned.makeCompressed();
  ComplexMatrix matrix = g_aligned;
  ComplexKlu lu(matrix);
  double pivoted_residual = -1.0;  // none yet: the first frequency searches pivots

  std::unique_ptr<StaticOperator> static_operator;
  for (size_t step = 0; step < frequencies.size(); ++step) {
    if (!keep_going(options.progress, static_cast<long>(step),
                    static_cast<long>(frequencies.size()), "AC frequencies"))
      return finish(cancelled_status());
    const double f = frequencies[step];
    const double omega = two_pi * f;
    Eigen::VectorXcd y;
    if (omega == 0.0) {
      // Limit ω → 0: displacements from the static operator, velocities zero.
      if (!static_operator) static_operator = std::make_unique<StaticOperator>(system, g_matrix);
      Eigen::VectorXcd z;
      std::string why;
      if (static_operator->excites_divided_rows(rhs))
        return finish(Status::failure("at f = 0: a source drives a constant velocity"));
      if (!static_operator->solve(rhs, z, why)) return finish(Status::failure("at f = 0: " + why));
      const double residual =
          (static_operator->matrix().cast<std::complex<double>>() * z - rhs).norm() / rhs_norm;
      result.max_relative_residual = std::max(result.max_relative_residual, residual);
      if (Status accurate = check_residual(residual, "the AC solve at f = 0 (static limit)");
          !accurate.ok)
        return finish(accurate);
      for (size_t p = 0; p < probes.size(); ++p) {
        std::complex<double> sum = 0.0;
        for (const auto& [index, coefficient] : probes[p].terms) {
          const bool mech = static_operator->mechanical()[static_cast<size_t>(index)];
          if ((mech ? 1 : 0) - probes[p].integrations == 0) sum += coefficient * z[index];
        }
        if (Status finite = check_finite_response(sum, probes[p], f); !finite.ok)
          return finish(finite);
        result.values[p].push_back(sum);
      }
      continue;
    }
    const std::complex<double> j_omega(0.0, omega);
    for (Eigen::Index k = 0; k < matrix.nonZeros(); ++k)
      matrix.valuePtr()[k] = g_aligned.valuePtr()[k] + j_omega * c_aligned.valuePtr()[k];
    // Reused pivots first; a pivot search again when the residual is more than 4× that of the
    // last pivoted factorisation (and above rounding, 1e-13): the pivots went bad.
    double residual = 0.0;
    for (bool pivoting : {false, true}) {
      if (!lu.factor(matrix, pivoting)) {
        if (!pivoting) continue;
        return finish(Status::failure("the AC matrix is singular at f = " + hz(f) +
                                      " (an undamped pole exactly on the grid?)"));
      }
      y = scaled_rhs;
      if (!lu.solve(y) || !y.allFinite()) {
        if (!pivoting) continue;
        return finish(Status::failure("the AC solve gave non-finite values at f = " + hz(f)));
      }
      residual = (matrix * y - scaled_rhs).norm() / scaled_rhs_norm;
      if (pivoting) {
        pivoted_residual = residual;
        ++result.pivot_searches;
        break;
      }
      if (residual <= std::max(1e-13, 4 * pivoted_residual)) break;
    }
    result.max_relative_residual = std::max(result.max_relative_residual, residual);
    if (Status accurate = check_residual(residual, "the AC solve at f = " + hz(f)); !accurate.ok)
      return finish(accurate);
    y = scaling.column.cast<std::complex<double>>().cwiseProduct(y);
    for (size_t p = 0; p < probes.size(); ++p) {
      const std::complex<double> value = probe_phasor(probes[p], y, omega);
      if (Status finite = check_finite_response(value, probes[p], f); !finite.ok)
        return finish(finite);
      result.values[p].push_back(value);
    }
  }
  return finish(Status::success());
}

}  // namespace emnet
