// JSON of an identification (emnet/report/identify_json.hpp).
#include "emnet/report/identify_json.hpp"

namespace emnet {

Json to_json(const IdentifyResult& result, const IdentifyOptions& options,
             const IdentifyReportContext& context) {
  const FittedValue& fitted = result.parameter;
  Json out = {
      {"automatic_choices", to_json(context.automatic_choices)},
      {"parameter", fitted.key},
      {"value", fitted.value},
      {"unit", fitted.unit},
      {"mode", options.mode_number},
      {"target_hz", options.target_hz},
      {"achieved_hz", result.achieved_hz},
      {"iterations", result.stiffness_iterations},
      {"accuracy", {{"frequency_residual", result.frequency_residual}}},
      {"cost",
       {{"modal_solves", result.modal_solves}, {"periodic_solves", result.periodic_solves}}},
      {"command", context.command},
      {"total_seconds", context.total_seconds}};
  if (options.peak) {
    out["loss_factor"] = result.loss_factor;
    out["peak_probe"] = options.peak->output;
    out["target_peak_m"] = options.peak->value;
    out["achieved_peak_m"] = result.achieved_peak;
    out["peak_rounds"] = result.peak_rounds;
    if (result.validity) out["validity"] = to_json(*result.validity);
  }
  if (!result.notes.empty()) out["notes"] = result.notes;
  return out;
}

}  // namespace emnet
