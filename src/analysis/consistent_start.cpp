// Consistent start values by Newton's method on (u'_d, u_a): see consistent_start.hpp.
#include "consistent_start.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace emnet {

ConsistentStart::ConsistentStart(const DisplacementForm& form)
    : form_(form), absolute_e_(form.e().cwiseAbs()), absolute_a_(form.a().cwiseAbs()) {}

// Normwise backward error of F in the equilibrated rows: ‖R·F‖∞ / ‖R·(|E||u'| + |A||u| + |f| +
// |ĝ|)‖∞. A row-by-row measure would be fooled by rows whose terms are all rounding noise
// (1e-319 at N = 1000, where the residual is of the same size).
double ConsistentStart::relative_residual(double source_time, const Eigen::VectorXd& u,
                                          const Eigen::VectorXd& up,
                                          const Eigen::VectorXd& residual) const {
  const Eigen::VectorXd f = form_.f(source_time);
  const Eigen::VectorXd linear = form_.e() * up + form_.a() * u - f;
  const Eigen::VectorXd terms = absolute_e_ * up.cwiseAbs() + absolute_a_ * u.cwiseAbs() +
                                f.cwiseAbs() + (residual - linear).cwiseAbs();
  const double size = scaling_.row.cwiseProduct(terms).lpNorm<Eigen::Infinity>();
  const double error = scaling_.row.cwiseProduct(residual).lpNorm<Eigen::Infinity>();
  return error == 0.0 ? 0.0 : error / size;
}

// J_w = [∂F/∂u'_d, ∂F/∂u_a] at (u, u').
Eigen::SparseMatrix<double> ConsistentStart::consistency_matrix(const Eigen::VectorXd& u,
                                                                const Eigen::VectorXd& up) const {
  const int n = form_.size();
  const std::vector<bool>& differential = form_.differential();
  Eigen::SparseMatrix<double> d_u, d_up;
  form_.linearised(u, up, d_u, d_up);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(d_u.nonZeros() + d_up.nonZeros()));
  for (int col = 0; col < n; ++col) {
    const Eigen::SparseMatrix<double>& source = differential[static_cast<size_t>(col)] ? d_up : d_u;
    for (Eigen::SparseMatrix<double>::InnerIterator it(source, col); it; ++it)
      if (it.value() != 0.0) entries.emplace_back(it.row(), col, it.value());
  }
  Eigen::SparseMatrix<double> matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  return matrix;
}

bool ConsistentStart::same_as_factorised(const Eigen::SparseMatrix<double>& matrix) const {
  if (!factorised_ || matrix.nonZeros() != factorised_matrix_.nonZeros()) return false;
  const Eigen::Index n = matrix.outerSize(), nonzeros = matrix.nonZeros();
  return std::equal(matrix.outerIndexPtr(), matrix.outerIndexPtr() + n + 1,
                    factorised_matrix_.outerIndexPtr()) &&
         std::equal(matrix.innerIndexPtr(), matrix.innerIndexPtr() + nonzeros,
                    factorised_matrix_.innerIndexPtr()) &&
         std::equal(matrix.valuePtr(), matrix.valuePtr() + nonzeros, factorised_matrix_.valuePtr());
}

// Scaling and LU of J_w. Both are functions of J_w alone, so an identical J_w (every edge of a
// linear network) reuses them. At N = 3000 an edge took 0.12 s (two equilibrations of 37 ms,
// one per Newton iteration, and an LU of 20 ms), against 0.8 s for all of IDA's steps over
// two periods; a converged iterate now needs neither.
Status ConsistentStart::factorise(Eigen::SparseMatrix<double> matrix) {
  if (same_as_factorised(matrix)) return Status::success();
  factorised_ = false;
  scaling_ = equilibrate(matrix);
  Eigen::SparseMatrix<double> scaled_matrix = scaled(matrix, scaling_);
  scaled_matrix.makeCompressed();
  lu_.compute(scaled_matrix);
  if (lu_.info() != Eigen::Success)
    return Status::failure("the consistency matrix [∂F/∂u'_d, ∂F/∂u_a] is singular (index > 1?)");
  factorised_matrix_ = std::move(matrix);
  factorised_ = true;
  return Status::success();
}

Status ConsistentStart::make_consistent(double source_time, Eigen::VectorXd& u,
                                        Eigen::VectorXd& up) {
  const int n = form_.size();
  const std::vector<bool>& differential = form_.differential();
  Eigen::VectorXd trial_u = u, trial_up = up;
  for (int k = 0; k < n; ++k)
    if (!differential[static_cast<size_t>(k)]) trial_up[k] = 0.0;
  Eigen::VectorXd residual;
  double worst = 0.0;
  for (int iteration = 0; iteration < 20; ++iteration) {
    form_.residual(source_time, trial_u, trial_up, residual);
    if (!residual.allFinite()) return Status::failure("the residual is not finite");
    // The first test uses the scaling of J_w at the start values; later ones that of the
    // previous iterate's J_w (the same for a linear network), so that a converged iterate
    // needs no new J_w.
    if (iteration == 0)
      if (Status status = factorise(consistency_matrix(trial_u, trial_up)); !status.ok())
        return status;
    worst = relative_residual(source_time, trial_u, trial_up, residual);
    if (worst <= 1e-14 || (iteration > 0 && worst <= 1e-11)) {
      u = trial_u;
      up = trial_up;
      return Status::success();
    }
    if (iteration > 0)
      if (Status status = factorise(consistency_matrix(trial_u, trial_up)); !status.ok())
        return status;
    const Eigen::VectorXd step =
        scaling_.column.cwiseProduct(lu_.solve(scaling_.row.cwiseProduct(residual)));
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

Status make_consistent(const DisplacementForm& form, double source_time, Eigen::VectorXd& u,
                       Eigen::VectorXd& up) {
  ConsistentStart start(form);
  return start.make_consistent(source_time, u, up);
}

}  // namespace emnet
