// JSON of the AC study, as `emnet ac --json` prints it (keys in this order): scene,
// automatic_choices, segments, input (the AC input's description), frequencies_hz, probes
// [{name, description, unit, magnitude [unit], phase_deg}], resonances_hz (in the band),
// accuracy {max_relative_residual, method ("direct" or "pole-residue"); pole-residue:
// check_points, check_deviation (of each output's peak), eigenvector_condition; direct: note,
// why the pole-residue form was not used, when it was tried}, cost {ac_seconds, total_seconds},
// reduction (with the modal reduction only: the reduced model's fields, clustered_poles,
// all_poles_below_cutoff_found, correction_order, error_estimate, measured_error,
// probe_errors {probe: error}, check_frequencies_hz, note, cost {reduce_seconds,
// evaluate_seconds, check_seconds}), validity. Phase = arg(value)·180/π [deg].
#pragma once

#include <string>
#include <vector>

#include "emnet/model/model.hpp"
#include "emnet/network/output.hpp"
#include "emnet/report/json.hpp"
#include "emnet/studies/ac_study.hpp"

namespace emnet {

/// `result` of a successful run_ac_study on `model` with `probes`; `input` is the AC input's
/// description (ac_input_description, report/describe.hpp), `total_seconds` the whole command [s].
Json to_json(const AcStudyResult& result, const Model& model, const std::vector<Probe>& probes,
             const std::string& input, double total_seconds);

}  // namespace emnet
