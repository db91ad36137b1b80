// JSON of a switching sweep (emnet/studies/switching_sweep.hpp), as `emnet sweep-switching
// --json` prints it and emnet.sweep_switching returns it. Keys in this order: scene,
// automatic_choices, method (exact, shooting or reduced), notes, frequencies_hz [Hz], outputs
// [{name, description, unit, left, right}] (the periodic minimum and maximum per frequency, in
// the output's unit), sweep_peak_hz [Hz] (the largest peak-to-peak of the last output; 0 for no
// frequency), accuracy {worst_periodicity_residual}, cost {solve_seconds, total_seconds};
// reduction when the sweep was reduced (the reduced model's fields, emnet/report/json.hpp, then
// check_reference ("full" or "wider reduction"), check_frequencies_hz, edge_estimates, errors,
// measured_error, cost {reduce_seconds, reduced_seconds_per_frequency, reference_build_seconds,
// reference_seconds_per_frequency, reduced_sweep_seconds, and against the full sweep
// full_sweep_seconds_estimated}); shape when asked (SwitchingSweepOptions::shape_instants; its
// keys: emnet/report/json.hpp); validity.
#pragma once

#include <string>
#include <vector>

#include "emnet/model/model.hpp"
#include "emnet/report/json.hpp"
#include "emnet/studies/switching_sweep.hpp"

namespace emnet {

/// The JSON of a successful switching sweep.
/// @param result         the SwitchingSweepResult of `run_switching_sweep` (status ok)
/// @param model          the model it swept (its scene's name and automatic choices)
/// @param notes          the run's notes: the swept model's (SweptModel::notes), then the
///                       result's
/// @param total_seconds  the whole run, from its start [s]
Json to_json(const SwitchingSweepResult& result, const Model& model,
             const std::vector<std::string>& notes, double total_seconds);

}  // namespace emnet
