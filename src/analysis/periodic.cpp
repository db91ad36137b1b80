// Periodic steady state: exact (eigen-decomposed state equation) and shooting (IDA + Newton).
// See include/emnet/analysis/periodic.hpp for the method.
#include "emnet/analysis/periodic.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include "core/timed.hpp"
#include "displacement_form.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/units.hpp"
#include "exponential_series.hpp"
#include "state_space.hpp"

namespace emnet {

Status require_piecewise_linear(const System& system);  // transient_exact.cpp

namespace {

using Complex = std::complex<double>;

// Extremes of every probe over one period from samples (times, values), with the sampled
// extreme refined by `refine(probe, sample index, is_maximum)` → (time, value).
template <class Refine>
void fill_extremes(PeriodicResult& result, const Refine& refine) {
  const size_t probes = result.values.size();
  result.minimum.assign(probes, 0.0);
  result.maximum.assign(probes, 0.0);
  result.minimum_time.assign(probes, 0.0);
  result.maximum_time.assign(probes, 0.0);
  for (size_t p = 0; p < probes; ++p) {
    const auto& v = result.values[p];
    if (v.empty()) continue;
    const size_t low = static_cast<size_t>(std::min_element(v.begin(), v.end()) - v.begin());
    const size_t high = static_cast<size_t>(std::max_element(v.begin(), v.end()) - v.begin());
    std::tie(result.minimum_time[p], result.minimum[p]) = refine(p, low, false);
    std::tie(result.maximum_time[p], result.maximum[p]) = refine(p, high, true);
  }
}

}  // namespace

std::optional<System> steady_period_system(const System& system, double period) {
  double latest_delay = 0.0;
  bool shift = false;
  for (const Waveform& w : system.excitation().waveforms) {
    if (w.shape != Waveform::Shape::pulse || !(w.period > 0.0) || !(w.delay > 0.0)) continue;
    latest_delay = std::max(latest_delay, w.delay);
    // The pulse of the period before the delay reaches over t = 0 (beyond rounding), or the
    // first period has no pulse at all.
    const double reach = w.delay - w.period + w.rise + w.width + w.fall;
    shift |= reach > 1e-12 * w.period || w.delay >= w.period;
  }
  if (!shift) return std::nullopt;
  const double offset = std::ceil(latest_delay / period) * period;
  Excitation excitation = system.excitation();
  for (Waveform& w : excitation.waveforms)
    if (w.shape == Waveform::Shape::pulse && w.period > 0.0) w.delay -= offset;
  return system.with_excitation(std::move(excitation));
}

std::vector<double> constant_intervals(const System& system, double period) {
  std::vector<double> edges{0.0};
  for (double t : system.breakpoints(0.0, period))
    if (t < period * (1 - 1e-12)) edges.push_back(t);
  edges.push_back(period);
  return edges;
}

Status periodic_interval_starts(const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
                                const std::vector<Eigen::VectorXcd>& particular,
                                const std::vector<Eigen::VectorXcd>& particular_slope,
                                const std::vector<bool>& fixed_at_zero,
                                std::vector<Eigen::VectorXcd>& start_of, double& residual) {
  const size_t intervals = edges.size() - 1;
  auto advance = [&](const Eigen::VectorXcd& xi, size_t i) {
    const double h = edges[i + 1] - edges[i];
    // ξ_p(h) + e^{Λh}·(ξ − ξ_p(0)); ξ_p(h) = ξ_p(0) on a constant interval.
    const Eigen::VectorXcd particular_end =
        particular_slope.empty() ? particular[i]
                                 : Eigen::VectorXcd(particular[i] + h * particular_slope[i]);
    return Eigen::VectorXcd(particular_end +
                            ((lambda * h).array().exp() * (xi - particular[i]).array()).matrix());
  };
  Eigen::VectorXcd xi = Eigen::VectorXcd::Zero(lambda.size());
  for (size_t i = 0; i < intervals; ++i) xi = advance(xi, i);
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    if (static_cast<size_t>(k) < fixed_at_zero.size() && fixed_at_zero[static_cast<size_t>(k)]) {
      xi[k] = 0.0;  // a constraint's invariant: zero in every consistent state
      continue;
    }
    const Complex growth = 1.0 - std::exp(lambda[k] * edges.back());
    if (std::abs(growth) < 1e-14)
      return Status::failure(
          "an undamped mode is in exact resonance with the drive: no periodic state");
    xi[k] /= growth;
  }
  start_of.assign(intervals, {});
  for (size_t i = 0; i < intervals; ++i) {
    start_of[i] = xi;
    xi = advance(xi, i);
  }
  residual = (xi - start_of[0]).norm() / std::max(start_of[0].norm(), 1e-300);
  return check_residual(residual, "periodic state x(T) = x(0)");
}

void sample_periodic_series(const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
                            const std::vector<ExponentialSeries>& series, int samples,
                            PeriodicResult& result) {
  const double period = edges.back();
  const size_t intervals = edges.size() - 1;
  auto locate = [&](double t) {
    size_t i = 0;
    while (i + 1 < intervals && t >= edges[i + 1]) ++i;
    return i;
  };
  // The affine part's slope of probe p in interval i (0 where the sources are constant).
  auto slope_of = [&](size_t p, size_t i) {
    return series[p].slope.empty() ? 0.0 : series[p].slope[i];
  };
  // Where each term has decayed below rounding: beyond h = cutoff[p][i][k] the term
  // a_ik·e^{λ_k h} is smaller than 2⁻⁶⁰ of S_p = max_i (|p_i| + Σ_k |a_ik|), a bound on |p| and
  // on the sum's own rounding scale, so leaving it out changes a value by less than n·2⁻⁶⁰·S_p,
  // far below the n·2⁻⁵³·S_p rounding of the sum itself (Kelvin–Voigt damping makes the higher
  // modes decay fast: far from a switching edge a few terms are left).
  std::vector<std::vector<Eigen::VectorXd>> cutoff(series.size());
  for (size_t p = 0; p < series.size(); ++p) {
    double scale = 0.0;
    for (size_t i = 0; i < intervals; ++i)
      scale = std::max(scale,
                       std::abs(series[p].offset[i]) + series[p].coefficient[i].cwiseAbs().sum());
    const double negligible = std::ldexp(scale, -60);
    for (size_t i = 0; i < intervals; ++i) {
      Eigen::VectorXd after(lambda.size());
      for (Eigen::Index k = 0; k < lambda.size(); ++k) {
        const double size = std::abs(series[p].coefficient[i][k]);
        const double rate = -lambda[k].real();
        after[k] = size <= negligible ? -1.0
                   : rate > 0.0       ? std::log(size / negligible) / rate
                                      : std::numeric_limits<double>::infinity();
      }
      cutoff[p].push_back(std::move(after));
    }
  }
  // Conjugate pairs: a real output's terms over a pair of poles λ, λ̄ (adjacent and exactly
  // conjugate, as the real Schur form gives them) have conjugate coefficients, so their sum is
  // 2·Re of one of them: each evaluation takes one complex exponential per pair. Where a pair's
  // coefficients are not conjugate to 1e-12 of their size in every series (or the poles are not
  // paired), every term is taken as it is.
  std::vector<Eigen::Index> terms;
  std::vector<double> weights;
  conjugate_pairs(
      lambda,
      [&](Eigen::Index k) {
        for (const ExponentialSeries& s : series)
          for (size_t i = 0; i < intervals; ++i) {
            const Complex a = s.coefficient[i][k], b = s.coefficient[i][k + 1];
            if (!(std::abs(b - std::conj(a)) <= 1e-12 * std::abs(a))) return false;
          }
        return true;
      },
      terms, weights);
  // Value and two derivatives of probe p at offset h into interval i.
  auto evaluate = [&](size_t p, size_t i, double h, double* d1, double* d2) {
    const Eigen::VectorXcd& a = series[p].coefficient[i];
    const Eigen::VectorXd& after = cutoff[p][i];
    double sum = 0.0, first = 0.0, second = 0.0;
    for (size_t j = 0; j < terms.size(); ++j) {
      const Eigen::Index k = terms[j];
      if (h > after[k] && (weights[j] == 1.0 || h > after[k + 1])) continue;
      const Complex term = weights[j] * a[k] * std::exp(lambda[k] * h);
      sum += term.real();
      first += (term * lambda[k]).real();
      second += (term * lambda[k] * lambda[k]).real();
    }
    if (d1) *d1 = first + slope_of(p, i);
    if (d2) *d2 = second;
    return series[p].offset[i] + slope_of(p, i) * h + sum;
  };

  // The global extremes, not only the sampled ones. Inside interval i, for h ≥ a (the affine
  // part of a ramp has no curvature, so the bound is the exponentials' alone),
  // |p''(h)| ≤ K_i(a) = Σ_k |a_ik|·|λ_k|²·e^{Re λ_k·a} (Re λ_k ≤ 0), so on a gap [a, b] p exceeds
  // max(p(a), p(b)) by at most K_i(a)·(b − a)²/8. Gaps whose bound passes the best value found
  // are halved until it does not (to 1e-11 of the largest |p|), and the best point is then
  // polished by Newton on p'(t) = 0 to rounding. K_i(a) shrinks quickly away from a switching
  // edge, where the fast modes it excites have decayed. Measured: on the fish fin near its
  // resonance (ζ1 ≈ 0.015) Newton from the largest of 256 samples alone found a local maximum
  // 1.2e-5 below the global one, hidden between samples by a second mode's ripple.
  // The bound's terms |a_ik|·|λ_k|², one per term of `terms` (a pair's two added: they share
  // Re λ, so one exponential e^{Re λ·a} serves both), with those decay rates and |λ|.
  std::vector<std::vector<Eigen::VectorXd>> curvature_terms(series.size());
  Eigen::VectorXd decay(static_cast<Eigen::Index>(terms.size())),
      magnitude(static_cast<Eigen::Index>(terms.size()));
  for (size_t j = 0; j < terms.size(); ++j) {
    decay[static_cast<Eigen::Index>(j)] = lambda[terms[j]].real();
    magnitude[static_cast<Eigen::Index>(j)] = std::abs(lambda[terms[j]]);
  }
  for (size_t p = 0; p < series.size(); ++p)
    for (size_t i = 0; i < intervals; ++i) {
      const Eigen::VectorXd all =
          series[p].coefficient[i].cwiseAbs().cwiseProduct(lambda.cwiseAbs2());
      Eigen::VectorXd merged(static_cast<Eigen::Index>(terms.size()));
      for (size_t j = 0; j < terms.size(); ++j)
        merged[static_cast<Eigen::Index>(j)] =
            all[terms[j]] + (weights[j] == 2.0 ? all[terms[j] + 1] : 0.0);
      curvature_terms[p].push_back(std::move(merged));
    }

  // Uniform samples: inside an interval e^{λ(h+Δ)} = e^{λh}·e^{λΔ}, one exponential per
  // interval and per sample step instead of one per sample and probe (relative rounding grows
  // like the number of samples, ~1e-14 for 256).
  result.values.assign(series.size(), {});
  const double sample_step = period / samples;
  const Eigen::VectorXcd step_factor = (lambda * sample_step).array().exp();
  Eigen::VectorXcd e;
  size_t current = intervals;  // none yet
  double current_h = 0.0;
  for (int s = 0; s < samples; ++s) {
    const double t = period * s / samples;
    const size_t i = locate(t);
    const double h = t - edges[i];
    if (i != current || std::abs(h - (current_h + sample_step)) > 1e-9 * sample_step) {
      e = (lambda * h).array().exp();
    } else {
      e = e.cwiseProduct(step_factor);
    }
    current = i;
    current_h = h;
    result.times.push_back(t);
    for (size_t p = 0; p < series.size(); ++p)
      result.values[p].push_back(series[p].offset[i] + slope_of(p, i) * h +
                                 series[p].coefficient[i].cwiseProduct(e).sum().real());
  }
  fill_extremes(result, [&](size_t p, size_t sample, bool maximum) {
    const double sign = maximum ? 1.0 : -1.0;
    const auto& values = result.values[p];
    double largest = 0.0;
    for (double v : values) largest = std::max(largest, std::abs(v));
    const double tolerance = 1e-11 * largest;
    double best = sign * values[sample];
    size_t best_interval = locate(result.times[sample]);
    double best_h = result.times[sample] - edges[best_interval];
    struct Point {
      double h, value, curvature;  // offset into the interval, sign·p and K_i there (or −1)
    };
    struct Gap {
      size_t interval;
      Point left, right;
    };
    std::vector<Gap> gaps;
    gaps.reserve(result.times.size() + 2 * intervals + 64);
    for (size_t i = 0; i < intervals; ++i) {
      const double length = edges[i + 1] - edges[i];
      std::vector<Point> points{
          {0.0, sign * evaluate(p, i, 0.0, nullptr, nullptr), curvature_terms[p][i].sum()}};
      for (size_t s = 0; s < result.times.size(); ++s)
        if (result.times[s] > edges[i] && result.times[s] < edges[i + 1])
          points.push_back({result.times[s] - edges[i], sign * values[s], -1.0});
      points.push_back({length, sign * evaluate(p, i, length, nullptr, nullptr), 0.0});
      for (size_t k = 0; k + 1 < points.size(); ++k) gaps.push_back({i, points[k], points[k + 1]});
      for (const Point& point : points)
        if (point.value > best) best = point.value, best_interval = i, best_h = point.h;
    }
    // Newton on p'(h) = 0 from h in interval i. A local maximum of sign·p found inside the
    // interval also gives the window around it where p is concave (|p‴| ≤ J_i(a) =
    // Σ_k |a_ik|·|λ_k|³·e^{Re λ_k·a} for h ≥ a), in which it is the only maximum.
    struct Window {
      size_t interval;
      double low, high;
    };
    std::vector<Window> concave;
    auto polish = [&](size_t i, double h) {
      const double length = edges[i + 1] - edges[i];
      double d1 = 0.0, d2 = 0.0;
      for (int iteration = 0; iteration < 30; ++iteration) {
        evaluate(p, i, h, &d1, &d2);
        if (d2 == 0.0) break;
        const double next = std::clamp(h - d1 / d2, 0.0, length);
        if (std::abs(next - h) <= 1e-15 * length) break;
        h = next;
      }
      const double value = sign * evaluate(p, i, h, &d1, &d2);
      if (value > best) best = value, best_interval = i, best_h = h;
      if (h > 0.0 && h < length && sign * d2 < 0.0) {
        const double from = std::max(0.0, h - sample_step);
        const double third = curvature_terms[p][i].cwiseProduct(magnitude).dot(
            (decay * from).array().exp().matrix());
        const double radius = std::min(-sign * d2 / third, h - from);
        if (radius > 0.0) concave.push_back({i, h - radius, std::min(h + radius, length)});
      }
    };
    polish(best_interval, best_h);
    for (int evaluations = 0; !gaps.empty() && evaluations < 100000; ++evaluations) {
      Gap gap = gaps.back();
      gaps.pop_back();
      const double width = gap.right.h - gap.left.h;
      const double higher = std::max(gap.left.value, gap.right.value);
      if (width <= 1e-15 * period) continue;
      // K_i(0) first; K_i(a) (n exponentials) only when that bound does not settle the gap.
      const double widest = curvature_terms[p][gap.interval].sum();
      if (higher + widest * width * width / 8.0 <= best + tolerance) continue;
      bool inside = false;
      for (const Window& w : concave)
        inside |= w.interval == gap.interval && w.low <= gap.left.h && gap.right.h <= w.high;
      if (inside) continue;
      if (gap.left.curvature < 0.0)
        gap.left.curvature =
            curvature_terms[p][gap.interval].dot((decay * gap.left.h).array().exp().matrix());
      if (higher + gap.left.curvature * width * width / 8.0 <= best + tolerance) continue;
      // K_i(a) decreases with a: the left end's bound holds on both halves.
      const double h = 0.5 * (gap.left.h + gap.right.h);
      const Point middle{h, sign * evaluate(p, gap.interval, h, nullptr, nullptr),
                         gap.left.curvature};
      if (middle.value > best + tolerance) polish(gap.interval, h);
      if (middle.value > best) best = middle.value, best_interval = gap.interval, best_h = h;
      gaps.push_back({gap.interval, gap.left, middle});
      gaps.push_back({gap.interval, middle, gap.right});
    }
    double t = edges[best_interval] + best_h;
    if (t >= period) t -= period;
    return std::pair<double, double>(t, sign * best);
  });
}

struct PeriodicSolver::Impl {
  explicit Impl(const System& reference)
      : system(reference),
        form(system),
        space(form, characteristic_angular_frequency(system, 0.0)) {
    // Every pole (repeated semi-simple ones with an orthonormal eigenspace basis,
    // LinearStateSpace::ModalBasis::of); usable up to a vector condition of 1e12.
    LinearStateSpace::ModalBasis basis;
    LinearStateSpace::ModalBasis::of(space.m(), basis);
    lambda = basis.values;
    vectors = basis.vectors;
    vectors_lu = basis.vectors_lu;
    const double condition = basis.condition;
    if (!(condition < 1e12))
      throw std::runtime_error(
          "the state matrix is too close to defective for the exact "
          "periodic method (condition " +
          std::to_string(condition) +
          "); the shooting method (a periodic state by Newton on one period of IDA) does not "
          "need the decomposition");
    // Poles at s = 0: the invariants of differentiated constraints (zero for every consistent
    // state), or a free body when there are more of them than hidden constraints (solve()).
    invariant.assign(static_cast<size_t>(lambda.size()), false);
    for (Eigen::Index k = 0; k < lambda.size(); ++k)
      if ((invariant[static_cast<size_t>(k)] =
               std::abs(lambda[k]) < 1e-9 * lambda.cwiseAbs().maxCoeff()))
        ++zero_poles;
  }
  std::vector<bool> invariant;
  Eigen::Index zero_poles = 0;
  // Per probe seen so far (by name and terms), reused across solves: gᵀ·V, the probe's row on
  // the modal coordinates, and h, its row on the sources (p = gᵀ·x + h·f on a constant
  // interval).
  struct ProbeRows {
    Eigen::RowVectorXcd modes;
    Eigen::RowVectorXd sources;
  };
  mutable std::map<std::string, ProbeRows> probe_rows;
  // The state space's maps (u, u' and N·f as matrices) and V⁻¹·N, the sources' forcing in modal
  // coordinates (q = V⁻¹·N·f), made at the first solve.
  mutable LinearStateSpace::StateMaps maps;
  mutable Eigen::MatrixXcd modal_forcing;
  System system;
  DisplacementForm form;
  LinearStateSpace space;
  Eigen::VectorXcd lambda;
  Eigen::MatrixXcd vectors;
  Eigen::PartialPivLU<Eigen::MatrixXcd> vectors_lu;
};

PeriodicSolver::PeriodicSolver(const System& system) {
  try {
    impl_ = std::make_unique<Impl>(system);
  } catch (const std::exception& e) {
    status_ = Status::failure(e.what());
  }
}

PeriodicSolver::~PeriodicSolver() = default;

PeriodicResult PeriodicSolver::solve(const System& given, const std::vector<Probe>& probes,
                                     double period, int samples) const {
  const std::optional<System> steady = steady_period_system(given, period);
  const System& system = steady ? *steady : given;
  Timed<PeriodicResult> timed;
  PeriodicResult& result = timed.result;
  result.method = Method::exact;
  result.period = period;
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  if (!impl_) return finish(status_);
  if (Status pieces = require_piecewise_linear(system); !pieces.ok()) return finish(pieces);
  if (system.size() != impl_->system.size() || system.is_nonlinear())
    return finish(Status::failure("the network differs from the one the solver decomposed"));
  for (const Probe& probe : probes)
    if (!is_linear(probe))
      return finish(Status::failure("the exact periodic state takes linear outputs; probe '" +
                                    probe.name + "' squares a voltage"));
  const DisplacementForm& form = impl_->form;  // E, A and probes as for `system`
  const LinearStateSpace& space = impl_->space;
  const Eigen::VectorXcd& lambda = impl_->lambda;
  const Eigen::Index nd = space.state_size();

  // The intervals over one period on which the sources are affine, f = f₀,i + h·f₁,i, and the
  // particular state of each, affine too: in modal coordinates q = V⁻¹·N·f,
  // ξ_p,i(h) = a_i + h·b_i with b_i = −Λ⁻¹·q₁,i and a_i = −Λ⁻¹·(q₀,i − b_i) (b_i = 0 on a
  // constant interval, a_i = −Λ⁻¹·q₀,i as before).
  const std::vector<double> edges = constant_intervals(system, period);
  const size_t intervals = edges.size() - 1;
  std::vector<AffinePiece> f(intervals);
  std::vector<Eigen::VectorXcd> particular(intervals), particular_slope;
  bool any_ramp = false;
  for (size_t i = 0; i < intervals; ++i) {
    // this system's sources, as form.f would give them
    f[i] = affine_piece(system, form.size(), edges[i], edges[i + 1]);
    any_ramp |= f[i].ramp();
  }
  if (any_ramp) particular_slope.assign(intervals, Eigen::VectorXcd::Zero(nd));
  // Poles at s = 0 up to the number of hidden constraints are their invariants, which no drive
  // excites: whatever forcing reaches them is rounding (it grows with V's condition: 1.1e-9 of
  // the forcing's scale on the 100-segment fish fin). More zero poles than that mean a free body,
  // which has no periodic state when the drive reaches it.
  const bool free_body =
      impl_->zero_poles > static_cast<Eigen::Index>(form.hidden_constraints().size());
  const auto free_body_failure = Status::failure(
      "the network has a pole at s = 0 that the drive excites "
      "(a free body): no periodic state");
  if (impl_->modal_forcing.size() == 0) {
    impl_->maps = space.state_maps();
    impl_->modal_forcing = impl_->vectors_lu.solve(impl_->maps.forcing_matrix.cast<Complex>());
  }
  for (size_t i = 0; i < intervals; ++i) {
    const Eigen::VectorXcd modal_forcing = impl_->modal_forcing * f[i].start;
    particular[i] = Eigen::VectorXcd::Zero(nd);
    const double forcing_scale = modal_forcing.cwiseAbs().maxCoeff();
    for (Eigen::Index k = 0; k < nd; ++k) {
      if (!impl_->invariant[static_cast<size_t>(k)]) {
        particular[i][k] = -modal_forcing[k] / lambda[k];
      } else if (free_body && std::abs(modal_forcing[k]) > 1e-9 * forcing_scale) {
        return finish(free_body_failure);
      }
    }
    if (!f[i].ramp()) continue;
    const Eigen::VectorXcd modal_slope = impl_->modal_forcing * f[i].slope;
    const double slope_scale = modal_slope.cwiseAbs().maxCoeff();
    for (Eigen::Index k = 0; k < nd; ++k) {
      if (!impl_->invariant[static_cast<size_t>(k)]) {
        particular_slope[i][k] = -modal_slope[k] / lambda[k];
        particular[i][k] += particular_slope[i][k] / lambda[k];
      } else if (free_body && std::abs(modal_slope[k]) > 1e-9 * slope_scale) {
        return finish(free_body_failure);
      }
    }
  }
  std::vector<Eigen::VectorXcd> start_of;
  if (Status periodic =
          periodic_interval_starts(lambda, edges, particular, particular_slope, impl_->invariant,
                                   start_of, result.periodicity_residual);
      !periodic.ok())
    return finish(periodic);

  // Each probe is linear in (x, f, f'): p = gᵀx + c(f) + d(f'). In modal coordinates, inside
  // interval i, p(h) = p_i + s_i·h + Re Σ_k a_ik·e^{λ_k h} with a_ik = (gᵀV)_k·(ξ_i − a_i)_k,
  // p_i = p(V·a_i, f₀,i, f₁,i) and s_i = Re (gᵀV)·b_i + c(f₁,i).
  Eigen::VectorXd u, up;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(nd);
  const Eigen::VectorXd no_force = Eigen::VectorXd::Zero(form.size());
  auto probe_at = [&](const Probe& probe, const Eigen::VectorXd& x, const Eigen::VectorXd& fi) {
    space.full_state(x, fi, u, up);
    return form.probe(probe, u, up);
  };
  auto probe_on_ramp = [&](const Probe& probe, const Eigen::VectorXd& x, const AffinePiece& fi) {
    space.full_state(x, fi.start, fi.slope, u, up);
    return form.probe(probe, u, up);
  };
  std::vector<ExponentialSeries> series(probes.size());
  for (size_t p = 0; p < probes.size(); ++p) {
    // gᵀV depends on the probe and the decomposition only: computed once per solver.
    std::string key = probes[p].name + "/" + std::to_string(probes[p].integrations);
    for (const auto& [index, coefficient] : probes[p].terms)
      key += "/" + std::to_string(index) + ":" + std::to_string(coefficient);
    auto cached = impl_->probe_rows.find(key);
    if (cached == impl_->probe_rows.end()) {
      // The probe is linear in (u, u'): its value on each column of the maps.
      const LinearStateSpace::StateMaps& maps = impl_->maps;
      Eigen::VectorXd g(nd);
      for (Eigen::Index k = 0; k < nd; ++k)
        g[k] = form.probe(probes[p], maps.u_x.col(k), maps.up_x.col(k));
      Eigen::RowVectorXd sources(form.size());
      for (Eigen::Index j = 0; j < form.size(); ++j)
        sources[j] = form.probe(probes[p], maps.u_f.col(j), maps.up_f.col(j));
      cached = impl_->probe_rows
                   .emplace(key, Impl::ProbeRows{g.transpose().cast<Complex>() * impl_->vectors,
                                                 sources})
                   .first;
    }
    const Eigen::RowVectorXcd& g_modes = cached->second.modes;
    for (size_t i = 0; i < intervals; ++i) {
      if (!f[i].ramp()) {
        // gᵀ·Re(V·a) + h·f = Re(gᵀV·a) + h·f: the probe's rows, no state rebuilt.
        series[p].offset.push_back((g_modes * particular[i]).value().real() +
                                   cached->second.sources.dot(f[i].start));
        series[p].slope.push_back(0.0);
      } else {
        const Eigen::VectorXd x_particular = (impl_->vectors * particular[i]).real();
        series[p].offset.push_back(probe_on_ramp(probes[p], x_particular, f[i]));
        series[p].slope.push_back((g_modes * particular_slope[i]).value().real() +
                                  probe_at(probes[p], zero, f[i].slope));
      }
      series[p].coefficient.push_back(
          g_modes.transpose().cwiseProduct(start_of[i] - particular[i]));
    }
  }
  sample_periodic_series(lambda, edges, series, samples, result);
  return finish(Status::success());
}

namespace {

// A one-period run stopped by the caller's cancellation (its Status code), out of the shooting
// iteration.
struct ShootingCancelled {};

}  // namespace

PeriodicResult run_periodic_shooting(const System& given, const std::vector<Probe>& probes,
                                     double period, double rtol, int samples,
                                     const Progress* progress) {
  const std::optional<System> steady = steady_period_system(given, period);
  const System& system = steady ? *steady : given;
  Timed<PeriodicResult> timed;
  PeriodicResult& result = timed.result;
  result.method = Method::shooting;
  result.period = period;
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  try {
    const DisplacementForm form(system);
    std::vector<int> state;  // the differential unknowns
    for (int k = 0; k < form.size(); ++k)
      if (form.differential()[static_cast<size_t>(k)]) state.push_back(k);
    const Eigen::Index nd = static_cast<Eigen::Index>(state.size());
    // Consistent states satisfy the hidden constraints (rows the form differentiated); the
    // shooting variables ξ parametrise that subspace: x = P·ξ, P an orthonormal null-space basis.
    Eigen::MatrixXd constraints(static_cast<Eigen::Index>(form.hidden_constraints().size()), nd);
    {
      const Eigen::MatrixXd e = Eigen::MatrixXd(form.e());
      for (size_t r = 0; r < form.hidden_constraints().size(); ++r)
        for (Eigen::Index k = 0; k < nd; ++k)
          constraints(static_cast<Eigen::Index>(r), k) =
              e(form.hidden_constraints()[r], state[static_cast<size_t>(k)]);
    }
    Eigen::MatrixXd basis = Eigen::MatrixXd::Identity(nd, nd);
    if (constraints.rows() > 0) {
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(constraints, Eigen::ComputeFullV);
      Eigen::Index rank = 0;
      const auto& sv = svd.singularValues();
      while (rank < sv.size() && sv[rank] > 1e-12 * sv[0]) ++rank;
      basis = svd.matrixV().rightCols(nd - rank);
    }
    const Eigen::Index nv = basis.cols();
    CancellationOnly cancellation(progress);
    TransientOptions options;
    options.end_time = period;
    options.relative_tolerance = rtol;
    options.progress = &cancellation;
    auto one_period = [&](const Eigen::VectorXd& x0, Eigen::VectorXd& x_end) {
      options.initial_state = Eigen::VectorXd::Zero(form.size());
      for (Eigen::Index k = 0; k < nd; ++k)
        (*options.initial_state)[state[static_cast<size_t>(k)]] = x0[k];
      const TransientResult run = run_transient_ida(system, {}, options);
      if (run.status.cancelled()) throw ShootingCancelled{};
      if (!run.status.ok()) throw std::runtime_error(run.status.message);
      x_end.resize(nd);
      for (Eigen::Index k = 0; k < nd; ++k)
        x_end[k] = run.final_state[state[static_cast<size_t>(k)]];
    };
    Eigen::VectorXd xi = Eigen::VectorXd::Zero(nv), x = Eigen::VectorXd::Zero(nd), x_end;
    one_period(x, x_end);
    for (int iteration = 1; iteration <= 10; ++iteration) {
      result.newton_iterations = iteration;
      const Eigen::VectorXd residual = basis.transpose() * (x_end - x);
      // Jacobian of ξ ↦ Pᵀ(x(T) − x) by finite differences of one-period runs; a linear
      // network converges in one step, up to the integration error.
      const double scale = std::max(x_end.norm(), 1e-300);
      Eigen::MatrixXd jacobian(nv, nv);
      for (Eigen::Index k = 0; k < nv; ++k) {
        const double step = std::sqrt(rtol) * scale;
        const Eigen::VectorXd perturbed = x + step * basis.col(k);
        Eigen::VectorXd perturbed_end;
        one_period(perturbed, perturbed_end);
        jacobian.col(k) = (basis.transpose() * (perturbed_end - perturbed) - residual) / step;
      }
      const Eigen::VectorXd correction = jacobian.fullPivLu().solve(-residual);
      xi += correction;
      x = basis * xi;
      one_period(x, x_end);
      result.periodicity_residual = (x_end - x).norm() / std::max(x.norm(), 1e-300);
      if (correction.norm() <= 10 * rtol * std::max(xi.norm(), 1e-300)) break;
    }
    // One more period from the periodic state, sampled.
    options.initial_state = Eigen::VectorXd::Zero(form.size());
    for (Eigen::Index k = 0; k < nd; ++k)
      (*options.initial_state)[state[static_cast<size_t>(k)]] = x[k];
    for (int s = 0; s < samples; ++s) options.output_times.push_back(period * s / samples);
    if (Status periodic = check_residual(result.periodicity_residual, "shooting: x(T) = x(0)");
        !periodic.ok())
      return finish(periodic);
    const TransientResult run = run_transient_ida(system, probes, options);
    if (!run.status.ok()) return finish(run.status);
    result.times = run.times;
    result.values = run.values;
    // Sampled extremes refined by a parabola through the neighbouring samples.
    fill_extremes(result, [&](size_t p, size_t s, bool) {
      const auto& v = result.values[p];
      const size_t n = v.size();
      const double left = v[(s + n - 1) % n], middle = v[s], right = v[(s + 1) % n];
      const double curvature = left - 2 * middle + right;
      const double step = period / samples;
      if (curvature == 0.0) return std::pair<double, double>(result.times[s], middle);
      const double offset = 0.5 * (left - right) / curvature;
      return std::pair<double, double>(result.times[s] + offset * step,
                                       middle - 0.25 * (left - right) * offset);
    });
    return finish(Status::success());
  } catch (const ShootingCancelled&) {
    return finish(cancelled_status());
  } catch (const std::exception& e) {
    return finish(Status::failure(std::string("shooting: ") + e.what()));
  }
}

void check_periodic_memory(int unknowns, const std::string& field) {
  const double bytes = periodic_memory_bytes(unknowns);
  if (bytes <= kPeriodicDenseMemoryLimit) return;
  throw OptionError(field, "the exact periodic method decomposes a dense matrix of the network's " +
                               std::to_string(unknowns) + " unknowns: about " +
                               format_number("%.3g", bytes / 1e9) +
                               " GB (256 bytes per unknown squared), where at most " +
                               format_number("%.0f", kPeriodicDenseMemoryLimit / 1e9) +
                               " GB is allowed (inclusive); use fewer {" + field +
                               "}, the modal "
                               "reduction or the shooting method where the command has them");
}

}  // namespace emnet
