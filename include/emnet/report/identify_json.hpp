// JSON of an identification (emnet/studies/identify.hpp), as `emnet identify --json` prints it
// and emnet.identify returns it. Keys in this order: automatic_choices, parameter (its
// canonical key), value [SI], unit, mode, target_hz [Hz], achieved_hz [Hz], iterations (modal
// solves of the last resonance fit), command, total_seconds [s]; with a peak target also
// loss_factor [-], peak_probe, target_peak_m, achieved_peak_m, peak_rounds and validity; notes
// when there are any.
#pragma once

#include <string>
#include <vector>

#include "emnet/report/json.hpp"
#include "emnet/scene/scene.hpp"
#include "emnet/studies/identify.hpp"

namespace emnet {

// What the JSON of an identification says besides the IdentifyResult and its options.
struct IdentifyReportContext {
  std::vector<AutomaticChoice> automatic_choices;  // the scene's: what each "auto" key became
  // What re-identifies the values in the front-end that ran it, for the scene's [provenance].
  std::string command;
  double total_seconds = 0.0;  // the whole run, from its start [s]
};

/// The JSON of a successful identification.
/// @param result   the IdentifyResult of `identify` (status ok)
/// @param options  the options it ran with (mode, target frequency [Hz], peak target)
/// @param context  the scene's automatic choices, the command and the run's seconds
Json to_json(const IdentifyResult& result, const IdentifyOptions& options,
             const IdentifyReportContext& context);

}  // namespace emnet
