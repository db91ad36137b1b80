// Modal analysis: poles of the displacement-form pencil by shift-invert, rigid-body motions
// projected out, a first-order error bound per pole; see analysis.hpp.
#include <Eigen/QR>
#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "core/timed.hpp"
#include "dense_decompositions.hpp"
#include "displacement_form.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/core/option_error.hpp"
#include "equilibration.hpp"
#include "modal_eigenpairs.hpp"
#include "pole_bounds.hpp"
#include "rigid_body_space.hpp"

namespace emnet {

namespace {

constexpr double two_pi = 6.283185307179586476925286766559;
using Complex = std::complex<double>;

// Shift when Â is singular (rigid-body motions, projected out), relative to ‖Â‖/‖Ê‖: positive
// (a passive network has no pole there), small against the lowest elastic pole (equilibrated,
// |ŝ| = 0.08 for the fish fin at N = 7 up to 2.5 at N = 100 000), and large enough that the
// rigid-body space's eigenvalue 1/σ̂ of T does not magnify the projector's rounding (1e-13)
// beyond 1e-11.
constexpr double kRigidShift = 1e-2;

// The eigenpairs of a shift-invert operator with |μ| above rounding (the pencil's infinite
// poles map to μ = 0, perturbed by √ε for the index-2 blocks of massless nodes): dense.
// The eigenpairs of t with |μ| above 1e-7 of the largest; with `left`, also t's left vectors
// (tᵀ·y = μ·y) of the same eigenvalues, from the same Schur form.
Eigenpairs dense_eigenpairs(const Eigen::MatrixXd& t, std::string& why,
                            Eigenpairs* left = nullptr) {
  Eigenpairs out;
  const RealEigenDecomposition solver = real_eigen_decomposition(t, left != nullptr);
  if (!solver.converged) {
    why = "dense eigen-decomposition did not converge";
    return out;
  }
  const Eigen::VectorXcd& values = solver.values;
  const double largest = values.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < values.size(); ++k)
    if (std::abs(values[k]) > 1e-7 * largest) {
      out.values.push_back(values[k]);
      out.vectors.push_back(solver.vectors.col(k));
      if (left) {
        left->values.push_back(values[k]);
        left->vectors.push_back(solver.left_vectors.col(k));
      }
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

// Reports phase `step` of the modal analysis' six; false when cancelled.
bool phase(const ModalOptions& options, long step, const char* what) {
  return keep_going(options.progress, step, 6, what);
}

// The displacement-form pencil linearised at the operating point and equilibrated: everything
// after it works on (Â, Ê) with poles ŝ = s/ω₀, so that thresholds relative to the largest entry
// or eigenvalue do not depend on the units (equilibration.hpp); poles and vectors are mapped
// back at the end.
struct EquilibratedPencil {
  std::unique_ptr<DisplacementForm> form;
  DiagonalScaling scaling;
  Eigen::SparseMatrix<double> a_hat, e_hat;
  double a_norm = 0.0, e_norm = 0.0;
};

// Fills `pencil` (whose form is made) at `operating_point` (y at rest; empty: zero).
Status linearise_and_equilibrate(const System& system, const Eigen::VectorXd& operating_point,
                                 EquilibratedPencil& pencil) {
  const DisplacementForm& form = *pencil.form;
  if (operating_point.size() != 0 && operating_point.size() != system.size())
    return Status::failure("the operating point has " + std::to_string(operating_point.size()) +
                           " entries, the network " + std::to_string(system.size()) + " unknowns");
  const Eigen::VectorXd rest = operating_point.size() == 0
                                   ? Eigen::VectorXd(Eigen::VectorXd::Zero(system.size()))
                                   : operating_point;  // empty: at zero (a linear network)
  Eigen::SparseMatrix<double> a_matrix, e_matrix;
  form.linearised(form.from_rest(rest), Eigen::VectorXd::Zero(form.size()), a_matrix, e_matrix);
  pencil.scaling = equilibrate_pencil(a_matrix, e_matrix);
  pencil.a_hat = scaled(a_matrix, pencil.scaling);
  pencil.e_hat = scaled(e_matrix, pencil.scaling, pencil.scaling.frequency);
  pencil.a_norm = sparse_one_norm(pencil.a_hat);
  pencil.e_norm = sparse_one_norm(pencil.e_hat);
  if (pencil.e_norm == 0.0) return Status::failure("the network stores no energy: no poles");
  return Status::success();
}

// Factorises Â + σ̂·Ê into `lu` at σ̂ = 0 unless Â is singular there: then rigid-body motions have
// the pole s = 0; they are found by rank-revealing QR (`rigid`, and result.rigid_body_modes) and
// projected out, at the small positive shift kRigidShift.
Status factorise_shifted(const EquilibratedPencil& pencil, const System& system,
                         const ModalOptions& options, ShiftInvertLu& lu, double& sigma_hat,
                         RigidBodySpace& rigid, ModalResult& result) {
  auto factorise = [&](double sigma) {
    Eigen::SparseMatrix<double> shifted = pencil.a_hat + sigma * pencil.e_hat;
    shifted.makeCompressed();
    lu.analyzePattern(shifted);
    lu.factorize(shifted);
    return lu.info() == Eigen::Success;
  };
  sigma_hat = 0.0;
  if (factorise(0.0)) return Status::success();
  sigma_hat = kRigidShift * pencil.a_norm / pencil.e_norm;
  if (!factorise(sigma_hat))
    return Status::failure(
        "the pencil is singular for every shift (the network has no well-defined dynamics)");
  if (!phase(options, 2, "modal analysis: rigid-body motions (sparse QR)"))
    return cancelled_status();
  rigid = rigid_body_space(pencil.a_hat, pencil.e_hat);
  if (!rigid.failure.empty()) return Status::failure("rigid-body motions: " + rigid.failure);
  result.rigid_body_modes = rigid_body_motions(rigid, pencil.scaling, *pencil.form, system.size());
  return Status::success();
}

// Every eigenpair of T (and, with options.error_bounds, of the transposed operator, whose
// failure only leaves the bounds to inverse iteration) by dense decompositions.
Status dense_operator_eigenpairs(const EquilibratedPencil& pencil, ShiftInvertLu& lu,
                                 const RigidBodySpace& rigid, const ModalOptions& options,
                                 Eigenpairs& right, Eigenpairs& left) {
  std::string why;
  Eigen::MatrixXd t = lu.solve(Eigen::MatrixXd(pencil.e_hat));
  if (rigid.right.cols() > 0) t -= rigid.right * (rigid.projector_left.transpose() * t);
  if (!t.allFinite()) return Status::failure("shift-invert operator is not finite");
  // The transposed pencil's operator S = (Â + σ̂Ê)⁻ᵀ·Êᵀ has the eigenvectors (Â + σ̂Ê)⁻ᵀ·y of
  // T's left vectors y (Tᵀ·y = μ·y), which T's own Schur form gives: one decomposition for
  // both. With a rigid-body projector S is projected apart, and decomposed itself.
  const bool left_from_t = options.error_bounds && rigid.right.cols() == 0;
  right = dense_eigenpairs(t, why, left_from_t ? &left : nullptr);
  if (!why.empty()) return Status::failure(why);
  if (left_from_t) {
    for (Eigen::VectorXcd& y : left.vectors) {
      y = lu.transpose().solve(Eigen::VectorXd(y.real())).cast<Complex>() +
          Complex(0.0, 1.0) * lu.transpose().solve(Eigen::VectorXd(y.imag())).cast<Complex>();
      y.normalize();
    }
  } else if (options.error_bounds) {
    Eigen::MatrixXd s = lu.transpose().solve(Eigen::MatrixXd(pencil.e_hat.transpose()));
    if (rigid.left.cols() > 0) s -= rigid.left * (rigid.transposed_projector_left.transpose() * s);
    left = dense_eigenpairs(s, why);
  }
  return Status::success();
}

// The poles of the eigenpairs, repeated ones spanned, each with its error bound when
// options.error_bounds (and result.bound_seconds); spurious infinite ones left out (with a note).
std::vector<PoleEstimate> bounded_poles(const EquilibratedPencil& pencil, const Eigenpairs& right,
                                        const Eigenpairs& left, double sigma_hat,
                                        const ModalOptions& options, ModalResult& result) {
  std::vector<PoleEstimate> poles = poles_of(right, sigma_hat);
  span_repeated_poles(pencil.a_hat, pencil.e_hat, poles);
  if (!options.error_bounds) {
    for (PoleEstimate& pole : poles) pole.reason = "not computed (error_bounds off)";
    return poles;
  }
  const auto start = std::chrono::steady_clock::now();
  std::vector<TransposedEigenpair> lefts;
  for (PoleEstimate& left_pole : poles_of(left, sigma_hat))
    lefts.push_back({left_pole.pole, std::move(left_pole.right)});
  bound_poles(pencil.a_hat, pencil.e_hat, lefts, poles);
  // A computed eigenvalue far above the lowest poles whose error bound exceeds its own size is
  // no pole: the pencil's infinite eigenvalues come out so, perturbed by rounding to
  // |μ| ~ ε^(1/k)·‖T‖ for index-k blocks (measured: the damped fin at N = 100, dense, gave
  // seven "modes" of 2 to 45 MHz and real poles to −4e8 1/s with bounds of 2 to 3400 times
  // their size, beside four modes bounded to 4e-10). Poles within 1e4 of the lowest stay,
  // bounded or not (the fin's Kelvin–Voigt relaxations near −1/τ: a cluster of ~190 poles,
  // most of them not bounded individually).
  double lowest = std::numeric_limits<double>::infinity();
  for (const PoleEstimate& pole : poles) lowest = std::min(lowest, std::abs(pole.pole));
  const auto leave_out = [&](auto spurious, const std::string& what) {
    const size_t before = poles.size();
    poles.erase(std::remove_if(poles.begin(), poles.end(), spurious), poles.end());
    if (poles.size() < before)
      result.note += std::string(result.note.empty() ? "" : "; ") +
                     std::to_string(before - poles.size()) + what;
  };
  leave_out(
      [&](const PoleEstimate& pole) {
        return !pole.bounded && pole.bound > std::abs(pole.pole) &&
               std::abs(pole.pole) > 1e4 * lowest;
      },
      " computed eigenvalue(s) above 1e4 times the lowest pole with an error bound larger than "
      "themselves left out (infinite eigenvalues of the pencil perturbed by rounding)");
  // Likewise a computed eigenvalue whose bound exceeds its size cannot be told from s = 0: where
  // the network moves as a rigid body (the pole s = 0, projected out before the eigen-solver,
  // reported apart) it is what rounding left of that pole's Jordan chain (measured: a free–free
  // beam of 40 segments by Arnoldi, a real "pole" of +6094 1/s with a bound of 4.8e4 times it).
  if (!result.rigid_body_modes.empty())
    leave_out(
        [](const PoleEstimate& pole) { return !pole.bounded && pole.bound > std::abs(pole.pole); },
        " computed eigenvalue(s) with an error bound larger than themselves left out (they "
        "cannot be told from the rigid-body motions' pole s = 0)");
  result.bound_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return poles;
}

// The Mode of a pole estimate on the equilibrated pencil: pole and error in 1/s, its residual,
// and (options.keep_vectors) the velocity form's vector, normalised.
Mode mode_of(const PoleEstimate& estimate, const EquilibratedPencil& pencil,
             const Eigen::SparseMatrix<Complex>& ac, const Eigen::SparseMatrix<Complex>& ec,
             int size, const ModalOptions& options) {
  const double omega0 = pencil.scaling.frequency;
  const DisplacementForm& form = *pencil.form;
  Mode mode;
  mode.pole = omega0 * estimate.pole;
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
                             ((pencil.a_norm + std::abs(estimate.pole) * pencil.e_norm) * norm);
  if (options.keep_vectors) {
    // The velocity form's vector: across values of mechanical nodes are velocities s·z.
    const Eigen::VectorXcd u = pencil.scaling.column.cast<Complex>().cwiseProduct(x);
    Eigen::VectorXcd y(size);
    for (int i = 0; i < size; ++i)
      y[i] = !form.mechanical(i)        ? u[i]
             : form.velocity_of(i) >= 0 ? u[form.velocity_of(i)]
                                        : mode.pole * u[i];
    const double y_norm = y.norm();
    mode.vector = y_norm > 0.0 ? Eigen::VectorXcd(y / y_norm) : y;
  }
  return mode;
}

// The poles as modes, real poles and overdamped pairs of `result`, each list sorted.
void record_modes(const std::vector<PoleEstimate>& poles, const EquilibratedPencil& pencil,
                  int size, const ModalOptions& options, ModalResult& result) {
  const Eigen::SparseMatrix<Complex> ac = pencil.a_hat.cast<Complex>();
  const Eigen::SparseMatrix<Complex> ec = pencil.e_hat.cast<Complex>();
  for (const PoleEstimate& estimate : poles) {
    Mode mode = mode_of(estimate, pencil, ac, ec, size, options);
    const bool oscillatory = mode.pole.imag() > 0.0;
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
  EquilibratedPencil pencil;
  try {
    pencil.form = std::make_unique<DisplacementForm>(system, DisplacementForm::Use::eigenvalues);
  } catch (const std::runtime_error& error) {
    return finish(Status::failure(std::string("no displacement form: ") + error.what()));
  }
  const int n = pencil.form->size();
  result.pencil_size = n;
  if (!phase(options, 0, "modal analysis: equilibration")) return finish(cancelled_status());
  if (Status equilibrated = linearise_and_equilibrate(system, operating_point, pencil);
      !equilibrated.ok())
    return finish(equilibrated);

  if (!phase(options, 1, "modal analysis: sparse LU")) return finish(cancelled_status());
  ShiftInvertLu lu;
  double sigma_hat = 0.0;
  RigidBodySpace rigid;
  if (Status factorised = factorise_shifted(pencil, system, options, lu, sigma_hat, rigid, result);
      !factorised.ok())
    return finish(factorised);
  result.shift = sigma_hat * pencil.scaling.frequency;

  if (!phase(options, 3, "modal analysis: eigenvalues")) return finish(cancelled_status());
  Eigenpairs right_pairs, left_pairs;
  const bool dense = system.size() <= options.dense_limit || options.count >= n - 2;
  result.method = dense ? Method::dense : Method::arnoldi;
  const Status found =
      dense ? dense_operator_eigenpairs(pencil, lu, rigid, options, right_pairs, left_pairs)
            : arnoldi_eigenpairs(lu, pencil.e_hat, rigid, sigma_hat, options, right_pairs,
                                 left_pairs, result);
  if (!found.ok()) return finish(found);
  result.complete = dense;

  if (!phase(options, 5, "modal analysis: error bounds")) return finish(cancelled_status());
  const std::vector<PoleEstimate> poles =
      bounded_poles(pencil, right_pairs, left_pairs, sigma_hat, options, result);
  record_modes(poles, pencil, system.size(), options, result);
  return finish(Status::success());
}

}  // namespace

void validate(const ModalOptions& options) {
  if (options.count < 0) throw OptionError("count", "must be >= 0");
  if (options.dense_limit < 0) throw OptionError("dense_limit", "must be >= 0");
  if (options.first_request < 0) throw OptionError("first_request", "must be >= 0");
}

ModalResult run_modes(const System& system, const Eigen::VectorXd& operating_point,
                      const ModalOptions& options) {
  validate(options);
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
