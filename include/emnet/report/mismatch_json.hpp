// JSON of the mismatch study (emnet/studies/mismatch.hpp), as `emnet mismatch --json` prints it
// and emnet.mismatch returns it. Keys in this order: automatic_choices, output, frequency_hz
// [Hz], nominal {left_m, right_m} (the periodic minimum and maximum without mismatch [m]), cases
// [{key, change, left_m, right_m, asymmetry, asymmetry_per_unit_change}] (each parameter at −X
// then +X), total_seconds [s], validity, notes when there are any.
#pragma once

#include <vector>

#include "emnet/report/json.hpp"
#include "emnet/scene/scene.hpp"
#include "emnet/studies/mismatch.hpp"

namespace emnet {

/// The JSON of a successful mismatch study.
/// @param result             the MismatchResult of `run_mismatch` (status ok)
/// @param automatic_choices  the scene's: what each "auto" key became
/// @param total_seconds      the whole run, from its start [s]
Json to_json(const MismatchResult& result, const std::vector<AutomaticChoice>& automatic_choices,
             double total_seconds);

}  // namespace emnet
