// Exact transient of a linear network under piecewise-linear sources: the state equation of
// state_space.hpp stepped by matrix exponentials from breakpoint to breakpoint and to every
// output time, the sources affine on each interval (constant, or a ramp of a pulse's edge or of
// a piecewise-linear source). Rounding is the only error.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/timed.hpp"
#include "displacement_form.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/transient.hpp"
#include "state_space.hpp"
#include "transient_finite.hpp"

namespace emnet {

Status require_piecewise_linear(const System& system) {
  for (const auto& w : system.excitation.waveforms)
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
  result.method = "exact";
  result.values.assign(probes.size(), {});
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  if (Status pieces = require_piecewise_linear(system); !pieces.ok) return finish(pieces);
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
      if (!rest.status.ok)
        return finish(Status::failure("static start state: " + rest.status.message));
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
    // eigen-basis an output inside an interval starting at x₀, where f = f₀ + s·f₁, costs n
    // exponentials and a dot product per probe:
    //   p(t₀ + h) = p(x₀, f₀, f₁) + Re Σ_k (gᵀV)_k·(r_k·h·φ₁(λ_k h) + q_k·h²·φ₂(λ_k h)) + h·c(f₁),
    //   r = V⁻¹·(M·x₀ + N·f₀),  q = V⁻¹·N·f₁ (the ramp terms only where f₁ ≠ 0).
    const LinearStateSpace::ModalBasis* basis = space.modal_basis();
    std::vector<Eigen::RowVectorXcd> probe_modes;
    const Eigen::VectorXd no_force = Eigen::VectorXd::Zero(form.size());
    if (basis) {
      for (const Probe& probe : probes) {
        Eigen::RowVectorXd g(space.state_size());
        for (Eigen::Index k = 0; k < space.state_size(); ++k) {
          Eigen::VectorXd unit = Eigen::VectorXd::Zero(space.state_size());
          unit[k] = 1.0;
          space.full_state(unit, no_force, u, up);
          g[k] = form.probe(probe, u, up);
        }
        probe_modes.push_back(g.cast<std::complex<double>>() * basis->vectors);
      }
    }
    const Eigen::VectorXd no_state = Eigen::VectorXd::Zero(space.state_size());
    for (double stop : stops) {
      if (stop <= t) continue;
      // The sources on [t, stop]: f₀ + (τ − t)·f₁, f₁ = 0 on a constant interval.
      const AffinePiece f = affine_piece(system, form.size(), t, stop);
      const bool ramp = f.ramp();
      const Eigen::VectorXd nf = space.forcing(f.start);
      const Eigen::VectorXd nf_slope = ramp ? space.forcing(f.slope) : Eigen::VectorXd();
      std::vector<double> start_values, ramp_values;
      std::vector<Eigen::RowVectorXcd> weights, ramp_weights;
      if (basis && next_output < outputs.size() && outputs[next_output] <= stop) {
        if (ramp)
          space.full_state(x, f.start, f.slope, u, up);
        else
          space.full_state(x, f.start, u, up);
        const Eigen::VectorXcd rate =
            basis->vectors_lu.solve((space.m() * x + nf).cast<std::complex<double>>());
        for (size_t k = 0; k < probes.size(); ++k) {
          start_values.push_back(form.probe(probes[k], u, up));
          weights.push_back(probe_modes[k].cwiseProduct(rate.transpose()));
        }
        if (ramp) {
          const Eigen::VectorXcd ramp_rate =
              basis->vectors_lu.solve(nf_slope.cast<std::complex<double>>());
          space.full_state(no_state, f.slope, u, up);  // c(f₁)
          for (size_t k = 0; k < probes.size(); ++k) {
            ramp_values.push_back(form.probe(probes[k], u, up));
            ramp_weights.push_back(probe_modes[k].cwiseProduct(ramp_rate.transpose()));
          }
        }
      }
      while (next_output < outputs.size() && outputs[next_output] <= stop) {
        const double h = outputs[next_output] - t;
        if (h >= 0.0) {
          result.times.push_back(outputs[next_output]);
          if (basis) {
            const Eigen::VectorXcd increments = basis->increments(h);
            if (!ramp) {
              for (size_t k = 0; k < probes.size(); ++k)
                result.values[k].push_back(start_values[k] +
                                           (weights[k] * increments).value().real());
            } else {
              const Eigen::VectorXcd ramp_increments = basis->ramp_increments(h);
              for (size_t k = 0; k < probes.size(); ++k)
                result.values[k].push_back(
                    start_values[k] + (weights[k] * increments).value().real() +
                    (ramp_weights[k] * ramp_increments).value().real() + h * ramp_values[k]);
            }
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
      if (!ramp)
        x = space.project(space.advance(cache.get(stop - t), x, nf), f.start);
      else
        x = space.project(space.advance(cache.get_ramp(stop - t), x, nf, nf_slope), f.at(stop - t));
      ++result.statistics.restarts;
      t = stop;
    }
    result.statistics.steps = static_cast<long>(cache.size());  // distinct exponentials
    if (Status finite = check_finite_outputs(result, probes, "the exact method"); !finite.ok)
      return finish(Status::failure(finite.message +
                                    " (values beyond double precision: check the scene's "
                                    "magnitudes)"));
    return finish(Status::success());
  } catch (const std::exception& e) {
    return finish(Status::failure(std::string("exact transient: ") + e.what()));
  }
}

}  // namespace emnet
