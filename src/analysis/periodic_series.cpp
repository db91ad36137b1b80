// Sampling and extremes of the periodic state's exponential series: see exponential_series.hpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "exponential_series.hpp"
#include "state_space.hpp"

namespace emnet {

namespace {

using Complex = std::complex<double>;

// The series of every probe with what evaluating them and bounding their curvature needs.
class SeriesEvaluator {
 public:
  SeriesEvaluator(const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
                  const std::vector<ExponentialSeries>& series,
                  const Eigen::VectorXcd& forced_exponents)
      : lambda_(lambda),
        mu_(forced_exponents),
        edges_(edges),
        series_(series),
        intervals_(edges.size() - 1) {
    find_cutoffs();
    pair_conjugates();
    form_curvature_terms();
    form_forced_bounds();
    // K_i(0), which the extremes search asks for every gap: summed once.
    widest_curvature_.assign(series_.size(), std::vector<double>(intervals_, 0.0));
    for (size_t p = 0; p < series_.size(); ++p)
      for (size_t i = 0; i < intervals_; ++i)
        widest_curvature_[p][i] =
            curvature_terms_[p][i].sum() + (has_forced(p) ? forced_curvature_[p][i].sum() : 0.0);
  }

  size_t intervals() const { return intervals_; }
  const std::vector<double>& edges() const { return edges_; }
  // One pole of each conjugate pair (and the real ones), with the factor 2 (or 1) of each.
  const std::vector<Eigen::Index>& terms() const { return terms_; }
  const std::vector<double>& weights() const { return weights_; }
  // The interval holding t.
  size_t locate(double t) const {
    size_t i = 0;
    while (i + 1 < intervals_ && t >= edges_[i + 1]) ++i;
    return i;
  }
  // The affine part's slope of probe p in interval i (0 where the sources are constant).
  double slope_of(size_t p, size_t i) const {
    return series_[p].slope.empty() ? 0.0 : series_[p].slope[i];
  }
  // Value and two derivatives of probe p at offset h into interval i.
  double evaluate(size_t p, size_t i, double h, double* d1, double* d2) const {
    const Eigen::VectorXcd& a = series_[p].coefficient[i];
    const Eigen::VectorXd& after = cutoff_[p][i];
    double sum = 0.0, first = 0.0, second = 0.0;
    for (size_t j = 0; j < terms_.size(); ++j) {
      const Eigen::Index k = terms_[j];
      if (h > after[k] && (weights_[j] == 1.0 || h > after[k + 1])) continue;
      const Complex term = weights_[j] * a[k] * std::exp(lambda_[k] * h);
      sum += term.real();
      first += (term * lambda_[k]).real();
      second += (term * lambda_[k] * lambda_[k]).real();
    }
    if (has_forced(p)) add_forced(p, i, h, sum, first, second);
    if (d1) *d1 = first + slope_of(p, i);
    if (d2) *d2 = second;
    return series_[p].offset[i] + slope_of(p, i) * h + sum;
  }
  // The forced part of probe p at offset h into interval i (no derivatives).
  double forced_value(size_t p, size_t i, double h) const {
    double sum = 0.0, first = 0.0, second = 0.0;
    if (has_forced(p)) add_forced(p, i, h, sum, first, second);
    return sum;
  }
  bool has_forced(size_t p) const { return !series_[p].forced.empty(); }
  // K_i(0) of probe p: the bound on |p''| over all of interval i.
  double widest_curvature(size_t p, size_t i) const { return widest_curvature_[p][i]; }
  // K_i(a) of probe p: the bound on |p''| in interval i for h ≥ a.
  double curvature_after(size_t p, size_t i, double a) const {
    double bound = curvature_terms_[p][i].dot((decay_ * a).array().exp().matrix());
    if (has_forced(p))
      bound += forced_curvature_[p][i].dot((forced_decay_ * a).array().exp().matrix());
    return bound;
  }
  // J_i(a) of probe p: the bound on |p‴| in interval i for h ≥ a.
  double third_derivative_after(size_t p, size_t i, double a) const {
    double bound =
        curvature_terms_[p][i].cwiseProduct(magnitude_).dot((decay_ * a).array().exp().matrix());
    if (has_forced(p)) bound += forced_third_[p][i].dot((forced_decay_ * a).array().exp().matrix());
    return bound;
  }

 private:
  // The forced terms' value and two derivatives at h, added to sum, first and second:
  // (C·e^{μh})' = (C' + μ·C)·e^{μh}, (C·e^{μh})'' = (C'' + 2μ·C' + μ²·C)·e^{μh}.
  void add_forced(size_t p, size_t i, double h, double& sum, double& first, double& second) const {
    const ExponentialSeries::ForcedTerms& c = series_[p].forced[i];
    for (Eigen::Index m = 0; m < mu_.size(); ++m) {
      // A real exponent (an RC loop's) needs no sine and cosine.
      const Complex mu = mu_[m],
                    e = mu.imag() == 0.0 ? Complex(std::exp(mu.real() * h)) : std::exp(mu * h);
      const Complex poly = c(m, 0) + h * (c(m, 1) + h * c(m, 2));
      const Complex slope = c(m, 1) + 2.0 * h * c(m, 2), curvature = 2.0 * c(m, 2);
      sum += (poly * e).real();
      first += ((slope + mu * poly) * e).real();
      second += ((curvature + 2.0 * mu * slope + mu * mu * poly) * e).real();
    }
  }

  // Bounds on the forced terms' second and third derivatives for h ≥ a in an interval of length
  // H: with |C^(j)(h)| ≤ Σ_{k≥j} k!/(k−j)!·|c_k|·H^{k−j} = C̄_j, |(C·e^{μh})''| ≤ (C̄₂ + 2|μ|·C̄₁
  // + |μ|²·C̄₀)·e^{Re μ·a} and |(C·e^{μh})‴| ≤ (3|μ|·C̄₂ + 3|μ|²·C̄₁ + |μ|³·C̄₀)·e^{Re μ·a}
  // (C‴ = 0). An exponent with Re μ > 0 (rounding of a sum of stable poles) is bounded at h = H.
  void form_forced_bounds() {
    forced_decay_ = Eigen::VectorXd::Zero(mu_.size());
    for (Eigen::Index m = 0; m < mu_.size(); ++m) forced_decay_[m] = std::min(mu_[m].real(), 0.0);
    forced_curvature_.assign(series_.size(), {});
    forced_third_.assign(series_.size(), {});
    for (size_t p = 0; p < series_.size(); ++p) {
      if (!has_forced(p)) continue;
      for (size_t i = 0; i < intervals_; ++i) {
        const double length = edges_[i + 1] - edges_[i];
        const ExponentialSeries::ForcedTerms& c = series_[p].forced[i];
        Eigen::VectorXd second(mu_.size()), third(mu_.size());
        for (Eigen::Index m = 0; m < mu_.size(); ++m) {
          const double c0 = std::abs(c(m, 0)), c1 = std::abs(c(m, 1)), c2 = std::abs(c(m, 2));
          const double bar0 = c0 + c1 * length + c2 * length * length;
          const double bar1 = c1 + 2.0 * c2 * length, bar2 = 2.0 * c2;
          const double r = std::abs(mu_[m]);
          const double growth = std::exp(std::max(mu_[m].real(), 0.0) * length);
          second[m] = (bar2 + 2.0 * r * bar1 + r * r * bar0) * growth;
          third[m] = (3.0 * r * bar2 + 3.0 * r * r * bar1 + r * r * r * bar0) * growth;
        }
        forced_curvature_[p].push_back(std::move(second));
        forced_third_[p].push_back(std::move(third));
      }
    }
  }

  // The largest |forced part| of probe p in interval i (a bound).
  double forced_scale(size_t p, size_t i) const {
    return has_forced(p) ? forced_bound(series_[p].forced[i], mu_, edges_[i + 1] - edges_[i]) : 0.0;
  }

  // Where each term has decayed below rounding: beyond h = cutoff[p][i][k] the term
  // a_ik·e^{λ_k h} is smaller than 2⁻⁶⁰ of S_p = max_i (|p_i| + Σ_k |a_ik|), a bound on |p| and
  // on the sum's own rounding scale, so leaving it out changes a value by less than n·2⁻⁶⁰·S_p,
  // far below the n·2⁻⁵³·S_p rounding of the sum itself (Kelvin–Voigt damping makes the higher
  // modes decay fast: far from a switching edge a few terms are left).
  void find_cutoffs() {
    cutoff_.assign(series_.size(), {});
    for (size_t p = 0; p < series_.size(); ++p) {
      double scale = 0.0;
      for (size_t i = 0; i < intervals_; ++i)
        scale = std::max(scale, std::abs(series_[p].offset[i]) +
                                    moduli(series_[p].coefficient[i]).sum() + forced_scale(p, i));
      const double negligible = std::ldexp(scale, -60);
      for (size_t i = 0; i < intervals_; ++i) {
        Eigen::VectorXd after(lambda_.size());
        for (Eigen::Index k = 0; k < lambda_.size(); ++k) {
          const double size = modulus(series_[p].coefficient[i][k]);
          const double rate = -lambda_[k].real();
          after[k] = size <= negligible ? -1.0
                     : rate > 0.0       ? std::log(size / negligible) / rate
                                        : std::numeric_limits<double>::infinity();
        }
        cutoff_[p].push_back(std::move(after));
      }
    }
  }

  // Conjugate pairs: a real output's terms over a pair of poles λ, λ̄ (adjacent and exactly
  // conjugate, as the real Schur form gives them) have conjugate coefficients, so their sum is
  // 2·Re of one of them: each evaluation takes one complex exponential per pair. Where a pair's
  // coefficients are not conjugate to 1e-12 of their size in every series (or the poles are not
  // paired), every term is taken as it is.
  void pair_conjugates() {
    conjugate_pairs(
        lambda_,
        [&](Eigen::Index k) {
          for (const ExponentialSeries& s : series_)
            for (size_t i = 0; i < intervals_; ++i) {
              const Complex a = s.coefficient[i][k], b = s.coefficient[i][k + 1];
              if (!(std::abs(b - std::conj(a)) <= 1e-12 * std::abs(a))) return false;
            }
          return true;
        },
        terms_, weights_);
  }

  // The curvature bound's terms |a_ik|·|λ_k|², one per term of `terms_` (a pair's two added:
  // they share Re λ, so one exponential e^{Re λ·a} serves both), with those decay rates and |λ|.
  void form_curvature_terms() {
    curvature_terms_.assign(series_.size(), {});
    decay_.resize(static_cast<Eigen::Index>(terms_.size()));
    magnitude_.resize(static_cast<Eigen::Index>(terms_.size()));
    for (size_t j = 0; j < terms_.size(); ++j) {
      decay_[static_cast<Eigen::Index>(j)] = lambda_[terms_[j]].real();
      magnitude_[static_cast<Eigen::Index>(j)] = std::abs(lambda_[terms_[j]]);
    }
    for (size_t p = 0; p < series_.size(); ++p)
      for (size_t i = 0; i < intervals_; ++i) {
        const Eigen::VectorXd all =
            moduli(series_[p].coefficient[i]).cwiseProduct(lambda_.cwiseAbs2());
        Eigen::VectorXd merged(static_cast<Eigen::Index>(terms_.size()));
        for (size_t j = 0; j < terms_.size(); ++j)
          merged[static_cast<Eigen::Index>(j)] =
              all[terms_[j]] + (weights_[j] == 2.0 ? all[terms_[j] + 1] : 0.0);
        curvature_terms_[p].push_back(std::move(merged));
      }
  }

  const Eigen::VectorXcd& lambda_;
  const Eigen::VectorXcd& mu_;  // the forced exponents
  const std::vector<double>& edges_;
  const std::vector<ExponentialSeries>& series_;
  size_t intervals_;
  std::vector<std::vector<Eigen::VectorXd>> cutoff_;
  std::vector<Eigen::Index> terms_;
  std::vector<double> weights_;
  std::vector<std::vector<Eigen::VectorXd>> curvature_terms_;
  std::vector<std::vector<double>> widest_curvature_;  // [probe][interval]: K_i(0)
  Eigen::VectorXd decay_, magnitude_;
  // Per probe and interval, per forced exponent: the bounds' factors on |p''| and |p‴|, and
  // min(Re μ, 0).
  std::vector<std::vector<Eigen::VectorXd>> forced_curvature_, forced_third_;
  Eigen::VectorXd forced_decay_;
};

// Uniform samples: inside an interval e^{λ(h+Δ)} = e^{λh}·e^{λΔ}, one exponential per
// interval and per sample step instead of one per sample and probe (relative rounding grows
// like the number of samples, ~1e-14 for 256). Over the evaluator's terms (one pole of each
// conjugate pair, factor 2), and only the real part of each product: a quarter of the
// arithmetic of the full complex sum.
void sample_uniformly(const SeriesEvaluator& evaluator, const Eigen::VectorXcd& lambda,
                      const std::vector<ExponentialSeries>& series, int samples,
                      PeriodicResult& result) {
  const std::vector<double>& edges = evaluator.edges();
  const double period = edges.back();
  const std::vector<Eigen::Index>& terms = evaluator.terms();
  const Eigen::Index count = static_cast<Eigen::Index>(terms.size());
  Eigen::VectorXcd half_lambda(count);
  Eigen::VectorXd factor(count);
  for (Eigen::Index j = 0; j < count; ++j) {
    half_lambda[j] = lambda[terms[static_cast<size_t>(j)]];
    factor[j] = evaluator.weights()[static_cast<size_t>(j)];
  }
  // Per probe and interval: factor·Re a and −factor·Im a of each term, so that a sample is
  // Re Σ factor·a·e = Σ (factor·Re a)·Re e + (−factor·Im a)·Im e.
  std::vector<std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>>> parts(series.size());
  for (size_t p = 0; p < series.size(); ++p)
    for (size_t i = 0; i < evaluator.intervals(); ++i) {
      Eigen::VectorXd real(count), imaginary(count);
      for (Eigen::Index j = 0; j < count; ++j) {
        const Complex a = series[p].coefficient[i][terms[static_cast<size_t>(j)]];
        real[j] = factor[j] * a.real();
        imaginary[j] = -factor[j] * a.imag();
      }
      parts[p].emplace_back(std::move(real), std::move(imaginary));
    }
  result.values.assign(series.size(), {});
  for (std::vector<double>& values : result.values) values.reserve(static_cast<size_t>(samples));
  result.times.reserve(static_cast<size_t>(samples));
  const double sample_step = period / samples;
  const Eigen::VectorXcd step_factor = (half_lambda * sample_step).array().exp();
  Eigen::VectorXcd e;
  size_t current = evaluator.intervals();  // none yet
  double current_h = 0.0;
  for (int s = 0; s < samples; ++s) {
    const double t = period * s / samples;
    const size_t i = evaluator.locate(t);
    const double h = t - edges[i];
    if (i != current || std::abs(h - (current_h + sample_step)) > 1e-9 * sample_step) {
      e = (half_lambda * h).array().exp();
    } else {
      e = e.cwiseProduct(step_factor);
    }
    current = i;
    current_h = h;
    result.times.push_back(t);
    for (size_t p = 0; p < series.size(); ++p) {
      const auto& [real, imaginary] = parts[p][i];
      result.values[p].push_back(series[p].offset[i] + evaluator.slope_of(p, i) * h +
                                 real.dot(e.real()) + imaginary.dot(e.imag()) +
                                 evaluator.forced_value(p, i, h));
    }
  }
}

// The global extreme of one probe, not only the sampled one. Inside interval i, for h ≥ a (the
// affine part of a ramp has no curvature, so the bound is the exponentials' alone),
// |p''(h)| ≤ K_i(a) = Σ_k |a_ik|·|λ_k|²·e^{Re λ_k·a} (Re λ_k ≤ 0), so on a gap [a, b] p exceeds
// max(p(a), p(b)) by at most K_i(a)·(b − a)²/8. Gaps whose bound passes the best value found
// are halved until it does not (to 1e-11 of the largest |p|), and the best point is then
// polished by Newton on p'(t) = 0 to rounding. K_i(a) shrinks quickly away from a switching
// edge, where the fast modes it excites have decayed. Measured: on the fish fin near its
// resonance (ζ1 ≈ 0.015) Newton from the largest of 256 samples alone found a local maximum
// 1.2e-5 below the global one, hidden between samples by a second mode's ripple.
class ExtremeSearch {
 public:
  // The maximum (`maximum`) or minimum of probe p, from its sampled extreme `sample`; the
  // samples `sample_step` apart.
  ExtremeSearch(const SeriesEvaluator& evaluator, const PeriodicResult& result, size_t p,
                size_t sample, bool maximum, double sample_step)
      : evaluator_(evaluator),
        result_(result),
        p_(p),
        sign_(maximum ? 1.0 : -1.0),
        period_(evaluator.edges().back()),
        sample_step_(sample_step) {
    double largest = 0.0;
    for (double v : result.values[p]) largest = std::max(largest, std::abs(v));
    tolerance_ = 1e-11 * largest;
    best_ = sign_ * result.values[p][sample];
    best_interval_ = evaluator.locate(result.times[sample]);
    best_h_ = result.times[sample] - evaluator.edges()[best_interval_];
  }

  // (time, value) of the extreme.
  std::pair<double, double> find() {
    seed_gaps();
    polish(best_interval_, best_h_);
    halve_gaps();
    double t = evaluator_.edges()[best_interval_] + best_h_;
    if (t >= period_) t -= period_;
    return {t, sign_ * best_};
  }

 private:
  struct Point {
    double h, value, curvature;  // offset into the interval, sign·p and K_i there (or −1)
  };
  struct Gap {
    size_t interval;
    Point left, right;
  };
  // Where sign·p is concave around a local maximum found by polish: its only maximum there.
  struct Window {
    size_t interval;
    double low, high;
  };

  void improve(double value, size_t interval, double h) {
    if (value > best_) best_ = value, best_interval_ = interval, best_h_ = h;
  }

  // The gaps between the interval ends and the samples inside each interval.
  void seed_gaps() {
    const std::vector<double>& edges = evaluator_.edges();
    const std::vector<double>& times = result_.times;
    const std::vector<double>& values = result_.values[p_];
    gaps_.reserve(times.size() + 2 * evaluator_.intervals() + 64);
    for (size_t i = 0; i < evaluator_.intervals(); ++i) {
      const double length = edges[i + 1] - edges[i];
      std::vector<Point> points{{0.0, sign_ * evaluator_.evaluate(p_, i, 0.0, nullptr, nullptr),
                                 evaluator_.widest_curvature(p_, i)}};
      for (size_t s = 0; s < times.size(); ++s)
        if (times[s] > edges[i] && times[s] < edges[i + 1])
          points.push_back({times[s] - edges[i], sign_ * values[s], -1.0});
      points.push_back({length, sign_ * evaluator_.evaluate(p_, i, length, nullptr, nullptr), 0.0});
      for (size_t k = 0; k + 1 < points.size(); ++k) gaps_.push_back({i, points[k], points[k + 1]});
      for (const Point& point : points)
        if (point.value > best_) best_ = point.value, best_interval_ = i, best_h_ = point.h;
    }
  }

  // Newton on p'(h) = 0 from h in interval i. A local maximum of sign·p found inside the
  // interval also gives the window around it where p is concave (|p‴| ≤ J_i(a) =
  // Σ_k |a_ik|·|λ_k|³·e^{Re λ_k·a} for h ≥ a), in which it is the only maximum.
  void polish(size_t i, double h) {
    const std::vector<double>& edges = evaluator_.edges();
    const double length = edges[i + 1] - edges[i];
    double d1 = 0.0, d2 = 0.0;
    for (int iteration = 0; iteration < 30; ++iteration) {
      evaluator_.evaluate(p_, i, h, &d1, &d2);
      if (d2 == 0.0) break;
      const double next = std::clamp(h - d1 / d2, 0.0, length);
      if (std::abs(next - h) <= 1e-15 * length) break;
      h = next;
    }
    const double value = sign_ * evaluator_.evaluate(p_, i, h, &d1, &d2);
    improve(value, i, h);
    if (h > 0.0 && h < length && sign_ * d2 < 0.0) {
      const double from = std::max(0.0, h - sample_step_);
      const double third = evaluator_.third_derivative_after(p_, i, from);
      const double radius = std::min(-sign_ * d2 / third, h - from);
      if (radius > 0.0) concave_.push_back({i, h - radius, std::min(h + radius, length)});
    }
  }

  // Halves every gap whose curvature bound could hide a value above the best one.
  void halve_gaps() {
    for (int evaluations = 0; !gaps_.empty() && evaluations < 100000; ++evaluations) {
      Gap gap = gaps_.back();
      gaps_.pop_back();
      const double width = gap.right.h - gap.left.h;
      const double higher = std::max(gap.left.value, gap.right.value);
      if (width <= 1e-15 * period_) continue;
      // K_i(0) first; K_i(a) (n exponentials) only when that bound does not settle the gap.
      const double widest = evaluator_.widest_curvature(p_, gap.interval);
      if (higher + widest * width * width / 8.0 <= best_ + tolerance_) continue;
      bool inside = false;
      for (const Window& w : concave_)
        inside |= w.interval == gap.interval && w.low <= gap.left.h && gap.right.h <= w.high;
      if (inside) continue;
      if (gap.left.curvature < 0.0)
        gap.left.curvature = evaluator_.curvature_after(p_, gap.interval, gap.left.h);
      if (higher + gap.left.curvature * width * width / 8.0 <= best_ + tolerance_) continue;
      // K_i(a) decreases with a: the left end's bound holds on both halves.
      const double h = 0.5 * (gap.left.h + gap.right.h);
      const Point middle{h, sign_ * evaluator_.evaluate(p_, gap.interval, h, nullptr, nullptr),
                         gap.left.curvature};
      if (middle.value > best_ + tolerance_) polish(gap.interval, h);
      improve(middle.value, gap.interval, h);
      gaps_.push_back({gap.interval, gap.left, middle});
      gaps_.push_back({gap.interval, middle, gap.right});
    }
  }

  const SeriesEvaluator& evaluator_;
  const PeriodicResult& result_;
  size_t p_;
  double sign_, period_, sample_step_, tolerance_ = 0.0;
  double best_ = 0.0;
  size_t best_interval_ = 0;
  double best_h_ = 0.0;
  std::vector<Gap> gaps_;
  std::vector<Window> concave_;
};

}  // namespace

double forced_bound(const ExponentialSeries::ForcedTerms& c, const Eigen::VectorXcd& mu,
                    double length) {
  double bound = 0.0;
  for (Eigen::Index m = 0; m < mu.size(); ++m)
    bound +=
        (std::abs(c(m, 0)) + std::abs(c(m, 1)) * length + std::abs(c(m, 2)) * length * length) *
        std::exp(std::max(mu[m].real(), 0.0) * length);
  return bound;
}

void sample_periodic_series(const Eigen::VectorXcd& lambda, const std::vector<double>& edges,
                            const std::vector<ExponentialSeries>& series, int samples,
                            PeriodicResult& result, const Eigen::VectorXcd& forced_exponents) {
  const SeriesEvaluator evaluator(lambda, edges, series, forced_exponents);
  sample_uniformly(evaluator, lambda, series, samples, result);
  const double sample_step = edges.back() / samples;
  fill_extremes(result, [&](size_t p, size_t sample, bool maximum) {
    return ExtremeSearch(evaluator, result, p, sample, maximum, sample_step).find();
  });
}

}  // namespace emnet
