// Static analysis: displacements at rest from the s → 0 expansion of the pencil.
// See include/emnet/analysis/analysis.hpp for the method.
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/timed.hpp"
#include "emnet/analysis/analysis.hpp"
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

Status check_residual(double residual, const std::string& what) {
  static_assert(kResidualLimit == 1e-8, "the message below names the limit");
  if (residual <= kResidualLimit) return Status::success();
  char value[32];
  std::snprintf(value, sizeof value, "%.3g", residual);
  return Status::failure(
      what + ": relative residual " +
      (std::isfinite(residual) ? std::string(value) : "not finite (" + std::string(value) + ")") +
      ", where at most 1e-8 is accepted: the solve did not solve its system "
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

  Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  auto residual = [&](const Eigen::VectorXd& state) {
    Eigen::VectorXd g;
    system.nonlinear(rest_state(state, linear.mechanical()), g, nullptr);
    return Eigen::VectorXd(linear.matrix() * state + g - b);
  };
  // A failed solve; when it left a non-finite step, the failure names its first unknown.
  auto solve_failure = [&](const std::string& why, const Eigen::VectorXcd& step, int iteration) {
    for (Eigen::Index k = 0; k < step.size() && k < n; ++k)
      if (!std::isfinite(step[k].real()) || !std::isfinite(step[k].imag()))
        return Status::failure(why + ": unknown '" + system.unknowns[static_cast<size_t>(k)].name +
                               "' at Newton iteration " + std::to_string(iteration));
    return Status::failure(why);
  };
  const double b_norm = b.norm();
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    // Newton's count is not known ahead (2-5 iterations usually): no total, no estimate.
    if (!keep_going(options.progress, 0, 0,
                    "static state (" + std::to_string(n) + " unknowns), Newton iteration " +
                        std::to_string(iteration)))
      return finish(cancelled_status());
    result.newton_iterations = iteration;
    const Eigen::VectorXd r = residual(z);
    Eigen::VectorXd step;
    if (system.is_nonlinear()) {
      const StaticOperator jacobian(system,
                                    linearised_g(system, rest_state(z, linear.mechanical())));
      if (!jacobian.factorised())
        return finish(Status::failure("the static Jacobian is singular at Newton iteration " +
                                      std::to_string(iteration)));
      Eigen::VectorXcd complex_step;
      std::string why;
      if (!jacobian.solve(-r.cast<std::complex<double>>(), complex_step, why))
        return finish(solve_failure(why, complex_step, iteration));
      step = complex_step.real();
    } else {
      Eigen::VectorXcd complex_step;
      std::string why;
      if (!linear.solve(-r.cast<std::complex<double>>(), complex_step, why))
        return finish(solve_failure(why, complex_step, iteration));
      step = complex_step.real();
    }
    z += step;
    for (int k = 0; k < n; ++k)
      if (!std::isfinite(z[k]))
        return finish(Status::failure("the static solution became non-finite at Newton iteration " +
                                      std::to_string(iteration) + " (unknown '" +
                                      system.unknowns[static_cast<size_t>(k)].name + "')"));
    if (step.norm() <= options.tolerance * z.norm() || step.norm() == 0.0) break;
    if (iteration == options.max_iterations)
      return finish(Status::failure("Newton did not converge in " +
                                    std::to_string(options.max_iterations) + " iterations"));
  }
  result.state = z;
  result.operating_point = rest_state(z, linear.mechanical());
  const double r_norm = residual(z).norm();
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
