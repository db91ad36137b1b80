// Periodic steady state by shooting (any network, with IDA): Newton on the state ξ at the
// period's start for ξ(T; ξ) − ξ = 0, each residual one period of IDA.
//
// Newton starts from the periodic state of the network linearised about its static state (exact
// per interval of the sources, state_space.hpp), plus the nonlinear part a sweep carries over
// from its neighbouring frequencies. The Jacobian of the period map starts as the
// linearisation's: Φ(T) − I of its state equation x' = M·x, so a linear network is periodic at
// the first run. Each step improves it by Broyden's update of its inverse, so a weakly
// nonlinear network (large kinematics at a swing of a tenth of its length, DEAs' back-coupling)
// converges in a few one-period runs. Where the contraction stalls (a strongly nonlinear state
// far from the linearisation) the Jacobian is formed again by finite differences of one-period
// runs, one per state. ξ are the linearisation's states restricted to the hidden constraints'
// null space: x = P·ξ, P orthonormal, and IDA starts from u = U·x (U: the state's unknowns).
#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/timed.hpp"
#include "dense_decompositions.hpp"
#include "displacement_form.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/analysis/transient.hpp"
#include "exponential_series.hpp"
#include "state_space.hpp"

namespace emnet {

namespace {

// A one-period run stopped by the caller's cancellation (its Status code), out of the shooting
// iteration.
struct ShootingCancelled {};

// Iterations of the Newton–Broyden loop, and how many of them may contract by less than half
// before the Jacobian is formed again by finite differences (once).
constexpr int kShootingIterations = 30;
constexpr int kSlowStepsBeforeFiniteDifferences = 3;
// A step below this many relative tolerances of ξ that no longer shrinks is the integration's
// noise (Shooting::at_the_integrations_noise), and ξ periodic to IDA's accuracy: the periodicity
// residual is then held to this many tolerances, or kResidualLimit if that is larger.
constexpr double kNoiseSteps = 1000.0;
// The periodicity residual of IDA's period map at a periodic ξ, in relative tolerances of ξ:
// 4 to 300 measured at rtol 1e-9 on the fish fin (7 segments, small and large kinematics), 190
// at rtol 1e-10.
constexpr double kNoiseResidual = 300.0;
// A Newton step whose period run fails, or whose residual is more than kResidualGrowth times the
// last, is halved, at most kStepHalvings times (the last one is taken as it is, its failure
// reported).
constexpr double kResidualGrowth = 2.0;
constexpr int kStepHalvings = 8;

// The network linearised about its static state (or rest, where that fails) as a state space,
// with the basis of the states that satisfy the hidden constraints. It depends on the network's
// matrices and static state only, not on the period: a sweep keeps it (ShootingCache).
struct Linearisation {
  Eigen::VectorXd u_static;
  Eigen::SparseMatrix<double> d_u, d_up;
  std::unique_ptr<LinearStateSpace> space;
  Eigen::MatrixXd basis, u_of_xi;
  Eigen::MatrixXcd modal_inverse;  // V⁻¹ of M's modal basis, when it has one

  // The same linearisation: bit for bit the same matrices and static state.
  bool same(const Eigen::VectorXd& u, const Eigen::SparseMatrix<double>& a,
            const Eigen::SparseMatrix<double>& e) const {
    return u.size() == u_static.size() && u == u_static && identical(a, d_u) && identical(e, d_up);
  }

 private:
  static bool identical(const Eigen::SparseMatrix<double>& x,
                        const Eigen::SparseMatrix<double>& y) {
    if (x.rows() != y.rows() || x.cols() != y.cols() || x.nonZeros() != y.nonZeros() ||
        !x.isCompressed() || !y.isCompressed())
      return false;
    const auto n = static_cast<size_t>(x.nonZeros());
    return std::equal(x.outerIndexPtr(), x.outerIndexPtr() + x.outerSize() + 1,
                      y.outerIndexPtr()) &&
           std::equal(x.innerIndexPtr(), x.innerIndexPtr() + n, y.innerIndexPtr()) &&
           std::equal(x.valuePtr(), x.valuePtr() + n, y.valuePtr());
  }
};

}  // namespace

struct ShootingCache::Impl {
  std::shared_ptr<const Linearisation> last;
  int reuses = 0;
};
ShootingCache::ShootingCache() : impl_(std::make_unique<Impl>()) {}
ShootingCache::~ShootingCache() = default;
int ShootingCache::reuses() const {
  return impl_->reuses;
}

namespace {

// An orthonormal basis of the null space of `constraints` (the identity without rows).
Eigen::MatrixXd constrained_basis(const Eigen::MatrixXd& constraints, Eigen::Index n) {
  if (constraints.rows() == 0) return Eigen::MatrixXd::Identity(n, n);
  const RealSingularValueDecomposition svd = jacobi_svd(constraints, Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singular_values;
  Eigen::Index rank = 0;
  while (rank < sv.size() && sv[rank] > 1e-12 * sv[0]) ++rank;
  return svd.v.rightCols(n - rank);
}

// The linearisation of `system` (its form `form`), `cache`'s when it is the same, else made
// (and kept there). `angular_frequency`: the state space's time unit, the first period's.
std::shared_ptr<const Linearisation> linearisation_of(const System& system,
                                                      const DisplacementForm& form,
                                                      double angular_frequency,
                                                      ShootingCache::Impl* kept) {
  const StaticResult rest = solve_static(system);
  Eigen::VectorXd u =
      rest.status.ok() ? form.from_static(rest.state) : Eigen::VectorXd::Zero(form.size());
  Eigen::SparseMatrix<double> d_u, d_up;
  form.linearised(u, Eigen::VectorXd::Zero(form.size()), d_u, d_up);
  d_u.makeCompressed();
  d_up.makeCompressed();
  if (kept && kept->last && kept->last->same(u, d_u, d_up)) {
    ++kept->reuses;
    return kept->last;
  }
  auto made = std::make_shared<Linearisation>();
  made->space = std::make_unique<LinearStateSpace>(form, d_u, d_up, angular_frequency);
  made->basis =
      constrained_basis(made->space->hidden_constraints_on_state(), made->space->state_size());
  made->u_of_xi = made->space->u_of_state() * made->basis;
  if (const LinearStateSpace::ModalBasis* modal = made->space->modal_basis())
    made->modal_inverse = modal->vectors_lu.inverse();
  made->u_static = std::move(u);
  made->d_u = std::move(d_u);
  made->d_up = std::move(d_up);
  if (kept) kept->last = made;
  return made;
}

// The shooting unknowns ξ: the states of the network's linearisation about its static state
// that satisfy the hidden constraints, with the linearisation's Jacobian Φ(T) − I on them and
// its periodic state.
class ShootingCoordinates {
 public:
  ShootingCoordinates(const System& system, const DisplacementForm& form, double period,
                      ShootingCache::Impl* kept)
      : linear_(linearisation_of(system, form, 2 * M_PI / period, kept)),
        space_(linear_->space.get()),
        basis_(linear_->basis),
        u_of_xi_(linear_->u_of_xi) {
    jacobian_ = basis_.transpose() * period_map_less_identity(period) * basis_;
    linear_periodic_ = linear_periodic_xi(system, form, linear_->u_static, period);
  }
  Eigen::Index size() const { return basis_.cols(); }
  /// The network's unknowns u to start IDA from at ξ.
  Eigen::VectorXd start(const Eigen::VectorXd& xi) const { return u_of_xi_ * xi; }
  /// ξ of the network's unknowns u.
  Eigen::VectorXd of(const Eigen::VectorXd& u) const {
    return basis_.transpose() * space_->state_of(u);
  }
  /// Φ(T) − I of the linearisation, on ξ.
  const Eigen::MatrixXd& linear_jacobian() const { return jacobian_; }
  /// ξ of the linearisation's periodic state under the network's sources: Newton's first
  /// guess, exact for a linear network.
  const Eigen::VectorXd& linear_periodic_state() const { return linear_periodic_; }

 private:
  // Φ(T) − I of the linearisation's state equation: per pole e^{λT} − 1 = λ·T·φ₁(λT) in M's
  // modal basis, when it has a well-conditioned one (O(n³) once, and the linear periodic state
  // uses the same basis); else Γ(T)·M from the exponential of [[M, I], [0, 0]]·T, which a stiff
  // M makes costly (336 ms on the tweezer jaw's 216 states: about 30 squarings of 432 × 432).
  Eigen::MatrixXd period_map_less_identity(double period) const {
    if (const LinearStateSpace::ModalBasis* modal = space_->modal_basis()) {
      Eigen::VectorXcd change(modal->values.size());
      for (Eigen::Index k = 0; k < change.size(); ++k)
        change[k] =
            modal->values[k] * LinearStateSpace::ModalBasis::increment(modal->values[k], period);
      return (modal->vectors * change.asDiagonal() * linear_->modal_inverse).real();
    }
    return space_->propagator(period).gamma * space_->m();
  }

  // N·f over one interval of length h, f = f₀ + s·f₁ (slope: f₁ ≠ 0).
  struct AffineForcing {
    double length;
    Eigen::VectorXd start, slope;
    bool ramp;
  };

  // The state after the intervals from zero. In modal coordinates (q' = λ·q + V⁻¹·N·f) each
  // interval is O(n) once M is decomposed (a dense exponential of 2n or 3n per interval took
  // 0.3 s each on the gripper's 248 unknowns); propagators where M has no well-conditioned basis.
  Eigen::VectorXd forced_response(const std::vector<AffineForcing>& pieces) const {
    if (const LinearStateSpace::ModalBasis* modal = space_->modal_basis()) {
      auto modal_of = [&](const Eigen::VectorXd& v) -> Eigen::VectorXcd {
        return modal->vectors_lu.solve(v.cast<std::complex<double>>());
      };
      Eigen::VectorXcd q = Eigen::VectorXcd::Zero(modal->values.size());
      for (const AffineForcing& piece : pieces) {
        q += modal->increments(piece.length)
                 .cwiseProduct(modal->values.cwiseProduct(q) + modal_of(piece.start));
        if (piece.ramp)
          q += modal->ramp_increments(piece.length).cwiseProduct(modal_of(piece.slope));
      }
      return (modal->vectors * q).real();
    }
    Eigen::VectorXd x = Eigen::VectorXd::Zero(space_->state_size());
    for (const AffineForcing& piece : pieces)
      x = piece.ramp
              ? space_->advance(space_->ramp_propagator(piece.length), x, piece.start, piece.slope)
              : space_->advance(space_->propagator(piece.length), x, piece.start);
    return x;
  }

  // The linearisation about u_s, d_u·δu + d_up·δu' = −F(t, u_s, 0), is affine in time over each
  // interval of the period where the sources are (F is affine in them: the sources' b(t) and the
  // DEAs' forces of ideal drives): its state advances exactly there, from zero to the forced
  // response c at T; the periodic start then solves (Φ(T) − I)·x₀ = −c on ξ, and
  // ξ = ξ(u_s) + x₀.
  Eigen::VectorXd linear_periodic_xi(const System& system, const DisplacementForm& form,
                                     const Eigen::VectorXd& u_static, double period) const {
    const Eigen::VectorXd at_rest = Eigen::VectorXd::Zero(form.size());
    auto forcing_at = [&](double t) {
      Eigen::VectorXd residual;
      form.residual(t, u_static, at_rest, residual);
      return Eigen::VectorXd(-residual);
    };
    std::vector<AffineForcing> pieces;
    double start = 0.0;
    for (const double end : interval_ends(system, period)) {
      // Two points inside the interval, so that a jump at either end is not seen.
      const double h = end - start;
      const Eigen::VectorXd early = forcing_at(start + 0.25 * h),
                            late = forcing_at(start + 0.75 * h);
      const Eigen::VectorXd slope = (late - early) / (0.5 * h);
      pieces.push_back({h, space_->forcing(early - 0.25 * h * slope), space_->forcing(slope),
                        (slope.array() != 0.0).any()});
      start = end;
    }
    const Eigen::VectorXd forced = forced_response(pieces);
    const Eigen::VectorXd periodic_part =
        jacobian_.fullPivLu().solve(-(basis_.transpose() * forced));
    const Eigen::VectorXd xi = basis_.transpose() * space_->state_of(u_static) + periodic_part;
    // A linearisation without a periodic state (an undamped mode in resonance): rest instead.
    return xi.allFinite() ? xi : Eigen::VectorXd::Zero(basis_.cols());
  }

  std::shared_ptr<const Linearisation> linear_;
  const LinearStateSpace* space_;
  const Eigen::MatrixXd& basis_;
  const Eigen::MatrixXd& u_of_xi_;
  Eigen::MatrixXd jacobian_;
  Eigen::VectorXd linear_periodic_;
};

// Sampled extremes refined by a parabola through the neighbouring samples (`step` apart).
void fill_sampled_extremes(PeriodicResult& result, double step) {
  fill_extremes(result, [&](size_t p, size_t low, size_t high) {
    const auto& v = result.values[p];
    const size_t n = v.size();
    const auto parabola = [&](size_t s) {
      const double left = v[(s + n - 1) % n], middle = v[s], right = v[(s + 1) % n];
      const double curvature = left - 2 * middle + right;
      if (curvature == 0.0) return std::pair<double, double>(result.times[s], middle);
      const double offset = 0.5 * (left - right) / curvature;
      return std::pair<double, double>(result.times[s] + offset * step,
                                       middle - 0.25 * (left - right) * offset);
    };
    return std::array<std::pair<double, double>, 2>{parabola(low), parabola(high)};
  });
}

// IDA's options for one period from t = 0 at `rtol`, cancelled through `cancellation`.
TransientOptions one_period_options(double period, double rtol, CancellationOnly& cancellation) {
  TransientOptions options;
  options.end_time = period;
  options.relative_tolerance = rtol;
  options.progress = &cancellation;
  return options;
}

// `samples` instants over one period, at t = T·s/samples.
std::vector<double> sample_times(double period, int samples) {
  std::vector<double> times;
  for (int s = 0; s < samples; ++s) times.push_back(period * s / samples);
  return times;
}

// One shooting solve: the period map, the Newton–Broyden iteration, the sampled last period.
class Shooting {
 public:
  // The run from the converged ξ (a step below the tolerance: the last) samples `probes` at
  // `samples` points, the result's period.
  Shooting(const System& system, const std::vector<Probe>& probes, double period, double rtol,
           int samples, const Progress* progress, ShootingCache::Impl* kept)
      : system_(system),
        probes_(probes),
        form_(system),
        coordinates_(system, form_, period, kept),
        cancellation_(progress),
        options_(one_period_options(period, rtol, cancellation_)),
        rtol_(rtol),
        sample_times_(sample_times(period, samples)) {}

  // The periodic ξ (its period is last_period()); `iterations` and `residual`
  // (‖ξ(T) − ξ‖/‖ξ‖) say how it converged.
  // @throws std::runtime_error when IDA fails; ShootingCancelled
  Eigen::VectorXd solve(const Eigen::VectorXd* nonlinear_part, int& iterations, double& residual) {
    Eigen::VectorXd xi = coordinates_.linear_periodic_state();
    if (nonlinear_part && nonlinear_part->size() == form_.size())
      xi += coordinates_.of(*nonlinear_part);
    Eigen::VectorXd r = period_residual(xi);
    Eigen::MatrixXd inverse = inverse_of(coordinates_.linear_jacobian());
    int slow_steps = 0;
    bool refreshed = false;
    double previous_step = 0.0;
    for (iterations = 1; iterations <= kShootingIterations; ++iterations) {
      Eigen::VectorXd step = -(inverse * r);
      Eigen::VectorXd r_next;
      bool converged = false, halved = false;
      double size = 0.0;
      for (int halving = 0;; ++halving) {
        const Eigen::VectorXd trial = xi + step;
        size = std::max(trial.norm(), 1e-300);
        const double step_norm = step.norm();
        converged =
            step_norm <= 10 * rtol_ * size ||
            at_the_integrations_noise(step_norm, previous_step, size) ||
            (halving == 0 && residual_at_the_integrations_noise(r.norm(), step_norm, size)) ||
            (halving == 0 && remaining_error_below_tolerance(step_norm, previous_step, size));
        if (converged || halving == kStepHalvings) {
          r_next = period_residual(trial, converged);
          break;
        }
        // Far from the periodic state (a strongly nonlinear one, the linearisation's first
        // guess far off) a full step can start IDA where it cannot integrate, or multiply the
        // residual: the step is halved (a backtracking line search), Broyden's update then
        // taking the step made.
        std::optional<Eigen::VectorXd> tried = period_residual_if_integrable(trial);
        if (tried && tried->norm() <= kResidualGrowth * r.norm()) {
          r_next = std::move(*tried);
          break;
        }
        step *= 0.5;
        halved = true;
      }
      xi += step;
      previous_step = halved ? 0.0 : step.norm();
      residual = r_next.norm() / size;
      if (converged) return xi;
      // Broyden's ("good") update of the inverse: the secant condition on this step.
      const Eigen::VectorXd change = r_next - r;
      const Eigen::VectorXd inverse_change = inverse * change;
      const double denominator = step.dot(inverse_change);
      if (std::abs(denominator) > 1e-300)
        inverse += (step - inverse_change) * (step.transpose() * inverse) / denominator;
      slow_steps = r_next.norm() > 0.5 * r.norm() ? slow_steps + 1 : 0;
      r = r_next;
      if (slow_steps >= kSlowStepsBeforeFiniteDifferences && !refreshed) {
        inverse = inverse_of(finite_difference_jacobian(xi, r));
        refreshed = true;
        slow_steps = 0;
      }
    }
    iterations = kShootingIterations;
    return xi;  // not converged: the residual says so
  }

  // The network's unknowns IDA starts from at ξ.
  Eigen::VectorXd start(const Eigen::VectorXd& xi) const { return coordinates_.start(xi); }
  // The network's unknowns at the linearisation's periodic state (the first guess's base).
  Eigen::VectorXd linear_start() const {
    return coordinates_.start(coordinates_.linear_periodic_state());
  }
  // The one-period runs made so far.
  int runs() const { return runs_; }
  // The last period run: from the ξ solve returned, with the probes' samples when it converged.
  const TransientResult& last_period() const { return last_run_; }

 private:
  // ξ(T; ξ) − ξ by one period of IDA, `sampled` or not (the samples cost a return from IDA each:
  // 15 % of a sweep's time when every run took them).
  Eigen::VectorXd period_residual(const Eigen::VectorXd& xi, bool sampled = false) {
    options_.initial_state = coordinates_.start(xi);
    options_.output_times = sampled ? sample_times_ : std::vector<double>{};
    ++runs_;
    last_run_ = run_transient_ida(system_, sampled ? probes_ : std::vector<Probe>{}, options_);
    if (last_run_.status.cancelled()) throw ShootingCancelled{};
    if (!last_run_.status.ok()) throw std::runtime_error(last_run_.status.message);
    return coordinates_.of(last_run_.final_state) - xi;
  }

  // period_residual, or nothing where IDA fails (not where it was cancelled).
  std::optional<Eigen::VectorXd> period_residual_if_integrable(const Eigen::VectorXd& xi) {
    try {
      return period_residual(xi);
    } catch (const std::runtime_error&) {
      return std::nullopt;
    }
  }

  // ∂(ξ(T) − ξ)/∂ξ at ξ (with residual r there) by forward differences, one period per column.
  Eigen::MatrixXd finite_difference_jacobian(const Eigen::VectorXd& xi, const Eigen::VectorXd& r) {
    const double scale = std::max({xi.norm(), (xi + r).norm(), 1e-300});
    const double h = std::sqrt(rtol_) * scale;
    Eigen::MatrixXd jacobian(xi.size(), xi.size());
    for (Eigen::Index k = 0; k < xi.size(); ++k) {
      Eigen::VectorXd perturbed = xi;
      perturbed[k] += h;
      jacobian.col(k) = (period_residual(perturbed) - r) / h;
    }
    return jacobian;
  }

  // The period map is IDA's, as accurate as its tolerance: steps that stop shrinking (by half)
  // below kNoiseSteps·rtol of ξ are its noise, which no further step removes. Its size depends
  // on IDA's absolute tolerances (from the static state and the AC input's scale): 1e-7 of ξ at
  // rtol 1e-9 on the fish fin driven at 400 V with large kinematics.
  bool at_the_integrations_noise(double step, double previous_step, double size) const {
    return previous_step > 0.0 && step >= 0.5 * previous_step && step <= kNoiseSteps * rtol_ * size;
  }

  // A residual within the period map's noise (kNoiseResidual·rtol of ξ) says ξ is periodic to
  // IDA's accuracy whatever the steps did before; the step it gives, below kNoiseSteps·rtol of ξ,
  // is the last. On a linear network started from its exact periodic state this ends the
  // iteration at the first run: the steps in IDA's noise neither shrink nor stall by half, so
  // neither test above saw it, and up to six runs were spent there.
  bool residual_at_the_integrations_noise(double residual, double step, double size) const {
    return residual <= kNoiseResidual * rtol_ * size && step <= kNoiseSteps * rtol_ * size;
  }

  // Newton's contraction ρ = ‖step‖/‖previous step‖ (both full steps) bounds the error left
  // after this step by ρ/(1 − ρ)·‖step‖: when that is below 10·rtol of ξ, under the period map's
  // own noise (~100·rtol), the step is the last. Without it the loop ran two or three more
  // one-period runs into that noise before at_the_integrations_noise saw it stall.
  bool remaining_error_below_tolerance(double step, double previous_step, double size) const {
    if (previous_step <= 0.0) return false;
    const double contraction = step / previous_step;
    return contraction <= 0.5 && contraction / (1 - contraction) * step <= 10 * rtol_ * size;
  }

  static Eigen::MatrixXd inverse_of(const Eigen::MatrixXd& jacobian) {
    return jacobian.fullPivLu().inverse();
  }

  const System& system_;
  const std::vector<Probe>& probes_;
  const DisplacementForm form_;
  const ShootingCoordinates coordinates_;
  CancellationOnly cancellation_;
  TransientOptions options_;
  double rtol_;
  std::vector<double> sample_times_;
  TransientResult last_run_;
  int runs_ = 0;
};

}  // namespace

namespace {

// ‖u(T) − u(0)‖/‖u(0)‖ over the differential unknowns, the state (the algebraic ones of a start
// state are made consistent by IDA at t = 0, so they differ from the given ones by design).
double differential_residual(const DisplacementForm& form, const Eigen::VectorXd& start,
                             const Eigen::VectorXd& end) {
  double change = 0.0, size = 0.0;
  for (int k = 0; k < form.size(); ++k) {
    if (!form.differential()[static_cast<size_t>(k)]) continue;
    change += (end[k] - start[k]) * (end[k] - start[k]);
    size += start[k] * start[k];
  }
  return std::sqrt(change) / std::max(std::sqrt(size), 1e-300);
}

}  // namespace

PeriodicResult sample_periodic_state(const System& given, const std::vector<Probe>& probes,
                                     double period, double rtol, int samples,
                                     const Eigen::VectorXd& start_state, const Progress* progress) {
  const std::optional<System> steady = steady_period_system(given, period);
  const System& system = steady ? *steady : given;
  Timed<PeriodicResult> timed;
  PeriodicResult& result = timed.result;
  result.method = Method::shooting;
  result.period = period;
  CancellationOnly cancellation(progress);
  TransientOptions options = one_period_options(period, rtol, cancellation);
  options.initial_state = start_state;
  options.output_times = sample_times(period, samples);
  const TransientResult run = run_transient_ida(system, probes, options);
  if (run.status.cancelled()) return timed.finish(cancelled_status());
  if (!run.status.ok())
    return timed.finish(Status::failure("periodic state: " + run.status.message));
  result.period_runs = 1;
  result.start_state = start_state;
  result.periodicity_residual =
      differential_residual(DisplacementForm(system), start_state, run.final_state);
  result.times = run.times;
  result.values = run.values;
  fill_sampled_extremes(result, period / samples);
  return timed.finish(Status::success());
}

double shooting_residual_limit(double rtol) {
  return std::max(kResidualLimit, kNoiseSteps * rtol);
}

PeriodicResult run_periodic_shooting(const System& given, const std::vector<Probe>& probes,
                                     double period, double rtol, int samples,
                                     const Progress* progress,
                                     const Eigen::VectorXd* nonlinear_part, ShootingCache* cache) {
  const std::optional<System> steady = steady_period_system(given, period);
  const System& system = steady ? *steady : given;
  Timed<PeriodicResult> timed;
  PeriodicResult& result = timed.result;
  result.method = Method::shooting;
  result.period = period;
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  try {
    Shooting shooting(system, probes, period, rtol, samples, progress,
                      cache ? cache->impl_.get() : nullptr);
    const Eigen::VectorXd xi =
        shooting.solve(nonlinear_part, result.newton_iterations, result.periodicity_residual);
    result.period_runs = shooting.runs();
    if (Status periodic = check_residual(result.periodicity_residual, "shooting: x(T) = x(0)",
                                         shooting_residual_limit(rtol));
        !periodic.ok())
      return finish(periodic);
    const TransientResult& run = shooting.last_period();
    result.start_state = shooting.start(xi);
    result.linear_start_state = shooting.linear_start();
    result.times = run.times;
    result.values = run.values;
    fill_sampled_extremes(result, period / samples);
    return finish(Status::success());
  } catch (const ShootingCancelled&) {
    return finish(cancelled_status());
  } catch (const std::exception& e) {
    return finish(Status::failure(std::string("shooting: ") + e.what()));
  }
}

}  // namespace emnet
