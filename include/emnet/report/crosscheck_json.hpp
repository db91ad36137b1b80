// JSON of a cross-check against ngspice (emnet/verification/crosscheck.hpp), as `emnet
// crosscheck --json` prints it and emnet.crosscheck returns it. Keys in this order: scene,
// automatic_choices, backend, status ("ok" or "failure"), failure (its message, when failed),
// pass (every difference within its tolerance), rows [{analysis, quantity, largest_difference
// (relative; null when not finite), where, tolerance, pass, basis}], timings [{analysis,
// ngspice_seconds, ngspice_total_seconds, emnet_seconds, emnet_what}], notes, total_seconds [s].
#pragma once

#include "emnet/model/model.hpp"
#include "emnet/report/json.hpp"
#include "emnet/verification/crosscheck.hpp"

namespace emnet {

/// The JSON of a cross-check, failed or not.
/// @param report         the CrosscheckReport of `run_crosscheck`
/// @param model          the model it checked (its scene's name and automatic choices)
/// @param total_seconds  the whole run, from its start [s]
Json to_json(const CrosscheckReport& report, const Model& model, double total_seconds);

}  // namespace emnet
