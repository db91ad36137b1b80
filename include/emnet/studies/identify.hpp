// Identification of the beam's bending stiffness from a measured resonance, and optionally of
// its loss factor from a measured periodic peak deflection.
//
// 1. Stiffness: the fixed point of EI ← EI·(f_target/f)², from the scene's EI, with f the damped
//    frequency of mode `mode_number` (run_modes about the operating point). Undamped frequencies
//    scale as √EI exactly when EI is the only stiffness; damping, the DEAs' stiffness and the
//    electrical poles make the update a fixed-point iteration, which converges in a few steps.
//    Converged when |f − f_target| ≤ frequency_tolerance·f_target.
// 2. Peak (with `peak`): the periodic peak max(|min|, |max|) of the output under the scene's
//    square wave switched at f_target (at peak.voltage when given; periodic_peak.hpp: DEAs as
//    ideal voltage-driven forces) falls monotonically with the loss factor η, so η is bisected in
//    log η over [loss_factor_low, loss_factor_high] until high/low ≤ 1 + bisection_ratio; then
//    the stiffness is fitted again at that η (the damping moves the damped frequency a little),
//    and the two alternate until both change by at most round_tolerance (relative).
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
  std::optional<PeakTarget> peak;
  double frequency_tolerance = 1e-10;  // relative, of the stiffness fit
  int stiffness_iterations = 30;       // fixed-point iterations of one stiffness fit, at most
  double loss_factor_low = 1e-5, loss_factor_high = 2.0;  // the bisection's bracket of η
  double bisection_ratio = 1e-12;                         // stop when high/low ≤ 1 + this
  int bisection_steps = 80;                               // at most, per round
  double round_tolerance = 1e-9;  // relative change of η and EI that ends the rounds
  int peak_rounds = 10;           // at most
  Progress* progress = nullptr;   // one report per trial; cancelled: Status "cancelled"
};

struct FittedValue {
  std::string key;   // the parameter table's key: "beam.bending_stiffness"
  std::string unit;  // SI unit of the value ("" for dimensionless)
  double value = 0.0;
};

struct IdentifyResult {
  Status status;
  // beam.bending_stiffness, then with a peak target damping.loss_factor.
  std::vector<FittedValue> fitted;
  double bending_stiffness = 0.0;   // [N·m²]
  double loss_factor = 0.0;         // [-]; with a peak target
  double achieved_hz = 0.0;         // mode mode_number at the fitted values [Hz]
  double frequency_residual = 0.0;  // (achieved_hz − target_hz) / target_hz
  int stiffness_iterations = 0;     // of the last stiffness fit
  double achieved_peak = 0.0;       // the periodic peak at the fitted values; with a peak target
  double peak_residual = 0.0;       // (achieved_peak − peak.value) / peak.value
  int peak_rounds = 0;              // rounds of loss factor and stiffness
  long modal_solves = 0, periodic_solves = 0;  // the trials
  // The validity of the achieved peak at the measurement's drive levels; with a peak target.
  std::optional<Validity> validity;
  std::vector<std::string> notes;
  double seconds = 0.0;
};

// Throws InputError for a bad target (where "--resonance", "--mode", "--peak"), a fitted key the
// scene takes as given (key "provenance.<key>"), or a peak target on a scene without
// damping.loss_factor. A target out of reach (no loss factor in the bracket gives the peak, a
// stiffness fit that does not converge, no such mode) and any numerical failure are the Status.
IdentifyResult identify(const Scene& scene, const IdentifyOptions& options);

}  // namespace emnet
