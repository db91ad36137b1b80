// Consistent start values by Newton's method on (u'_d, u_a): see consistent_start.hpp.
#include "consistent_start.hpp"

#include <Eigen/SparseLU>
#include <cmath>
#include <string>
#include <vector>

#include "equilibration.hpp"

namespace emnet {

namespace {

Eigen::SparseMatrix<double> from_triplets(int n, const std::vector<Eigen::Triplet<double>>& t) {
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

// Normwise backward error of F in the equilibrated rows: ‖R·F‖∞ / ‖R·(|E||u'| + |A||u| + |f| +
// |ĝ|)‖∞. A row-by-row measure would be fooled by rows whose terms are all rounding noise
// (1e-319 at N = 1000, where the residual is of the same size).
double relative_residual(const DisplacementForm& form, double source_time, const Eigen::VectorXd& u,
                         const Eigen::VectorXd& up, const Eigen::VectorXd& residual,
                         const Eigen::VectorXd& row_scale) {
  const Eigen::VectorXd linear = form.e() * up + form.a() * u - form.f(source_time);
  const Eigen::VectorXd terms = form.e().cwiseAbs() * up.cwiseAbs() +
                                form.a().cwiseAbs() * u.cwiseAbs() +
                                form.f(source_time).cwiseAbs() + (residual - linear).cwiseAbs();
  const double size = row_scale.cwiseProduct(terms).lpNorm<Eigen::Infinity>();
  const double error = row_scale.cwiseProduct(residual).lpNorm<Eigen::Infinity>();
  return error == 0.0 ? 0.0 : error / size;
}

}  // namespace

Status make_consistent(const DisplacementForm& form, double source_time, Eigen::VectorXd& u,
                       Eigen::VectorXd& up) {
  const int n = form.size();
  const std::vector<bool>& differential = form.differential();
  Eigen::VectorXd trial_u = u, trial_up = up;
  for (int k = 0; k < n; ++k)
    if (!differential[static_cast<size_t>(k)]) trial_up[k] = 0.0;
  Eigen::VectorXd residual;
  double worst = 0.0;
  for (int iteration = 0; iteration < 20; ++iteration) {
    form.residual(source_time, trial_u, trial_up, residual);
    if (!residual.allFinite()) return Status::failure("the residual is not finite");
    // J_w: ∂F/∂u' on differential columns, ∂F/∂u on algebraic ones.
    Eigen::SparseMatrix<double> d_u, d_up;
    form.linearised(trial_u, trial_up, d_u, d_up);
    std::vector<Eigen::Triplet<double>> entries;
    for (int col = 0; col < n; ++col) {
      const Eigen::SparseMatrix<double>& source =
          differential[static_cast<size_t>(col)] ? d_up : d_u;
      for (Eigen::SparseMatrix<double>::InnerIterator it(source, col); it; ++it)
        if (it.value() != 0.0) entries.emplace_back(it.row(), col, it.value());
    }
    Eigen::SparseMatrix<double> jacobian = from_triplets(n, entries);
    const DiagonalScaling scaling = equilibrate(jacobian);
    worst = relative_residual(form, source_time, trial_u, trial_up, residual, scaling.row);
    if (worst <= 1e-14 || (iteration > 0 && worst <= 1e-11)) {
      u = trial_u;
      up = trial_up;
      return Status::success();
    }
    Eigen::SparseMatrix<double> scaled_jacobian = scaled(jacobian, scaling);
    scaled_jacobian.makeCompressed();
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
    lu.compute(scaled_jacobian);
    if (lu.info() != Eigen::Success)
      return Status::failure("the consistency matrix [∂F/∂u'_d, ∂F/∂u_a] is singular (index > 1?)");
    const Eigen::VectorXd step =
        scaling.column.cwiseProduct(lu.solve(scaling.row.cwiseProduct(residual)));
    if (!step.allFinite()) return Status::failure("the Newton step is not finite");
    for (int k = 0; k < n; ++k) {
      if (differential[static_cast<size_t>(k)])
        trial_up[k] -= step[k];
      else
        trial_u[k] -= step[k];
    }
  }
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "Newton did not converge (relative residual %.3g)", worst);
  return Status::failure(buffer);
}

}  // namespace emnet
