// JSON of a cross-check (emnet/report/crosscheck_json.hpp).
#include "emnet/report/crosscheck_json.hpp"

#include <cmath>

namespace emnet {

Json to_json(const CrosscheckReport& report, const Model& model, double total_seconds) {
  Json out;
  out["scene"] = model.scene.name;
  out["automatic_choices"] = to_json(model.automatic_choices);
  out["backend"] = report.backend;
  out["status"] = report.status.ok() ? "ok" : "failure";
  if (!report.status.ok()) out["failure"] = report.status.message;
  out["pass"] = report.all_pass();
  out["rows"] = Json::array();
  for (const auto& row : report.rows)
    out["rows"].push_back(
        {{"analysis", crosscheck_analysis_name(row.analysis)},
         {"quantity", row.quantity},
         {"largest_difference",
          std::isfinite(row.largest_difference) ? Json(row.largest_difference) : Json(nullptr)},
         {"where", row.where},
         {"tolerance", row.tolerance},
         {"pass", row.pass},
         {"basis", row.basis}});
  out["timings"] = Json::array();
  for (const auto& timing : report.timings)
    out["timings"].push_back({{"analysis", crosscheck_analysis_name(timing.analysis)},
                              {"ngspice_seconds", timing.ngspice_seconds},
                              {"ngspice_total_seconds", timing.ngspice_total_seconds},
                              {"emnet_seconds", timing.emnet_seconds},
                              {"emnet_what", timing.emnet_what}});
  out["notes"] = report.notes;
  out["total_seconds"] = total_seconds;
  return out;
}

}  // namespace emnet
