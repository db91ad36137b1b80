// Periodic steady state: the exact method (eigen-decomposed state equation); shooting is in
// periodic_shooting.cpp.
// See include/emnet/analysis/periodic.hpp for the method.
#include "emnet/analysis/periodic.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include "core/timed.hpp"
#include "dense_decompositions.hpp"
#include "displacement_form.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/units.hpp"
#include "exponential_series.hpp"
#include "periodic_cascade.hpp"
#include "state_space.hpp"

namespace emnet {

Status require_piecewise_linear(const System& system);  // transient_exact.cpp

namespace {

using Complex = std::complex<double>;

// The state space of `form`: its linear part, which for a cascade (a network whose only
// nonlinearity is the DEAs' force, periodic_cascade.hpp) is its linearisation at zero, where
// the force k_F·u² and its derivative vanish; the force is then a source of it. Throws, saying
// why, for any other nonlinear network.
LinearStateSpace linear_part(const DisplacementForm& form, const System& system,
                             std::vector<SquaredSource>& squared) {
  if (!system.is_nonlinear())
    return LinearStateSpace(form, characteristic_angular_frequency(system, 0.0));
  if (Status cascade = cascade_sources(system, form, squared); !cascade.ok())
    throw std::runtime_error(cascade.message);
  Eigen::SparseMatrix<double> d_u, d_up;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(form.size());
  form.linearised(zero, zero, d_u, d_up);
  return LinearStateSpace(form, d_u, d_up, characteristic_angular_frequency(system, 0.0));
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
  // ξ_p(h) = ξ_p(0) on a constant interval.
  std::vector<Eigen::VectorXcd> particular_end = particular;
  if (!particular_slope.empty())
    for (size_t i = 0; i + 1 < edges.size(); ++i)
      particular_end[i] += (edges[i + 1] - edges[i]) * particular_slope[i];
  return periodic_starts_from_particulars(lambda, edges, particular, particular_end, fixed_at_zero,
                                          start_of, residual);
}

Status periodic_starts_from_particulars(const Eigen::VectorXcd& lambda,
                                        const std::vector<double>& edges,
                                        const std::vector<Eigen::VectorXcd>& particular_start,
                                        const std::vector<Eigen::VectorXcd>& particular_end,
                                        const std::vector<bool>& fixed_at_zero,
                                        std::vector<Eigen::VectorXcd>& start_of, double& residual) {
  const size_t intervals = edges.size() - 1;
  std::vector<Eigen::VectorXcd> propagator(intervals);  // e^{Λh} of each interval, once
  for (size_t i = 0; i < intervals; ++i)
    propagator[i] = (lambda * (edges[i + 1] - edges[i])).array().exp();
  auto advance = [&](const Eigen::VectorXcd& xi, size_t i) {
    // ξ_p(h) + e^{Λh}·(ξ − ξ_p(0)).
    return Eigen::VectorXcd(particular_end[i] +
                            (propagator[i].array() * (xi - particular_start[i]).array()).matrix());
  };
  Eigen::VectorXcd xi = Eigen::VectorXcd::Zero(lambda.size());
  for (size_t i = 0; i < intervals; ++i) xi = advance(xi, i);
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    if (static_cast<size_t>(k) < fixed_at_zero.size() && fixed_at_zero[static_cast<size_t>(k)]) {
      xi[k] = 0.0;  // a constraint's invariant: zero in every consistent state
      continue;
    }
    const Complex growth = 1.0 - std::exp(lambda[k] * edges.back());
    if (modulus(growth) < 1e-14)
      return Status::failure(
          "an undamped mode is in exact resonance with the drive: no periodic state");
    xi[k] *= reciprocal(growth);
  }
  start_of.assign(intervals, {});
  for (size_t i = 0; i < intervals; ++i) {
    start_of[i] = xi;
    xi = advance(xi, i);
  }
  residual = (xi - start_of[0]).norm() / std::max(start_of[0].norm(), 1e-300);
  return check_residual(residual, "periodic state x(T) = x(0)");
}

struct PeriodicSolver::Impl {
  explicit Impl(const System& reference)
      : system(reference), form(system), space(linear_part(form, system, squared)) {
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
    inverse_lambda = Eigen::VectorXcd::Zero(lambda.size());
    const double largest = lambda.cwiseAbs().maxCoeff();
    for (Eigen::Index k = 0; k < lambda.size(); ++k)
      if ((invariant[static_cast<size_t>(k)] = std::abs(lambda[k]) < 1e-9 * largest))
        ++zero_poles;
      else
        inverse_lambda[k] = reciprocal(lambda[k]);
  }
  std::vector<bool> invariant;
  Eigen::VectorXcd inverse_lambda;  // 1/λ_k (0 for the invariants), for the particular states
  Eigen::Index zero_poles = 0;
  // The DEAs' forces as sources d_j·u_j² of the linear part (a cascade; empty for a linear
  // network), and V⁻¹·N·d_j as columns (made at the first solve, with the check that the
  // voltages do not see the forces).
  std::vector<SquaredSource> squared;
  mutable Eigen::MatrixXcd squared_forcing;
  // Per probe seen so far (by name and terms), reused across solves: gᵀ·V, the probe's row on
  // the modal coordinates, and h, its row on the sources (p = gᵀ·x + h·f on a constant
  // interval).
  struct ProbeRows {
    Eigen::RowVectorXcd modes;
    Eigen::RowVectorXd sources;
    // A cascade's: the probe's feed-through of each squared source, on u² and on (u²)'.
    Eigen::VectorXd squared_feed, squared_rate_feed;
  };
  mutable std::map<std::string, ProbeRows> probe_rows;
  // V⁻¹·N·e_r, the forcing of a source on row r in modal coordinates (q = V⁻¹·N·f), made for
  // the rows a solve's sources use (a few: the whole V⁻¹·N took 11 ms of the tweezer jaw's
  // decomposition).
  mutable std::vector<Eigen::VectorXcd> modal_forcing_columns;
  Eigen::VectorXcd modal_forcing(const Eigen::VectorXd& f) const {
    if (modal_forcing_columns.empty())
      modal_forcing_columns.resize(static_cast<size_t>(form.size()));
    Eigen::VectorXcd q = Eigen::VectorXcd::Zero(space.state_size());
    for (Eigen::Index r = 0; r < f.size(); ++r) {
      if (f[r] == 0.0) continue;
      Eigen::VectorXcd& column = modal_forcing_columns[static_cast<size_t>(r)];
      if (column.size() == 0)
        column =
            vectors_lu.solve(space.forcing(Eigen::VectorXd::Unit(form.size(), r)).cast<Complex>());
      q += f[r] * column;
    }
    return q;
  }
  // Whether `given` is the decomposed network with piecewise-linear sources (and, for a
  // cascade, its stages apart): a failed Status saying why not.
  Status check(const System& given) const;
  // The particular state a_i (`particular`) and b_i (`particular_slope`, empty when no interval
  // ramps) of each interval's sources `f` (solve); fails for a free body the drive reaches.
  Status particular_states(const std::vector<AffinePiece>& f,
                           std::vector<Eigen::VectorXcd>& particular,
                           std::vector<Eigen::VectorXcd>& particular_slope) const;
  // The probe's rows, from the cache or computed and cached.
  const ProbeRows& probe_rows_of(const Probe& probe) const;
  // Whether the particular states must keep modes at s = 0 out of the drive (more zero poles
  // than hidden constraints: a free body).
  bool free_body() const {
    return zero_poles > static_cast<Eigen::Index>(form.hidden_constraints().size());
  }
  // squared_forcing, and the check that no mode carries both a DEA's voltage and a DEA's force
  // (the stages of the cascade follow one another): made once.
  Status prepare_cascade() const;
  // The cascade's first stage: the functionals squared (the DEAs' voltages, then those of the
  // probes' squares in order), their series from the linear stage and their squares: the
  // DEAs' (`forces`, the second stage's sources) and the probes' (`probe_squares`).
  struct FirstStage {
    std::vector<Probe> functionals;
    std::vector<ExponentialSeries> series;
    SquareExponents exponents;
    std::vector<std::vector<ExponentialSeries::ForcedTerms>> forces, probe_squares;
  };
  FirstStage first_stage(const std::vector<double>& edges, const std::vector<AffinePiece>& f,
                         const std::vector<Eigen::VectorXcd>& particular,
                         const std::vector<Eigen::VectorXcd>& particular_slope,
                         const std::vector<Eigen::VectorXcd>& linear_start_of,
                         const std::vector<Probe>& probes) const;
  // Whether the functionals squared do not move with the DEAs' forces (`response`): a failed
  // Status saying which does.
  Status unmoved_by_the_forces(const std::vector<double>& edges, const FirstStage& stage,
                               const ForcedModalResponse& response) const;
  // The cascade's probe series (periodic_cascade.hpp) from the linear stage's particular states
  // and periodic starts, with the exponents of their forced parts and the periodicity residual.
  Status cascade_series(const std::vector<double>& edges, const std::vector<AffinePiece>& f,
                        const std::vector<Eigen::VectorXcd>& particular,
                        const std::vector<Eigen::VectorXcd>& particular_slope,
                        const std::vector<Eigen::VectorXcd>& linear_start_of,
                        const std::vector<Probe>& probes, std::vector<ExponentialSeries>& series,
                        Eigen::VectorXcd& exponents, double& residual) const;
  // The forced part of a probe (rows) on interval i: its modes' particular states and its
  // feed-through of the squared sources.
  ExponentialSeries::ForcedTerms forced_terms(
      const ProbeRows& rows, size_t i, const SquareExponents& exponents,
      const ForcedModalResponse& response,
      const std::vector<std::vector<ExponentialSeries::ForcedTerms>>& squares) const;
  // The probe's exponential series over the intervals (solve).
  ExponentialSeries probe_series(const Probe& probe, const std::vector<AffinePiece>& f,
                                 const std::vector<Eigen::VectorXcd>& particular,
                                 const std::vector<Eigen::VectorXcd>& particular_slope,
                                 const std::vector<Eigen::VectorXcd>& start_of) const;
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

Status PeriodicSolver::usable() const {
  if (!impl_) return status_;
  return impl_->squared.empty() ? Status::success() : impl_->prepare_cascade();
}

Status exact_periodic_applies(const System& system) {
  if (!system.is_nonlinear()) return Status::success();
  try {
    const DisplacementForm form(system);
    std::vector<SquaredSource> squared;
    return cascade_sources(system, form, squared);
  } catch (const std::exception& e) {
    return Status::failure(e.what());
  }
}

Status PeriodicSolver::Impl::check(const System& given) const {
  if (Status pieces = require_piecewise_linear(given); !pieces.ok()) return pieces;
  if (given.size() != system.size() || given.is_nonlinear() != system.is_nonlinear() ||
      (system.is_nonlinear() && !same_cascade(given.nonlinear_elements, system.nonlinear_elements)))
    return Status::failure("the network differs from the one the solver decomposed");
  if (!squared.empty()) return prepare_cascade();
  return Status::success();
}

Status PeriodicSolver::Impl::particular_states(
    const std::vector<AffinePiece>& f, std::vector<Eigen::VectorXcd>& particular,
    std::vector<Eigen::VectorXcd>& particular_slope) const {
  const Eigen::Index nd = space.state_size();
  const size_t intervals = f.size();
  particular.assign(intervals, Eigen::VectorXcd());
  bool any_ramp = false;
  for (const AffinePiece& piece : f) any_ramp |= piece.ramp();
  if (any_ramp) particular_slope.assign(intervals, Eigen::VectorXcd::Zero(nd));
  // Poles at s = 0 up to the number of hidden constraints are their invariants, which no drive
  // excites: whatever forcing reaches them is rounding (it grows with V's condition: 1.1e-9 of
  // the forcing's scale on the 100-segment fish fin). More zero poles than that mean a free body,
  // which has no periodic state when the drive reaches it.
  const bool free_body = this->free_body();
  const auto free_body_failure = Status::failure(
      "the network has a pole at s = 0 that the drive excites "
      "(a free body): no periodic state");
  for (size_t i = 0; i < intervals; ++i) {
    const Eigen::VectorXcd forcing = modal_forcing(f[i].start);
    particular[i] = Eigen::VectorXcd::Zero(nd);
    const double forcing_scale = moduli(forcing).maxCoeff();
    for (Eigen::Index k = 0; k < nd; ++k) {
      if (!invariant[static_cast<size_t>(k)]) {
        particular[i][k] = -forcing[k] * inverse_lambda[k];
      } else if (free_body && std::abs(forcing[k]) > 1e-9 * forcing_scale) {
        return free_body_failure;
      }
    }
    if (!f[i].ramp()) continue;
    const Eigen::VectorXcd modal_slope = modal_forcing(f[i].slope);
    const double slope_scale = moduli(modal_slope).maxCoeff();
    for (Eigen::Index k = 0; k < nd; ++k) {
      if (!invariant[static_cast<size_t>(k)]) {
        particular_slope[i][k] = -modal_slope[k] * inverse_lambda[k];
        particular[i][k] += particular_slope[i][k] * inverse_lambda[k];
      } else if (free_body && std::abs(modal_slope[k]) > 1e-9 * slope_scale) {
        return free_body_failure;
      }
    }
  }
  return Status::success();
}

const PeriodicSolver::Impl::ProbeRows& PeriodicSolver::Impl::probe_rows_of(
    const Probe& probe) const {
  // gᵀV depends on the probe and the decomposition only: computed once per solver. The key is
  // the probe's name and the bytes of its linear form (exact, and cheap: to_string took 2 % of a
  // design study, and its six decimals could not tell coefficients 1e-7 apart).
  std::string key = probe.name;
  key.push_back('\0');
  auto append = [&key](const auto& value) {
    key.append(reinterpret_cast<const char*>(&value), sizeof value);
  };
  append(probe.integrations);
  for (const auto& [index, coefficient] : probe.terms) {
    append(index);
    append(coefficient);
  }
  auto cached = probe_rows.find(key);
  if (cached != probe_rows.end()) return cached->second;
  // The probe is linear in (u, u'): its rows on the state, the sources and their slope.
  Eigen::RowVectorXd on_u, on_up;
  form.probe_rows(probe, on_u, on_up);
  const LinearStateSpace::OutputRows output = space.output_rows(on_u, on_up);
  ProbeRows rows{output.state.cast<Complex>() * vectors, output.source, {}, {}};
  if (!squared.empty()) {
    rows.squared_feed.resize(static_cast<Eigen::Index>(squared.size()));
    rows.squared_rate_feed.resize(rows.squared_feed.size());
    for (size_t j = 0; j < squared.size(); ++j) {
      rows.squared_feed[static_cast<Eigen::Index>(j)] = output.source.dot(squared[j].direction);
      rows.squared_rate_feed[static_cast<Eigen::Index>(j)] = output.slope.dot(squared[j].direction);
    }
  }
  return probe_rows.emplace(key, std::move(rows)).first->second;
}

ExponentialSeries PeriodicSolver::Impl::probe_series(
    const Probe& probe, const std::vector<AffinePiece>& f,
    const std::vector<Eigen::VectorXcd>& particular,
    const std::vector<Eigen::VectorXcd>& particular_slope,
    const std::vector<Eigen::VectorXcd>& start_of) const {
  const ProbeRows& rows = probe_rows_of(probe);
  const Eigen::RowVectorXcd& g_modes = rows.modes;
  Eigen::VectorXd u, up;
  ExponentialSeries series;
  for (size_t i = 0; i < f.size(); ++i) {
    if (!f[i].ramp()) {
      // gᵀ·Re(V·a) + h·f = Re(gᵀV·a) + h·f: the probe's rows, no state rebuilt.
      series.offset.push_back((g_modes * particular[i]).value().real() +
                              rows.sources.dot(f[i].start));
      series.slope.push_back(0.0);
    } else {
      const Eigen::VectorXd x_particular = (vectors * particular[i]).real();
      space.full_state(x_particular, f[i].start, f[i].slope, u, up);
      series.offset.push_back(form.probe(probe, u, up));
      space.full_state(Eigen::VectorXd::Zero(space.state_size()), f[i].slope, u, up);
      series.slope.push_back((g_modes * particular_slope[i]).value().real() +
                             form.probe(probe, u, up));
    }
    series.coefficient.push_back(g_modes.transpose().cwiseProduct(start_of[i] - particular[i]));
  }
  return series;
}

namespace {

Status voltage_sees_the_motion(const SquaredSource& source) {
  return Status::failure("DEA " + source.name +
                         "'s voltage depends on the beam's motion (an element of the circuit "
                         "couples them): the exact cascade needs the DEAs' voltages to follow "
                         "from the circuit alone; the shooting method serves this network");
}

}  // namespace

Status PeriodicSolver::Impl::prepare_cascade() const {
  if (squared_forcing.size() != 0) return Status::success();
  const auto sources = static_cast<Eigen::Index>(squared.size());
  Eigen::MatrixXcd forcing(space.state_size(), sources);
  for (Eigen::Index j = 0; j < sources; ++j)
    forcing.col(j) = modal_forcing(squared[static_cast<size_t>(j)].direction);
  // A mode that carries a voltage and is forced by a DEA (beyond the decomposition's rounding:
  // 5e-15 of the product of the largest of each on the tweezer jaw) would make the voltage
  // depend on the motion. (Whether a solve's voltages move with the forces at all is checked
  // on its numbers: cascade_series.)
  for (const SquaredSource& source : squared) {
    const Eigen::VectorXd voltage_modes =
        probe_rows_of(source.voltage).modes.cwiseAbs().transpose();
    for (Eigen::Index j = 0; j < sources; ++j) {
      const Eigen::VectorXd forced = forcing.col(j).cwiseAbs();
      const double shared = voltage_modes.cwiseProduct(forced).maxCoeff();
      if (shared > 1e-9 * voltage_modes.maxCoeff() * forced.maxCoeff())
        return voltage_sees_the_motion(source);
    }
  }
  squared_forcing = forcing;
  return Status::success();
}

ExponentialSeries::ForcedTerms PeriodicSolver::Impl::forced_terms(
    const ProbeRows& rows, size_t i, const SquareExponents& exponents,
    const ForcedModalResponse& response,
    const std::vector<std::vector<ExponentialSeries::ForcedTerms>>& squares) const {
  const Eigen::Index terms = exponents.mu.size();
  const Eigen::RowVectorXcd through_modes = rows.modes * response.coefficients[i];
  ExponentialSeries::ForcedTerms forced(terms, 3);
  for (Eigen::Index m = 0; m < terms; ++m)
    for (int d = 0; d < 3; ++d) forced(m, d) = through_modes[3 * m + d];
  for (size_t j = 0; j < squares.size(); ++j) {
    const ExponentialSeries::ForcedTerms& w = squares[j][i];
    const double feed = rows.squared_feed[static_cast<Eigen::Index>(j)];
    const double rate = rows.squared_rate_feed[static_cast<Eigen::Index>(j)];
    if (feed != 0.0) forced += feed * w;
    if (rate == 0.0) continue;
    // (P·e^{μh})' = (P' + μ·P)·e^{μh}.
    for (Eigen::Index m = 0; m < terms; ++m) {
      const Complex mu = exponents.mu[m];
      forced(m, 0) += rate * (w(m, 1) + mu * w(m, 0));
      forced(m, 1) += rate * (2.0 * w(m, 2) + mu * w(m, 1));
      forced(m, 2) += rate * mu * w(m, 2);
    }
  }
  return forced;
}

PeriodicSolver::Impl::FirstStage PeriodicSolver::Impl::first_stage(
    const std::vector<double>& edges, const std::vector<AffinePiece>& f,
    const std::vector<Eigen::VectorXcd>& particular,
    const std::vector<Eigen::VectorXcd>& particular_slope,
    const std::vector<Eigen::VectorXcd>& linear_start_of, const std::vector<Probe>& probes) const {
  FirstStage stage;
  for (const SquaredSource& source : squared) stage.functionals.push_back(source.voltage);
  for (const Probe& probe : probes)
    for (size_t k = 0; k < probe.squares.size(); ++k) {
      Probe functional;
      functional.name = "\x01" + probe.name + "^2#" + std::to_string(k);
      functional.terms = probe.squares[k].terms;
      stage.functionals.push_back(std::move(functional));
    }
  for (const Probe& functional : stage.functionals)
    stage.series.push_back(
        probe_series(functional, f, particular, particular_slope, linear_start_of));
  stage.exponents = square_exponents(lambda, edges, stage.series);
  for (size_t j = 0; j < stage.series.size(); ++j)
    (j < squared.size() ? stage.forces : stage.probe_squares)
        .push_back(squared_terms(stage.series[j], stage.exponents));
  return stage;
}

Status PeriodicSolver::Impl::unmoved_by_the_forces(const std::vector<double>& edges,
                                                   const FirstStage& stage,
                                                   const ForcedModalResponse& response) const {
  // In a cascade a squared functional's own response to the forces (through any mode or
  // feed-through) is the decomposition's rounding: above 1e-9 of its size, the stages are
  // coupled (the DEAs' voltages) or the probe squares what the forces move.
  for (size_t j = 0; j < stage.functionals.size(); ++j) {
    const ProbeRows& rows = probe_rows_of(stage.functionals[j]);
    const ExponentialSeries& series = stage.series[j];
    double size = 0.0, moved = 0.0;
    for (size_t i = 0; i + 1 < edges.size(); ++i) {
      size = std::max(size, std::abs(series.offset[i]) + moduli(series.coefficient[i]).sum());
      moved = std::max(moved,
                       forced_bound(forced_terms(rows, i, stage.exponents, response, stage.forces),
                                    stage.exponents.mu, edges[i + 1] - edges[i]));
    }
    if (moved <= 1e-9 * size) continue;
    if (j < squared.size()) return voltage_sees_the_motion(squared[j]);
    return Status::failure(
        "a probe squares a quantity that the DEAs' forces move: the exact "
        "cascade squares what the circuit alone sets (a DEA's voltage); the "
        "shooting method serves it");
  }
  return Status::success();
}

Status PeriodicSolver::Impl::cascade_series(const std::vector<double>& edges,
                                            const std::vector<AffinePiece>& f,
                                            const std::vector<Eigen::VectorXcd>& particular,
                                            const std::vector<Eigen::VectorXcd>& particular_slope,
                                            const std::vector<Eigen::VectorXcd>& linear_start_of,
                                            const std::vector<Probe>& probes,
                                            std::vector<ExponentialSeries>& series,
                                            Eigen::VectorXcd& exponents, double& residual) const {
  // The first stage: the DEAs' voltages (and the functionals probes square) of the linear part,
  // and their squares; the second: every mode under the DEAs' squares.
  const FirstStage stage =
      first_stage(edges, f, particular, particular_slope, linear_start_of, probes);
  ForcedModalResponse response;
  if (Status forced = forced_modal_response(lambda, edges, stage.exponents, squared_forcing,
                                            stage.forces, invariant, free_body(), response);
      !forced.ok())
    return forced;
  if (Status unmoved = unmoved_by_the_forces(edges, stage, response); !unmoved.ok()) return unmoved;
  // The periodic state from both particular states.
  const size_t intervals = edges.size() - 1;
  std::vector<Eigen::VectorXcd> particular_start(intervals), particular_end(intervals);
  for (size_t i = 0; i < intervals; ++i) {
    const double h = edges[i + 1] - edges[i];
    particular_start[i] = particular[i] + response.start[i];
    particular_end[i] = particular[i] + response.end[i];
    if (!particular_slope.empty()) particular_end[i] += h * particular_slope[i];
  }
  std::vector<Eigen::VectorXcd> start_of;
  if (Status periodic = periodic_starts_from_particulars(
          lambda, edges, particular_start, particular_end, invariant, start_of, residual);
      !periodic.ok())
    return periodic;
  // Each probe: the linear stage's series with the homogeneous part measured from both
  // particular states, plus the forced part and the squares it takes.
  std::vector<Eigen::VectorXcd> homogeneous_from(intervals);
  for (size_t i = 0; i < intervals; ++i) homogeneous_from[i] = start_of[i] - response.start[i];
  series.clear();
  size_t next_square = 0;
  for (const Probe& probe : probes) {
    ExponentialSeries s = probe_series(probe, f, particular, particular_slope, homogeneous_from);
    const ProbeRows& rows = probe_rows_of(probe);
    for (size_t i = 0; i < intervals; ++i)
      s.forced.push_back(forced_terms(rows, i, stage.exponents, response, stage.forces));
    for (const SquaredTerm& square : probe.squares) {
      for (size_t i = 0; i < intervals; ++i)
        s.forced[i] += square.factor * stage.probe_squares[next_square][i];
      ++next_square;
    }
    series.push_back(std::move(s));
  }
  exponents = stage.exponents.mu;
  return Status::success();
}

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
  if (Status usable = impl_->check(system); !usable.ok()) return finish(usable);

  // The intervals over one period on which the sources are affine, f = f₀,i + h·f₁,i, and the
  // particular state of each, affine too: in modal coordinates q = V⁻¹·N·f,
  // ξ_p,i(h) = a_i + h·b_i with b_i = −Λ⁻¹·q₁,i and a_i = −Λ⁻¹·(q₀,i − b_i) (b_i = 0 on a
  // constant interval, a_i = −Λ⁻¹·q₀,i as before).
  const std::vector<double> edges = constant_intervals(system, period);
  std::vector<AffinePiece> f(edges.size() - 1);
  for (size_t i = 0; i < f.size(); ++i)  // this system's sources, as form.f would give them
    f[i] = affine_piece(system, impl_->form.size(), edges[i], edges[i + 1]);
  std::vector<Eigen::VectorXcd> particular, particular_slope;
  if (Status particular_ok = impl_->particular_states(f, particular, particular_slope);
      !particular_ok.ok())
    return finish(particular_ok);
  std::vector<Eigen::VectorXcd> start_of;
  if (Status periodic =
          periodic_interval_starts(impl_->lambda, edges, particular, particular_slope,
                                   impl_->invariant, start_of, result.periodicity_residual);
      !periodic.ok())
    return finish(periodic);

  // Each probe is linear in (x, f, f'): p = gᵀx + c(f) + d(f'). In modal coordinates, inside
  // interval i, p(h) = p_i + s_i·h + Re Σ_k a_ik·e^{λ_k h} with a_ik = (gᵀV)_k·(ξ_i − a_i)_k,
  // p_i = p(V·a_i, f₀,i, f₁,i) and s_i = Re (gᵀV)·b_i + c(f₁,i).
  std::vector<ExponentialSeries> series;
  Eigen::VectorXcd forced_exponents;
  const bool squares =
      std::any_of(probes.begin(), probes.end(), [](const Probe& p) { return !is_linear(p); });
  if (impl_->squared.empty() && !squares) {
    for (const Probe& probe : probes)
      series.push_back(impl_->probe_series(probe, f, particular, particular_slope, start_of));
  } else if (Status cascade =
                 impl_->cascade_series(edges, f, particular, particular_slope, start_of, probes,
                                       series, forced_exponents, result.periodicity_residual);
             !cascade.ok()) {
    return finish(cascade);
  }
  sample_periodic_series(impl_->lambda, edges, series, samples, result, forced_exponents);
  return finish(Status::success());
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
