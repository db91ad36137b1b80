// Modal analysis: poles of the pencil (G + J_g, C) by shift-invert; see analysis.hpp.
#include <Spectra/GenEigsSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "emnet/analysis.hpp"
#include "equilibration.hpp"
#include "timed.hpp"

namespace emnet {

namespace {

constexpr double two_pi = 6.283185307179586476925286766559;

// A pole with |Im s| ≤ kNearlyReal·|s| (damping ratio above 1 − 5e-11) is real: rounding splits a
// repeated real pole into a complex pair ~√ε apart. Measured: the fish fin with the ideal drive
// and loss factor 1e-5 has repeated Kelvin–Voigt poles at −1/τ (τ = 2.5e-7 s) that came out as
// a "mode" at 0.0071 Hz with |Im s|/|s| = 1.1e-8.
constexpr double kNearlyReal = 1e-5;

// y ↦ (G + σC)⁻¹·C·y for Spectra.
class ShiftInvertOperator {
 public:
  using Scalar = double;
  ShiftInvertOperator(const Eigen::SparseLU<Eigen::SparseMatrix<double>>& lu,
                      const Eigen::SparseMatrix<double>& c)
      : lu_(lu), c_(c) {}
  Eigen::Index rows() const { return c_.rows(); }
  Eigen::Index cols() const { return c_.cols(); }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, c_.cols());
    Eigen::Map<Eigen::VectorXd> y(y_out, c_.rows());
    y = lu_.solve(c_ * x);
  }

 private:
  const Eigen::SparseLU<Eigen::SparseMatrix<double>>& lu_;
  const Eigen::SparseMatrix<double>& c_;
};

}  // namespace

ModalResult run_modes(const System& system, const Eigen::VectorXd& operating_point,
                      const ModalOptions& options) {
  Timed<ModalResult> timed;
  ModalResult& result = timed.result;
  const int n = system.size();
  result.unknowns = n;
  auto finish = [&](Status status) { return timed.finish(std::move(status)); };
  if (sparse_one_norm(system.C) == 0.0)
    return finish(Status::failure("the network stores no energy: no poles"));
  // Everything below works on the equilibrated pencil (Ĝ, Ĉ) with poles ŝ = s/ω₀, so that
  // thresholds relative to the largest entry or eigenvalue do not depend on the units
  // (equilibration.hpp); poles and vectors are mapped back at the end.
  const Eigen::SparseMatrix<double> unscaled_g = linearised_g(system, operating_point);
  const DiagonalScaling scaling = equilibrate_pencil(unscaled_g, system.C);
  const double omega0 = scaling.frequency;
  const Eigen::SparseMatrix<double> g_matrix = scaled(unscaled_g, scaling);
  const Eigen::SparseMatrix<double> c_matrix = scaled(system.C, scaling, omega0);
  const double g_norm = sparse_one_norm(g_matrix), c_norm = sparse_one_norm(c_matrix);

  // Shift: σ = 0 unless G is singular there (a free body has a pole at 0).
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  const double scale = g_norm / c_norm;
  bool factorised = false;
  for (double sigma : {0.0, -1e-3 * scale, -1e-6 * scale, -1.0}) {
    Eigen::SparseMatrix<double> shifted = g_matrix + sigma * c_matrix;
    shifted.makeCompressed();
    lu.analyzePattern(shifted);
    lu.factorize(shifted);
    if (lu.info() == Eigen::Success) {
      result.shift = sigma * omega0;
      factorised = true;
      break;
    }
  }
  if (!factorised) return finish(Status::failure("the pencil (G, C) is singular for every shift"));

  std::vector<std::complex<double>> mus;
  std::vector<Eigen::VectorXcd> vectors;
  const bool dense = n <= options.dense_limit || options.count >= n - 2;
  if (dense) {
    result.method = "dense";
    const Eigen::MatrixXd identity_c = Eigen::MatrixXd(c_matrix);
    const Eigen::MatrixXd a = lu.solve(identity_c);
    if (!a.allFinite()) return finish(Status::failure("shift-invert operator is not finite"));
    Eigen::EigenSolver<Eigen::MatrixXd> solver(a, options.keep_vectors);
    if (solver.info() != Eigen::Success)
      return finish(Status::failure("dense eigen-decomposition did not converge"));
    const Eigen::VectorXcd values = solver.eigenvalues();
    double largest = 0.0;
    for (Eigen::Index k = 0; k < values.size(); ++k)
      largest = std::max(largest, std::abs(values[k]));
    // Infinite poles map to μ = 0, perturbed by rounding (√ε for the index-2 blocks of
    // massless nodes); finite poles are kept when |μ| clears that level.
    const double threshold = 1e-7 * largest;
    for (Eigen::Index k = 0; k < values.size(); ++k)
      if (std::abs(values[k]) > threshold) {
        mus.push_back(values[k]);
        vectors.push_back(options.keep_vectors ? Eigen::VectorXcd(solver.eigenvectors().col(k))
                                               : Eigen::VectorXcd());
      }
    result.complete = true;
  } else {
    result.method = "arnoldi";
    // The poles nearest σ = 0 come first (|μ| = 1/|s − σ|). Ask for exactly the conjugate pairs
    // of the wanted modes: a request that ends inside a cluster (the overdamped relaxation poles
    // of Kelvin–Voigt damping near −1/τ, more of them the finer the beam) does not converge and
    // costs the whole restart budget (N = 4000: 2.1 s with 60 restarts against 0.1 s). Real
    // poles (RC loops, relaxations) that take converged places are counted, and the request
    // grows by as many. Well separated poles converge in 1–3 restarts; the budget is 10.
    const int wanted_modes = options.count > 0 ? options.count : 10;
    int nev = std::min(2 * std::min(wanted_modes, 3), n - 3);  // grows by doubling
    ShiftInvertOperator op(lu, c_matrix);
    for (int attempt = 0;; ++attempt) {
      const int ncv = std::min(n - 1, std::max(2 * nev + 1, 20));
      Spectra::GenEigsSolver<ShiftInvertOperator> eigs(op, nev, ncv);
      eigs.init();
      // Converged pairs are exact eigenpairs (their residuals are checked below), so they are
      // kept when the request does not converge as a whole, and the shortfall is reported.
      const Eigen::Index converged = eigs.compute(Spectra::SortRule::LargestMagn, 10, 1e-12);
      result.iterations += eigs.num_iterations();
      if (converged == 0)
        return finish(Status::failure("Arnoldi iteration converged to no pole; try --count 5"));
      const Eigen::VectorXcd values = eigs.eigenvalues();
      int oscillatory = 0, real = 0;
      for (Eigen::Index k = 0; k < values.size(); ++k)
        (std::abs(values[k].imag()) > kNearlyReal * std::abs(values[k]) ? oscillatory : real) += 1;
      const int modes_found = oscillatory / 2;
      // Growing the request helps only when real poles took converged places; a request that
      // did not converge has reached a cluster, and a larger one would not converge either.
      const bool grow =
          converged == nev && modes_found < wanted_modes && attempt < 2 && nev < n - 3;
      if (!grow) {
        result.note = converged < nev ? std::to_string(converged) + " of the " +
                                            std::to_string(nev) + " poles requested converged"
                                      : "";
        const Eigen::MatrixXcd eigenvectors = eigs.eigenvectors();
        for (Eigen::Index k = 0; k < values.size(); ++k) {
          mus.push_back(values[k]);
          vectors.push_back(eigenvectors.col(k));
        }
        break;
      }
      nev = std::min(n - 3, std::max(2 * nev, real + 2 * wanted_modes));
    }
  }

  const Eigen::SparseMatrix<std::complex<double>> gc = g_matrix.cast<std::complex<double>>();
  const Eigen::SparseMatrix<std::complex<double>> cc = c_matrix.cast<std::complex<double>>();
  for (size_t k = 0; k < mus.size(); ++k) {
    const std::complex<double> scaled_pole = result.shift / omega0 - 1.0 / mus[k];
    const std::complex<double> pole = omega0 * scaled_pole;
    if (pole.imag() < -kNearlyReal * std::abs(pole)) continue;  // one of each conjugate pair
    const bool oscillatory = std::abs(pole.imag()) > kNearlyReal * std::abs(pole);
    Mode mode;
    mode.pole = std::complex<double>(pole.real(), oscillatory ? std::abs(pole.imag()) : 0.0);
    mode.natural_frequency_hz = std::abs(mode.pole) / two_pi;
    mode.frequency_hz = std::abs(mode.pole.imag()) / two_pi;
    mode.damping_ratio = std::abs(pole) > 0.0 ? -mode.pole.real() / std::abs(mode.pole) : 0.0;
    if (vectors[k].size() == n) {
      Eigen::VectorXcd x = vectors[k];  // of the equilibrated pencil
      if (pole.imag() < 0.0) x = x.conjugate();
      const std::complex<double> scaled_mode_pole = mode.pole / omega0;
      const double norm = x.norm();
      if (norm > 0.0) {
        mode.relative_residual = (gc * x + scaled_mode_pole * (cc * x)).norm() /
                                 ((g_norm + std::abs(scaled_mode_pole) * c_norm) * norm);
      }
      if (options.keep_vectors) {
        const Eigen::VectorXcd physical =
            scaling.column.cast<std::complex<double>>().cwiseProduct(x);
        mode.vector = physical / physical.norm();
      }
    }
    (oscillatory ? result.modes : result.real_poles).push_back(std::move(mode));
  }
  std::sort(result.modes.begin(), result.modes.end(),
            [](const Mode& a, const Mode& b) { return a.frequency_hz < b.frequency_hz; });
  std::sort(result.real_poles.begin(), result.real_poles.end(),
            [](const Mode& a, const Mode& b) { return std::abs(a.pole) < std::abs(b.pole); });
  return finish(Status::success());
}

}  // namespace emnet
