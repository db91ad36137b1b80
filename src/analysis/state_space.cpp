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

// The same where `leading`'s columns span exactly the coordinates `used` (Ê's used columns, or
// the used rows' full Q): the complement is the unit vectors of the other coordinates, no QR
// (which took 3–5 ms of the tweezer jaw's 259 unknowns).
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

// Ê's rows and columns with a nonzero entry, and Ê on them. Most rows of the displacement form
// are algebraic (no Ê entry at all); zero rows and columns only add zero singular values.
struct UsedPart {
  std::vector<Eigen::Index> rows, columns;
  Eigen::MatrixXd matrix;
};

UsedPart used_part(const Eigen::MatrixXd& e) {
  UsedPart used;
  for (Eigen::Index i = 0; i < e.rows(); ++i) {
    if ((e.row(i).array() != 0.0).any()) used.rows.push_back(i);
    if ((e.col(i).array() != 0.0).any()) used.columns.push_back(i);
  }
  used.matrix.resize(static_cast<Eigen::Index>(used.rows.size()),
                     static_cast<Eigen::Index>(used.columns.size()));
  for (Eigen::Index i = 0; i < used.matrix.rows(); ++i)
    for (Eigen::Index j = 0; j < used.matrix.cols(); ++j)
      used.matrix(i, j) =
          e(used.rows[static_cast<size_t>(i)], used.columns[static_cast<size_t>(j)]);
  return used;
}

// Ê = U·[T 0; 0 0]·Vᵀ with U (left) and V (right) orthogonal and T (r × r, r = rank Ê) upper
// triangular.
struct DescriptorSplit {
  Eigen::MatrixXd left, right, leading;
};

// An upper-triangular T as Eigen's condition estimator wants a decomposition: solve() and
// adjoint().solve() (Hager's 1-norm estimate of T⁻¹ from a few triangular solves).
struct TriangularSolver {
  using MatrixType = Eigen::MatrixXd;
  using Scalar = double;
  using RealScalar = double;
  const Eigen::MatrixXd& matrix;
  bool transposed = false;
  Eigen::Index rows() const { return matrix.rows(); }
  Eigen::Index cols() const { return matrix.cols(); }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const {
    if (transposed) return matrix.triangularView<Eigen::Upper>().transpose().solve(b);
    return matrix.triangularView<Eigen::Upper>().solve(b);
  }
  TriangularSolver adjoint() const { return {matrix, !transposed}; }
};

// Where Ê has full column rank on its used columns (every shipped scene's displacement form
// has), one Householder QR splits it: Ê_used = Q·[T; 0], V the unit vectors of the used columns
// (no right rotation: the state is those scaled unknowns), U = Q on the used rows completed by
// the unit vectors of the others. False where T's 1-norm condition estimate exceeds 1e8 (or
// more columns than rows): a rank decision is then needed, which the SVD makes. On the fish
// fin's 49 × 42 Ê the QR takes a fifth of the SVD's instructions, and the AC check against
// direct solves moved from 2.2e-12 to 5.4e-13 of the peak.
bool split_by_qr(const UsedPart& used, Eigen::Index n, DescriptorSplit& split) {
  const Eigen::Index m = used.matrix.rows(), k = used.matrix.cols();
  if (k == 0 || m < k) return false;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(used.matrix);
  split.leading = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  const double norm = split.leading.cwiseAbs().colwise().sum().maxCoeff();
  const double reciprocal_condition =
      Eigen::internal::rcond_estimate_helper(norm, TriangularSolver{split.leading});
  if (!(reciprocal_condition >= 1e-8)) return false;
  const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(m, m);
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(n, m), columns = Eigen::MatrixXd::Zero(n, k);
  for (Eigen::Index i = 0; i < m; ++i) rows.row(used.rows[static_cast<size_t>(i)]) = q.row(i);
  for (Eigen::Index j = 0; j < k; ++j) columns(used.columns[static_cast<size_t>(j)], j) = 1.0;
  split.left = completed_by_unit_vectors(rows, used.rows);
  split.right = completed_by_unit_vectors(columns, used.columns);
  return true;
}

// By the SVD of Ê_used (T = diag(σ₁..σᵣ), r the singular values above 1e-12·σ₁), the singular
// vectors of the nonzero ones placed on the used rows and columns, each basis completed.
DescriptorSplit split_by_svd(const UsedPart& used, Eigen::Index n) {
  DescriptorSplit split;
  Eigen::Index rank = 0;
  Eigen::MatrixXd u_leading = Eigen::MatrixXd::Zero(n, 0), v_leading = u_leading;
  if (used.matrix.size() > 0) {
    const RealSingularValueDecomposition svd =
        divide_and_conquer_svd(used.matrix, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd& sigma = svd.singular_values;
    while (rank < sigma.size() && sigma[rank] > 1e-12 * sigma[0]) ++rank;
    split.leading = sigma.head(rank).asDiagonal();
    u_leading = v_leading = Eigen::MatrixXd::Zero(n, rank);
    for (Eigen::Index i = 0; i < used.matrix.rows(); ++i)
      u_leading.row(used.rows[static_cast<size_t>(i)]) = svd.u.row(i).head(rank);
    for (Eigen::Index j = 0; j < used.matrix.cols(); ++j)
      v_leading.row(used.columns[static_cast<size_t>(j)]) = svd.v.row(j).head(rank);
  }
  split.left = completed_basis(u_leading);
  split.right = rank == static_cast<Eigen::Index>(used.columns.size())
                    ? completed_by_unit_vectors(v_leading, used.columns)
                    : completed_basis(v_leading);
  return split;
}

DescriptorSplit split_descriptor(const Eigen::MatrixXd& e, LinearStateSpace::Split method) {
  const UsedPart used = used_part(e);
  DescriptorSplit split;
  if (method == LinearStateSpace::Split::automatic && split_by_qr(used, e.rows(), split))
    return split;
  return split_by_svd(used, e.rows());
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
                                   double angular_frequency, Split split_method) {
  n_ = form.size();
  const DiagonalScaling scaling = equilibrate_pencil(a_matrix, e_matrix, angular_frequency);
  time_scale_ = scaling.frequency;
  row_scale_ = scaling.row;
  column_scale_ = scaling.column;
  const DescriptorSplit split =
      split_descriptor(Eigen::MatrixXd(scaled(e_matrix, scaling, time_scale_)), split_method);
  nd_ = split.leading.rows();
  na_ = n_ - nd_;
  left_ = split.left;
  right_ = split.right;
  leading_ = split.leading;
  const Eigen::MatrixXd a_hat = (left_.transpose() * scaled(a_matrix, scaling)) * right_;
  const Eigen::MatrixXd a11 = a_hat.topLeftCorner(nd_, nd_), a21 = a_hat.bottomLeftCorner(na_, nd_),
                        a22 = a_hat.bottomRightCorner(na_, na_);
  a12_ = a_hat.topRightCorner(nd_, na_);
  a22_lu_.compute(a22);
  if (na_ > 0 && !a22_lu_.isInvertible())
    throw std::runtime_error("the network's DAE has index > 1 or no unique solution");
  a22_inv_a21_ = na_ > 0 ? Eigen::MatrixXd(a22_lu_.solve(a21)) : Eigen::MatrixXd(0, nd_);
  m_ = leading_solve(Eigen::MatrixXd(a12_ * a22_inv_a21_ - a11));
  if (!m_.allFinite()) throw std::runtime_error("the reduced state matrix is not finite");
  balance(m_, balance_, balanced_m_);
  // Hidden constraints H·u = 0 (differentiated levers, displacement_form.hpp) are invariants of
  // the state equation: M has a zero eigenvalue for each, and rounding in M·x + N·f would
  // let the state drift along them (a lever slowly violating its kinematics). project_with()
  // removes that drift along M's null vectors.
  const std::vector<int>& hidden = form.hidden_constraints();
  const Eigen::Index k = static_cast<Eigen::Index>(hidden.size());
  if (k > 0 && k <= nd_) {
    Eigen::MatrixXd h(k, n_);
    const Eigen::SparseMatrix<double, Eigen::RowMajor> e_rows = e_matrix;
    for (Eigen::Index i = 0; i < k; ++i) h.row(i) = Eigen::RowVectorXd(e_rows.row(hidden[i]));
    constraint_ = h;  // its null vectors are found on the first project_with()
    hidden_rows_ = h;
  }
}

Eigen::MatrixXd LinearStateSpace::leading_solve(Eigen::MatrixXd x) const {
  // d/dt = ω₀·d/dt̂: the physical-time state equation is ω₀ times the scaled one.
  leading_.triangularView<Eigen::Upper>().solveInPlace(x);
  return time_scale_ * x;
}

Eigen::VectorXd LinearStateSpace::leading_solve(Eigen::VectorXd x) const {
  leading_.triangularView<Eigen::Upper>().solveInPlace(x);  // as a vector: no blocked kernel
  return time_scale_ * x;
}

void LinearStateSpace::prepare_projection() const {
  projection_prepared_ = true;
  const Eigen::Index k = constraint_.rows();
  if (k == 0) return;
  // The null space of the balanced M is the orthogonal complement of its rows' span: the last k
  // columns of Q in a column-pivoted (rank-revealing) QR of its transpose. The null space is
  // exactly k-dimensional (one per hidden constraint), so the rank gap is structural; the
  // constraint_lu_ check below catches a basis that is not it. On the fish fin it takes a
  // third of the SVD's instructions.
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(balanced_m_.transpose());
  null_vectors_ = balance_.asDiagonal() *
                  (qr.householderQ() * Eigen::MatrixXd::Identity(nd_, nd_).rightCols(k));
  Eigen::VectorXd u, up;
  Eigen::MatrixXd h_null(k, k);
  const Eigen::VectorXd no_force = Eigen::VectorXd::Zero(n_);
  for (Eigen::Index j = 0; j < k; ++j) {
    full_state(null_vectors_.col(j), no_force, u, up);
    h_null.col(j) = constraint_ * u;
  }
  constraint_lu_.compute(h_null);
  if (constraint_lu_.rcond() < 1e-12) constraint_.resize(0, 0);  // not the invariants
  if (constraint_.size() > 0) constraint_on_state_ = constraint_ * u_of_state();
}

Eigen::VectorXd LinearStateSpace::sources_in_constraints(const Eigen::VectorXd& f) const {
  if (!projection_prepared_) prepare_projection();
  if (constraint_.size() == 0) return Eigen::VectorXd();
  Eigen::VectorXd u, up;
  full_state(Eigen::VectorXd::Zero(nd_), f, u, up);
  return constraint_ * u;
}

Eigen::VectorXd LinearStateSpace::project_with(
    const Eigen::VectorXd& x, const Eigen::VectorXd& sources_in_constraints) const {
  if (!projection_prepared_) prepare_projection();
  if (constraint_.size() == 0) return x;
  return x -
         null_vectors_ * constraint_lu_.solve(constraint_on_state_ * x + sources_in_constraints);
}

Eigen::VectorXd LinearStateSpace::forcing(const Eigen::VectorXd& f) const {
  const Eigen::VectorXd f_hat = left_.transpose() * row_scale_.cwiseProduct(f);
  if (na_ == 0) return leading_solve(Eigen::VectorXd(f_hat.head(nd_)));
  const Eigen::VectorXd a22_inv_f2 = a22_lu_.solve(f_hat.tail(na_));
  return leading_solve(Eigen::VectorXd(f_hat.head(nd_) - a12_ * a22_inv_f2));
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
  const Eigen::RowVectorXd gamma =
      time_scale_ *
      Eigen::VectorXd(leading_.triangularView<Eigen::Upper>().transpose().solve(beta.transpose()))
          .transpose();
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
