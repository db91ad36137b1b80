// Modal analysis: poles of the displacement-form pencil by shift-invert, rigid-body motions
// projected out, a first-order error bound per pole; see analysis.hpp.
#include <Spectra/GenEigsSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "core/timed.hpp"
#include "displacement_form.hpp"
#include "emnet/analysis/analysis.hpp"
#include "equilibration.hpp"
#include "pole_bounds.hpp"
#include "rigid_body_space.hpp"

namespace emnet {

namespace {

constexpr double two_pi = 6.283185307179586476925286766559;
using Complex = std::complex<double>;
using Lu = Eigen::SparseLU<Eigen::SparseMatrix<double>>;

// Shift when Â is singular (rigid-body motions, projected out), relative to ‖Â‖/‖Ê‖: positive
// (a passive network has no pole there), small against the lowest elastic pole (equilibrated,
// |ŝ| = 0.08 for the fish fin at N = 7 up to 2.5 at N = 100 000), and large enough that the
// rigid-body space's eigenvalue 1/σ̂ of T does not magnify the projector's rounding (1e-13)
// beyond 1e-11.
constexpr double kRigidShift = 1e-2;

// x ↦ (I − Π)·(Â + σÊ)⁻¹·Ê·x for Spectra, Π = V·Lᵀ the rigid-body projector (none: no columns);
// `transposed`: x ↦ (I − Πᵀ')·(Â + σÊ)⁻ᵀ·Êᵀ·x, the same for the transposed pencil, whose
// eigenvectors are the left vectors.
// Thrown out of Spectra by the operator when the analysis is cancelled.
struct ModalCancelled {};

class ShiftInvertOperator {
 public:
  using Scalar = double;
  ShiftInvertOperator(Lu& lu, const Eigen::SparseMatrix<double>& e, const Eigen::MatrixXd& right,
                      const Eigen::MatrixXd& left, bool transposed, Progress* progress)
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
  Lu& lu_;  // SparseLU::transpose() is not const
  const Eigen::SparseMatrix<double>& e_;
  Eigen::SparseMatrix<double> e_transposed_;
  const Eigen::MatrixXd& right_;
  const Eigen::MatrixXd& left_;
  bool transposed_;
  Progress* progress_;
  mutable long applications_ = 0;
};

struct Eigenpairs {
  std::vector<Complex> values;  // μ
  std::vector<Eigen::VectorXcd> vectors;
};

// The eigenpairs of a shift-invert operator with |μ| above rounding (the pencil's infinite
// poles map to μ = 0, perturbed by √ε for the index-2 blocks of massless nodes): dense.
Eigenpairs dense_eigenpairs(const Eigen::MatrixXd& t, std::string& why) {
  Eigenpairs out;
  Eigen::EigenSolver<Eigen::MatrixXd> solver(t, true);
  if (solver.info() != Eigen::Success) {
    why = "dense eigen-decomposition did not converge";
    return out;
  }
  const Eigen::VectorXcd values = solver.eigenvalues();
  const double largest = values.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < values.size(); ++k)
    if (std::abs(values[k]) > 1e-7 * largest) {
      out.values.push_back(values[k]);
      out.vectors.push_back(solver.eigenvectors().col(k));
    }
  return out;
}

// One of each conjugate pair, Im ŝ ≥ 0, real poles with real vectors: ŝ = σ̂ − 1/μ. A pole with
// Im ŝ < 0 whose partner is missing (Arnoldi converged one of the pair at the end of its list)
// stands for the pair.
std::vector<PoleEstimate> poles_of(const Eigenpairs& pairs, double sigma_hat) {
  std::vector<PoleEstimate> poles;
  for (size_t k = 0; k < pairs.values.size(); ++k) {
    const Complex pole = sigma_hat - 1.0 / pairs.values[k];
    if (pole.imag() < -kNearlyReal * std::abs(pole)) {
      bool partner = false;
      for (const Complex& mu : pairs.values)
        partner = partner ||
                  std::abs(std::conj(mu) - pairs.values[k]) <= 1e-8 * std::abs(pairs.values[k]);
      if (partner) continue;
    }
    const bool oscillatory = std::abs(pole.imag()) > kNearlyReal * std::abs(pole);
    PoleEstimate estimate;
    estimate.pole = Complex(pole.real(), oscillatory ? std::abs(pole.imag()) : 0.0);
    estimate.right =
        pole.imag() < 0.0 ? Eigen::VectorXcd(pairs.vectors[k].conjugate()) : pairs.vectors[k];
    if (!oscillatory) {  // a real vector times a phase: undo the phase
      Eigen::Index largest = 0;
      estimate.right.cwiseAbs().maxCoeff(&largest);
      const Complex phase = estimate.right[largest] / std::abs(estimate.right[largest]);
      estimate.right = (estimate.right / phase).real().cast<Complex>();
    }
    poles.push_back(std::move(estimate));
  }
  return poles;
}

// The rigid-body motions as displacement fields on the system's unknowns: an orthonormal basis,
// each with its largest entry positive.
std::vector<Eigen::VectorXd> rigid_body_motions(const RigidBodySpace& space,
                                                const DiagonalScaling& scaling,
                                                const DisplacementForm& form, int size) {
  Eigen::MatrixXd motions = Eigen::MatrixXd::Zero(size, space.null_vectors.cols());
  for (Eigen::Index j = 0; j < motions.cols(); ++j) {
    const Eigen::VectorXd u = scaling.column.cwiseProduct(space.null_vectors.col(j));
    for (int i = 0; i < size; ++i)
      if (form.mechanical(i)) motions(i, j) = u[i];
  }
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(motions);
  const Eigen::MatrixXd basis = qr.householderQ() * Eigen::MatrixXd::Identity(size, motions.cols());
  std::vector<Eigen::VectorXd> out;
  for (Eigen::Index j = 0; j < basis.cols(); ++j) {
    Eigen::VectorXd displacement = basis.col(j);
    Eigen::Index largest = 0;
    displacement.cwiseAbs().maxCoeff(&largest);
    if (displacement[largest] < 0.0) displacement = -displacement;
    out.push_back(displacement);
  }
  return out;
}

// run_modes without its guard.
ModalResult compute_modes(const System& system, const Eigen::VectorXd& operating_point,
                          const ModalOptions& options) {
  Timed<ModalResult> timed;
  ModalResult& result = timed.result;
  result.unknowns = system.size();
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  if (sparse_one_norm(system.C) == 0.0)
    return finish(Status::failure("the network stores no energy: no poles"));
  std::unique_ptr<DisplacementForm> form;
  try {
    form = std::make_unique<DisplacementForm>(system, DisplacementForm::Use::eigenvalues);
  } catch (const std::runtime_error& error) {
    return finish(Status::failure(std::string("no displacement form: ") + error.what()));
  }
  const int n = form->size();
  result.pencil_size = n;
  auto phase = [&](long step, const char* what) {
    return keep_going(options.progress, step, 6, what);
  };
  if (!phase(0, "modal analysis: equilibration")) return finish(cancelled_status());
  if (operating_point.size() != 0 && operating_point.size() != system.size())
    return finish(
        Status::failure("the operating point has " + std::to_string(operating_point.size()) +
                        " entries, the network " + std::to_string(system.size()) + " unknowns"));
  const Eigen::VectorXd rest = operating_point.size() == 0
                                   ? Eigen::VectorXd(Eigen::VectorXd::Zero(system.size()))
                                   : operating_point;  // empty: at zero (a linear network)
  Eigen::SparseMatrix<double> a_matrix, e_matrix;
  form->linearised(form->from_rest(rest), Eigen::VectorXd::Zero(n), a_matrix, e_matrix);
  // Everything below works on the equilibrated pencil (Â, Ê) with poles ŝ = s/ω₀, so that
  // thresholds relative to the largest entry or eigenvalue do not depend on the units
  // (equilibration.hpp); poles and vectors are mapped back at the end.
  const DiagonalScaling scaling = equilibrate_pencil(a_matrix, e_matrix);
  const double omega0 = scaling.frequency;
  const Eigen::SparseMatrix<double> a_hat = scaled(a_matrix, scaling);
  const Eigen::SparseMatrix<double> e_hat = scaled(e_matrix, scaling, omega0);
  const double a_norm = sparse_one_norm(a_hat), e_norm = sparse_one_norm(e_hat);
  if (e_norm == 0.0) return finish(Status::failure("the network stores no energy: no poles"));

  // Shift σ̂ = 0 unless Â is singular there: then rigid-body motions have the pole s = 0; they
  // are found by rank-revealing QR and projected out, at the small positive shift kRigidShift.
  if (!phase(1, "modal analysis: sparse LU")) return finish(cancelled_status());
  Lu lu;
  auto factorise = [&](double sigma) {
    Eigen::SparseMatrix<double> shifted = a_hat + sigma * e_hat;
    shifted.makeCompressed();
    lu.analyzePattern(shifted);
    lu.factorize(shifted);
    return lu.info() == Eigen::Success;
  };
  double sigma_hat = 0.0;
  RigidBodySpace rigid;
  if (!factorise(0.0)) {
    sigma_hat = kRigidShift * a_norm / e_norm;
    if (!factorise(sigma_hat))
      return finish(Status::failure(
          "the pencil is singular for every shift (the network has no well-defined dynamics)"));
    if (!phase(2, "modal analysis: rigid-body motions (sparse QR)"))
      return finish(cancelled_status());
    rigid = rigid_body_space(a_hat, e_hat);
    if (!rigid.failure.empty())
      return finish(Status::failure("rigid-body motions: " + rigid.failure));
    result.rigid_body_modes = rigid_body_motions(rigid, scaling, *form, system.size());
  }
  result.shift = sigma_hat * omega0;

  if (!phase(3, "modal analysis: eigenvalues")) return finish(cancelled_status());
  Eigenpairs right_pairs, left_pairs;
  const bool dense = system.size() <= options.dense_limit || options.count >= n - 2;
  std::string why;
  if (dense) {
    result.method = Method::dense;
    Eigen::MatrixXd t = lu.solve(Eigen::MatrixXd(e_hat));
    if (rigid.right.cols() > 0) t -= rigid.right * (rigid.projector_left.transpose() * t);
    if (!t.allFinite()) return finish(Status::failure("shift-invert operator is not finite"));
    right_pairs = dense_eigenpairs(t, why);
    if (!why.empty()) return finish(Status::failure(why));
    if (options.error_bounds) {
      Eigen::MatrixXd s = lu.transpose().solve(Eigen::MatrixXd(e_hat.transpose()));
      if (rigid.left.cols() > 0)
        s -= rigid.left * (rigid.transposed_projector_left.transpose() * s);
      left_pairs = dense_eigenpairs(s, why);
      why.clear();  // without left vectors the bounds fall back to inverse iteration
    }
    result.complete = true;
  } else {
    result.method = Method::arnoldi;
    // The poles nearest σ come first (|μ| = 1/|s − σ|). Ask for exactly the conjugate pairs
    // of the wanted modes: a request that ends inside a cluster (the overdamped relaxation poles
    // of Kelvin–Voigt damping near −1/τ, more of them the finer the beam) does not converge and
    // costs the whole restart budget (N = 4000: 2.1 s with 60 restarts against 0.1 s). Real
    // poles (RC loops, relaxations) that take converged places are counted, and the request
    // grows by as many. Well separated poles converge in 1–3 restarts; the budget is 10.
    const int wanted_modes = options.count > 0 ? options.count : 10;
    int nev = std::min(2 * std::min(wanted_modes, 3), n - 3);  // grows by doubling
    const bool has_rigid_space = rigid.right.cols() > 0;
    auto arnoldi = [&](ShiftInvertOperator& op, Eigenpairs& out) -> Eigen::Index {
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
      result.iterations += eigs.num_iterations();
      const Eigen::VectorXcd values = eigs.eigenvalues();
      const Eigen::MatrixXcd vectors = eigs.eigenvectors();
      out = {};
      for (Eigen::Index k = 0; k < values.size(); ++k) {
        out.values.push_back(values[k]);
        out.vectors.push_back(vectors.col(k));
      }
      return converged;
    };
    bool cancelled = false;
    auto run = [&](ShiftInvertOperator& op, Eigenpairs& out) -> Eigen::Index {
      try {
        return arnoldi(op, out);
      } catch (const ModalCancelled&) {
        cancelled = true;
        return -1;
      }
    };
    ShiftInvertOperator op(lu, e_hat, rigid.right, rigid.projector_left, false, options.progress);
    for (int attempt = 0;; ++attempt) {
      const Eigen::Index converged = run(op, right_pairs);
      if (cancelled) return finish(cancelled_status());
      if (converged == 0)
        return finish(Status::failure(
            "shift-invert Arnoldi converged to no pole in " + std::to_string(result.iterations) +
            " restarts (the poles nearest s = 0 form a cluster); --dense computes every pole of "
            "a pencil up to its size limit"));
      // Modes by the mode rule (is_resonance); real poles and overdamped pairs are the
      // others, which take converged places without being wanted.
      int resonant = 0, others = 0;
      for (const Complex& mu : right_pairs.values)
        (is_resonance(sigma_hat - 1.0 / mu) ? resonant : others) += 1;
      // Growing the request helps only when the others took converged places; a request that
      // did not converge has reached a cluster, and a larger one would not converge either.
      const bool grow =
          converged == nev && resonant / 2 < wanted_modes && attempt < 2 && nev < n - 3;
      if (!grow) {
        // A shortfall matters when it costs wanted modes (not when only the partner of the
        // last conjugate pair is missing: the pair stands for itself, poles_of).
        if (converged < nev && (resonant + 1) / 2 < wanted_modes)
          result.note = std::to_string(converged) + " of the " + std::to_string(nev) +
                        " poles requested converged";
        break;
      }
      nev = std::min(n - 3, std::max(2 * nev, others + 2 * wanted_modes));
    }
    if (options.error_bounds) {
      ShiftInvertOperator transposed(lu, e_hat, rigid.left, rigid.transposed_projector_left, true,
                                     options.progress);
      if (!phase(4, "modal analysis: left vectors")) return finish(cancelled_status());
      run(transposed, left_pairs);
      if (cancelled) return finish(cancelled_status());
    }
  }

  if (!phase(5, "modal analysis: error bounds")) return finish(cancelled_status());
  std::vector<PoleEstimate> poles = poles_of(right_pairs, sigma_hat);
  span_repeated_poles(a_hat, e_hat, poles);
  if (options.error_bounds) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<TransposedEigenpair> lefts;
    for (PoleEstimate& left : poles_of(left_pairs, sigma_hat))
      lefts.push_back({left.pole, std::move(left.right)});
    bound_poles(a_hat, e_hat, lefts, poles);
    // A computed eigenvalue far above the lowest poles whose error bound exceeds its own size is
    // no pole: the pencil's infinite eigenvalues come out so, perturbed by rounding to
    // |μ| ~ ε^(1/k)·‖T‖ for index-k blocks (measured: the damped fin at N = 100, dense, gave
    // seven "modes" of 2 to 45 MHz and real poles to −4e8 1/s with bounds of 2 to 3400 times
    // their size, beside four modes bounded to 4e-10). Poles within 1e4 of the lowest stay,
    // bounded or not (the fin's Kelvin–Voigt relaxations near −1/τ: a cluster of ~190 poles,
    // most of them not bounded individually).
    double lowest = std::numeric_limits<double>::infinity();
    for (const PoleEstimate& pole : poles) lowest = std::min(lowest, std::abs(pole.pole));
    const size_t before = poles.size();
    poles.erase(std::remove_if(poles.begin(), poles.end(),
                               [&](const PoleEstimate& pole) {
                                 return !pole.bounded && pole.bound > std::abs(pole.pole) &&
                                        std::abs(pole.pole) > 1e4 * lowest;
                               }),
                poles.end());
    if (poles.size() < before)
      result.note += std::string(result.note.empty() ? "" : "; ") +
                     std::to_string(before - poles.size()) +
                     " computed eigenvalue(s) above 1e4 times the lowest pole with an error "
                     "bound larger than themselves left out (infinite eigenvalues of the pencil "
                     "perturbed by rounding)";
    result.bound_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } else {
    for (PoleEstimate& pole : poles) pole.reason = "not computed (error_bounds off)";
  }

  const Eigen::SparseMatrix<Complex> ac = a_hat.cast<Complex>();
  const Eigen::SparseMatrix<Complex> ec = e_hat.cast<Complex>();
  const int size = system.size();
  for (const PoleEstimate& estimate : poles) {
    Mode mode;
    mode.pole = omega0 * estimate.pole;
    const bool oscillatory = mode.pole.imag() > 0.0;
    mode.natural_frequency_hz = std::abs(mode.pole) / two_pi;
    mode.frequency_hz = std::abs(mode.pole.imag()) / two_pi;
    mode.damping_ratio = std::abs(mode.pole) > 0.0 ? -mode.pole.real() / std::abs(mode.pole) : 0.0;
    mode.pole_error = omega0 * estimate.bound;
    mode.error_bounded = estimate.bounded;
    mode.unbounded_reason = estimate.reason;
    const Eigen::VectorXcd& x = estimate.right;
    const double norm = x.norm();
    if (norm > 0.0)
      mode.relative_residual = (ac * x + estimate.pole * (ec * x)).norm() /
                               ((a_norm + std::abs(estimate.pole) * e_norm) * norm);
    if (options.keep_vectors) {
      // The velocity form's vector: across values of mechanical nodes are velocities s·z.
      const Eigen::VectorXcd u = scaling.column.cast<Complex>().cwiseProduct(x);
      Eigen::VectorXcd y(size);
      for (int i = 0; i < size; ++i)
        y[i] = !form->mechanical(i)        ? u[i]
               : form->velocity_of(i) >= 0 ? u[form->velocity_of(i)]
                                           : mode.pole * u[i];
      const double y_norm = y.norm();
      mode.vector = y_norm > 0.0 ? Eigen::VectorXcd(y / y_norm) : y;
    }
    std::vector<Mode>& list = !oscillatory              ? result.real_poles
                              : is_resonance(mode.pole) ? result.modes
                                                        : result.overdamped_pairs;
    list.push_back(std::move(mode));
  }
  std::sort(result.modes.begin(), result.modes.end(),
            [](const Mode& a, const Mode& b) { return a.frequency_hz < b.frequency_hz; });
  for (auto* list : {&result.real_poles, &result.overdamped_pairs})
    std::sort(list->begin(), list->end(),
              [](const Mode& a, const Mode& b) { return std::abs(a.pole) < std::abs(b.pole); });
  // ModalResult's invariants: modes are resonances (Im s > 0, the mode rule), the overdamped
  // pairs oscillatory but not resonances.
  assert(std::all_of(result.modes.begin(), result.modes.end(), [](const Mode& mode) {
    return mode.pole.imag() > 0.0 && is_resonance(mode.pole);
  }));
  assert(std::none_of(result.overdamped_pairs.begin(), result.overdamped_pairs.end(),
                      [](const Mode& mode) { return is_resonance(mode.pole); }));
  return finish(Status::success());
}

}  // namespace

ModalResult run_modes(const System& system, const Eigen::VectorXd& operating_point,
                      const ModalOptions& options) {
  // An eigen-solver that gives up (Eigen's or Spectra's "Schur decomposition failed", on a
  // pencil whose values span hundreds of orders of magnitude, e.g. a 1e300 kg mass) is a
  // numerical failure with its reason, not an internal error.
  try {
    return compute_modes(system, operating_point, options);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& error) {
    ModalResult failed;
    failed.unknowns = system.size();
    failed.status = Status::failure(
        std::string("the eigen-solver failed: ") + error.what() +
        " (the network's values may span too many orders of magnitude for double precision)");
    return failed;
  }
}

}  // namespace emnet
