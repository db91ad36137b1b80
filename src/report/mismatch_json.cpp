// JSON of the mismatch study (emnet/report/mismatch_json.hpp).
#include "emnet/report/mismatch_json.hpp"

namespace emnet {

Json to_json(const MismatchResult& result, const std::vector<AutomaticChoice>& automatic_choices,
             double total_seconds) {
  Json out = {{"automatic_choices", to_json(automatic_choices)},
              {"output", result.output},
              {"frequency_hz", result.frequency_hz},
              {"method", method_name(result.method)},
              {"nominal",
               {{"left_m", result.nominal_left},
                {"right_m", result.nominal_right},
                {"asymmetry", result.nominal_asymmetry}}},
              {"cases", Json::array()},
              {"total_seconds", total_seconds}};
  for (const MismatchRow& row : result.rows)
    out["cases"].push_back({{"label", row.label},
                            {"key", row.key},
                            {"change", row.change},
                            {"left_m", row.left},
                            {"right_m", row.right},
                            {"asymmetry", row.asymmetry},
                            {"asymmetry_per_unit_change", row.asymmetry_per_unit_change}});
  out["validity"] = to_json(result.validity);
  if (!result.notes.empty()) out["notes"] = result.notes;
  return out;
}

}  // namespace emnet
