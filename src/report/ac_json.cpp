// JSON of the AC study (report/ac_json.hpp).
#include "emnet/report/ac_json.hpp"

#include <cmath>
#include <complex>

#include "emnet/core/constants.hpp"

namespace emnet {

Json to_json(const AcStudyResult& result, const Model& model, const std::vector<Probe>& probes,
             const std::string& input, double total_seconds) {
  Json out;
  out["scene"] = model.scene.name;
  out["automatic_choices"] = to_json(model.automatic_choices);
  add_mesh_json(out, model);
  out["input"] = input;
  out["notes"] = result.notes;
  out["frequencies_hz"] = result.ac.frequencies;
  out["probes"] = Json::array();
  for (size_t k = 0; k < probes.size(); ++k) {
    std::vector<double> magnitude, phase;
    for (const auto& v : result.ac.values[k]) {
      magnitude.push_back(std::abs(v));
      phase.push_back(std::arg(v) * 180.0 / kPi);
    }
    out["probes"].push_back({{"name", probes[k].name},
                             {"description", probes[k].description},
                             {"unit", probes[k].unit},
                             {"magnitude", magnitude},
                             {"phase_deg", phase}});
  }
  out["resonances_hz"] = result.resonances_hz;
  if (result.reduction)  // measured against the full model (the reduced sweep has no residual)
    out["accuracy"] = {{"method", method_name(Method::reduced)},
                       {"measured_error", result.reduction->measured_error},
                       {"error_estimate", result.reduction->error_estimate},
                       {"tolerance", result.reduction->model.tolerance},
                       {"tolerance_met", result.reduction->tolerance_met}};
  else
    out["accuracy"] = {{"max_relative_residual", result.ac.max_relative_residual},
                       {"method", method_name(result.ac.method)}};
  if (result.ac.method == Method::pole_residue)
    out["accuracy"].update({{"check_points", result.ac.check_points},
                            {"check_deviation", result.ac.check_deviation},
                            {"eigenvector_condition", result.ac.basis_condition}});
  else if (!result.ac.note.empty())
    out["accuracy"]["note"] = result.ac.note;
  out["cost"] = {{"ac_seconds", result.ac.seconds}, {"total_seconds", total_seconds}};
  if (result.reduction) {
    const AcReductionResult& r = *result.reduction;
    const ModalReduction& m = r.model;
    Json errors = Json::object();
    for (size_t k = 0; k < probes.size(); ++k) errors[probes[k].name] = r.probe_errors[k];
    Json reduced = to_json(m, r.tolerance_met);
    reduced.update({{"clustered_poles", m.clustered_poles},
                    {"all_poles_below_cutoff_found", m.all_found},
                    {"correction_order", m.correction_order},
                    {"error_estimate", r.error_estimate},
                    {"measured_error", r.measured_error},
                    {"probe_errors", errors},
                    {"check_frequencies_hz", r.check_frequencies},
                    {"note", m.note},
                    {"cost",
                     {{"reduce_seconds", r.reduce_seconds},
                      {"evaluate_seconds", r.evaluate_seconds},
                      {"check_seconds", r.check_seconds}}}});
    out["reduction"] = reduced;
  }
  out["validity"] = to_json(result.validity);
  return out;
}

}  // namespace emnet
