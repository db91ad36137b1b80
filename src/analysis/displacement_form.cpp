// Displacement form of the network DAE: see displacement_form.hpp.
#include "displacement_form.hpp"

#include <algorithm>
#include <stdexcept>

#include "emnet/analysis/analysis.hpp"

namespace emnet {

DisplacementForm::DisplacementForm(const System& system, Use use) : system_(system) {
  const RowClassification rows = classify_rows(system, system.G);
  mechanical_ = rows.mechanical;
  divided_ = rows.divided;
  assemble(use);
  if (use == Use::eigenvalues) return;
  differentiate_hidden_constraints();
}

void DisplacementForm::assemble(Use use) {
  const System& system = system_;
  const int n = system.size();
  // Velocity unknowns: mechanical columns that carry a capacitance (mass, inertia).
  velocity_of_.assign(static_cast<size_t>(n), -1);
  size_ = n;
  for (int col = 0; col < n; ++col)
    if (mechanical_[static_cast<size_t>(col)] && system.C.col(col).nonZeros() > 0)
      velocity_of_[static_cast<size_t>(col)] = size_++;

  std::vector<Eigen::Triplet<double>> e_entries, a_entries;
  auto add_g = [&](int row, int col, double value) {
    if (!mechanical_[static_cast<size_t>(col)]) {
      a_entries.emplace_back(row, col, value);
    } else if (divided_[static_cast<size_t>(row)]) {
      a_entries.emplace_back(row, col, value);  // integrated row: displacement
    } else if (velocity_of(col) >= 0) {
      a_entries.emplace_back(row, velocity_of(col), value);  // v
    } else {
      e_entries.emplace_back(row, col, value);  // z'
    }
  };
  for (int col = 0; col < n; ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(system.G, col); it; ++it)
      add_g(static_cast<int>(it.row()), col, it.value());
  for (int col = 0; col < n; ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(system.C, col); it; ++it) {
      const int row = static_cast<int>(it.row());
      if (divided_[static_cast<size_t>(row)]) {
        if (mechanical_[static_cast<size_t>(col)])
          throw std::runtime_error("a capacitance in a compliance row of '" +
                                   system.unknowns[static_cast<size_t>(row)].name + "'");
        a_entries.emplace_back(row, col, it.value());  // integrated: L·i
      } else if (mechanical_[static_cast<size_t>(col)]) {
        e_entries.emplace_back(row, velocity_of(col), it.value());  // m·v'
      } else {
        e_entries.emplace_back(row, col, it.value());
      }
    }
  for (int col = 0; col < n; ++col)
    if (velocity_of(col) >= 0) {  // v − z' = 0
      a_entries.emplace_back(velocity_of(col), velocity_of(col), 1.0);
      e_entries.emplace_back(velocity_of(col), col, -1.0);
    }
  for (const auto& term : system.excitation().source_terms)
    if (use == Use::time_integration && divided_[static_cast<size_t>(term.row)])
      throw std::runtime_error("an across source drives the mechanical unknown '" +
                               system.unknowns[static_cast<size_t>(term.row)].name +
                               "' (only zero across sources, i.e. supports, are supported here)");
  e_.resize(size_, size_);
  a_.resize(size_, size_);
  e_.setFromTriplets(e_entries.begin(), e_entries.end());
  a_.setFromTriplets(a_entries.begin(), a_entries.end());
  e_.prune(0.0);
  a_.prune(0.0);
  differential_.assign(static_cast<size_t>(size_), false);
  for (int col = 0; col < size_; ++col)
    differential_[static_cast<size_t>(col)] = e_.col(col).nonZeros() > 0;
}

void DisplacementForm::differentiate_hidden_constraints() {
  const int n = system_.size();
  // Hidden constraints: an integrated row that ties differential unknowns together would make
  // the DAE index 2. It is replaced by its time derivative; the start states (rest, static)
  // satisfy the row itself, so the solution is the same. Such a row is
  //   - one all of whose unknowns are differential (a lever between nodes that all carry
  //     mass), or
  //   - one that holds a differential through quantity (a spring whose damper enters its nodes
  //     as τ times the spring force's rate, elements/inductor.hpp): that force is a state, and
  //     the row fixes it from displacements.
  // Differentiating a row makes its unknowns differential, which can make another row hidden,
  // so this repeats until nothing changes.
  const Eigen::SparseMatrix<double, Eigen::RowMajor> a_rows = a_, e_rows = e_;
  std::vector<bool> moved(static_cast<size_t>(size_), false);
  for (bool changed = true; changed;) {
    changed = false;
    for (int row = 0; row < size_; ++row) {
      if (!divided_[static_cast<size_t>(row)] || moved[static_cast<size_t>(row)]) continue;
      if (a_rows.row(row).nonZeros() == 0 || e_rows.row(row).nonZeros() != 0) continue;
      bool all_differential = true, holds_differential_force = false;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a_rows, row); it; ++it) {
        const bool differential = differential_[static_cast<size_t>(it.col())];
        const bool force = it.col() < n && !mechanical_[static_cast<size_t>(it.col())];
        all_differential = all_differential && differential;
        holds_differential_force = holds_differential_force || (differential && force);
      }
      if (!all_differential && !holds_differential_force) continue;
      moved[static_cast<size_t>(row)] = true;
      hidden_constraints_.push_back(row);
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a_rows, row); it; ++it)
        differential_[static_cast<size_t>(it.col())] = true;
      changed = true;
    }
  }
  if (!hidden_constraints_.empty()) {
    std::sort(hidden_constraints_.begin(), hidden_constraints_.end());
    std::vector<Eigen::Triplet<double>> moved_e, kept_a;
    for (int row = 0; row < size_; ++row)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a_rows, row); it; ++it)
        (moved[static_cast<size_t>(row)] ? moved_e : kept_a)
            .emplace_back(row, it.col(), it.value());
    for (int col = 0; col < size_; ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(e_, col); it; ++it)
        moved_e.emplace_back(it.row(), col, it.value());
    e_.setFromTriplets(moved_e.begin(), moved_e.end());
    a_.setFromTriplets(kept_a.begin(), kept_a.end());
  }
}

Eigen::VectorXd DisplacementForm::f(double t) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(size_);
  out.head(system_.size()) = system_.b(t);
  return out;
}

Eigen::VectorXd DisplacementForm::velocity_state(const Eigen::VectorXd& u,
                                                 const Eigen::VectorXd& up) const {
  const int n = system_.size();
  Eigen::VectorXd y(n);
  for (int k = 0; k < n; ++k) {
    if (!mechanical_[static_cast<size_t>(k)])
      y[k] = u[k];
    else
      y[k] = velocity_of(k) >= 0 ? u[velocity_of(k)] : up[k];
  }
  return y;
}

void DisplacementForm::residual(double source_time, const Eigen::VectorXd& u,
                                const Eigen::VectorXd& up, Eigen::VectorXd& out) const {
  // f(t) is b(t) followed by zeros: subtracting b alone gives the same values without a vector
  // of size n to allocate and fill per call (the residual is IDA's most frequent call). The two
  // products are evaluated apart, as in E·u' + A·u − f, so that the rounding is the same: a
  // product accumulated onto the other moved the 7-segment RC fin's error at rtol 1e-3 from
  // 1.32e-3 to 1.60e-3 of the peak.
  out = (e_ * up).eval() + (a_ * u).eval();
  out.head(system_.size()) -= system_.b(source_time);
  if (!system_.is_nonlinear()) return;
  Eigen::VectorXd g;
  system_.nonlinear(velocity_state(u, up), g, nullptr);
  out.head(system_.size()) += g;
}

void DisplacementForm::jacobian(double cj, const Eigen::VectorXd& u, const Eigen::VectorXd& up,
                                std::vector<Eigen::Triplet<double>>& out) const {
  out.clear();
  for (int col = 0; col < size_; ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(a_, col); it; ++it)
      out.emplace_back(it.row(), col, it.value());
    for (Eigen::SparseMatrix<double>::InnerIterator it(e_, col); it; ++it)
      out.emplace_back(it.row(), col, cj * it.value());
  }
  if (!system_.is_nonlinear()) return;
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> jg;
  system_.nonlinear(velocity_state(u, up), g, &jg);
  for (int col = 0; col < jg.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(jg, col); it; ++it) {
      if (!mechanical_[static_cast<size_t>(col)])
        out.emplace_back(it.row(), col, it.value());
      else if (velocity_of(col) >= 0)
        out.emplace_back(it.row(), velocity_of(col), it.value());
      else
        out.emplace_back(it.row(), col, cj * it.value());
    }
}

void DisplacementForm::linearised(const Eigen::VectorXd& u, const Eigen::VectorXd& up,
                                  Eigen::SparseMatrix<double>& d_u,
                                  Eigen::SparseMatrix<double>& d_up) const {
  std::vector<Eigen::Triplet<double>> with_derivative, without;
  jacobian(1.0, u, up, with_derivative);
  jacobian(0.0, u, up, without);
  d_u.resize(size_, size_);
  d_u.setFromTriplets(without.begin(), without.end());
  Eigen::SparseMatrix<double> sum(size_, size_);
  sum.setFromTriplets(with_derivative.begin(), with_derivative.end());
  d_up = sum - d_u;
  d_up.prune(0.0);
  d_u.makeCompressed();
  d_up.makeCompressed();
}

Eigen::VectorXd DisplacementForm::from_rest(const Eigen::VectorXd& y) const {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(size_);
  for (int k = 0; k < system_.size(); ++k)
    if (!mechanical_[static_cast<size_t>(k)]) u[k] = y[k];
  return u;
}

Eigen::VectorXd DisplacementForm::from_static(const Eigen::VectorXd& z) const {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(size_);
  u.head(system_.size()) = z;
  return u;
}

double DisplacementForm::probe(const Probe& probe, const Eigen::VectorXd& u,
                               const Eigen::VectorXd& up) const {
  double value = 0.0;
  for_each_probe_term(probe, [&](bool on_rate, int index, double coefficient) {
    value += coefficient * (on_rate ? up[index] : u[index]);
  });
  // Squares (a DEA's k_F·u²) of electrical voltages, which u holds as they are.
  return value + squares_value(probe, u);
}

void DisplacementForm::probe_rows(const Probe& probe, Eigen::RowVectorXd& on_u,
                                  Eigen::RowVectorXd& on_up) const {
  on_u = Eigen::RowVectorXd::Zero(size_);
  on_up = Eigen::RowVectorXd::Zero(size_);
  for_each_probe_term(probe, [&](bool on_rate, int index, double coefficient) {
    (on_rate ? on_up : on_u)[index] += coefficient;
  });
}

}  // namespace emnet
