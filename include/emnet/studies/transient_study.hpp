// The transient study: a scene's time response to its drive over a number of switching periods,
// with what `emnet tran` reports beside it (the outputs, the validity of their peaks).
//
//   - The outputs: the scene's recorded outputs (transient_output_list, emnet/model/outputs.hpp:
//     the probes with P_k replaced by dx_k = P_k − P1 when P1 exists, each DEA's capacitor
//     voltage and current when it has an electrical model), or the ones given.
//   - The run: `periods` periods of the drive's frequency (or `switching_hz`), output times
//     equally spaced at `points_per_period` per period from t = 0, with IDA or the exact method
//     (emnet/analysis/transient.hpp), from rest or from the static state of the first half-period.
//   - Validity: each deflection output's largest |value| [m] against the deflection limit, the
//     drive's peak voltages against breakdown (emnet/model/validity.hpp).
// Options are checked first (TransientStudyOptions::validate), each OptionError naming its field
// ("periods"), which each front-end words as its own option.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/model/deformed_shape.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/scene/scene.hpp"
#include "emnet/studies/resolve.hpp"

namespace emnet {

// Output times × (outputs + the time) stored at most (160 MB of doubles).
inline constexpr double kTransientMaximumStoredValues = 2e7;

enum class TransientMethod { ida, exact };

struct TransientStudyOptions {
  std::optional<double> switching_hz;  // the drive's frequency [Hz]; default drive.frequency
  double periods = 10.0;               // (0, 1e6]
  int points_per_period = 100;         // [2, 100000]
  TransientMethod method = TransientMethod::ida;
  double rtol = 1e-6;     // IDA: [1e-13, 1)
  double atol = 0.0;      // IDA: >= 0; 0: rtol times a scale per unknown
  double max_step = 0.0;  // IDA: >= 0; 0: no limit [s]
  StartState start = StartState::rest;
  // Output texts: a name of transient_output_list (dx4, u_A) or any probe parse_probe takes;
  // empty: transient_output_list.
  std::vector<std::string> outputs;
  /// How the scene's remaining "auto" keys are resolved; the study prepares large kinematics for
  /// dynamics itself (LargeKinematicsUse::dynamics, whatever large_kinematics says here).
  PrepareOptions prepare;
  // > 0: the beam's deformed shape (result.shape) at this many of the last period's output
  // times, evenly among them; from 2 to points_per_period. 0: none.
  int shape_instants = 0;
  Progress* progress = nullptr;  // one report per output time

  /// The checks of the options alone, as run_transient_study makes them first.
  /// @throws OptionError naming the field out of its range above ("periods", "rtol", ...)
  void validate() const;
};

struct TransientStudyResult {
  Status status;  // the analysis's failure, "tran: <why>"
  Model model;
  System system;
  std::vector<Probe> outputs;
  TransientResult result;
  Validity validity;
  double frequency_hz = 0.0;
  double end_time = 0.0;               // [s]
  std::string start_text;              // the start state in words
  std::optional<DeformedShape> shape;  // with options.shape_instants
  double seconds = 0.0;                // the whole study
};

// The outputs of `texts` (see TransientStudyOptions::outputs) for `model`.
std::vector<Probe> transient_outputs(const Model& model, const std::vector<std::string>& texts);

// Throws InputError for a bad option, a scene without a drive frequency, the exact method on a
// nonlinear network, or more than kTransientMaximumStoredValues values to store; numerical
// failure is the Status.
TransientStudyResult run_transient_study(Scene scene, const TransientStudyOptions& options);

}  // namespace emnet
