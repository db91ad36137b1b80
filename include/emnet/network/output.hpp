// An output of a network: a linear functional of its unknowns y, or the time integral of one,
// plus (for a force that is the square of a voltage) squares of linear functionals.
//
// Analyses evaluate outputs (static value, AC phasor, time course, mode shape) without knowing
// what built them; the model layer makes them from a scene's probes (deflection at x, DEA
// voltage, a support's reaction, a spring's force, …), tests make them directly.
//
// Terms may name any unknown of y: a node's across value or a branch's through quantity (an
// inductor's current is a spring's force, a lever's current the force through a beam segment).
//
// Value:  p(y) = Σ c·y[index]  (time-integrated `integrations` times)
//              + Σ_squares factor·(Σ d·y[index])²                     (squares: integrations 0)
// The squares make p nonlinear (a DEA's force k_F·u²): static and transient analyses evaluate
// them as they are; whatever linearises (AC, mode shapes) uses linearised_probe about its
// operating point y₀: p ≈ p(y₀) + Σ c·δy + Σ 2·factor·(Σ d·y₀)·(Σ d·δy), i.e. the small-signal
// part 2·factor·u₀·U of factor·u². An analysis that cannot linearise (no operating point)
// refuses a probe with squares.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <string>
#include <utility>
#include <vector>

#include "emnet/core/quantity.hpp"

namespace emnet {

/// A linear functional Σ coefficient·y[index] over the unknowns.
using LinearTerms = std::vector<std::pair<int, double>>;

/// factor·(Σ c·y[index])², e.g. k_F·u² with terms {electrode node: 1}.
struct SquaredTerm {
  double factor = 0.0;
  LinearTerms terms;  ///< the functional squared
};

/// An output: a linear functional of y (plus squares, see above). For `integrations` = 1 the
/// linear part is the time integral of the functional (a deflection from velocities:
/// W = V/(jω) in AC).
struct Probe {
  std::string name;
  ProbeQuantity quantity = ProbeQuantity::deflection;
  std::string unit;                  ///< the unit of its value
  LinearTerms terms;                 ///< the linear part
  int integrations = 0;              ///< time integrations of the linear part
  std::string description;           ///< "deflection at x = 70.0 mm"
  std::vector<SquaredTerm> squares;  ///< empty for a linear probe
};

/// Whether `probe` has no squares.
inline bool is_linear(const Probe& probe) {
  return probe.squares.empty();
}
/// Σ c·y over `terms` (a row of y; unknowns beyond y's size are an error of the caller).
double linear_value(const LinearTerms& terms, const Eigen::VectorXd& y);
/// Σ factor·(Σ d·y)² over the probe's squares, at y (across values, not integrated).
double squares_value(const Probe& probe, const Eigen::VectorXd& y);
/// The probe's small-signal part about `operating_point` (see above): its squares become
/// linear terms 2·factor·u₀·d, the description says so with u₀. A linear probe is returned as
/// it is.
Probe linearised_probe(const Probe& probe, const Eigen::VectorXd& operating_point);

/// The phasor of a linear probe from the phasors `y` of the system's unknowns.
/// @param omega  angular frequency [rad/s], for the probe's integrations
/// @throws std::invalid_argument when `probe` has squares (take linearised_probe first)
std::complex<double> probe_phasor(const Probe& probe, const Eigen::VectorXcd& y, double omega);

}  // namespace emnet
