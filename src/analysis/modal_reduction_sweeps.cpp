// The sweeps of a modal reduction: the AC sweep checked against the full model at a few
// frequencies (run_ac_reduced) and the periodic steady state of the reduced model
// (ReducedPeriodicSolver); see include/emnet/analysis/modal_reduction.hpp. The reduction itself
// is built in modal_reduction.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "core/timed.hpp"
#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"
#include "exponential_series.hpp"
#include "reduced_periodic.hpp"

namespace emnet {

Status require_piecewise_linear(const System& system);  // transient_exact.cpp

namespace {
constexpr double two_pi = 6.283185307179586476925286766559;
using Complex = std::complex<double>;
}  // namespace

std::vector<double> check_frequencies(const std::vector<double>& grid,
                                      const std::vector<std::vector<Complex>>& values, int spread) {
  std::set<size_t> picked;
  if (grid.empty()) return {};
  const size_t last = grid.size() - 1;
  for (int k = 0; k < spread; ++k)
    picked.insert(
        spread > 1 ? static_cast<size_t>(std::llround(static_cast<double>(last) * k / (spread - 1)))
                   : 0);
  for (const auto& series : values) {
    size_t best = 0;
    for (size_t f = 0; f < series.size(); ++f)
      if (std::abs(series[f]) > std::abs(series[best])) best = f;
    if (best <= last) picked.insert(best);
  }
  std::vector<double> out;
  for (size_t index : picked) out.push_back(grid[index]);
  return out;
}

std::vector<double> errors_relative_to_peak(const std::vector<std::vector<Complex>>& values,
                                            const std::vector<std::vector<Complex>>& reference) {
  std::vector<double> errors;
  for (size_t p = 0; p < reference.size(); ++p) {
    double largest = 0.0, difference = 0.0;
    for (size_t f = 0; f < reference[p].size(); ++f) {
      largest = std::max(largest, std::abs(reference[p][f]));
      difference = std::max(difference, std::abs(values[p][f] - reference[p][f]));
    }
    errors.push_back(largest > 0.0 ? difference / largest : (difference > 0.0 ? 1.0 : 0.0));
  }
  return errors;
}

AcReductionResult run_ac_reduced(const System& system, const Eigen::VectorXd& operating_point,
                                 const std::vector<double>& frequencies,
                                 const std::vector<Probe>& probes, ReductionOptions options) {
  if (options.band == 0.0 && !frequencies.empty())
    options.band = *std::max_element(frequencies.begin(), frequencies.end());
  validate(options);
  Timed<AcReductionResult> timed;
  AcReductionResult& result = timed.result;
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  const Eigen::VectorXcd rhs = system.b_ac();
  if (rhs.norm() == 0.0)
    return finish(Status::failure(
        "the scene has no AC excitation (no drive and no load): every response would be zero"));

  Stopwatch start;
  result.model = reduce_modal(system, operating_point, {rhs}, options);
  result.reduce_seconds = start.seconds();
  if (!result.model.status.ok()) return finish(result.model.status);

  start.restart();
  result.ac.frequencies = frequencies;
  result.ac.values.assign(probes.size(), {});
  for (size_t p = 0; p < probes.size(); ++p)
    for (double f : frequencies)
      result.ac.values[p].push_back(result.model.response(probes[p], two_pi * f));
  result.evaluate_seconds = start.seconds();
  result.ac.seconds = result.reduce_seconds + result.evaluate_seconds;
  result.ac.method = Method::reduced;
  for (size_t p = 0; p < probes.size(); ++p)
    for (size_t f = 0; f < frequencies.size(); ++f)
      if (!std::isfinite(std::abs(result.ac.values[p][f]))) {
        char at[40];
        std::snprintf(at, sizeof at, "%.9g Hz", frequencies[f]);
        return finish(Status::failure("the reduced model gave a non-finite response: probe '" +
                                      probes[p].name + "' at f = " + at));
      }

  // The check: the full model at a few frequencies of the sweep.
  start.restart();
  result.check_frequencies = check_frequencies(frequencies, result.ac.values);
  const AcResult full = run_ac(system, operating_point, result.check_frequencies, probes);
  result.check_seconds = start.seconds();
  if (!full.status.ok()) return finish(full.status.with_context("full model check: "));
  std::vector<std::vector<Complex>> reduced_at_checks(probes.size());
  for (size_t p = 0; p < probes.size(); ++p)
    for (double f : result.check_frequencies)
      reduced_at_checks[p].push_back(result.model.response(probes[p], two_pi * f));
  result.probe_errors = errors_relative_to_peak(reduced_at_checks, full.values);
  // The a-priori estimate at the band's edge, or the sweep's if it reaches beyond it.
  const double omega =
      two_pi * std::max(options.band, frequencies.empty() ? 0.0
                                                          : *std::max_element(frequencies.begin(),
                                                                              frequencies.end()));
  for (size_t p = 0; p < probes.size(); ++p) {
    result.measured_error = std::max(result.measured_error, result.probe_errors[p]);
    double largest = 0.0;
    for (const Complex& v : full.values[p]) largest = std::max(largest, std::abs(v));
    if (largest > 0.0)
      result.error_estimate =
          std::max(result.error_estimate,
                   result.model.truncation_factor_at(omega) *
                       std::abs(result.model.correction_response(probes[p], omega)) / largest);
  }
  result.tolerance_met = result.measured_error <= options.tolerance;
  return finish(Status::success());
}

ReducedPeriodicSolver::ReducedPeriodicSolver(const System& system,
                                             const ReductionOptions& options) {
  validate(options);
  std::vector<Eigen::VectorXcd> inputs;
  for (const auto& term : system.excitation().source_terms) {
    auto found = std::find(waveforms_.begin(), waveforms_.end(), term.waveform);
    size_t j = static_cast<size_t>(found - waveforms_.begin());
    if (found == waveforms_.end()) {
      waveforms_.push_back(term.waveform);
      inputs.push_back(Eigen::VectorXcd::Zero(system.size()));
    }
    inputs[j][term.row] += term.coefficient;
  }
  if (inputs.empty()) {
    reduction_.status = Status::failure("the network has no source: nothing to reduce");
    return;
  }
  ReductionOptions periodic = options;
  if (!(periodic.cutoff_hz > 0.0)) periodic.cutoff_hz = options.band / options.tolerance;
  periodic.series_correction = false;
  if (system.is_nonlinear()) {
    // Arnoldi may stop at a Kelvin–Voigt cluster: the beam's truncated part is exact but for
    // its transients, which the solve states (truncation_estimate).
    reduce_cascade(system, periodic, std::move(inputs));
    return;
  }
  periodic.dense_limit = std::max(options.dense_limit, 600);
  reduction_ = reduce_modal(system, Eigen::VectorXd::Zero(system.size()), inputs, periodic);
}

InputPieces input_pieces(const System& system, const std::vector<int>& waveforms,
                         const std::vector<double>& edges) {
  const size_t intervals = edges.size() - 1, inputs = waveforms.size();
  InputPieces pieces;
  pieces.value.assign(intervals, std::vector<double>(inputs));
  pieces.slope.assign(intervals, std::vector<double>(inputs, 0.0));
  pieces.ramp.assign(intervals, false);
  for (size_t i = 0; i < intervals; ++i) {
    const double middle = 0.5 * (edges[i] + edges[i + 1]);
    for (size_t j = 0; j < inputs; ++j) {
      const Waveform& waveform = system.excitation().waveforms[static_cast<size_t>(waveforms[j])];
      pieces.value[i][j] = waveform.value(middle);
      pieces.slope[i][j] = waveform.slope(middle);
      if (pieces.slope[i][j] != 0.0) {
        pieces.value[i][j] -= (middle - edges[i]) * pieces.slope[i][j];
        pieces.ramp[i] = true;
      }
    }
  }
  return pieces;
}

bool InputPieces::any_ramp() const {
  return std::find(ramp.begin(), ramp.end(), true) != ramp.end();
}

void affine_particulars(const Eigen::VectorXcd& lambda, const Eigen::MatrixXcd& beta,
                        const InputPieces& inputs, std::vector<Eigen::VectorXcd>& particular,
                        std::vector<Eigen::VectorXcd>& slope) {
  const size_t intervals = inputs.value.size();
  const Eigen::Index modes = lambda.size(), count = beta.cols();
  const Eigen::VectorXcd inverse = lambda.unaryExpr([](Complex l) { return reciprocal(l); });
  particular.assign(intervals, Eigen::VectorXcd::Zero(modes));
  slope.clear();
  if (inputs.any_ramp()) slope.assign(intervals, Eigen::VectorXcd::Zero(modes));
  for (size_t i = 0; i < intervals; ++i) {
    const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(inputs.value[i].data(), count);
    particular[i] = -(beta * u.cast<Complex>()).cwiseProduct(inverse);
    if (!inputs.ramp[i]) continue;
    const Eigen::VectorXd rate = Eigen::Map<const Eigen::VectorXd>(inputs.slope[i].data(), count);
    slope[i] = -(beta * rate.cast<Complex>()).cwiseProduct(inverse);
    particular[i] += slope[i].cwiseProduct(inverse);
  }
}

std::vector<double> input_feed(const ModalReduction& reduction, const Probe& probe, size_t inputs) {
  std::vector<double> d(inputs, 0.0);
  for (const auto& [index, c] : probe.terms)
    for (size_t j = 0; j < inputs; ++j) d[j] += c * reduction.correction[j][index].real();
  return d;
}

ExponentialSeries affine_series(const Eigen::VectorXcd& g, const std::vector<double>& feed,
                                const InputPieces& inputs,
                                const std::vector<Eigen::VectorXcd>& particular,
                                const std::vector<Eigen::VectorXcd>& slope,
                                const std::vector<Eigen::VectorXcd>& homogeneous) {
  ExponentialSeries series;
  for (size_t i = 0; i < inputs.value.size(); ++i) {
    double value = 0.0, rate = 0.0;
    for (size_t j = 0; j < feed.size(); ++j) {
      value += feed[j] * inputs.value[i][j];
      rate += feed[j] * inputs.slope[i][j];
    }
    series.offset.push_back(value + g.cwiseProduct(particular[i]).sum().real());
    if (inputs.ramp[i]) rate += g.cwiseProduct(slope[i]).sum().real();
    series.slope.push_back(rate);
    series.coefficient.push_back(g.cwiseProduct(homogeneous[i]));
  }
  return series;
}

namespace {

// The largest step of `w` within a period [its unit]: a pulse's high − low, a pwl's largest
// difference between consecutive points, a sine's peak-to-peak, 0 for dc.
double largest_step(const Waveform& w) {
  switch (w.shape) {
    case Waveform::Shape::pulse:
      return std::abs(w.pulse_high - w.dc);
    case Waveform::Shape::sine:
      return 2.0 * std::abs(w.amplitude);
    case Waveform::Shape::pwl: {
      double step = 0.0;
      for (size_t k = 0; k + 1 < w.points.size(); ++k)
        step = std::max(step, std::abs(w.points[k + 1].second - w.points[k].second));
      return step;
    }
    case Waveform::Shape::dc:
      return 0.0;
  }
  return 0.0;
}

}  // namespace

double ReducedPeriodicSolver::edge_error_estimate(const System& system,
                                                  const std::vector<Probe>& probes,
                                                  const std::vector<double>& scale) const {
  double worst = 0.0;
  for (size_t p = 0; p < probes.size() && p < scale.size(); ++p) {
    double error = 0.0;
    for (size_t j = 0; j < waveforms_.size(); ++j)
      error += std::abs(reduction_.correction_response(probes[p], 0.0, static_cast<int>(j))) *
               largest_step(system.excitation().waveforms[static_cast<size_t>(waveforms_[j])]);
    if (scale[p] > 0.0) worst = std::max(worst, error / scale[p]);
  }
  return worst;
}

PeriodicResult ReducedPeriodicSolver::solve(const System& given, const std::vector<Probe>& probes,
                                            double period, int samples) const {
  const std::optional<System> steady = steady_period_system(given, period);
  const System& system = steady ? *steady : given;
  Timed<PeriodicResult> timed;
  PeriodicResult& result = timed.result;
  result.method = Method::reduced;
  result.period = period;
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  if (!reduction_.status.ok()) return finish(reduction_.status);
  if (Status pieces = require_piecewise_linear(system); !pieces.ok()) return finish(pieces);
  if (system.size() != reduction_.full_unknowns || system.is_nonlinear() != (cascade_ != nullptr))
    return finish(Status::failure("the network differs from the one that was reduced"));
  for (const Probe& probe : probes)
    for (const auto& [index, coefficient] : probe.terms)
      if ((reduction_.mechanical[static_cast<size_t>(index)] ? 1 : 0) != probe.integrations)
        return finish(Status::failure("probe " + probe.name +
                                      ": the reduced periodic method takes displacement-like "
                                      "probes only (deflection, rotation)"));
  for (int w : waveforms_)
    if (w >= static_cast<int>(system.excitation().waveforms.size()))
      return finish(Status::failure("the network's sources differ from the reduced one's"));
  if (cascade_) return solve_cascade(system, probes, period, samples);

  const std::vector<KeptPole>& kept = reduction_.kept;
  const size_t modes = kept.size(), inputs = waveforms_.size();
  const std::vector<double> edges = constant_intervals(system, period);
  const InputPieces pieces = input_pieces(system, waveforms_, edges);
  Eigen::VectorXcd lambda(static_cast<Eigen::Index>(modes));
  Eigen::MatrixXcd beta(static_cast<Eigen::Index>(modes), static_cast<Eigen::Index>(inputs));
  for (size_t k = 0; k < modes; ++k) {
    lambda[static_cast<Eigen::Index>(k)] = kept[k].pole;
    for (size_t j = 0; j < inputs; ++j)
      beta(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) = reduction_.beta[k][j];
  }
  std::vector<Eigen::VectorXcd> particular, particular_slope;
  affine_particulars(lambda, beta, pieces, particular, particular_slope);
  std::vector<Eigen::VectorXcd> start_of;
  if (Status periodic = periodic_interval_starts(lambda, edges, particular, particular_slope, {},
                                                 start_of, result.periodicity_residual);
      !periodic.ok())
    return finish(periodic);

  // Probe p: Re Σ_k g_k·q_k over the kept poles (one of each conjugate pair, its row doubled)
  // and the static correction D·u(t) as a feed-through that follows the inputs' ramps.
  std::vector<Eigen::VectorXcd> homogeneous(start_of.size());
  for (size_t i = 0; i < start_of.size(); ++i) homogeneous[i] = start_of[i] - particular[i];
  std::vector<ExponentialSeries> series;
  for (const Probe& probe : probes) {
    Eigen::VectorXcd g = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(modes));
    for (const auto& [index, c] : probe.terms)
      for (size_t k = 0; k < modes; ++k)
        g[static_cast<Eigen::Index>(k)] +=
            c * kept[k].z_vector[index] * (kept[k].oscillatory ? 2.0 : 1.0);
    series.push_back(affine_series(g, input_feed(reduction_, probe, inputs), pieces, particular,
                                   particular_slope, homogeneous));
  }
  sample_periodic_series(lambda, edges, series, samples, result);
  return finish(Status::success());
}

double extremes_difference(const PeriodicResult& reduced, const PeriodicResult& full) {
  if (reduced.minimum.size() != full.minimum.size() || full.values.size() != full.minimum.size())
    return -1.0;
  double worst = 0.0;
  for (size_t p = 0; p < full.minimum.size(); ++p) {
    double largest = 0.0;
    for (double v : full.values[p]) largest = std::max(largest, std::abs(v));
    const double difference = std::max(std::abs(reduced.minimum[p] - full.minimum[p]),
                                       std::abs(reduced.maximum[p] - full.maximum[p]));
    worst = std::max(worst, largest > 0.0 ? difference / largest : difference);
  }
  return worst;
}

double periodic_difference(const PeriodicResult& reduced, const PeriodicResult& full) {
  if (reduced.values.size() != full.values.size()) return -1.0;
  double worst = 0.0;
  for (size_t p = 0; p < full.values.size(); ++p) {
    if (reduced.values[p].size() != full.values[p].size()) return -1.0;
    double largest = 0.0, difference = 0.0;
    for (size_t s = 0; s < full.values[p].size(); ++s) {
      largest = std::max(largest, std::abs(full.values[p][s]));
      difference = std::max(difference, std::abs(reduced.values[p][s] - full.values[p][s]));
    }
    worst = std::max(worst, largest > 0.0 ? difference / largest : difference);
  }
  return worst;
}

}  // namespace emnet
