// JSON of a switching sweep (emnet/report/switching_sweep_json.hpp).
#include "emnet/report/switching_sweep_json.hpp"

namespace emnet {

namespace {

// "reduction": the reduced model and its check against the reference, with the costs.
Json reduction_check_json(const SwitchingSweepReductionCheck& check,
                          const SwitchingSweepResult& result) {
  const double count = static_cast<double>(result.frequencies.size());
  Json reduced = to_json(check.model, check.tolerance_met);
  reduced.update({{"check_reference", check.against_full ? "full" : "wider reduction"},
                  {"check_frequencies_hz", check.frequencies},
                  {"edge_estimates", check.edge_estimates},
                  {"errors", check.errors},
                  {"measured_error", check.measured_error},
                  {"extreme_errors", check.extreme_errors},
                  {"measured_extremes_error", check.measured_extremes_error},
                  {"cascade", check.cascade},
                  {"cost",
                   {{"reduce_seconds", check.build_seconds},
                    {"reduced_seconds_per_frequency", check.reduced_solve_seconds},
                    {"reference_build_seconds", check.full_build_seconds},
                    {"reference_seconds_per_frequency", check.full_solve_seconds},
                    {"reduced_sweep_seconds", check.build_seconds + result.solve_seconds}}}});
  if (check.against_full)
    reduced["cost"]["full_sweep_seconds_estimated"] =
        check.full_build_seconds + count * check.full_solve_seconds;
  return reduced;
}

}  // namespace

Json to_json(const SwitchingSweepResult& result, const Model& model,
             const std::vector<std::string>& notes, double total_seconds) {
  Json out;
  out["scene"] = model.scene.name;
  out["automatic_choices"] = to_json(model.automatic_choices);
  out["method"] = method_name(result.method);
  out["notes"] = notes;
  out["frequencies_hz"] = result.frequencies;
  out["outputs"] = Json::array();
  for (const auto& output : result.outputs)
    out["outputs"].push_back({{"name", output.probe.name},
                              {"description", output.probe.description},
                              {"unit", output.probe.unit},
                              {"left", output.left},
                              {"right", output.right}});
  out["sweep_peak_hz"] = result.frequencies.empty() ? 0.0 : result.frequencies[result.peak_index];
  if (result.first_mode_hz) out["first_mode_hz"] = *result.first_mode_hz;
  out["accuracy"] = {{"worst_periodicity_residual", result.worst_periodicity_residual}};
  out["cost"] = {{"solves", result.solves},
                 {"period_runs", result.period_runs},
                 {"unknowns", result.unknowns},
                 {"decomposition_seconds", result.decomposition_seconds},
                 {"solve_seconds", result.solve_seconds},
                 {"total_seconds", total_seconds}};
  if (result.reduction) out["reduction"] = reduction_check_json(*result.reduction, result);
  if (result.shape) out["shape"] = to_json(*result.shape);
  out["validity"] = to_json(result.validity);
  return out;
}

}  // namespace emnet
