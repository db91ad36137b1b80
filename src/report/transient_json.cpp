// JSON of a transient run (emnet/report/transient_json.hpp).
#include "emnet/report/transient_json.hpp"

namespace emnet {

Json to_json(const TransientResult& result, const std::vector<Probe>& probes,
             const TransientRunDescription& run) {
  Json out;
  out["scene"] = run.scene;
  out["automatic_choices"] = to_json(run.automatic_choices);
  out["method"] = result.method_text();
  out["start_state"] = run.start_state;
  out["switching_frequency_hz"] = run.switching_frequency_hz;
  out["periods"] = run.periods;
  out["rtol"] = run.relative_tolerance;
  out["times_s"] = result.times;
  out["outputs"] = Json::array();
  for (size_t k = 0; k < probes.size(); ++k)
    out["outputs"].push_back({{"name", probes[k].name},
                              {"description", probes[k].description},
                              {"unit", probes[k].unit},
                              {"values", result.values[k]}});
  const IntegratorStatistics& statistics = result.statistics;
  out["statistics"] = {{"steps", statistics.steps},
                       {"residual_evaluations", statistics.residual_evaluations},
                       {"jacobian_evaluations", statistics.jacobian_evaluations},
                       {"newton_iterations", statistics.newton_iterations},
                       {"error_test_failures", statistics.error_test_failures},
                       {"convergence_failures", statistics.convergence_failures},
                       {"restarts", statistics.restarts}};
  out["cost"] = {{"integration_seconds", result.seconds}, {"total_seconds", run.total_seconds}};
  if (run.shape) out["shape"] = to_json(*run.shape);
  out["validity"] = to_json(run.validity);
  return out;
}

}  // namespace emnet
