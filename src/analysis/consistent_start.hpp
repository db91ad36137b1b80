// Consistent values at the start of a constant-source interval of the displacement form
//   F(t, u, u') = E·u' + A·u + ĝ(u, u') − f(t) = 0:
// the differential unknowns u_d are continuous across a source edge; the algebraic unknowns
// u_a and the derivatives u'_d follow the new sources (u'_a is set to zero; it does not enter
// F). For an index-1 form the square system F = 0 in w = (u'_d, u_a) has the Jacobian
//   J_w = [∂F/∂u'_d  ∂F/∂u_a],
// which is non-singular; it is solved by Newton's method (one step for a linear network) with a
// sparse LU of the equilibrated J_w (equilibration.hpp), so that stiffness and mixed units do
// not matter. Converged means a normwise backward error in the equilibrated rows below 1e-11
// (1e-14 before any Newton step). This replaces IDACalcIC, whose Newton iteration uses the
// integrator's matrix ∂F/∂u + c_j·∂F/∂u' with c_j from a guessed first step and stalls on stiff
// networks (the 500-segment fish fin with zero rise time failed at t = 0).
//
// A transient run makes a start consistent at every switching edge; ConsistentStart keeps the
// scaling and LU of the last J_w for the next edge, where a linear network has the same J_w.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <string>

#include "displacement_form.hpp"
#include "emnet/core/errors.hpp"
#include "equilibration.hpp"

namespace emnet {

class ConsistentStart {
 public:
  // `form` must outlive this object.
  explicit ConsistentStart(const DisplacementForm& form);
  // Makes (u, up) consistent at source_time keeping u_d. On failure u and up are unchanged and
  // the status says why.
  Status make_consistent(double source_time, Eigen::VectorXd& u, Eigen::VectorXd& up);

 private:
  Eigen::SparseMatrix<double> consistency_matrix(const Eigen::VectorXd& u,
                                                 const Eigen::VectorXd& up) const;
  bool same_as_factorised(const Eigen::SparseMatrix<double>& matrix) const;
  Status factorise(Eigen::SparseMatrix<double> matrix);
  double relative_residual(double source_time, const Eigen::VectorXd& u, const Eigen::VectorXd& up,
                           const Eigen::VectorXd& residual) const;

  const DisplacementForm& form_;
  Eigen::SparseMatrix<double> absolute_e_, absolute_a_;  // |E|, |A|
  // The last J_w factorised, its equilibration and the LU of the equilibrated matrix.
  bool factorised_ = false;
  Eigen::SparseMatrix<double> factorised_matrix_;
  DiagonalScaling scaling_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
};

// One start made consistent, with a ConsistentStart of its own.
Status make_consistent(const DisplacementForm& form, double source_time, Eigen::VectorXd& u,
                       Eigen::VectorXd& up);

}  // namespace emnet
