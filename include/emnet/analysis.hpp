// Analyses over one assembled System (DESIGN §5). Each takes the System (and, where it
// linearises, an operating point) and returns a Result with a Status; numerical failure is
// a status, never an exception.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#include <string>
#include <vector>

#include "emnet/errors.hpp"
#include "emnet/model.hpp"
#include "emnet/network.hpp"
#include "emnet/progress.hpp"

namespace emnet {

// A linear solve whose relative residual ‖A·x − b‖/‖b‖ is above this, or not finite, has not
// solved its system: the analyses return a failed Status then (static, AC, the exact periodic
// state), never a result. Rounding of the equilibrated systems is 1e-16..1e-13; 1e-8 leaves
// room for ill-conditioned but meaningful networks and none for a garbage answer.
inline constexpr double kResidualLimit = 1e-8;
// The failed Status for `residual` of `what` above kResidualLimit or not finite; success
// otherwise.
Status check_residual(double residual, const std::string& what);

// ---- static / operating point -----------------------------------------------------------
//
// A mechanical network at rest has zero velocities; what is wanted is displacements. Write
// every mechanical across unknown as s·(displacement) and expand (G + s·C)·y = b about s = 0:
// rows whose s⁰ part vanishes (compliance and lever rows, which relate velocities only) are
// divided by s. What is left at s = 0 is the static system K·z + g(z) = b(0) in
//   z = [displacements (m, rad) on mechanical nodes; voltages on electrical nodes;
//        through quantities (forces, torques, currents) on branches],
// solved by Newton with a sparse LU. Built from G and C alone: no element is special-cased.
struct StaticOptions {
  double tolerance = 1e-12;  // Newton: relative step size
  int max_iterations = 50;
  Progress* progress = nullptr;  // a report per Newton iteration; cancelled: Status "cancelled"
};

struct StaticResult {
  Status status;
  Eigen::VectorXd state;            // z, see above
  Eigen::VectorXd operating_point;  // y at rest: velocities 0, everything else from z
  double relative_residual = 0.0;   // ‖K·z + g − b‖ / ‖b‖ (above kResidualLimit: failed)
  int newton_iterations = 0;
  double seconds = 0.0;
};

StaticResult solve_static(const System& system, const StaticOptions& options = {});
// Value of a probe at rest (deflections and rotations; velocities are zero).
double static_probe_value(const System& system, const StaticResult& result, const Probe& probe);

// Which unknowns are mechanical across values (velocities), and which rows have no s⁰ part
// once those are written as s·(displacement) (compliance and lever rows): `divided`.
struct RowClassification {
  std::vector<bool> mechanical;
  std::vector<bool> divided;
};
RowClassification classify_rows(const System& system, const Eigen::SparseMatrix<double>& g_matrix);

// The static operator of the linearised system, for reuse (AC at f = 0).
class StaticOperator {
 public:
  StaticOperator(const System& system, const Eigen::SparseMatrix<double>& linearised_g);
  // Solves matrix()·z = rhs; false (with a reason) when the operator is singular.
  bool solve(const Eigen::VectorXcd& rhs, Eigen::VectorXcd& z, std::string& why) const;
  // A right-hand side on a row divided by s is a constant velocity: no static state.
  bool excites_divided_rows(const Eigen::VectorXcd& rhs) const;
  const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }
  const std::vector<bool>& divided_rows() const { return divided_; }
  const std::vector<bool>& mechanical() const { return mechanical_; }
  bool factorised() const { return factorised_; }

 private:
  Eigen::SparseMatrix<double> matrix_;
  std::vector<bool> divided_;
  std::vector<bool> mechanical_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
  bool factorised_ = false;
};

// G + ∂g/∂y at y.
Eigen::SparseMatrix<double> linearised_g(const System& system, const Eigen::VectorXd& y);

// ---- AC ----------------------------------------------------------------------------------
//
// Small-signal response about the operating point: (G + J_g + jω·C)·Y = B_ac with B_ac the
// sources' AC phasors plus direct excitations (System::b_ac). At f = 0 a displacement probe
// is the static response to B_ac (the limit of V/(jω)).
std::vector<double> frequency_grid(double from, double to, int points, bool log);

struct AcOptions {
  Progress* progress = nullptr;  // one report per frequency; cancelled: Status "cancelled"
};

struct AcResult {
  Status status;
  std::vector<double> frequencies;                        // Hz
  std::vector<std::vector<std::complex<double>>> values;  // [probe][frequency]
  double max_relative_residual = 0.0;  // worst ‖A·Y − B‖/‖B‖ over the sweep
  int pivot_searches = 0;  // factorisations with a pivot search (the first, and where reused
                           // pivots gave 4× the residual of the last search)
  double seconds = 0.0;
};

// A relative residual above kResidualLimit at any frequency is a failed Status naming it.
AcResult run_ac(const System& system, const Eigen::VectorXd& operating_point,
                const std::vector<double>& frequencies, const std::vector<Probe>& probes,
                const AcOptions& options = {});
std::complex<double> probe_phasor(const Probe& probe, const Eigen::VectorXcd& y, double omega);

// ---- modal -------------------------------------------------------------------------------
//
// Poles s of the pencil: det(G + J_g + s·C) = 0. Shift-invert: with A = (G + J_g + σC)⁻¹·C,
// A·x = μ·x gives s = σ − 1/μ; the pencil's infinite eigenvalues (algebraic unknowns) map to
// μ = 0 and drop out. Small systems: dense eigen-decomposition of A, every finite pole.
// Large systems: implicitly restarted Arnoldi (Spectra) for the `count` poles nearest σ,
// one sparse LU.
struct ModalOptions {
  int count = 0;          // large systems: oscillatory poles wanted (0: the 10 lowest)
  int dense_limit = 600;  // unknowns up to which the dense method is used
  bool keep_vectors = true;
};

struct Mode {
  std::complex<double> pole;          // s [1/s], Im ≥ 0
  double frequency_hz = 0.0;          // |Im s| / 2π (damped)
  double natural_frequency_hz = 0.0;  // |s| / 2π
  double damping_ratio = 0.0;         // −Re s / |s|
  // ‖(Ĝ + ŝĈ)·x̂‖ / ((‖Ĝ‖ + |ŝ|·‖Ĉ‖)·‖x̂‖) on the equilibrated pencil (unit-free).
  double relative_residual = 0.0;
  Eigen::VectorXcd vector;  // y-space eigenvector (across values are velocities)
};

struct ModalResult {
  Status status;
  std::vector<Mode> modes;       // oscillatory poles (Im s > 0), sorted by frequency
  std::vector<Mode> real_poles;  // non-oscillatory poles (RC, overdamped), sorted by |s|
  std::string method;            // "dense" or "arnoldi"
  int unknowns = 0;
  double shift = 0.0;
  double seconds = 0.0;
  bool complete = false;  // true when every finite pole was computed
  std::string note;       // e.g. how many of the requested poles converged
  long iterations = 0;    // Arnoldi restarts over all attempts (0 for dense)
};

ModalResult run_modes(const System& system, const Eigen::VectorXd& operating_point,
                      const ModalOptions& options = {});

}  // namespace emnet
