// The modal analysis' eigenpairs of large pencils by shift-invert Arnoldi (Spectra): see
// modal_eigenpairs.hpp.
#include <Spectra/GenEigsSolver.h>

#include <algorithm>
#include <cmath>

#include "modal_eigenpairs.hpp"

namespace emnet {

namespace {

using Complex = std::complex<double>;

// Thrown out of Spectra by the operator when the analysis is cancelled.
struct ModalCancelled {};

// x ↦ (I − Π)·(Â + σÊ)⁻¹·Ê·x for Spectra, Π = V·Lᵀ the rigid-body projector (none: no columns);
// `transposed`: x ↦ (I − Πᵀ')·(Â + σÊ)⁻ᵀ·Êᵀ·x, the same for the transposed pencil, whose
// eigenvectors are the left vectors.
class ShiftInvertOperator {
 public:
  using Scalar = double;
  ShiftInvertOperator(ShiftInvertLu& lu, const Eigen::SparseMatrix<double>& e,
                      const Eigen::MatrixXd& right, const Eigen::MatrixXd& left, bool transposed,
                      Progress* progress)
      : lu_(lu), e_(e), right_(right), left_(left), transposed_(transposed), progress_(progress) {
    if (transposed_) e_transposed_ = e.transpose();
  }
  Eigen::Index rows() const { return e_.rows(); }
  Eigen::Index cols() const { return e_.cols(); }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, e_.cols());
    Eigen::Map<Eigen::VectorXd> y(y_out, e_.rows());
    if (transposed_)
      y = lu_.transpose().solve(e_transposed_ * x);
    else
      y = lu_.solve(e_ * x);
    if (right_.cols() > 0) y -= right_ * (left_.transpose() * y);
    ++applications_;
    if (!keep_going(progress_, applications_, 0,
                    transposed_ ? "modal analysis: Arnoldi, left vectors (solves)"
                                : "modal analysis: Arnoldi (solves)"))
      throw ModalCancelled{};
  }

 private:
  ShiftInvertLu& lu_;  // SparseLU::transpose() is not const
  const Eigen::SparseMatrix<double>& e_;
  Eigen::SparseMatrix<double> e_transposed_;
  const Eigen::MatrixXd& right_;
  const Eigen::MatrixXd& left_;
  bool transposed_;
  Progress* progress_;
  mutable long applications_ = 0;
};

// One Arnoldi run for `nev` eigenpairs of `op` into `out`; returns how many converged and adds
// the restarts to `iterations`. Throws ModalCancelled when cancelled.
Eigen::Index arnoldi(ShiftInvertOperator& op, int nev, bool has_rigid_space, Eigenpairs& out,
                     long& iterations) {
  const int n = static_cast<int>(op.rows());
  const int ncv = std::min(n - 1, std::max(2 * nev + 1, 20));
  Spectra::GenEigsSolver<ShiftInvertOperator> eigs(op, nev, ncv);
  if (has_rigid_space) {
    // A start vector inside the projected space (the operator applied once): from a random
    // one, whose rigid-body part the first step amplifies by 1/σ̂² along the Jordan chain
    // and then cancels, Spectra returned a spurious real pole (free–free cantilever,
    // N = 40: s = +563 1/s in place of one of the 1159 Hz pair).
    Eigen::VectorXd start(n), projected(n);
    for (int i = 0; i < n; ++i) start[i] = std::cos(0.7 * i + 0.3);
    op.perform_op(start.data(), projected.data());
    eigs.init(projected.data());
  } else {
    eigs.init();
  }
  // Converged pairs are eigenpairs to their residual (bounded below), so they are kept
  // when the request does not converge as a whole, and the shortfall is reported.
  const Eigen::Index converged = eigs.compute(Spectra::SortRule::LargestMagn, 10, 1e-12);
  iterations += eigs.num_iterations();
  const Eigen::VectorXcd values = eigs.eigenvalues();
  const Eigen::MatrixXcd vectors = eigs.eigenvectors();
  out = {};
  for (Eigen::Index k = 0; k < values.size(); ++k) {
    out.values.push_back(values[k]);
    out.vectors.push_back(vectors.col(k));
  }
  return converged;
}

// The right eigenpairs, the request `nev` grown while real poles and overdamped pairs take
// converged places (arnoldi_eigenpairs); `nev` ends as the last request. Throws ModalCancelled
// when cancelled.
Status grown_right_eigenpairs(ShiftInvertOperator& op, bool has_rigid_space, double sigma_hat,
                              int wanted_modes, int& nev, Eigenpairs& right, ModalResult& result) {
  const int n = static_cast<int>(op.rows());
  for (int attempt = 0;; ++attempt) {
    const Eigen::Index converged = arnoldi(op, nev, has_rigid_space, right, result.iterations);
    if (converged == 0)
      return Status::failure("shift-invert Arnoldi converged to no pole in " +
                             std::to_string(result.iterations) +
                             " restarts (the poles nearest s = 0 form a cluster); the dense method "
                             "computes every pole of "
                             "a pencil up to its size limit");
    // Modes by the mode rule (is_resonance); real poles and overdamped pairs are the
    // others, which take converged places without being wanted.
    int resonant = 0, others = 0;
    for (const Complex& mu : right.values)
      (is_resonance(sigma_hat - 1.0 / mu) ? resonant : others) += 1;
    // Growing the request helps only when the others took converged places; a request that
    // did not converge has reached a cluster, and a larger one would not converge either.
    const bool grow = converged == nev && resonant / 2 < wanted_modes && attempt < 2 && nev < n - 3;
    if (!grow) {
      // A shortfall matters when it costs wanted modes (not when only the partner of the
      // last conjugate pair is missing: the pair stands for itself, poles_of).
      if (converged < nev && (resonant + 1) / 2 < wanted_modes)
        result.note = std::to_string(converged) + " of the " + std::to_string(nev) +
                      " poles requested converged: poles beyond a cluster of nearly equal real "
                      "poles, such as Kelvin-Voigt relaxations near -1/tau, are not reached (the "
                      "dense method computes every pole)";
      return Status::success();
    }
    nev = std::min(n - 3, std::max(2 * nev, others + 2 * wanted_modes));
  }
}

}  // namespace

Status arnoldi_eigenpairs(ShiftInvertLu& lu, const Eigen::SparseMatrix<double>& e_hat,
                          const RigidBodySpace& rigid, double sigma_hat,
                          const ModalOptions& options, Eigenpairs& right, Eigenpairs& left,
                          ModalResult& result) {
  // The poles nearest σ come first (|μ| = 1/|s − σ|). Ask for exactly the conjugate pairs
  // of the wanted modes: a request that ends inside a cluster (the overdamped relaxation poles
  // of Kelvin–Voigt damping near −1/τ, more of them the finer the beam) does not converge and
  // costs the whole restart budget (N = 4000: 2.1 s with 60 restarts against 0.1 s). Real
  // poles (RC loops, relaxations) that take converged places are counted, and the request
  // grows by as many. Well separated poles converge in 1–3 restarts; the budget is 10.
  const int wanted_modes = options.count > 0 ? options.count : 10;
  const int n = static_cast<int>(e_hat.rows());
  int nev =
      std::min(options.first_request > 0 ? options.first_request : 2 * std::min(wanted_modes, 3),
               n - 3);  // grows by doubling
  const bool has_rigid_space = rigid.right.cols() > 0;
  try {
    ShiftInvertOperator op(lu, e_hat, rigid.right, rigid.projector_left, false, options.progress);
    if (Status grown = grown_right_eigenpairs(op, has_rigid_space, sigma_hat, wanted_modes, nev,
                                              right, result);
        !grown.ok())
      return grown;
    result.last_request = nev;
    if (options.error_bounds) {
      ShiftInvertOperator transposed(lu, e_hat, rigid.left, rigid.transposed_projector_left, true,
                                     options.progress);
      if (!keep_going(options.progress, 4, 6, "modal analysis: left vectors"))
        return cancelled_status();
      arnoldi(transposed, nev, has_rigid_space, left, result.iterations);
    }
  } catch (const ModalCancelled&) {
    return cancelled_status();
  }
  return Status::success();
}

}  // namespace emnet
