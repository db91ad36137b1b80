// The displacement form of the network DAE, shared by the transient analyses.
//
// Start from C·y' + G·y + g(y) = b(t) (velocity form). Let z be the unknowns of the static
// analysis (displacements on mechanical nodes, the rest as in y) and give every mechanical node
// with a mass or inertia a velocity unknown v = z'. With u = [z; v]:
//   rows with an s⁰ part (KCL, electrical):  C·y' + G·y + g(y) = b     with y built from u, u'
//   rows without (compliance, lever):         integrated once: G_mech·z + C_other·z = 0
//   kinematic rows:                           v − z' = 0
// where a mechanical across value in y is v when the node has one, else z'. Residual:
//   F(t, u, u') = E·u' + A·u + ĝ(u, u') − f(t).
// The integration constants are zero for a start at rest or at a static state (both satisfy
// the integrated rows), so the two forms have the same solutions.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <stdexcept>
#include <string>
#include <vector>

#include "emnet/network/network.hpp"
#include "emnet/network/output.hpp"

namespace emnet {

class DisplacementForm {
 public:
  // What the form is for.
  //   time_integration: hidden constraints (integrated rows that tie differential unknowns
  //     together, index 2) are each replaced by their derivative (index 1; the row itself is an
  //     invariant of consistent states), and a source on an integrated row (a constant velocity:
  //     no state at rest) is refused;
  //   eigenvalues: the pencil E·s + A alone: hidden constraints are kept as they are (their
  //     derivatives would add a spurious pole at s = 0 each) and sources do not matter.
  enum class Use { time_integration, eigenvalues };
  // Throws std::runtime_error when the network cannot be written so (a mechanical across
  // source with a non-zero value, a mass in a compliance row).
  explicit DisplacementForm(const System& system, Use use = Use::time_integration);

  int size() const { return size_; }
  const System& system() const { return system_; }
  const Eigen::SparseMatrix<double>& e() const { return e_; }
  const Eigen::SparseMatrix<double>& a() const { return a_; }
  const std::vector<bool>& differential() const { return differential_; }
  // Index of the velocity unknown of system column c, or −1.
  int velocity_of(int column) const { return velocity_of_[static_cast<size_t>(column)]; }
  bool mechanical(int column) const { return mechanical_[static_cast<size_t>(column)]; }
  // Rows replaced by their time derivative (hidden constraints among differential unknowns):
  // every consistent state also satisfies e().row(r)·u = 0 for each of them.
  const std::vector<int>& hidden_constraints() const { return hidden_constraints_; }

  // f(t): b(t) on the rows that keep it, zero on integrated and kinematic rows.
  Eigen::VectorXd f(double t) const;
  // The velocity-form state y from u and u'.
  Eigen::VectorXd velocity_state(const Eigen::VectorXd& u, const Eigen::VectorXd& up) const;
  // F(t, u, u') = E·u' + A·u + ĝ − f(t), with f evaluated at `source_time` (a time inside
  // the current constant interval, so that a jump at its end is not seen early).
  void residual(double source_time, const Eigen::VectorXd& u, const Eigen::VectorXd& up,
                Eigen::VectorXd& out) const;
  // ∂F/∂u + cj·∂F/∂u' as triplets (the nonlinear part at u, u').
  void jacobian(double cj, const Eigen::VectorXd& u, const Eigen::VectorXd& up,
                std::vector<Eigen::Triplet<double>>& out) const;
  // The linearisation at (u, u'): ∂F/∂u and ∂F/∂u' (for a linear network a() and e()).
  void linearised(const Eigen::VectorXd& u, const Eigen::VectorXd& up,
                  Eigen::SparseMatrix<double>& d_u, Eigen::SparseMatrix<double>& d_up) const;
  // u of a state at rest given in the velocity form (velocities zero): y on the non-mechanical
  // unknowns, zero displacements (the linearisation does not depend on them).
  Eigen::VectorXd from_rest(const Eigen::VectorXd& y) const;
  // u from a static state z (velocities zero).
  Eigen::VectorXd from_static(const Eigen::VectorXd& z) const;
  // Value of a probe: deflections from z, velocities from v or z', voltages from z.
  double probe(const Probe& probe, const Eigen::VectorXd& u, const Eigen::VectorXd& up) const;
  // The linear part of probe() as rows: probe(p, u, u') = on_u·u + on_up·u' + its squares.
  void probe_rows(const Probe& probe, Eigen::RowVectorXd& on_u, Eigen::RowVectorXd& on_up) const;

 private:
  // E, A, the velocity unknowns and the differential ones from the row classification (the
  // constructor's first phase); throws where the network has no displacement form for `use`.
  void assemble(Use use);
  // Integrated rows that tie differential unknowns together, replaced by their derivatives
  // (the constructor's second phase, for time integration).
  void differentiate_hidden_constraints();
  // visit(on_rate, index, coefficient) for each linear term of the probe: the coefficient
  // multiplies u[index] (on_rate false) or u'[index] (on_rate true). A deflection is z, a
  // velocity v (the node's velocity unknown) or z'; an electrical quantity is read as it is.
  template <class Visit>
  void for_each_probe_term(const Probe& probe, Visit visit) const {
    for (const auto& [index, coefficient] : probe.terms) {
      const int power = (mechanical(index) ? 1 : 0) - probe.integrations;
      if (power == 0)
        visit(false, index, coefficient);
      else if (power == 1 && velocity_of(index) >= 0)
        visit(false, velocity_of(index), coefficient);
      else if (power == 1)
        visit(true, index, coefficient);
      else
        throw std::runtime_error("probe '" + probe.name + "' integrates an electrical quantity");
    }
  }

  const System& system_;
  int size_ = 0;
  std::vector<bool> mechanical_, divided_, differential_;
  std::vector<int> velocity_of_;
  std::vector<int> hidden_constraints_;
  Eigen::SparseMatrix<double> e_, a_;
};

}  // namespace emnet
