// Identification of one scene parameter from a measured resonance, and optionally of the loss
// factor from a measured periodic peak deflection.
//
// 1. Resonance: the parameter `parameter` (any numeric scene key the scene uses, as --set names
//    it: "beam.bending_stiffness" by default, "spring[clamp].stiffness", "mass[0].mass",
//    "section[1].bending_stiffness") is moved until the damped frequency f of mode `mode_number`
//    (run_modes about the operating point) is at the target. Converged when
//    |f − f_target| ≤ frequency_tolerance·f_target.
//    - beam.bending_stiffness: the fixed point EI ← EI·(f_target/f)², from the scene's EI.
//      Undamped frequencies scale as √EI exactly when EI is the only stiffness; damping, the
//      DEAs' stiffness and the electrical poles make the update a fixed-point iteration, which
//      converges in a few steps.
//    - any other key: a root of g(u) = f(e^u) − f_target in u = log(value), from the scene's
//      value (> 0). A bracket is sought by stepping u by ln 2, ln 4, ln 16, ln 256, then ln 1e4
//      per step in the direction that moves f toward the target (stiffnesses raise f, masses and
//      lengths lower it), at most bracket_span decades from the start; then Brent's method
//      (inverse quadratic interpolation and secant steps, safeguarded by bisection: R. P. Brent,
//      Algorithms for Minimization without Derivatives, 1973, ch. 4) on the bracket. A frequency
//      bounded in the parameter (a clamp's stiffness k: the pinned beam's at k → 0, the clamped
//      one's at k → ∞) levels off while the bracket is sought: when a step changes f by at most
//      saturation_tolerance (relative), or the changes shrink at least 10-fold per step and
//      the geometric series of the steps to come (change/(ratio − 1)) covers less than a tenth
//      of the gap to the target, the target is out of reach and the Status says which limit
//      stops it, with the frequency there (followed until a step changes it by at most
//      limit_tolerance, relative).
// 2. Peak (with `peak`): the periodic peak max(|min|, |max|) of the output under the scene's
//    square wave switched at f_target (at peak.voltage when given; periodic_peak.hpp: DEAs as
//    ideal voltage-driven forces) falls monotonically with the loss factor η, so η is bisected in
//    log η over [loss_factor_low, loss_factor_high] until high/low ≤ 1 + bisection_ratio; then
//    the parameter is fitted to the resonance again at that η (the damping moves the damped
//    frequency a little), and the two alternate until both change by at most round_tolerance
//    (relative).
//
// With beam.kinematics = "large" the mode is the one about the deflected static state, and a
// peak's periodic state is shot (periodic_peak.hpp, about 1e-7 of the peak): the bisection then
// stops at bisection_ratio ≥ 1e-6 and the rounds at round_tolerance ≥ 1e-5 (a note says so).
// "auto" kinematics are chosen once, on the given scene, for every trial.
//
// Every trial sets its values on a copy of the given scene (set_parameter,
// emnet/scene/parameters.hpp), so beam.segments = "auto" chosen before the call stays one
// network for the whole fit.
//
// Only parameters the scene marks as identified or assumed are fitted: a [provenance] entry
// starting "paper" or "data sheet" makes the key a given, and identify refuses to fit it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

// The measured periodic peak |output| the loss factor is fitted to.
struct PeakTarget {
  std::string output;    // an output of transient_output_list (dx4) or a probe (P4, tip)
  double value = 0.0;    // [output's unit, m for a deflection], > 0
  double voltage = 0.0;  // drive.voltage of the measurement [V]; 0: the scene's
};

struct IdentifyOptions {
  double target_hz = 0.0;  // the measured resonance [Hz], > 0
  int mode_number = 1;     // which oscillatory mode sits there, >= 1
  // The key fitted to the resonance, any form --set takes ("spring.clamp.stiffness").
  std::string parameter = "beam.bending_stiffness";
  std::optional<PeakTarget> peak;
  double frequency_tolerance = 1e-10;  // relative, of the resonance fit
  int stiffness_iterations = 30;       // fixed-point iterations of one EI fit, at most
  int root_iterations = 100;           // Brent steps of one fit of another key, at most
  double bracket_span = 12.0;          // decades from the start the bracket may reach, each way
  double saturation_tolerance = 1e-9;  // a relative change of f that means "levelled off"
  double limit_tolerance = 1e-6;       // out of reach: the last step's change, relative, at most
  double loss_factor_low = 1e-5, loss_factor_high = 2.0;  // the bisection's bracket of η
  double bisection_ratio = 1e-12;                         // stop when high/low ≤ 1 + this
  int bisection_steps = 80;                               // at most, per round
  double round_tolerance = 1e-9;  // relative change of η and EI that ends the rounds
  int peak_rounds = 10;           // at most
  Progress* progress = nullptr;   // one report per trial; cancelled: Status "cancelled"

  /// The checks of the options alone, as identify makes them first.
  /// @throws OptionError naming "target_hz" (not > 0), "mode_number" (< 1) or "peak" (a peak
  /// or voltage that is not positive)
  void validate() const;
};

struct FittedValue {
  std::string key;   // canonical: "beam.bending_stiffness", "spring[clamp].stiffness"
  std::string unit;  // SI unit of the value ("" for dimensionless; "N*m/rad" for a rotational k)
  double value = 0.0;
};

struct IdentifyResult {
  Status status;
  // The resonance's parameter (options.parameter, canonical key and unit), then with a peak
  // target damping.loss_factor. Empty when the fit failed.
  std::vector<FittedValue> fitted;
  FittedValue parameter;            // the resonance's parameter: fitted[0] once fitted
  double bending_stiffness = 0.0;   // [N·m²]; when the parameter is beam.bending_stiffness
  double loss_factor = 0.0;         // [-]; with a peak target
  double achieved_hz = 0.0;         // mode mode_number at the fitted values [Hz]
  double frequency_residual = 0.0;  // (achieved_hz − target_hz) / target_hz
  int stiffness_iterations = 0;     // modal solves of the last resonance fit (any parameter)
  double achieved_peak = 0.0;       // the periodic peak at the fitted values; with a peak target
  double peak_residual = 0.0;       // (achieved_peak − peak.value) / peak.value
  int peak_rounds = 0;              // rounds of loss factor and stiffness
  long modal_solves = 0, periodic_solves = 0;  // the trials
  // The validity of the achieved peak at the measurement's drive levels; with a peak target.
  std::optional<Validity> validity;
  std::vector<std::string> notes;
  double seconds = 0.0;
};

// Throws OptionError for a bad target (IdentifyOptions::validate), a bad parameter (the field
// "parameter" and the key: unknown, not a number, an integer, not used by the scene, not set,
// not > 0), InputError for a fitted key the scene takes as given (key "provenance.<key>"), or a
// peak target on a scene without damping.loss_factor. A target out of reach (no value of the
// parameter or no loss factor in the bracket gives it, a fit that does not converge, no such mode),
// a trial value the scene refuses and any numerical failure are the Status.
IdentifyResult identify(const Scene& scene, const IdentifyOptions& options);

}  // namespace emnet
