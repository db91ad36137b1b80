// Exact transient of a linear network under piecewise-constant sources.
//
// The displacement form E·u' + A·u = f(t) has index 1. With E = U·S·Vᵀ (rank r), u = V·w and
// Â = Uᵀ·A·V, f̂ = Uᵀ·f:  w₂ = Â₂₂⁻¹·(f̂₂ − Â₂₁·w₁) and, for the state x = w₁,
//   x' = M·x + N·f,   M = S₁⁻¹·(Â₁₂·Â₂₂⁻¹·Â₂₁ − Â₁₁),   N·f = S₁⁻¹·(f̂₁ − Â₁₂·Â₂₂⁻¹·f̂₂).
// Over an interval of constant f and length h:  x(t+h) = Φ(h)·x(t) + Γ(h)·N·f with
// Φ = e^{Mh}, Γ = ∫₀ʰ e^{Ms} ds, both from one exponential of the block matrix [[M, I], [0, 0]]·h
// (Van Loan), cached per distinct h. Rounding is the only error.
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <unsupported/Eigen/MatrixFunctions>

#include "displacement_form.hpp"
#include "emnet/analysis.hpp"
#include "emnet/transient.hpp"

namespace emnet {

namespace {

struct Propagator {
  Eigen::MatrixXd phi, gamma;
};

}  // namespace

TransientResult run_transient_exact(const System& system, const std::vector<Probe>& probes,
                                    const TransientOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  TransientResult result;
  result.method = "exact";
  result.values.assign(probes.size(), {});
  auto finish = [&](Status status) {
    result.status = std::move(status);
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  };
  if (system.is_nonlinear())
    return finish(Status::failure(
        "the exact method needs a linear network; this one has nonlinear DEAs (set "
        "drive.electrical_dynamics = false for ideal voltage-driven DEAs, or use IDA)"));
  for (const auto& w : system.waveforms) {
    const bool constant_pieces =
        w.shape == Waveform::Shape::dc ||
        (w.shape == Waveform::Shape::pulse && w.rise == 0.0 && w.fall == 0.0);
    if (!constant_pieces)
      return finish(Status::failure(
          "the exact method needs piecewise-constant sources (zero rise and fall times)"));
  }
  try {
    const DisplacementForm form(system);
    const int n = form.size();
    const Eigen::MatrixXd e = Eigen::MatrixXd(form.e()), a = Eigen::MatrixXd(form.a());
    // E = U·S·Vᵀ; with u = V·w and the rows taken by Uᵀ, the first r = rank(E) components w₁
    // are the state and w₂ follows algebraically (index 1: Â₂₂ invertible).
    const Eigen::BDCSVD<Eigen::MatrixXd> svd(e, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::VectorXd sigma = svd.singularValues();
    Eigen::Index nd = 0;
    while (nd < sigma.size() && sigma[nd] > 1e-12 * sigma[0]) ++nd;
    const Eigen::Index na = n - nd;
    const Eigen::MatrixXd& left = svd.matrixU();
    const Eigen::MatrixXd& right = svd.matrixV();
    const Eigen::MatrixXd a_hat = left.transpose() * a * right;
    const Eigen::MatrixXd a11 = a_hat.topLeftCorner(nd, nd), a12 = a_hat.topRightCorner(nd, na),
                          a21 = a_hat.bottomLeftCorner(na, nd),
                          a22 = a_hat.bottomRightCorner(na, na);
    const Eigen::FullPivLU<Eigen::MatrixXd> a22_lu(a22);
    if (na > 0 && !a22_lu.isInvertible())
      return finish(Status::failure("the network's DAE has index > 1 or no unique solution"));
    const Eigen::MatrixXd a22_inv_a21 =
        na > 0 ? Eigen::MatrixXd(a22_lu.solve(a21)) : Eigen::MatrixXd(0, nd);
    const Eigen::VectorXd sigma_inv = sigma.head(nd).cwiseInverse();
    const Eigen::MatrixXd m = sigma_inv.asDiagonal() * (a12 * a22_inv_a21 - a11);
    if (!m.allFinite()) return finish(Status::failure("the reduced state matrix is not finite"));

    // Forcing N·f (state equation) and Â₂₂⁻¹·f̂₂ (algebraic part) for a constant f.
    auto forcing = [&](const Eigen::VectorXd& f) {
      const Eigen::VectorXd f_hat = left.transpose() * f;
      const Eigen::VectorXd a22_inv_f2 =
          na > 0 ? Eigen::VectorXd(a22_lu.solve(f_hat.tail(na))) : Eigen::VectorXd(0);
      const Eigen::VectorXd nf = sigma_inv.asDiagonal() * (f_hat.head(nd) - a12 * a22_inv_f2);
      return std::pair<Eigen::VectorXd, Eigen::VectorXd>(nf, a22_inv_f2);
    };
    // Cached per interval length, quantised at 1e-13 of the run (rounding of t, not physics).
    std::map<long long, Propagator> cache;
    const double quantum = 1e-13 * std::max(options.end_time, 1e-300);
    auto propagator = [&](double h) -> const Propagator& {
      const long long key = std::llround(h / quantum);
      auto found = cache.find(key);
      if (found != cache.end()) return found->second;
      Eigen::MatrixXd augmented = Eigen::MatrixXd::Zero(2 * nd, 2 * nd);
      augmented.topLeftCorner(nd, nd) = m * h;
      augmented.topRightCorner(nd, nd) = Eigen::MatrixXd::Identity(nd, nd) * h;
      const Eigen::MatrixXd exponential = augmented.exp();
      return cache
          .emplace(key, Propagator{exponential.topLeftCorner(nd, nd),
                                   exponential.topRightCorner(nd, nd)})
          .first->second;
    };
    // Full u and u' from the state x = w₁ at a time where the forcing is f.
    auto full_state = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& f, Eigen::VectorXd& u,
                          Eigen::VectorXd& up) {
      const auto [nf, a22_inv_f2] = forcing(f);
      const Eigen::VectorXd xp = m * x + nf;
      Eigen::VectorXd w(n), wp(n);
      w.head(nd) = x;
      wp.head(nd) = xp;
      if (na > 0) {
        w.tail(na) = a22_inv_f2 - a22_inv_a21 * x;
        wp.tail(na) = -a22_inv_a21 * xp;
      }
      u = right * w;
      up = right * wp;
    };

    // Start: rest (x = 0) or the static state.
    Eigen::VectorXd x = Eigen::VectorXd::Zero(nd);
    if (options.start == StartState::static_) {
      const StaticResult rest = solve_static(system);
      if (!rest.status.ok)
        return finish(Status::failure("static start state: " + rest.status.message));
      x = (right.transpose() * form.from_static(rest.state)).head(nd);
    }
    std::vector<double> stops = system.breakpoints(0.0, options.end_time);
    if (stops.empty() || stops.back() < options.end_time) stops.push_back(options.end_time);
    std::vector<double> outputs = options.output_times;
    std::sort(outputs.begin(), outputs.end());
    size_t next_output = 0;
    double t = 0.0;
    Eigen::VectorXd u, up;
    for (double stop : stops) {
      if (stop <= t) continue;
      const Eigen::VectorXd f = form.f(0.5 * (t + stop));  // constant inside the interval
      const Eigen::VectorXd nf = forcing(f).first;
      const Eigen::VectorXd x_begin = x;
      while (next_output < outputs.size() && outputs[next_output] <= stop) {
        const double h = outputs[next_output] - t;
        if (h >= 0.0) {
          const Propagator& p = propagator(h);
          const Eigen::VectorXd x_out = p.phi * x_begin + p.gamma * nf;
          full_state(x_out, f, u, up);
          result.times.push_back(outputs[next_output]);
          for (size_t k = 0; k < probes.size(); ++k)
            result.values[k].push_back(form.probe(probes[k], u, up));
        }
        ++next_output;
      }
      const Propagator& p = propagator(stop - t);
      x = p.phi * x_begin + p.gamma * nf;
      ++result.statistics.restarts;
      t = stop;
    }
    result.statistics.steps = static_cast<long>(cache.size());  // distinct exponentials
    return finish(Status::success());
  } catch (const std::exception& e) {
    return finish(Status::failure(std::string("exact transient: ") + e.what()));
  }
}

}  // namespace emnet
