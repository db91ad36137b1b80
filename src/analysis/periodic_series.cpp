// Sampling and extremes of the periodic state's exponential series: see exponential_series.hpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
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
    form_bound_terms();
    form_forced_bounds();
    form_end_rows();
    // K_i(0) and M_i(0), which the extremes search asks for every gap: summed once.
    widest_curvature_.assign(series_.size(), std::vector<double>(intervals_, 0.0));
    widest_size_.assign(series_.size(), std::vector<double>(intervals_, 0.0));
    for (size_t p = 0; p < series_.size(); ++p)
      for (size_t i = 0; i < intervals_; ++i) {
        widest_curvature_[p][i] =
            curvature_terms_[p][i].sum() + (has_forced(p) ? forced_curvature_[p][i].sum() : 0.0);
        widest_size_[p][i] =
            size_terms_[p][i].sum() + (has_forced(p) ? forced_size_[p][i].sum() : 0.0);
      }
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
  // The length of a row of exponentials at one offset h: e^{λ_j·h} for each of `terms`, then
  // e^{μ_m·h} for each forced exponent.
  size_t row_width() const { return terms_.size() + static_cast<size_t>(mu_.size()); }
  // The row at h, from n complex exponentials (a real exponent's without sine and cosine).
  void fill_row(double h, Complex* row) const {
    for (size_t j = 0; j < terms_.size(); ++j) row[j] = std::exp(lambda_[terms_[j]] * h);
    for (Eigen::Index m = 0; m < mu_.size(); ++m)
      row[terms_.size() + static_cast<size_t>(m)] = forced_exponential(m, h);
  }
  // The row at h + Δ from the rows at h and at Δ: e^{λ(h+Δ)} = e^{λh}·e^{λΔ}, n products.
  void step_row(const Complex* at, const Complex* by, Complex* row) const {
    for (size_t k = 0; k < row_width(); ++k) row[k] = at[k] * by[k];
  }
  // Value and two derivatives (each may be null) of probe p at offset h into interval i, with
  // `row` the exponentials at h.
  double evaluate(size_t p, size_t i, double h, const Complex* row, double* d1, double* d2) const {
    const size_t forced = terms_.size();
    return evaluate_with(
        p, i, h, [row](size_t j) { return row[j]; },
        [row, forced](Eigen::Index m) { return row[forced + static_cast<size_t>(m)]; }, d1, d2);
  }
  // The same with the exponentials formed here, only for the terms that have not decayed.
  double evaluate(size_t p, size_t i, double h, double* d1, double* d2) const {
    return evaluate_with(
        p, i, h, [&](size_t j) { return std::exp(lambda_[terms_[j]] * h); },
        [&](Eigen::Index m) { return forced_exponential(m, h); }, d1, d2);
  }
  // The rows at the start (all 1) and the end of interval i.
  const Complex* start_row() const { return ones_.data(); }
  const Complex* end_row(size_t i) const { return end_rows_.data() + i * row_width(); }
  // The forced part of probe p at offset h into interval i (no derivatives), `forced` its
  // exponentials e^{μ_m·h}.
  double forced_value(size_t p, size_t i, double h, const Complex* forced) const {
    double sum = 0.0, first = 0.0, second = 0.0;
    if (has_forced(p))
      add_forced(
          p, i, h, [forced](Eigen::Index m) { return forced[m]; }, sum, first, second, false);
    return sum;
  }
  bool has_forced(size_t p) const { return !series_[p].forced.empty(); }
  // K_i(0) of probe p: the bound on |p''| over all of interval i.
  double widest_curvature(size_t p, size_t i) const { return widest_curvature_[p][i]; }
  // The bound of rise_after over all of interval i, whole terms only: every term by its
  // curvature or every term by its size, whichever is smaller (no exponentials).
  double widest_rise(size_t p, size_t i, double width) const {
    return std::min(widest_curvature_[p][i] * width * width / 8.0, 2.0 * widest_size_[p][i]);
  }
  // How far probe p can rise, on a gap [a, a + width] of interval i, above the larger of its
  // values at the gap's ends: each term either by its curvature bound (|term''|·width²/8) or by
  // twice its size (its share of the ends' values and of the value inside), whichever is
  // smaller. Also K_i(a) into `curvature`. The fast modes a switching edge excites have large
  // curvature and small size, so near an edge this bound is far below K_i(a)·width²/8.
  // `row`: the exponentials at a, whose moduli are the decays e^{Re λ·a} (a forced exponent
  // with Re μ > 0, bounded at the interval's end, is taken as 1).
  double rise_after(size_t p, size_t i, const Complex* row, double width, double& curvature) const {
    const double square = width * width / 8.0;
    double rise = 0.0;
    curvature = 0.0;
    const auto add = [&](const Eigen::VectorXd& curvatures, const Eigen::VectorXd& sizes,
                         const Complex* exponentials, const Eigen::VectorXd& decay) {
      for (Eigen::Index j = 0; j < curvatures.size(); ++j) {
        const double decayed = decay[j] < 0.0 ? modulus(exponentials[j]) : 1.0;
        curvature += curvatures[j] * decayed;
        rise += std::min(curvatures[j] * square, 2.0 * sizes[j]) * decayed;
      }
    };
    add(curvature_terms_[p][i], size_terms_[p][i], row, decay_);
    if (has_forced(p))
      add(forced_curvature_[p][i], forced_size_[p][i], row + terms_.size(), forced_decay_);
    return rise;
  }
  // J_i(a) of probe p: the bound on |p‴| in interval i for h ≥ a.
  double third_derivative_after(size_t p, size_t i, double a) const {
    double bound =
        curvature_terms_[p][i].cwiseProduct(magnitude_).dot((decay_ * a).array().exp().matrix());
    if (has_forced(p)) bound += forced_third_[p][i].dot((forced_decay_ * a).array().exp().matrix());
    return bound;
  }

 private:
  // evaluate with e^{λ_j·h} from exponential(j) (j over `terms`) and e^{μ_m·h} from
  // forced_exponential(m), each asked only for a term that has not decayed below rounding.
  template <class Exponential, class ForcedExponential>
  double evaluate_with(size_t p, size_t i, double h, const Exponential& exponential,
                       const ForcedExponential& forced_exponential, double* d1, double* d2) const {
    double sum = 0.0, first = 0.0, second = 0.0;
    const Eigen::VectorXcd& a = series_[p].coefficient[i];
    const Eigen::VectorXd& after = cutoff_[p][i];
    const bool derivatives = d1 || d2;
    for (size_t j = 0; j < terms_.size(); ++j) {
      const Eigen::Index k = terms_[j];
      if (h > after[k] && (weights_[j] == 1.0 || h > after[k + 1])) continue;
      const Complex term = weights_[j] * a[k] * exponential(j);
      sum += term.real();
      if (!derivatives) continue;
      first += (term * lambda_[k]).real();
      second += (term * lambda_[k] * lambda_[k]).real();
    }
    if (has_forced(p)) add_forced(p, i, h, forced_exponential, sum, first, second, derivatives);
    if (d1) *d1 = first + slope_of(p, i);
    if (d2) *d2 = second;
    return series_[p].offset[i] + slope_of(p, i) * h + sum;
  }

  // e^{μ_m·h}; a real exponent (an RC loop's) needs no sine and cosine.
  Complex forced_exponential(Eigen::Index m, double h) const {
    const Complex mu = mu_[m];
    return mu.imag() == 0.0 ? Complex(std::exp(mu.real() * h)) : std::exp(mu * h);
  }

  // The rows at each interval's start (all 1) and end.
  void form_end_rows() {
    ones_.assign(row_width(), Complex(1.0));
    end_rows_.resize(intervals_ * row_width());
    for (size_t i = 0; i < intervals_; ++i)
      fill_row(edges_[i + 1] - edges_[i], end_rows_.data() + i * row_width());
  }

  // The forced terms' value and two derivatives at h, added to sum, first and second, from
  // their exponentials e^{μ_m·h} (`forced`): (C·e^{μh})' = (C' + μ·C)·e^{μh},
  // (C·e^{μh})'' = (C'' + 2μ·C' + μ²·C)·e^{μh}.
  template <class ForcedExponential>
  void add_forced(size_t p, size_t i, double h, const ForcedExponential& forced, double& sum,
                  double& first, double& second, bool derivatives = true) const {
    const ExponentialSeries::ForcedTerms& c = series_[p].forced[i];
    for (Eigen::Index m = 0; m < mu_.size(); ++m) {
      const Complex mu = mu_[m], e = forced(m);
      const Complex poly = c(m, 0) + h * (c(m, 1) + h * c(m, 2));
      sum += (poly * e).real();
      if (!derivatives) continue;
      const Complex slope = c(m, 1) + 2.0 * h * c(m, 2), curvature = 2.0 * c(m, 2);
      first += ((slope + mu * poly) * e).real();
      second += ((curvature + 2.0 * mu * slope + mu * mu * poly) * e).real();
    }
  }

  // Bounds on the forced terms' size, second and third derivatives for h ≥ a in an interval of
  // length H: with |C^(j)(h)| ≤ Σ_{k≥j} k!/(k−j)!·|c_k|·H^{k−j} = C̄_j, |C·e^{μh}| ≤
  // C̄₀·e^{Re μ·a}, |(C·e^{μh})''| ≤ (C̄₂ + 2|μ|·C̄₁ + |μ|²·C̄₀)·e^{Re μ·a} and |(C·e^{μh})‴| ≤
  // (3|μ|·C̄₂ + 3|μ|²·C̄₁ + |μ|³·C̄₀)·e^{Re μ·a} (C‴ = 0). An exponent with Re μ > 0 (rounding of
  // a sum of stable poles) is bounded at h = H.
  void form_forced_bounds() {
    forced_decay_ = Eigen::VectorXd::Zero(mu_.size());
    for (Eigen::Index m = 0; m < mu_.size(); ++m) forced_decay_[m] = std::min(mu_[m].real(), 0.0);
    forced_size_.assign(series_.size(), {});
    forced_curvature_.assign(series_.size(), {});
    forced_third_.assign(series_.size(), {});
    for (size_t p = 0; p < series_.size(); ++p) {
      if (!has_forced(p)) continue;
      for (size_t i = 0; i < intervals_; ++i) {
        const double length = edges_[i + 1] - edges_[i];
        const ExponentialSeries::ForcedTerms& c = series_[p].forced[i];
        Eigen::VectorXd size(mu_.size()), second(mu_.size()), third(mu_.size());
        for (Eigen::Index m = 0; m < mu_.size(); ++m) {
          const double c0 = std::abs(c(m, 0)), c1 = std::abs(c(m, 1)), c2 = std::abs(c(m, 2));
          const double bar0 = c0 + c1 * length + c2 * length * length;
          const double bar1 = c1 + 2.0 * c2 * length, bar2 = 2.0 * c2;
          const double r = std::abs(mu_[m]);
          const double growth = std::exp(std::max(mu_[m].real(), 0.0) * length);
          size[m] = bar0 * growth;
          second[m] = (bar2 + 2.0 * r * bar1 + r * r * bar0) * growth;
          third[m] = (3.0 * r * bar2 + 3.0 * r * r * bar1 + r * r * r * bar0) * growth;
        }
        forced_size_[p].push_back(std::move(size));
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

  // The bounds' terms: |a_ik| (size) and |a_ik|·|λ_k|² (curvature), one per term of `terms_`
  // (a pair's two added: they share Re λ, so one exponential e^{Re λ·a} serves both), with
  // those decay rates and |λ|.
  void form_bound_terms() {
    size_terms_.assign(series_.size(), {});
    curvature_terms_.assign(series_.size(), {});
    decay_.resize(static_cast<Eigen::Index>(terms_.size()));
    magnitude_.resize(static_cast<Eigen::Index>(terms_.size()));
    for (size_t j = 0; j < terms_.size(); ++j) {
      decay_[static_cast<Eigen::Index>(j)] = lambda_[terms_[j]].real();
      magnitude_[static_cast<Eigen::Index>(j)] = std::abs(lambda_[terms_[j]]);
    }
    for (size_t p = 0; p < series_.size(); ++p)
      for (size_t i = 0; i < intervals_; ++i) {
        const Eigen::VectorXd size = moduli(series_[p].coefficient[i]);
        const Eigen::VectorXd curvature = size.cwiseProduct(lambda_.cwiseAbs2());
        const auto merged = [&](const Eigen::VectorXd& all) {
          Eigen::VectorXd one_per_term(static_cast<Eigen::Index>(terms_.size()));
          for (size_t j = 0; j < terms_.size(); ++j)
            one_per_term[static_cast<Eigen::Index>(j)] =
                all[terms_[j]] + (weights_[j] == 2.0 ? all[terms_[j] + 1] : 0.0);
          return one_per_term;
        };
        size_terms_[p].push_back(merged(size));
        curvature_terms_[p].push_back(merged(curvature));
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
  std::vector<std::vector<Eigen::VectorXd>> size_terms_, curvature_terms_;
  std::vector<std::vector<double>> widest_curvature_, widest_size_;  // [probe][interval] at 0
  Eigen::VectorXd decay_, magnitude_;
  std::vector<Complex> ones_, end_rows_;  // the rows at h = 0 and each interval's end
  // Per probe and interval, per forced exponent: the bounds' factors on |p|, |p''| and |p‴|,
  // and min(Re μ, 0).
  std::vector<std::vector<Eigen::VectorXd>> forced_size_, forced_curvature_, forced_third_;
  Eigen::VectorXd forced_decay_;
};

// Rows of exponentials (SeriesEvaluator::row_width long) handed out by pointer and kept while
// the pool lives: blocks of 64 rows, so that a row stays where it is as more are added.
class RowPool {
 public:
  explicit RowPool(size_t width) : width_(std::max<size_t>(width, 1)) {}
  Complex* add() {
    if (used_ == kRowsPerBlock) {
      blocks_.push_back(std::make_unique<Complex[]>(width_ * kRowsPerBlock));
      used_ = 0;
    }
    return blocks_.back().get() + width_ * used_++;
  }

 private:
  static constexpr size_t kRowsPerBlock = 64;
  size_t width_, used_ = kRowsPerBlock;
  std::vector<std::unique_ptr<Complex[]>> blocks_;
};

// The rows of one periodic solve: one per sample, and the steps e^{λΔ} by which the extremes
// search reaches a gap's middle from its left end (found by Δ to 1e-9 of it, and shared by
// every probe's search: the gaps of the sample grid halve alike).
class SolveRows {
 public:
  explicit SolveRows(const SeriesEvaluator& evaluator)
      : evaluator_(evaluator), pool_(evaluator.row_width()) {}
  RowPool& pool() { return pool_; }
  std::vector<const Complex*>& samples() { return samples_; }
  const std::vector<const Complex*>& samples() const { return samples_; }
  // The row e^{λΔ} of a step Δ within 1e-9·step of `step`, and that Δ.
  std::pair<const Complex*, double> step(double step) {
    for (const auto& [delta, row] : steps_)
      if (std::abs(delta - step) <= 1e-9 * step) return {row, delta};
    Complex* row = pool_.add();
    evaluator_.fill_row(step, row);
    steps_.emplace_back(step, row);
    return {row, step};
  }

 private:
  const SeriesEvaluator& evaluator_;
  RowPool pool_;
  std::vector<const Complex*> samples_;
  std::vector<std::pair<double, const Complex*>> steps_;
};

// Uniform samples: inside an interval e^{λ(h+Δ)} = e^{λh}·e^{λΔ}, one exponential per
// interval and per sample step instead of one per sample and probe (relative rounding grows
// like the number of samples, ~1e-14 for 256); the rows are kept for the extremes search. Over
// the evaluator's terms (one pole of each conjugate pair, factor 2), and only the real part of
// each product: a quarter of the arithmetic of the full complex sum.
void sample_uniformly(const SeriesEvaluator& evaluator,
                      const std::vector<ExponentialSeries>& series, int samples,
                      PeriodicResult& result, SolveRows& rows) {
  const std::vector<double>& edges = evaluator.edges();
  const double period = edges.back();
  const std::vector<Eigen::Index>& terms = evaluator.terms();
  const Eigen::Index count = static_cast<Eigen::Index>(terms.size());
  const Eigen::Index probes = static_cast<Eigen::Index>(series.size());
  // Per interval, a row per probe: factor·Re a and −factor·Im a of each term, so that the
  // samples of every probe are Re Σ factor·a·e = real·Re e + imaginary·Im e, two
  // matrix-vector products.
  std::vector<std::pair<Eigen::MatrixXd, Eigen::MatrixXd>> parts;
  for (size_t i = 0; i < evaluator.intervals(); ++i) {
    Eigen::MatrixXd real(probes, count), imaginary(probes, count);
    for (Eigen::Index p = 0; p < probes; ++p)
      for (Eigen::Index j = 0; j < count; ++j) {
        const double factor = evaluator.weights()[static_cast<size_t>(j)];
        const Complex a =
            series[static_cast<size_t>(p)].coefficient[i][terms[static_cast<size_t>(j)]];
        real(p, j) = factor * a.real();
        imaginary(p, j) = -factor * a.imag();
      }
    parts.emplace_back(std::move(real), std::move(imaginary));
  }
  result.values.assign(series.size(), {});
  for (std::vector<double>& values : result.values) values.reserve(static_cast<size_t>(samples));
  result.times.reserve(static_cast<size_t>(samples));
  rows.samples().reserve(static_cast<size_t>(samples));
  const double sample_step = period / samples;
  Complex* step_row = rows.pool().add();
  evaluator.fill_row(sample_step, step_row);
  const Complex* previous = nullptr;
  size_t current = evaluator.intervals();  // none yet
  double current_h = 0.0;
  Eigen::VectorXd real_e(count), imaginary_e(count), sums(probes);
  for (int s = 0; s < samples; ++s) {
    const double t = period * s / samples;
    const size_t i = evaluator.locate(t);
    const double h = t - edges[i];
    Complex* row = rows.pool().add();
    if (i != current || std::abs(h - (current_h + sample_step)) > 1e-9 * sample_step)
      evaluator.fill_row(h, row);
    else
      evaluator.step_row(previous, step_row, row);
    previous = row;
    rows.samples().push_back(row);
    current = i;
    current_h = h;
    result.times.push_back(t);
    for (Eigen::Index j = 0; j < count; ++j) {
      real_e[j] = row[j].real();
      imaginary_e[j] = row[j].imag();
    }
    sums.noalias() = parts[i].first * real_e;
    sums.noalias() += parts[i].second * imaginary_e;
    for (size_t p = 0; p < series.size(); ++p)
      result.values[p].push_back(series[p].offset[i] + evaluator.slope_of(p, i) * h +
                                 sums[static_cast<Eigen::Index>(p)] +
                                 evaluator.forced_value(p, i, h, row + count));
  }
}

// The global extremes of one probe, not only the sampled ones. Inside interval i, for h ≥ a
// (the affine part of a ramp has no curvature, so the bound is the exponentials' alone),
// |p''(h)| ≤ K_i(a) = Σ_k |a_ik|·|λ_k|²·e^{Re λ_k·a} (Re λ_k ≤ 0), so on a gap [a, b] p exceeds
// max(p(a), p(b)) by at most K_i(a)·(b − a)²/8. Split p into terms S bounded so and terms F
// bounded by their size M_F(a) = Σ_F |a_ik|·e^{Re λ_k·a}: p = s + f exceeds max(p(a), p(b)) by
// at most K_S(a)·(b − a)²/8 + 2·M_F(a) (f shifts the ends' values by M_F at most, and the value
// inside by M_F again). Each term goes where its share is smaller (rise_after): right after a
// switching edge the fast modes it excites curve hard but are small, and K_i(a)·(b − a)²/8
// alone would halve the gaps there until they decay. The same bound holds for −p, so the
// maximum and the minimum are searched together, on one set of gaps: a gap is halved while its
// bound could hide a value past either best value found (to 1e-11 of the largest |p|), and each
// best point is polished by Newton on p'(t) = 0 to rounding. Measured: on the fish fin near its
// resonance (ζ1 ≈ 0.015) Newton from the largest of 256 samples alone found a local maximum
// 1.2e-5 below the global one, hidden between samples by a second mode's ripple.
class ExtremesSearch {
 public:
  // The extremes of probe p, from its sampled minimum and maximum (sample indices); the samples
  // `sample_step` apart.
  ExtremesSearch(const SeriesEvaluator& evaluator, const PeriodicResult& result, SolveRows& rows,
                 size_t p, size_t lowest, size_t highest, double sample_step)
      : evaluator_(evaluator),
        result_(result),
        rows_(rows),
        p_(p),
        period_(evaluator.edges().back()),
        sample_step_(sample_step) {
    double largest = 0.0;
    for (double v : result.values[p]) largest = std::max(largest, std::abs(v));
    tolerance_ = 1e-11 * largest;
    sides_[0].sign = -1.0;
    for (Side& side : sides_) {
      const size_t sample = side.sign > 0.0 ? highest : lowest;
      side.best = side.sign * result.values[p][sample];
      side.interval = evaluator.locate(result.times[sample]);
      side.h = result.times[sample] - evaluator.edges()[side.interval];
    }
  }

  // (time, value) of the minimum and of the maximum.
  std::array<std::pair<double, double>, 2> find() {
    seed_gaps();
    for (size_t s = 0; s < 2; ++s) polish(s, sides_[s].interval, sides_[s].h);
    halve_gaps();
    std::array<std::pair<double, double>, 2> out;
    for (size_t s = 0; s < 2; ++s) {
      const Side& side = sides_[s];
      double t = evaluator_.edges()[side.interval] + side.h;
      if (t >= period_) t -= period_;
      out[s] = {t, side.sign * side.best};
    }
    return out;
  }

 private:
  // Where sign·p is concave around a local maximum found by polish: its only maximum there.
  struct Window {
    size_t interval;
    double low, high;
  };
  // The minimum (sign −1: the maximum of −p) or the maximum: the best sign·p found and where.
  struct Side {
    double sign = 1.0;
    double best = 0.0;
    size_t interval = 0;
    double h = 0.0;
    std::vector<Window> concave;
  };
  struct Point {
    double h, value, curvature;  // offset into the interval, p and K_i there (or −1)
    const Complex* row;          // the exponentials at h
  };
  // `rise`: a bound on |p| past the ends' values, from rise_after on this gap or on one holding
  // it (a narrower gap further from the edge has a smaller bound); `own`: made for this gap
  // itself, so that halving rather than forming it again is what can lower it. `open`: the
  // sides (bit 0 the minimum, bit 1 the maximum) whose bound this gap has yet to settle.
  struct Gap {
    size_t interval;
    Point left, right;
    double rise = std::numeric_limits<double>::infinity();
    bool own = false;
    unsigned open = 3;
  };

  // A value of p found at h in interval i, for both sides.
  void improve(double value, size_t interval, double h) {
    for (Side& side : sides_)
      if (side.sign * value > side.best)
        side.best = side.sign * value, side.interval = interval, side.h = h;
  }

  // The gaps between the interval ends and the samples inside each interval.
  void seed_gaps() {
    const std::vector<double>& edges = evaluator_.edges();
    const std::vector<double>& times = result_.times;
    const std::vector<double>& values = result_.values[p_];
    gaps_.reserve(times.size() + 2 * evaluator_.intervals() + 64);
    size_t sample = 0;  // the samples are in time order
    for (size_t i = 0; i < evaluator_.intervals(); ++i) {
      const double length = edges[i + 1] - edges[i];
      const Complex* start = evaluator_.start_row();
      Point left{0.0, evaluator_.evaluate(p_, i, 0.0, start, nullptr, nullptr),
                 evaluator_.widest_curvature(p_, i), start};
      improve(left.value, i, 0.0);
      while (sample < times.size() && times[sample] <= edges[i]) ++sample;
      for (; sample < times.size() && times[sample] < edges[i + 1]; ++sample) {
        const Point point{times[sample] - edges[i], values[sample], -1.0, rows_.samples()[sample]};
        gaps_.push_back({i, left, point});
        left = point;
      }
      const Complex* end = evaluator_.end_row(i);
      const Point right{length, evaluator_.evaluate(p_, i, length, end, nullptr, nullptr), 0.0,
                        end};
      improve(right.value, i, length);
      gaps_.push_back({i, left, right});
    }
  }

  // Newton on p'(h) = 0 from h in interval i, for side s. A local maximum of sign·p found
  // inside the interval also gives the window around it where sign·p is concave (|p‴| ≤
  // J_i(a) = Σ_k |a_ik|·|λ_k|³·e^{Re λ_k·a} for h ≥ a), in which it is the only maximum.
  void polish(size_t s, size_t i, double h) {
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
    const double value = evaluator_.evaluate(p_, i, h, &d1, &d2);
    improve(value, i, h);
    Side& side = sides_[s];
    if (h > 0.0 && h < length && side.sign * d2 < 0.0) {
      const double from = std::max(0.0, h - sample_step_);
      const double third = evaluator_.third_derivative_after(p_, i, from);
      const double radius = std::min(-side.sign * d2 / third, h - from);
      if (radius > 0.0) side.concave.push_back({i, h - radius, std::min(h + radius, length)});
    }
  }

  // The sides of `gap` its bounds settle: with `rise` the bound on p past the ends' values.
  unsigned settled(const Gap& gap, double rise) const {
    unsigned done = 0;
    for (unsigned s = 0; s < 2; ++s) {
      if (!(gap.open & (1u << s))) continue;
      const Side& side = sides_[s];
      const double higher = std::max(side.sign * gap.left.value, side.sign * gap.right.value);
      if (rise <= side.best + tolerance_ - higher) done |= 1u << s;
    }
    return done;
  }

  // Whether side s's concave windows hold the gap.
  bool in_a_window(const Gap& gap, size_t s) const {
    for (const Window& w : sides_[s].concave)
      if (w.interval == gap.interval && w.low <= gap.left.h && gap.right.h <= w.high) return true;
    return false;
  }

  // Halves every gap whose bound could hide a value past either best one.
  void halve_gaps() {
    for (int evaluations = 0; !gaps_.empty() && evaluations < 100000; ++evaluations) {
      Gap gap = gaps_.back();
      gaps_.pop_back();
      const double width = gap.right.h - gap.left.h;
      if (width <= 1e-15 * period_) continue;
      // The bounds at h = 0 first, the concave windows, then the cached bounds, then
      // rise_after at the gap's left end only when none settles the gap.
      gap.open &= ~settled(gap, evaluator_.widest_rise(p_, gap.interval, width));
      for (unsigned s = 0; s < 2; ++s)
        if ((gap.open & (1u << s)) && in_a_window(gap, s)) gap.open &= ~(1u << s);
      if (!gap.open) continue;
      const double curvature_rise = gap.left.curvature >= 0.0
                                        ? gap.left.curvature * width * width / 8.0
                                        : std::numeric_limits<double>::infinity();
      gap.open &= ~settled(gap, std::min(gap.rise, curvature_rise));
      if (gap.open && !gap.own) {
        gap.rise = evaluator_.rise_after(p_, gap.interval, gap.left.row, width, gap.left.curvature);
        gap.own = true;
        gap.open &= ~settled(gap, gap.rise);
      }
      if (!gap.open) continue;
      // K_i(a) and the rise decrease with a and with the width: both halves keep them. The
      // middle's exponentials from the left end's, by a step shared with other gaps.
      const auto [step_row, step] = rows_.step(0.5 * width);
      const double h = gap.left.h + step;
      Complex* row = rows_.pool().add();
      evaluator_.step_row(gap.left.row, step_row, row);
      const Point middle{h, evaluator_.evaluate(p_, gap.interval, h, row, nullptr, nullptr),
                         gap.left.curvature, row};
      for (size_t s = 0; s < 2; ++s)
        if ((gap.open & (1u << s)) && sides_[s].sign * middle.value > sides_[s].best + tolerance_)
          polish(s, gap.interval, h);
      improve(middle.value, gap.interval, h);
      gaps_.push_back({gap.interval, gap.left, middle, gap.rise, false, gap.open});
      gaps_.push_back({gap.interval, middle, gap.right, gap.rise, false, gap.open});
    }
  }

  const SeriesEvaluator& evaluator_;
  const PeriodicResult& result_;
  SolveRows& rows_;
  size_t p_;
  double period_, sample_step_, tolerance_ = 0.0;
  std::array<Side, 2> sides_;
  std::vector<Gap> gaps_;
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
  SolveRows rows(evaluator);
  sample_uniformly(evaluator, series, samples, result, rows);
  const double sample_step = edges.back() / samples;
  fill_extremes(result, [&](size_t p, size_t low, size_t high) {
    return ExtremesSearch(evaluator, result, rows, p, low, high, sample_step).find();
  });
}

}  // namespace emnet
