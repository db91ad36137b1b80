// AC analysis: (G + J_g + jω·C)·Y = B_ac at every frequency; KLU (SuiteSparse's LU for
// circuit matrices) with the symbolic analysis done once for the sweep, or, for small networks,
// the pole–residue form (ac_pole_residue.hpp) checked against that direct solve.
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "ac_pole_residue.hpp"
#include "complex_klu.hpp"
#include "core/timed.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/core/units.hpp"
#include "equilibration.hpp"
#include "static_operator.hpp"

namespace emnet {

namespace {
constexpr double two_pi = 6.283185307179586476925286766559;

std::string hz(double f) {
  return format_number("%.9g Hz", f);
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

namespace {

// The direct solve (G + J_g + jω·C)·Y = B_ac at one frequency at a time, KLU's symbolic analysis
// done once: the probes' values and the relative residual.
class DirectAcSolver {
 public:
  DirectAcSolver(const System& system, const Eigen::VectorXd& operating_point,
                 const std::vector<Probe>& probes)
      : system_(system),
        probes_(probes),
        g_matrix_(linearised_g(system, operating_point)),
        rhs_(system.b_ac()),
        rhs_norm_(rhs_.norm()) {
    if (rhs_norm_ == 0.0) return;
    // The pattern of G + C, with explicit zeros where only one of them has an entry.
    const ComplexMatrix pattern_g = g_matrix_.cast<std::complex<double>>();
    const ComplexMatrix pattern_c = system.C.cast<std::complex<double>>();
    // G and C on the common pattern (explicit zeros kept), so that each frequency only
    // rewrites the values: A(ω) = G + jω·C entry by entry.
    // Both equilibrated once for the sweep (rows R, columns D, equilibration.hpp): the solve
    // is R·A·D·ŷ = R·b, y = D·ŷ. Unscaled, KLU's answer near the fish fin's resonance at
    // N = 2000 changed by 1.5 % between two pivot orders of equal residual.
    const DiagonalScaling scaling = equilibrate_pencil(g_matrix_, system.C);
    column_scale_ = scaling.column.cast<std::complex<double>>();
    g_aligned_ = scaled(g_matrix_, scaling).cast<std::complex<double>>() + 0.0 * pattern_c;
    c_aligned_ = 0.0 * pattern_g + scaled(system.C, scaling).cast<std::complex<double>>();
    scaled_rhs_ = scaling.row.cast<std::complex<double>>().cwiseProduct(rhs_);
    scaled_rhs_norm_ = scaled_rhs_.norm();
    g_aligned_.makeCompressed();
    c_aligned_.makeCompressed();
    matrix_ = g_aligned_;
    lu_ = std::make_unique<ComplexKlu>(matrix_);
  }
  bool excited() const { return rhs_norm_ != 0.0; }
  const Eigen::SparseMatrix<double>& g_matrix() const { return g_matrix_; }

  // The probes' values at f into `values`; `residual` the solve's relative residual.
  Status solve(double f, std::vector<std::complex<double>>& values, double& residual,
               int& pivot_searches) {
    values.assign(probes_.size(), 0.0);
    const double omega = two_pi * f;
    if (omega == 0.0) return solve_static_limit(f, values, residual);
    const std::complex<double> j_omega(0.0, omega);
    for (Eigen::Index k = 0; k < matrix_.nonZeros(); ++k)
      matrix_.valuePtr()[k] = g_aligned_.valuePtr()[k] + j_omega * c_aligned_.valuePtr()[k];
    // Reused pivots first; a pivot search again when the residual is more than 4× that of the
    // last pivoted factorisation (and above rounding, 1e-13): the pivots went bad.
    Eigen::VectorXcd y;
    for (bool pivoting : {false, true}) {
      if (!lu_->factor(matrix_, pivoting)) {
        if (!pivoting) continue;
        return Status::failure("the AC matrix is singular at f = " + hz(f) +
                               " (an undamped pole exactly on the grid?)");
      }
      y = scaled_rhs_;
      if (!lu_->solve(y) || !y.allFinite()) {
        if (!pivoting) continue;
        return Status::failure("the AC solve gave non-finite values at f = " + hz(f));
      }
      residual = (matrix_ * y - scaled_rhs_).norm() / scaled_rhs_norm_;
      if (pivoting) {
        pivoted_residual_ = residual;
        ++pivot_searches;
        break;
      }
      if (residual <= std::max(1e-13, 4 * pivoted_residual_)) break;
    }
    if (Status accurate = check_residual(residual, "the AC solve at f = " + hz(f)); !accurate.ok())
      return accurate;
    y = column_scale_.cwiseProduct(y);
    for (size_t p = 0; p < probes_.size(); ++p) {
      values[p] = probe_phasor(probes_[p], y, omega);
      if (Status finite = check_finite_response(values[p], probes_[p], f); !finite.ok())
        return finite;
    }
    return Status::success();
  }

 private:
  using ComplexMatrix = Eigen::SparseMatrix<std::complex<double>>;

  // Limit ω → 0: displacements from the static operator, velocities zero.
  Status solve_static_limit(double f, std::vector<std::complex<double>>& values, double& residual) {
    if (!static_operator_) static_operator_ = std::make_unique<StaticOperator>(system_, g_matrix_);
    Eigen::VectorXcd z;
    std::string why;
    if (static_operator_->excites_divided_rows(rhs_))
      return Status::failure("at f = 0: a source drives a constant velocity");
    if (!static_operator_->solve(rhs_, z, why)) return Status::failure("at f = 0: " + why);
    residual =
        (static_operator_->matrix().cast<std::complex<double>>() * z - rhs_).norm() / rhs_norm_;
    if (Status accurate = check_residual(residual, "the AC solve at f = 0 (static limit)");
        !accurate.ok())
      return accurate;
    for (size_t p = 0; p < probes_.size(); ++p) {
      std::complex<double> sum = 0.0;
      for (const auto& [index, coefficient] : probes_[p].terms) {
        const bool mech = static_operator_->mechanical()[static_cast<size_t>(index)];
        if ((mech ? 1 : 0) - probes_[p].integrations == 0) sum += coefficient * z[index];
      }
      if (Status finite = check_finite_response(sum, probes_[p], f); !finite.ok()) return finite;
      values[p] = sum;
    }
    return Status::success();
  }

  const System& system_;
  const std::vector<Probe>& probes_;
  Eigen::SparseMatrix<double> g_matrix_;
  Eigen::VectorXcd rhs_, scaled_rhs_, column_scale_;
  double rhs_norm_ = 0.0, scaled_rhs_norm_ = 0.0;
  ComplexMatrix g_aligned_, c_aligned_, matrix_;
  std::unique_ptr<ComplexKlu> lu_;
  double pivoted_residual_ = -1.0;  // none yet: the first frequency searches pivots
  std::unique_ptr<StaticOperator> static_operator_;
};

}  // namespace

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
  if (!keep_going(options.progress, 0, 0, "AC matrices: equilibration and KLU's symbolic analysis"))
    return finish(cancelled_status());
  auto direct = std::make_unique<DirectAcSolver>(system, operating_point, probes);
  if (!direct->excited())
    return finish(Status::failure(
        "the scene has no AC excitation (no drive and no load): every response would be zero"));
  std::vector<std::complex<double>> values;
  double residual = 0.0;

  const bool pole_residue =
      options.method == AcMethod::pole_residue ||
      (options.method == AcMethod::automatic && system.size() <= kPoleResidueUnknowns &&
       frequencies.size() >= kPoleResidueFrequencies);
  if (pole_residue) {
    if (!keep_going(options.progress, 0, 0, "AC: poles and residues"))
      return finish(cancelled_status());
    PoleResidueSweep sweep =
        pole_residue_sweep(system, operating_point, direct->g_matrix(), frequencies, probes);
    if (sweep.applies) {
      // Checked against the direct solve where its rounding is largest.
      std::vector<double> peak(probes.size(), 0.0);  // the largest |v|, from the largest |v|²
      for (size_t p = 0; p < probes.size(); ++p) {
        for (const auto& v : sweep.values[p]) peak[p] = std::max(peak[p], std::norm(v));
        peak[p] = std::sqrt(peak[p]);
      }
      double deviation = 0.0;
      const std::vector<size_t> points = pole_residue_check_points(sweep, frequencies);
      for (size_t index : points) {
        if (Status solved =
                direct->solve(frequencies[index], values, residual, result.pivot_searches);
            !solved.ok())
          return finish(solved);
        result.max_relative_residual = std::max(result.max_relative_residual, residual);
        for (size_t p = 0; p < probes.size(); ++p)
          if (peak[p] > 0.0)
            deviation = std::max(deviation, std::abs(sweep.values[p][index] - values[p]) / peak[p]);
      }
      result.check_points = static_cast<int>(points.size());
      result.check_deviation = deviation;
      result.basis_condition = sweep.basis_condition;
      if (deviation <= kPoleResidueAgreement) {
        result.method = Method::pole_residue;
        result.values = std::move(sweep.values);
        result.poles = std::move(sweep.poles);
        return finish(Status::success());
      }
      result.note = "the pole-residue form differed from the direct solve by " +
                    format_number("%.2g", deviation) +
                    " of the peak at its check points: solved directly";
    } else {
      result.note = "pole-residue form not used: " + sweep.why_not;
    }
    if (options.method == AcMethod::pole_residue) return finish(Status::failure(result.note));
  }

  result.method = Method::direct;
  result.check_points = 0;
  result.check_deviation = 0.0;
  result.max_relative_residual = 0.0;
  result.pivot_searches = 0;
  // A fresh solver, so that a fall-back sweep is the direct method's own (the check solves
  // would have left their pivots behind).
  if (pole_residue) direct = std::make_unique<DirectAcSolver>(system, operating_point, probes);
  for (size_t step = 0; step < frequencies.size(); ++step) {
    if (!keep_going(options.progress, static_cast<long>(step),
                    static_cast<long>(frequencies.size()), "AC frequencies"))
      return finish(cancelled_status());
    if (Status solved = direct->solve(frequencies[step], values, residual, result.pivot_searches);
        !solved.ok())
      return finish(solved);
    result.max_relative_residual = std::max(result.max_relative_residual, residual);
    for (size_t p = 0; p < probes.size(); ++p) result.values[p].push_back(values[p]);
  }
  return finish(Status::success());
}

}  // namespace emnet
