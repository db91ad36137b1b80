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
          "not piecewise linear; use --method ida");
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
    const DisplacementForm form(system);
    const LinearStateSpace space(form, characteristic_angular_frequency(system, options.end_time));
    PropagatorCache cache(space, 1e-13 * std::max(options.end_time, 1e-300));

    Eigen::VectorXd x = Eigen::VectorXd::Zero(space.state_size());
    if (options.start == StartState::static_) {
      const StaticResult rest = solve_static(system);
      if (!rest.status.ok()) return finish(rest.status.with_context("static start state: "));
      x = space.state_of(form.from_static(rest.state));
    }
    const std::vector<double> stops = interval_ends(system, options.end_time);
    std::vector<double> outputs = options.output_times;
    std::sort(outputs.begin(), outputs.end());
    size_t next_output = 0;
    result.times.reserve(outputs.size());
    for (auto& series : result.values) series.reserve(outputs.size());
    double t = 0.0;
    Eigen::VectorXd u, up;
    // Outputs: each probe is linear in (x, f, f'), p = gᵀ·x + c(f) + d(f'), so with M's
    // eigen-basis an output inside an interval starting at x₀, where f = f₀ + s·f₁, is
    //   p(t₀ + h) = p(x₀, f₀, f₁) + Re Σ_k (gᵀV)_k·(r_k·h·φ₁(λ_k h) + q_k·h²·φ₂(λ_k h)) + h·c(f₁),
    //   r = V⁻¹·(M·x₀ + N·f₀),  q = V⁻¹·N·f₁ (the ramp terms only where f₁ ≠ 0),
    // the sum over one pole of each conjugate pair (ModalBasis::half) and h·φ₁, h²·φ₂ stepped
    // from output to output by ModalClock: a few products per pole and probe per output.
    const LinearStateSpace::ModalBasis* basis = space.modal_basis();
    Eigen::MatrixXcd probe_modes;  // [probe][half pole]: (gᵀV)_k·factor_k
    std::unique_ptr<ModalClock> clock;
    Eigen::MatrixXcd half_vectors;  // V's columns of ModalBasis::half, times their factor
    if (basis) {
      const Eigen::Index half = static_cast<Eigen::Index>(basis->half.size());
      probe_modes.resize(static_cast<Eigen::Index>(probes.size()), half);
      const Eigen::MatrixXd u_x = space.u_of_state();
      Eigen::RowVectorXd on_u, on_up;
      // u' of a state under zero sources is u_x·M·x.
      const Eigen::MatrixXd up_x = u_x * space.m();
      for (size_t k = 0; k < probes.size(); ++k) {
        form.probe_rows(probes[k], on_u, on_up);
        const Eigen::RowVectorXd g = on_u * u_x + on_up * up_x;
        const Eigen::RowVectorXcd modes = g.cast<std::complex<double>>() * basis->vectors;
        for (Eigen::Index j = 0; j < half; ++j)
          probe_modes(static_cast<Eigen::Index>(k), j) =
              modes[basis->half[static_cast<size_t>(j)]] * basis->half_factor[j];
      }
      clock = std::make_unique<ModalClock>(*basis);
      half_vectors.resize(basis->vectors.rows(), half);
      for (Eigen::Index j = 0; j < half; ++j)
        half_vectors.col(j) =
            basis->vectors.col(basis->half[static_cast<size_t>(j)]) * basis->half_factor[j];
    }
    auto half_of = [&](const Eigen::VectorXcd& full) {
      Eigen::VectorXcd out(static_cast<Eigen::Index>(basis->half.size()));
      for (size_t j = 0; j < basis->half.size(); ++j)
        out[static_cast<Eigen::Index>(j)] = full[basis->half[j]];
      return out;
    };
    const Eigen::VectorXd no_state = Eigen::VectorXd::Zero(space.state_size());
    for (double stop : stops) {
      if (stop <= t) continue;
      // The sources on [t, stop]: f₀ + (τ − t)·f₁, f₁ = 0 on a constant interval.
      const AffinePiece f = affine_piece(system, form.size(), t, stop);
      const bool ramp = f.ramp();
      const Eigen::VectorXd nf = space.forcing(f.start);
      const Eigen::VectorXd nf_slope = ramp ? space.forcing(f.slope) : Eigen::VectorXd();
      Eigen::VectorXd start_values, ramp_values;
      Eigen::VectorXcd rate, ramp_rate;  // [half pole]: V⁻¹·(M·x + N·f₀), V⁻¹·N·f₁
      Eigen::MatrixXcd weights, ramp_weights;  // [probe][half pole]
      const bool outputs_here = next_output < outputs.size() && outputs[next_output] <= stop;
      if (basis) {
        rate = half_of(basis->vectors_lu.solve((space.m() * x + nf).cast<std::complex<double>>()));
        if (ramp)
          ramp_rate = half_of(basis->vectors_lu.solve(nf_slope.cast<std::complex<double>>()));
        clock->restart(ramp);
      }
      if (basis && outputs_here) {
        if (ramp)
          space.full_state(x, f.start, f.slope, u, up);
        else
          space.full_state(x, f.start, u, up);
        start_values.resize(static_cast<Eigen::Index>(probes.size()));
        for (size_t k = 0; k < probes.size(); ++k)
          start_values[static_cast<Eigen::Index>(k)] = form.probe(probes[k], u, up);
        weights = probe_modes * rate.asDiagonal();
        if (ramp) {
          space.full_state(no_state, f.slope, u, up);  // c(f₁)
          ramp_values.resize(static_cast<Eigen::Index>(probes.size()));
          for (size_t k = 0; k < probes.size(); ++k)
            ramp_values[static_cast<Eigen::Index>(k)] = form.probe(probes[k], u, up);
          ramp_weights = probe_modes * ramp_rate.asDiagonal();
        }
      }
      Eigen::VectorXd values;
      while (next_output < outputs.size() && outputs[next_output] <= stop) {
        const double h = outputs[next_output] - t;
        if (h >= 0.0) {
          result.times.push_back(outputs[next_output]);
          if (basis) {
            clock->advance_to(h);
            values = start_values + (weights * clock->integral()).real();
            if (ramp) values += (ramp_weights * clock->ramp_integral()).real() + h * ramp_values;
            for (size_t k = 0; k < probes.size(); ++k)
              result.values[k].push_back(values[static_cast<Eigen::Index>(k)]);
          } else if (!ramp) {
            space.full_state(space.project(space.advance(cache.get(h), x, nf), f.start), f.start, u,
                             up);
            for (size_t k = 0; k < probes.size(); ++k)
              result.values[k].push_back(form.probe(probes[k], u, up));
          } else {
            const Eigen::VectorXd f_h = f.at(h);
            space.full_state(space.project(space.advance(cache.get_ramp(h), x, nf, nf_slope), f_h),
                             f_h, f.slope, u, up);
            for (size_t k = 0; k < probes.size(); ++k)
              result.values[k].push_back(form.probe(probes[k], u, up));
          }
        }
        ++next_output;
        if (!keep_going(options.progress, static_cast<long>(next_output),
                        static_cast<long>(outputs.size()), "output times"))
          return finish(cancelled_status());
      }
      if (cancel_requested(options.progress)) return finish(cancelled_status());
      const double length = stop - t;
      if (basis) {
        // The interval's end in the same modal form: x + Re V·(I(h)∘r + J(h)∘q), over one pole
        // of each pair (factor 2 for a pair) — no exponential of M.
        clock->advance_to(length);
        Eigen::VectorXcd modal = rate.cwiseProduct(clock->integral());
        if (ramp) modal += ramp_rate.cwiseProduct(clock->ramp_integral());
        x = space.project(x + (half_vectors * modal).real(), ramp ? f.at(length) : f.start);
      } else if (!ramp) {
        x = space.project(space.advance(cache.get(length), x, nf), f.start);
      } else {
        x = space.project(space.advance(cache.get_ramp(length), x, nf, nf_slope), f.at(length));
      }
      ++result.statistics.restarts;
      t = stop;
    }
    // Distinct exponentials of M (none in the modal form).
    result.statistics.steps = static_cast<long>(cache.size());
    if (Status finite = check_finite_outputs(result, probes, "the exact method"); !finite.ok())
      return finish(Status::failure(finite.message +
                                    " (values beyond double precision: check the scene's "
                                    "magnitudes)"));
    return finish(Status::success());
  } catch (const std::exception& e) {
    return finish(Status::failure(std::string("exact transient: ") + e.what()));
  }
}

}  // namespace emnet
