// Exact transient of a linear network under piecewise-linear sources: the state equation of
// state_space.hpp solved from breakpoint to breakpoint and to every output time, the sources
// affine on each interval (constant, or a ramp of a pulse's edge or of a piecewise-linear
// source): in M's eigen-basis where it is well conditioned (κ < 1e6), by matrix exponentials
// otherwise. Rounding is the only error.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "core/timed.hpp"
#include "displacement_form.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/transient.hpp"
#include "state_space.hpp"
#include "transient_finite.hpp"

namespace emnet {

Status require_piecewise_linear(const System& system) {
  for (const auto& w : system.excitation().waveforms)
    if (!w.piecewise_linear())
      return Status::failure(
          "the exact method needs piecewise-linear sources (dc, pulse, pwl): sine sources are "
          "not piecewise linear; use the IDA method");
  return Status::success();
}

std::vector<double> interval_ends(const System& system, double end_time) {
  std::vector<double> stops = system.breakpoints(0.0, end_time);
  // A last edge within rounding of the end is the end (not an interval of a few ulps).
  if (!stops.empty() && end_time - stops.back() <= 1e-12 * end_time) stops.pop_back();
  stops.push_back(end_time);
  return stops;
}

Status check_finite_outputs(const TransientResult& result, const std::vector<Probe>& probes,
                            const std::string& what) {
  auto time_text = [](double t) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", t);
    return std::string(buffer);
  };
  for (size_t i = 0; i < result.times.size(); ++i)
    if (!std::isfinite(result.times[i]))
      return Status::failure(what + " gave a non-finite output time (output " + std::to_string(i) +
                             ")");
  for (size_t p = 0; p < result.values.size(); ++p) {
    const std::string name = p < probes.size() ? probes[p].name : std::to_string(p);
    for (size_t i = 0; i < result.values[p].size(); ++i)
      if (!std::isfinite(result.values[p][i]))
        return Status::failure(
            what + " gave a non-finite value of output '" + name + "' at t = " +
            (i < result.times.size() ? time_text(result.times[i]) : std::string("?")) + " s");
  }
  return Status::success();
}

namespace {

// values += Re(weights·v), without a temporary: per output a handful of probes times the half
// poles, where Eigen's general complex matrix–vector product cost four times as much.
void add_real_products(const Eigen::MatrixXcd& weights, const Eigen::VectorXcd& v,
                       Eigen::VectorXd& values) {
  for (Eigen::Index j = 0; j < weights.cols(); ++j) {
    const double v_real = v[j].real(), v_imag = v[j].imag();
    for (Eigen::Index k = 0; k < weights.rows(); ++k)
      values[k] += weights(k, j).real() * v_real - weights(k, j).imag() * v_imag;
  }
}

// What an interval's sources give, the same on every interval with the same sources (a square
// wave's levels and edges repeat each period), so made once per distinct piece: N·f₀ and N·f₁;
// in the modal form q = V⁻¹·N·f₁ on the half poles, each probe's part of its value at the
// interval's start that the sources make (c(f₀) + d(f₁)), c(f₁) and the weights of q.
struct PieceTerms {
  Eigen::VectorXd start, slope;  // f₀ and f₁, the piece's key
  Eigen::VectorXd nf, nf_slope;
  // H·u of the sources f₀ and f₁ alone (LinearStateSpace::sources_in_constraints)
  Eigen::VectorXd constraints_start, constraints_slope;
  // H·u of the sources at `offset` into the interval, f₀ + offset·f₁, by linearity.
  Eigen::VectorXd constraints_at(double offset) const {
    if (constraints_slope.size() == 0) return constraints_start;
    return constraints_start + offset * constraints_slope;
  }
  Eigen::VectorXcd ramp_rate;                  // [half pole]
  Eigen::VectorXd source_values, ramp_values;  // [probe]
  Eigen::MatrixXcd ramp_weights;               // [probe][half pole]
};

// The sources on one interval [t, stop] (f₀ + (τ − t)·f₁, f₁ = 0 on a constant interval), its
// piece's terms, and in the modal form r = V⁻¹·(M·x + N·f₀) on the half poles and, where
// outputs fall inside, each probe's value at the start and its weights on the poles.
struct IntervalForcing {
  AffinePiece f;
  bool ramp = false;
  const PieceTerms* piece = nullptr;
  Eigen::VectorXcd rate;         // [half pole]
  Eigen::VectorXd start_values;  // [probe]
  Eigen::MatrixXcd weights;      // [probe][half pole]
};

// One exact transient (run_transient_exact): the state equation, the modal form of the outputs
// where M's eigen-basis is well conditioned, and the state x between breakpoints. Its
// construction throws where the network has no exact state equation.
class ExactRun {
 public:
  ExactRun(const System& system, const std::vector<Probe>& probes, const TransientOptions& options,
           TransientResult& result)
      : system_(system),
        probes_(probes),
        options_(options),
        result_(result),
        form_(system),
        space_(form_, characteristic_angular_frequency(system, options.end_time)),
        cache_(space_, 1e-13 * std::max(options.end_time, 1e-300)),
        x_(Eigen::VectorXd::Zero(space_.state_size())) {}

  Status set_start() {
    if (options_.start != StartState::static_) return Status::success();
    const StaticResult rest = solve_static(system_);
    if (!rest.status.ok()) return rest.status.with_context("static start state: ");
    x_ = space_.state_of(form_.from_static(rest.state));
    return Status::success();
  }

  Status run() {
    const std::vector<double> stops = interval_ends(system_, options_.end_time);
    outputs_ = options_.output_times;
    if (!std::is_sorted(outputs_.begin(), outputs_.end()))
      std::sort(outputs_.begin(), outputs_.end());
    result_.times.reserve(outputs_.size());
    for (auto& series : result_.values) series.reserve(outputs_.size());
    prepare_modal_outputs();
    double t = 0.0;
    for (double stop : stops) {
      if (stop <= t) continue;
      const IntervalForcing forcing = forcing_on(t, stop);
      if (Status recorded = record_outputs(forcing, t, stop); !recorded.ok()) return recorded;
      if (cancel_requested(options_.progress)) return cancelled_status();
      advance_state(forcing, stop - t);
      ++result_.statistics.restarts;
      t = stop;
    }
    // Distinct exponentials of M (none in the modal form).
    result_.statistics.steps = static_cast<long>(cache_.size());
    if (Status finite = check_finite_outputs(result_, probes_, "the exact method"); !finite.ok())
      return Status::failure(finite.message +
                             " (values beyond double precision: check the scene's "
                             "magnitudes)");
    return Status::success();
  }

 private:
  // Outputs: each probe is linear in (x, f, f'), p = gᵀ·x + c(f) + d(f'), so with M's
  // eigen-basis an output inside an interval starting at x₀, where f = f₀ + s·f₁, is
  //   p(t₀ + h) = p(x₀, f₀, f₁) + Re Σ_k (gᵀV)_k·(r_k·h·φ₁(λ_k h) + q_k·h²·φ₂(λ_k h)) + h·c(f₁),
  //   r = V⁻¹·(M·x₀ + N·f₀),  q = V⁻¹·N·f₁ (the ramp terms only where f₁ ≠ 0),
  // the sum over one pole of each conjugate pair (ModalBasis::half) and h·φ₁, h²·φ₂ stepped
  // from output to output by ModalClock: a few products per pole and probe per output.
  void prepare_modal_outputs() {
    basis_ = space_.modal_basis();
    if (!basis_) return;
    const Eigen::Index half = static_cast<Eigen::Index>(basis_->half.size());
    probe_modes_.resize(static_cast<Eigen::Index>(probes_.size()), half);
    Eigen::RowVectorXd on_u, on_up;
    output_rows_.clear();
    for (size_t k = 0; k < probes_.size(); ++k) {
      form_.probe_rows(probes_[k], on_u, on_up);
      output_rows_.push_back(space_.output_rows(on_u, on_up));
      // gᵀ: the probe's row on the state (u and u' = u_x·M·x of a state under zero sources).
      const Eigen::RowVectorXd& g = output_rows_.back().state;
      const Eigen::RowVectorXcd modes = g.cast<std::complex<double>>() * basis_->vectors;
      for (Eigen::Index j = 0; j < half; ++j)
        probe_modes_(static_cast<Eigen::Index>(k), j) =
            modes[basis_->half[static_cast<size_t>(j)]] * basis_->half_factor[j];
    }
    clock_ = std::make_unique<ModalClock>(*basis_);
    half_vectors_.resize(basis_->vectors.rows(), half);
    for (Eigen::Index j = 0; j < half; ++j)
      half_vectors_.col(j) =
          basis_->vectors.col(basis_->half[static_cast<size_t>(j)]) * basis_->half_factor[j];
    // V⁻¹'s rows of the half poles, by real and imaginary part: V⁻¹·r of a real r on the half
    // poles is two real products, where an LU solve gave every pole of a complex r.
    const Eigen::MatrixXcd inverse = basis_->vectors_lu.inverse();
    half_inverse_real_.resize(half, inverse.cols());
    half_inverse_imaginary_.resize(half, inverse.cols());
    for (Eigen::Index j = 0; j < half; ++j) {
      half_inverse_real_.row(j) = inverse.row(basis_->half[static_cast<size_t>(j)]).real();
      half_inverse_imaginary_.row(j) = inverse.row(basis_->half[static_cast<size_t>(j)]).imag();
    }
  }

  // V⁻¹·r on the half poles.
  Eigen::VectorXcd half_modal(const Eigen::VectorXd& r) const {
    Eigen::VectorXcd out(half_inverse_real_.rows());
    out.real() = half_inverse_real_ * r;
    out.imag() = half_inverse_imaginary_ * r;
    return out;
  }

  // The terms of the piece with sources f (made on its first interval; kept for the last
  // kPieces distinct pieces).
  const PieceTerms& piece_terms(const AffinePiece& f, bool ramp) {
    for (const PieceTerms& piece : pieces_)
      if (piece.start == f.start && piece.slope == f.slope) return piece;
    PieceTerms piece;
    piece.start = f.start;
    piece.slope = f.slope;
    piece.nf = space_.forcing(f.start);
    if (ramp) piece.nf_slope = space_.forcing(f.slope);
    piece.constraints_start = space_.sources_in_constraints(f.start);
    if (ramp) piece.constraints_slope = space_.sources_in_constraints(f.slope);
    if (basis_) {
      const Eigen::Index probes = static_cast<Eigen::Index>(probes_.size());
      piece.source_values.resize(probes);
      piece.ramp_values = Eigen::VectorXd::Zero(probes);
      for (Eigen::Index k = 0; k < probes; ++k) {
        const LinearStateSpace::OutputRows& rows = output_rows_[static_cast<size_t>(k)];
        piece.source_values[k] = rows.source.dot(f.start) + (ramp ? rows.slope.dot(f.slope) : 0.0);
        if (ramp) piece.ramp_values[k] = rows.source.dot(f.slope);  // c(f₁)
      }
      if (ramp) {
        piece.ramp_rate = half_modal(piece.nf_slope);
        piece.ramp_weights = probe_modes_ * piece.ramp_rate.asDiagonal();
      }
    }
    if (pieces_.size() < kPieces) {
      pieces_.push_back(std::move(piece));
      return pieces_.back();
    }
    PieceTerms& slot = pieces_[next_piece_];
    next_piece_ = (next_piece_ + 1) % kPieces;
    slot = std::move(piece);
    return slot;
  }

  // Every probe's value at (u, up_).
  Eigen::VectorXd probe_values() const {
    Eigen::VectorXd values(static_cast<Eigen::Index>(probes_.size()));
    for (size_t k = 0; k < probes_.size(); ++k)
      values[static_cast<Eigen::Index>(k)] = form_.probe(probes_[k], u_, up_);
    return values;
  }

  IntervalForcing forcing_on(double t, double stop) {
    IntervalForcing in;
    in.f = affine_piece(system_, form_.size(), t, stop);
    in.ramp = in.f.ramp();
    in.piece = &piece_terms(in.f, in.ramp);
    if (!basis_) return in;
    in.rate = half_modal(space_.m() * x_ + in.piece->nf);
    clock_->restart(in.ramp);
    const bool outputs_here = next_output_ < outputs_.size() && outputs_[next_output_] <= stop;
    if (!outputs_here) return in;
    // Each probe at the start, p = state·x + c(f₀) + d(f₁) (LinearStateSpace::output_rows).
    in.start_values = in.piece->source_values;
    for (size_t k = 0; k < probes_.size(); ++k)
      in.start_values[static_cast<Eigen::Index>(k)] += output_rows_[k].state.dot(x_);
    in.weights = probe_modes_ * in.rate.asDiagonal();
    return in;
  }

  // The outputs inside the interval starting at t, each at offset h.
  Status record_outputs(const IntervalForcing& in, double t, double stop) {
    Eigen::VectorXd values;
    while (next_output_ < outputs_.size() && outputs_[next_output_] <= stop) {
      const double h = outputs_[next_output_] - t;
      if (h >= 0.0) {
        result_.times.push_back(outputs_[next_output_]);
        if (basis_) {
          clock_->advance_to(h);
          values = in.start_values;
          add_real_products(in.weights, clock_->integral(), values);
          if (in.ramp) {
            add_real_products(in.piece->ramp_weights, clock_->ramp_integral(), values);
            values += h * in.piece->ramp_values;
          }
        } else if (!in.ramp) {
          space_.full_state(space_.project_with(space_.advance(cache_.get(h), x_, in.piece->nf),
                                                in.piece->constraints_start),
                            in.f.start, u_, up_);
          values = probe_values();
        } else {
          space_.full_state(space_.project_with(space_.advance(cache_.get_ramp(h), x_, in.piece->nf,
                                                               in.piece->nf_slope),
                                                in.piece->constraints_at(h)),
                            in.f.at(h), in.f.slope, u_, up_);
          values = probe_values();
        }
        for (size_t k = 0; k < probes_.size(); ++k)
          result_.values[k].push_back(values[static_cast<Eigen::Index>(k)]);
      }
      ++next_output_;
      if (!keep_going(options_.progress, static_cast<long>(next_output_),
                      static_cast<long>(outputs_.size()), "output times"))
        return cancelled_status();
    }
    return Status::success();
  }

  // x to the interval's end, `length` after its start.
  void advance_state(const IntervalForcing& in, double length) {
    if (basis_) {
      // The interval's end in the same modal form: x + Re V·(I(h)∘r + J(h)∘q), over one pole
      // of each pair (factor 2 for a pair) — no exponential of M.
      clock_->advance_to(length);
      Eigen::VectorXcd modal = in.rate.cwiseProduct(clock_->integral());
      if (in.ramp) modal += in.piece->ramp_rate.cwiseProduct(clock_->ramp_integral());
      x_ = space_.project_with(x_ + (half_vectors_ * modal).real(),
                               in.piece->constraints_at(length));
    } else if (!in.ramp) {
      x_ = space_.project_with(space_.advance(cache_.get(length), x_, in.piece->nf),
                               in.piece->constraints_start);
    } else {
      x_ = space_.project_with(
          space_.advance(cache_.get_ramp(length), x_, in.piece->nf, in.piece->nf_slope),
          in.piece->constraints_at(length));
    }
  }

  const System& system_;
  const std::vector<Probe>& probes_;
  const TransientOptions& options_;
  TransientResult& result_;
  const DisplacementForm form_;
  const LinearStateSpace space_;
  PropagatorCache cache_;
  Eigen::VectorXd x_, u_, up_;
  std::vector<double> outputs_;
  size_t next_output_ = 0;
  const LinearStateSpace::ModalBasis* basis_ = nullptr;
  Eigen::MatrixXcd probe_modes_;  // [probe][half pole]: (gᵀV)_k·factor_k
  std::unique_ptr<ModalClock> clock_;
  Eigen::MatrixXcd half_vectors_;  // V's columns of ModalBasis::half, times their factor
  Eigen::MatrixXd half_inverse_real_, half_inverse_imaginary_;  // V⁻¹'s rows of the half poles
  std::vector<LinearStateSpace::OutputRows> output_rows_;       // [probe]
  static constexpr size_t kPieces = 16;
  std::vector<PieceTerms> pieces_;
  size_t next_piece_ = 0;
};

}  // namespace

TransientResult run_transient_exact(const System& system, const std::vector<Probe>& probes,
                                    const TransientOptions& options) {
  Timed<TransientResult> timed;
  TransientResult& result = timed.result;
  result.method = Method::exact;
  result.values.assign(probes.size(), {});
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  if (Status pieces = require_piecewise_linear(system); !pieces.ok()) return finish(pieces);
  for (const Probe& probe : probes)
    if (!is_linear(probe))
      return finish(Status::failure("the exact method takes linear outputs; probe '" + probe.name +
                                    "' squares a voltage (use IDA)"));
  try {
    ExactRun run(system, probes, options, result);
    if (Status started = run.set_start(); !started.ok()) return finish(started);
    return finish(run.run());
  } catch (const std::exception& e) {
    return finish(Status::failure(std::string("exact transient: ") + e.what()));
  }
}

}  // namespace emnet
