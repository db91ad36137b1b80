// Linear state equation of the displacement form: see state_space.hpp. The exponentials are in
// state_space_propagator.cpp, the eigen-decomposition of M in state_space_modal_basis.cpp.
#include "state_space.hpp"

#include <Eigen/QR>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "dense_decompositions.hpp"
#include "equilibration.hpp"

namespace emnet {

namespace {

// The orthonormal n×r columns `leading` completed to an orthonormal basis of Rⁿ: the last n − r
// columns of the Q of a Householder QR of `leading` span its orthogonal complement. Eigen 3.4's
// BDCSVD can return singular vectors of exactly-zero singular values that are neither
// orthonormal nor a basis of the null space (measured on the fish fin's E at EI = 1.7e-3 N·m²,
// η = 0.029993: ‖UᵀU − I‖ = 1.41, a singular Â₂₂), so null spaces are built from the part
// belonging to the nonzero singular values, which is sound.
Eigen::MatrixXd completed_basis(const Eigen::MatrixXd& leading) {
  const Eigen::Index n = leading.rows(), r = leading.cols();
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(leading);
  Eigen::MatrixXd basis(n, n);
  basis.leftCols(r) = leading;
  // Q's last n − r columns alone: the reflectors applied to n − r unit vectors (forming all of
  // Q took 16 ms of the tweezer jaw's 259 unknowns).
  basis.rightCols(n - r) = qr.householderQ() * Eigen::MatrixXd::Identity(n, n).rightCols(n - r);
  return basis;
}

// The same where `leading`'s columns span exactly the coordinates `used` (E of full column rank
// on its used columns, as on the tweezer jaw): the complement is the unit vectors of
// the other coordinates, no QR (which took 3–5 ms of the tweezer jaw's 259 unknowns).
Eigen::MatrixXd completed_by_unit_vectors(const Eigen::MatrixXd& leading,
                                          const std::vector<Eigen::Index>& used) {
  const Eigen::Index n = leading.rows();
  Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(n, n);
  basis.leftCols(leading.cols()) = leading;
  std::vector<bool> in_use(static_cast<size_t>(n), false);
  for (Eigen::Index i : used) in_use[static_cast<size_t>(i)] = true;
  Eigen::Index next = leading.cols();
  for (Eigen::Index i = 0; i < n; ++i)
    if (!in_use[static_cast<size_t>(i)]) basis(i, next++) = 1.0;
  return basis;
}

}  // namespace

// Osborne's balancing: see state_space.hpp.
void balance(const Eigen::MatrixXd& m, Eigen::VectorXd& scale, Eigen::MatrixXd& balanced) {
  const Eigen::Index n = m.rows();
  scale = Eigen::VectorXd::Ones(n);
  balanced = m;
  for (int sweep = 0; sweep < 100; ++sweep) {
    bool changed = false;
    for (Eigen::Index k = 0; k < n; ++k) {
      const double column = balanced.col(k).cwiseAbs().sum() - std::abs(balanced(k, k));
      const double row = balanced.row(k).cwiseAbs().sum() - std::abs(balanced(k, k));
      if (column == 0.0 || row == 0.0) continue;
      const double factor = std::exp2(std::round(0.5 * std::log2(row / column)));
      if (factor == 1.0) continue;
      changed = true;
      balanced.col(k) *= factor;
      balanced.row(k) /= factor;
      scale[k] *= factor;
    }
    if (!changed) break;
  }
}

AffinePiece affine_piece(const System& system, int size, double t0, double t1) {
  const double middle = 0.5 * (t0 + t1);
  AffinePiece piece{Eigen::VectorXd::Zero(size), Eigen::VectorXd::Zero(size)};
  piece.slope.head(system.size()) = system.b_slope(middle);
  piece.start.head(system.size()) = system.b(middle);
  if (piece.ramp()) piece.start -= (middle - t0) * piece.slope;
  return piece;
}

double characteristic_angular_frequency(const System& system, double end_time) {
  double frequency = end_time > 0.0 ? 1.0 / end_time : 0.0;
  for (const auto& w : system.excitation().waveforms)
    if (w.period > 0.0) frequency = std::max(frequency, 1.0 / w.period);
  return 2 * M_PI * frequency;
}

LinearStateSpace::LinearStateSpace(const DisplacementForm& form, double angular_frequency)
    : LinearStateSpace(form, form.a(), form.e(), angular_frequency) {
  if (form.system().is_nonlinear())
    throw std::runtime_error(
        "the exact method needs a linear network; this one is nonlinear (DEAs with their "
        "electrical model: set drive.electrical_dynamics = false for ideal voltage-driven DEAs; "
        "large kinematics), so use IDA");
}

LinearStateSpace::LinearStateSpace(const DisplacementForm& form,
                                   const Eigen::SparseMatrix<double>& a_matrix,
                                   const Eigen::SparseMatrix<double>& e_matrix,
                                   double angular_frequency) {
  n_ = form.size();
  const DiagonalScaling scaling = equilibrate_pencil(a_matrix, e_matrix, angular_frequency);
  time_scale_ = scaling.frequency;
  row_scale_ = scaling.row;
  column_scale_ = scaling.column;
  const Eigen::MatrixXd e = Eigen::MatrixXd(scaled(e_matrix, scaling, time_scale_));
  // The SVD of Ê on its non-zero rows and columns only (most rows of the displacement form are
  // algebraic: no Ê entry at all). Zero rows and columns add nothing but zero singular values,
  // so the singular values and the singular vectors of the nonzero ones are Ê's, with zeros at
  // the left-out rows and columns; the rest of each basis is completed as before.
  std::vector<Eigen::Index> used_rows, used_columns;
  for (Eigen::Index i = 0; i < n_; ++i) {
    if ((e.row(i).array() != 0.0).any()) used_rows.push_back(i);
    if ((e.col(i).array() != 0.0).any()) used_columns.push_back(i);
  }
  Eigen::MatrixXd e_used(static_cast<Eigen::Index>(used_rows.size()),
                         static_cast<Eigen::Index>(used_columns.size()));
  for (Eigen::Index i = 0; i < e_used.rows(); ++i)
    for (Eigen::Index j = 0; j < e_used.cols(); ++j)
      e_used(i, j) = e(used_rows[static_cast<size_t>(i)], used_columns[static_cast<size_t>(j)]);
  Eigen::VectorXd sigma;
  Eigen::MatrixXd u_leading, v_leading;
  if (e_used.size() > 0) {
    const RealSingularValueDecomposition svd =
        divide_and_conquer_svd(e_used, Eigen::ComputeThinU | Eigen::ComputeThinV);
    sigma = svd.singular_values;
    while (nd_ < sigma.size() && sigma[nd_] > 1e-12 * sigma[0]) ++nd_;
    u_leading = Eigen::MatrixXd::Zero(n_, nd_);
    v_leading = Eigen::MatrixXd::Zero(n_, nd_);
    for (Eigen::Index i = 0; i < e_used.rows(); ++i)
      u_leading.row(used_rows[static_cast<size_t>(i)]) = svd.u.row(i).head(nd_);
    for (Eigen::Index j = 0; j < e_used.cols(); ++j)
      v_leading.row(used_columns[static_cast<size_t>(j)]) = svd.v.row(j).head(nd_);
  } else {
    u_leading = v_leading = Eigen::MatrixXd::Zero(n_, 0);
  }
  na_ = n_ - nd_;
  left_ = completed_basis(u_leading);
  right_ = nd_ == static_cast<Eigen::Index>(used_columns.size())
               ? completed_by_unit_vectors(v_leading, used_columns)
               : completed_basis(v_leading);
  const Eigen::MatrixXd a_hat = (left_.transpose() * scaled(a_matrix, scaling)) * right_;
  const Eigen::MatrixXd a11 = a_hat.topLeftCorner(nd_, nd_), a21 = a_hat.bottomLeftCorner(na_, nd_),
                        a22 = a_hat.bottomRightCorner(na_, na_);
  a12_ = a_hat.topRightCorner(nd_, na_);
  a22_lu_.compute(a22);
  if (na_ > 0 && !a22_lu_.isInvertible())
    throw std::runtime_error("the network's DAE has index > 1 or no unique solution");
  a22_inv_a21_ = na_ > 0 ? Eigen::MatrixXd(a22_lu_.solve(a21)) : Eigen::MatrixXd(0, nd_);
  // d/dt = ω₀·d/dt̂: the physical-time state equation is ω₀ times the scaled one.
  sigma_inv_ = time_scale_ * sigma.head(nd_).cwiseInverse();
  m_ = sigma_inv_.asDiagonal() * (a12_ * a22_inv_a21_ - a11);
  if (!m_.allFinite()) throw std::runtime_error("the reduced state matrix is not finite");
  balance(m_, balance_, balanced_m_);
  // Hidden constraints H·u = 0 (differentiated levers, displacement_form.hpp) are invariants of
  // the state equation: M has a zero eigenvalue for each, and rounding in M·x + N·f would
  // let the state drift along them (a lever slowly violating its kinematics). project()
  // removes that drift along M's null vectors.
  const std::vector<int>& hidden = form.hidden_constraints();
  const Eigen::Index k = static_cast<Eigen::Index>(hidden.size());
  if (k > 0 && k <= nd_) {
    Eigen::MatrixXd h(k, n_);
    const Eigen::SparseMatrix<double, Eigen::RowMajor> e_rows = e_matrix;
    for (Eigen::Index i = 0; i < k; ++i) h.row(i) = Eigen::RowVectorXd(e_rows.row(hidden[i]));
    constraint_ = h;  // its null vectors are found on the first project()
    hidden_rows_ = h;
  }
}

void LinearStateSpace::prepare_projection() const {
  projection_prepared_ = true;
  const Eigen::Index k = constraint_.rows();
  if (k == 0) return;
  // V alone: the null vectors are its last columns (U would double the cost and is not used).
  const Eigen::MatrixXd v = divide_and_conquer_svd(balanced_m_, Eigen::ComputeFullV).v;
  null_vectors_ = balance_.asDiagonal() * completed_basis(v.leftCols(nd_ - k)).rightCols(k);
  Eigen::VectorXd u, up;
  Eigen::MatrixXd h_null(k, k);
  const Eigen::VectorXd no_force = Eigen::VectorXd::Zero(n_);
  for (Eigen::Index j = 0; j < k; ++j) {
    full_state(null_vectors_.col(j), no_force, u, up);
    h_null.col(j) = constraint_ * u;
  }
  constraint_lu_.compute(h_null);
  if (constraint_lu_.rcond() < 1e-12) constraint_.resize(0, 0);  // not the invariants
}

Eigen::VectorXd LinearStateSpace::project(const Eigen::VectorXd& x,
                                          const Eigen::VectorXd& f) const {
  if (!projection_prepared_) prepare_projection();
  if (constraint_.size() == 0) return x;
  Eigen::VectorXd u, up;
  full_state(x, f, u, up);
  return x - null_vectors_ * constraint_lu_.solve(constraint_ * u);
}

Eigen::VectorXd LinearStateSpace::forcing(const Eigen::VectorXd& f) const {
  const Eigen::VectorXd f_hat = left_.transpose() * row_scale_.cwiseProduct(f);
  if (na_ == 0) return sigma_inv_.asDiagonal() * f_hat.head(nd_);
  const Eigen::VectorXd a22_inv_f2 = a22_lu_.solve(f_hat.tail(na_));
  return sigma_inv_.asDiagonal() * (f_hat.head(nd_) - a12_ * a22_inv_f2);
}

Eigen::MatrixXd LinearStateSpace::hidden_constraints_on_state() const {
  if (hidden_rows_.size() == 0) return Eigen::MatrixXd(0, nd_);
  return hidden_rows_ * u_of_state();
}

void LinearStateSpace::full_state(const Eigen::VectorXd& x, const Eigen::VectorXd& f,
                                  const Eigen::VectorXd& f_slope, Eigen::VectorXd& u,
                                  Eigen::VectorXd& up) const {
  full_state(x, f, u, up);
  if (na_ == 0) return;
  // The algebraic rates' part from the sources' slope: w₂' += Â₂₂⁻¹·f̂₂'.
  const Eigen::VectorXd slope_hat = left_.transpose() * row_scale_.cwiseProduct(f_slope);
  Eigen::VectorXd wp = Eigen::VectorXd::Zero(n_);
  wp.tail(na_) = a22_lu_.solve(slope_hat.tail(na_));
  up += column_scale_.cwiseProduct(right_ * wp);
}

void LinearStateSpace::full_state(const Eigen::VectorXd& x, const Eigen::VectorXd& f,
                                  Eigen::VectorXd& u, Eigen::VectorXd& up) const {
  const Eigen::VectorXd xp = m_ * x + forcing(f);
  Eigen::VectorXd w(n_), wp(n_);
  w.head(nd_) = x;
  wp.head(nd_) = xp;
  if (na_ > 0) {
    const Eigen::VectorXd f_hat = left_.transpose() * row_scale_.cwiseProduct(f);
    w.tail(na_) = a22_lu_.solve(f_hat.tail(na_)) - a22_inv_a21_ * x;
    wp.tail(na_) = -a22_inv_a21_ * xp;
  }
  u = column_scale_.cwiseProduct(right_ * w);
  up = column_scale_.cwiseProduct(right_ * wp);
}

LinearStateSpace::OutputRows LinearStateSpace::output_rows(const Eigen::RowVectorXd& on_u,
                                                           const Eigen::RowVectorXd& on_up) const {
  // u = C·R·w, u' = C·R·w' with w = [x; Â₂₂⁻¹·f̂₂ − Â₂₂⁻¹·Â₂₁·x], w' = [x'; −Â₂₂⁻¹·Â₂₁·x'],
  // x' = M·x + Σ⁻¹·(f̂₁ − Â₁₂·Â₂₂⁻¹·f̂₂), f̂ = Lᵀ·(r∘f) (full_state and forcing). With
  // a = on_u·C·R and b = on_up·C·R split as w: β = b₁ − b₂·Â₂₂⁻¹·Â₂₁, γ = β·Σ⁻¹,
  // δ = (a₂ − γ·Â₁₂)·Â₂₂⁻¹; then p = (a₁ − a₂·Â₂₂⁻¹·Â₂₁ + β·M)·x + [γ, δ]·f̂, and a slope adds
  // b₂·Â₂₂⁻¹·f̂₂'.
  const Eigen::RowVectorXd a = on_u.cwiseProduct(column_scale_.transpose()) * right_;
  const Eigen::RowVectorXd b = on_up.cwiseProduct(column_scale_.transpose()) * right_;
  Eigen::RowVectorXd beta = b.head(nd_), state = a.head(nd_);
  Eigen::RowVectorXd on_hat = Eigen::RowVectorXd::Zero(n_),
                     slope_hat = Eigen::RowVectorXd::Zero(n_);
  if (na_ > 0) {
    beta -= b.tail(na_) * a22_inv_a21_;
    state -= a.tail(na_) * a22_inv_a21_;
  }
  const Eigen::RowVectorXd gamma = beta.cwiseProduct(sigma_inv_.transpose());
  on_hat.head(nd_) = gamma;
  if (na_ > 0) {
    const Eigen::RowVectorXd rest = a.tail(na_) - gamma * a12_;
    on_hat.tail(na_) =
        Eigen::VectorXd(a22_lu_.transpose().solve(Eigen::VectorXd(rest.transpose()))).transpose();
    slope_hat.tail(na_) =
        Eigen::VectorXd(a22_lu_.transpose().solve(Eigen::VectorXd(b.tail(na_).transpose())))
            .transpose();
  }
  OutputRows rows;
  rows.state = state + beta * m_;
  rows.source = (on_hat * left_.transpose()).cwiseProduct(row_scale_.transpose());
  rows.slope = (slope_hat * left_.transpose()).cwiseProduct(row_scale_.transpose());
  return rows;
}

Eigen::MatrixXd LinearStateSpace::u_of_state() const {
  // u = C·V·w with w₁ = x, w₂ = −Â₂₂⁻¹·Â₂₁·x (no sources).
  Eigen::MatrixXd u_x = right_.leftCols(nd_);
  if (na_ > 0) u_x -= right_.rightCols(na_) * a22_inv_a21_;
  return column_scale_.asDiagonal() * u_x;
}

Eigen::VectorXd LinearStateSpace::state_of(const Eigen::VectorXd& u) const {
  return (right_.transpose() * u.cwiseQuotient(column_scale_)).head(nd_);
}

}  // namespace emnet
