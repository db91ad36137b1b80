// Static analysis: displacements at rest from the s → 0 expansion of the pencil.
// See include/emnet/analysis/analysis.hpp for the method.
#include <Eigen/SparseLU>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>

#include "core/timed.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/core/units.hpp"
#include "static_operator.hpp"

namespace emnet {

namespace {

std::vector<bool> mechanical_columns(const System& system) {
  std::vector<bool> mechanical(static_cast<size_t>(system.size()), false);
  for (int k = 0; k < system.size(); ++k) {
    const Unknown& u = system.unknowns[static_cast<size_t>(k)];
    mechanical[static_cast<size_t>(k)] =
        u.kind == Unknown::Kind::node_across && is_mechanical(u.domain);
  }
  return mechanical;
}

// y at rest from z: mechanical across values (velocities) are zero.
Eigen::VectorXd rest_state(const Eigen::VectorXd& z, const std::vector<bool>& mechanical) {
  Eigen::VectorXd y = z;
  for (Eigen::Index k = 0; k < y.size(); ++k)
    if (mechanical[static_cast<size_t>(k)]) y[k] = 0.0;
  return y;
}

}  // namespace

Status check_residual(double residual, const std::string& what, double limit) {
  if (residual <= limit) return Status::success();
  char value[32];
  std::snprintf(value, sizeof value, "%.3g", residual);
  const std::string accepted = short_number(limit);
  return Status::failure(
      what + ": relative residual " +
      (std::isfinite(residual) ? std::string(value) : "not finite (" + std::string(value) + ")") +
      ", where at most " + accepted +
      " is accepted: the solve did not solve its system "
      "(values beyond double precision, or a singular network)");
}

Eigen::SparseMatrix<double> linearised_g(const System& system, const Eigen::VectorXd& y) {
  if (!system.is_nonlinear()) return system.G;
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> jacobian;
  system.nonlinear(y, g, &jacobian);
  Eigen::SparseMatrix<double> sum = system.G + jacobian;
  sum.makeCompressed();
  return sum;
}

Eigen::VectorXcd small_signal_phasors(const System& system,
                                      const Eigen::SparseMatrix<double>& g_matrix, double omega,
                                      double* relative_residual) {
  using Complex = std::complex<double>;
  if (relative_residual) *relative_residual = std::numeric_limits<double>::infinity();
  Eigen::SparseMatrix<Complex> matrix =
      g_matrix.cast<Complex>() + Complex(0.0, omega) * system.C.cast<Complex>();
  matrix.makeCompressed();
  Eigen::SparseLU<Eigen::SparseMatrix<Complex>> lu(matrix);
  if (lu.info() != Eigen::Success) return {};
  const Eigen::VectorXcd input = system.b_ac();
  Eigen::VectorXcd y = lu.solve(input);
  if (relative_residual && y.allFinite())
    *relative_residual = (matrix * y - input).norm() / input.norm();
  return y;
}

RowClassification classify_rows(const System& system, const Eigen::SparseMatrix<double>& g_matrix) {
  RowClassification rows;
  rows.mechanical = mechanical_columns(system);
  const int n = system.size();
  // A row keeps an s⁰ part when G has an entry in a non-mechanical column.
  std::vector<bool> has_order_zero(static_cast<size_t>(n), false);
  for (int col = 0; col < n; ++col) {
    if (rows.mechanical[static_cast<size_t>(col)]) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(g_matrix, col); it; ++it)
      if (it.value() != 0.0) has_order_zero[static_cast<size_t>(it.row())] = true;
  }
  rows.divided.assign(static_cast<size_t>(n), false);
  for (int row = 0; row < n; ++row)
    rows.divided[static_cast<size_t>(row)] = !has_order_zero[static_cast<size_t>(row)];
  return rows;
}

StaticOperator::StaticOperator(const System& system, const Eigen::SparseMatrix<double>& g_matrix) {
  const RowClassification rows = classify_rows(system, g_matrix);
  mechanical_ = rows.mechanical;
  divided_ = rows.divided;
  const int n = system.size();
  // s⁰ part: G on non-mechanical columns. s¹ part: G on mechanical columns + C on the others.
  std::vector<Eigen::Triplet<double>> entries;
  for (int col = 0; col < n; ++col) {
    const bool mech = mechanical_[static_cast<size_t>(col)];
    for (Eigen::SparseMatrix<double>::InnerIterator it(g_matrix, col); it; ++it) {
      const bool divided = divided_[static_cast<size_t>(it.row())];
      if (mech == divided) entries.emplace_back(it.row(), col, it.value());
    }
    if (!mech)
      for (Eigen::SparseMatrix<double>::InnerIterator it(system.C, col); it; ++it)
        if (divided_[static_cast<size_t>(it.row())])
          entries.emplace_back(it.row(), col, it.value());
  }
  matrix_.resize(n, n);
  matrix_.setFromTriplets(entries.begin(), entries.end());
  matrix_.makeCompressed();
  lu_.analyzePattern(matrix_);
  lu_.factorize(matrix_);
  factorised_ = lu_.info() == Eigen::Success;
}

bool StaticOperator::excites_divided_rows(const Eigen::VectorXcd& rhs) const {
  for (Eigen::Index k = 0; k < rhs.size(); ++k)
    if (divided_[static_cast<size_t>(k)] && rhs[k] != 0.0) return true;
  return false;
}

bool StaticOperator::solve(const Eigen::VectorXcd& rhs, Eigen::VectorXcd& z,
                           std::string& why) const {
  if (!factorised_) {
    why =
        "the network has no unique static state (a free body, a mechanism, or a loop of "
        "across sources): check the beam's end conditions";
    return false;
  }
  Eigen::VectorXd re = lu_.solve(rhs.real());
  Eigen::VectorXd im = lu_.solve(rhs.imag());
  z = re.cast<std::complex<double>>() +
      std::complex<double>(0.0, 1.0) * im.cast<std::complex<double>>();
  if (!z.allFinite()) {
    why =
        "the static solve produced non-finite values (a singular network, or values beyond "
        "double precision)";
    return false;
  }
  return true;
}

namespace {

// The outcome of Newton's iteration at one load level.
struct NewtonOutcome {
  bool converged = false;
  bool cancelled = false;
  int iterations = 0;
  std::string why;  ///< why it did not converge
};

// Newton on K·z + g(z) = b from `z` (replaced by the solution when it converges): a sparse LU of
// the linear operator for a linear network, of the Jacobian at every iteration otherwise.
class StaticNewton {
 public:
  StaticNewton(const System& system, const StaticOperator& linear, const StaticOptions& options)
      : system_(system), linear_(linear), options_(options) {}

  Eigen::VectorXd residual(const Eigen::VectorXd& state, const Eigen::VectorXd& b) const {
    Eigen::VectorXd g;
    system_.nonlinear(rest_state(state, linear_.mechanical()), g, nullptr);
    return Eigen::VectorXd(linear_.matrix() * state + g - b);
  }

  NewtonOutcome solve(const Eigen::VectorXd& b, Eigen::VectorXd& z,
                      const std::string& stage) const {
    NewtonOutcome outcome;
    const int n = system_.size();
    // Newton converges fast or not at all: steps that have not shrunk for kStalledIterations
    // iterations in a row mean it is not converging (a load step too large), and the iteration
    // stops there instead of running to max_iterations.
    constexpr int kStalledIterations = 5;
    double smallest_step = std::numeric_limits<double>::infinity();
    int stalled = 0;
    for (int iteration = 1; iteration <= options_.max_iterations; ++iteration) {
      // Newton's count is not known ahead (2-5 iterations usually): no total, no estimate.
      if (!keep_going(options_.progress, 0, 0,
                      "static state (" + std::to_string(n) + " unknowns" + stage +
                          "), Newton iteration " + std::to_string(iteration))) {
        outcome.cancelled = true;
        return outcome;
      }
      outcome.iterations = iteration;
      Eigen::VectorXd step;
      if (!newton_step(residual(z, b), z, iteration, step, outcome.why)) return outcome;
      z += step;
      for (int k = 0; k < n; ++k)
        if (!std::isfinite(z[k])) {
          outcome.why = "the static solution became non-finite at Newton iteration " +
                        std::to_string(iteration) + " (unknown '" +
                        system_.unknowns[static_cast<size_t>(k)].name + "')";
          return outcome;
        }
      if (step.norm() <= options_.tolerance * z.norm() || step.norm() == 0.0) {
        outcome.converged = true;
        return outcome;
      }
      stalled = step.norm() < smallest_step ? 0 : stalled + 1;
      smallest_step = std::min(smallest_step, step.norm());
      if (stalled >= kStalledIterations && system_.is_nonlinear()) {
        outcome.why = "Newton's steps stopped shrinking at iteration " + std::to_string(iteration);
        return outcome;
      }
    }
    outcome.why =
        "Newton did not converge in " + std::to_string(options_.max_iterations) + " iterations";
    return outcome;
  }

 private:
  // The step −J⁻¹·r at z; false with `why` when the Jacobian is singular or the step not finite.
  bool newton_step(const Eigen::VectorXd& r, const Eigen::VectorXd& z, int iteration,
                   Eigen::VectorXd& step, std::string& why) const {
    Eigen::VectorXcd complex_step;
    if (system_.is_nonlinear()) {
      const StaticOperator jacobian(system_,
                                    linearised_g(system_, rest_state(z, linear_.mechanical())));
      if (!jacobian.factorised()) {
        why = "the static Jacobian is singular at Newton iteration " + std::to_string(iteration);
        return false;
      }
      if (!jacobian.solve(-r.cast<std::complex<double>>(), complex_step, why))
        return failed_step(complex_step, iteration, why);
    } else if (!linear_.solve(-r.cast<std::complex<double>>(), complex_step, why)) {
      return failed_step(complex_step, iteration, why);
    }
    step = complex_step.real();
    return true;
  }

  // A failed solve; when it left a non-finite step, `why` names its first unknown.
  bool failed_step(const Eigen::VectorXcd& step, int iteration, std::string& why) const {
    for (Eigen::Index k = 0; k < step.size() && k < system_.size(); ++k)
      if (!std::isfinite(step[k].real()) || !std::isfinite(step[k].imag())) {
        why += ": unknown '" + system_.unknowns[static_cast<size_t>(k)].name +
               "' at Newton iteration " + std::to_string(iteration);
        break;
      }
    return false;
  }

  const System& system_;
  const StaticOperator& linear_;
  const StaticOptions& options_;
};

std::string load_factor_text(double factor) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", factor);
  return text;
}

}  // namespace

StaticResult solve_static(const System& system, const StaticOptions& options) {
  Timed<StaticResult> timed;
  StaticResult& result = timed.result;
  const int n = system.size();
  const StaticOperator linear(system, system.G);
  const Eigen::VectorXd b = system.b_at_rest();
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  if (!linear.factorised())
    return finish(Status::failure(
        "the network has no unique static state (a free body, a mechanism, or a loop of across "
        "sources): check the beam's end conditions"));
  for (int k = 0; k < n; ++k)
    if (linear.divided_rows()[static_cast<size_t>(k)] && b[k] != 0.0)
      return finish(Status::failure("a source imposes a constant velocity on '" +
                                    system.unknowns[static_cast<size_t>(k)].name +
                                    "', so there is no static state"));
  const StaticNewton newton(system, linear, options);
  // Load stepping: the whole load first; where Newton fails, a step half as large from the last
  // state it reached, down to options.smallest_load_step; after a step of few iterations, the
  // next one twice as large.
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  double reached = 0.0, increment = 1.0;
  while (reached < 1.0) {
    const double target = std::min(1.0, reached + increment);
    const std::string stage =
        target < 1.0 || reached > 0.0 ? ", load factor " + load_factor_text(target) : "";
    Eigen::VectorXd trial = z;
    const NewtonOutcome outcome = newton.solve(target * b, trial, stage);
    result.newton_iterations += outcome.iterations;
    if (outcome.cancelled) return finish(cancelled_status());
    if (outcome.converged) {
      z = trial;
      reached = target;
      ++result.load_steps;
      if (outcome.iterations <= 4) increment *= 2.0;
      continue;
    }
    if (!system.is_nonlinear() || increment <= options.smallest_load_step)
      return finish(Status::failure(
          reached == 0.0 && !system.is_nonlinear()
              ? outcome.why
              : "no static state found beyond load factor " + load_factor_text(reached) +
                    " of the whole load (Newton from there, with load steps down to " +
                    load_factor_text(options.smallest_load_step) + ": " + outcome.why +
                    "); the load passes a limit point (buckling or snap-through), or the "
                    "state is beyond what the network can follow"));
    increment *= 0.5;
  }
  result.state = z;
  result.operating_point = rest_state(z, linear.mechanical());
  const double b_norm = b.norm();
  const double r_norm = newton.residual(z, b).norm();
  result.relative_residual = b_norm > 0.0 ? r_norm / b_norm : r_norm;
  return finish(check_residual(result.relative_residual, "static solve"));
}

double static_probe_value(const System& system, const StaticResult& result, const Probe& probe) {
  double value = 0.0;
  for (const auto& [index, coefficient] : probe.terms) {
    const Unknown& u = system.unknowns[static_cast<size_t>(index)];
    const bool mech = u.kind == Unknown::Kind::node_across && is_mechanical(u.domain);
    // z holds displacements on mechanical nodes (y = s·z) and across values elsewhere.
    const int power_of_s = (mech ? 1 : 0) - probe.integrations;
    if (power_of_s == 0) value += coefficient * result.state[index];
  }
  // Squares (a DEA's k_F·u²) of electrical voltages, which z holds as they are.
  return value + squares_value(probe, result.state);
}

}  // namespace emnet
