// JSON of a transient (time-domain) run, as the program's `tran --json` prints it: the run's
// description (scene, automatic choices, method, start state, switching frequency [Hz],
// periods, relative tolerance), the output times [s], each output's name, description, unit
// and values, IDA's statistics, the cost [s] and the validity.
//
// Every value written is finite: the transient analyses fail (Status) on a non-finite output.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "emnet/analysis/transient.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/network/output.hpp"
#include "emnet/report/json.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

/// What the JSON of a transient says besides the TransientResult and its outputs.
struct TransientRunDescription {
  std::string scene;                               ///< the scene's name
  std::vector<AutomaticChoice> automatic_choices;  ///< what each "auto" key became
  std::string start_state;                         ///< in words
  double switching_frequency_hz = 0.0;             ///< [Hz]
  double periods = 0.0;                            ///< number of switching periods integrated
  double relative_tolerance = 0.0;                 ///< IDA's rtol (written for both methods)
  Validity validity;                               ///< the run's validity, written as "validity"
  double total_seconds = 0.0;                      ///< the whole command, from its start [s]
  std::optional<DeformedShape> shape;  ///< the last period's shape, written as "shape" if set
};

/// Keys in this order: scene, automatic_choices, method, start_state, switching_frequency_hz,
/// periods, rtol, times_s, outputs [{name, description, unit, values}] (one per probe, values
/// per output time), statistics (steps, residual_evaluations, jacobian_evaluations,
/// newton_iterations, error_test_failures, convergence_failures, restarts), cost
/// (integration_seconds, total_seconds), shape (when asked: emnet/report/json.hpp), validity.
Json to_json(const TransientResult& result, const std::vector<Probe>& probes,
             const TransientRunDescription& run);

}  // namespace emnet
