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

// Largest |F_i| relative to the size of the terms of row i (|E||u'| + |A||u| + |f| + |ĝ|).
double relative_residual(const DisplacementForm& form, double source_time, const Eigen::VectorXd& u,
                         const Eigen::VectorXd& up, const Eigen::VectorXd& residual) {
  const Eigen::VectorXd terms = form.e().cwiseAbs() * up.cwiseAbs() +
                                form.a().cwiseAbs() * u.cwiseAbs() + form.f(source_time).cwiseAbs();
  const Eigen::VectorXd linear = form.e() * up + form.a() * u - form.f(source_time);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < residual.size(); ++i) {
    const double size = terms[i] + std::abs(residual[i] - linear[i]);  // + |ĝ_i|
    if (residual[i] != 0.0) worst = std::max(worst, std::abs(residual[i]) / size);
  }
  return worst;
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
    worst = relative_residual(form, source_time, trial_u, trial_up, residual);
    if (worst <= 1e-13 || (iteration > 0 && worst <= 1e-10 && !form.system().is_nonlinear())) {
      u = trial_u;
      up = trial_up;
      return Status::success();
    }
    // J_w: ∂F/∂u' on differential columns, ∂F/∂u on algebraic ones.
    std::vector<Eigen::Triplet<double>> with_derivative, without;
    form.jacobian(1.0, trial_u, trial_up, with_derivative);
    form.jacobian(0.0, trial_u, trial_up, without);
    const Eigen::SparseMatrix<double> d_u = from_triplets(n, without);
    const Eigen::SparseMatrix<double> d_up = from_triplets(n, with_derivative) - d_u;
    std::vector<Eigen::Triplet<double>> entries;
    for (int col = 0; col < n; ++col) {
      const Eigen::SparseMatrix<double>& source =
          differential[static_cast<size_t>(col)] ? d_up : d_u;
      for (Eigen::SparseMatrix<double>::InnerIterator it(source, col); it; ++it)
        if (it.value() != 0.0) entries.emplace_back(it.row(), col, it.value());
    }
    Eigen::SparseMatrix<double> jacobian = from_triplets(n, entries);
    const DiagonalScaling scaling = equilibrate(jacobian);
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
