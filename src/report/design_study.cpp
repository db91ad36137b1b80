// A design study's table as CSV or JSON (emnet/report/design_study.hpp).
#include "emnet/report/design_study.hpp"

#include "emnet/core/output_file.hpp"
#include "emnet/core/units.hpp"
#include "emnet/report/csv.hpp"

namespace emnet {

namespace {

// %.17g: the double reads back exactly.
std::string round_trip_number_text(double value) {
  return format_number("%.17g", value);
}

std::string status_text(const Status& status) {
  return status.ok() ? std::string("ok") : "failed: " + status.message;
}

}  // namespace

std::string validity_text(const VariantResult& row) {
  if (!row.status.ok()) return "";
  if (row.validity.within()) return "within";
  std::string text = "OUTSIDE:";
  for (const auto& violation : row.validity.violations) text += " " + violation.message + ";";
  text.pop_back();
  return text;
}

std::vector<std::string> design_study_header(const DesignStudyResult& result) {
  std::vector<std::string> header{"variant"};
  header.insert(header.end(), result.keys.begin(), result.keys.end());
  header.push_back("status");
  header.push_back("validity");
  header.insert(header.end(), result.columns.begin(), result.columns.end());
  return header;
}

Status write_design_study_csv(const std::string& path, const DesignStudyResult& result) {
  OutputFile out(path);
  std::string line;
  const auto header = design_study_header(result);
  for (std::size_t k = 0; k < header.size(); ++k) line += (k ? "," : "") + csv_field(header[k]);
  out.write(line + "\n");
  for (std::size_t i = 0; i < result.rows.size(); ++i) {
    line = std::to_string(i);
    for (double value : result.variants[i]) line += "," + round_trip_number_text(value);
    line += "," + csv_field(status_text(result.rows[i].status));
    line += "," + csv_field(validity_text(result.rows[i]));
    const auto& values = result.rows[i].values;
    for (std::size_t k = 0; k < result.columns.size(); ++k)
      line += "," + (k < values.size() ? round_trip_number_text(values[k]) : std::string());
    out.write(line + "\n");
  }
  return out.commit();
}

Json to_json(const DesignStudyResult& result) {
  Json json;
  json["keys"] = Json::array();
  for (std::size_t k = 0; k < result.keys.size(); ++k)
    json["keys"].push_back({{"key", result.keys[k]}, {"unit", result.key_units[k]}});
  json["columns"] = Json::array();
  for (std::size_t k = 0; k < result.columns.size(); ++k)
    json["columns"].push_back({{"name", result.columns[k]}, {"unit", result.units[k]}});
  json["rows"] = Json::array();
  for (std::size_t i = 0; i < result.rows.size(); ++i) {
    Json row;
    row["variant"] = i;
    Json values = Json::object();
    for (std::size_t k = 0; k < result.keys.size(); ++k)
      values[result.keys[k]] = result.variants[i][k];
    row["values"] = values;
    row["status"] = status_text(result.rows[i].status);
    row["validity"] = validity_text(result.rows[i]);
    if (result.rows[i].status.ok()) {
      Json results = Json::object();
      for (std::size_t k = 0; k < result.columns.size(); ++k)
        results[result.columns[k]] = result.rows[i].values[k];
      row["results"] = results;
    } else {
      row["results"] = nullptr;
    }
    json["rows"].push_back(row);
  }
  json["failed"] = result.failed;
  json["outside_validity"] = result.outside_validity;
  json["segments"] = result.segments;
  json["unknowns"] = result.unknowns;
  json["threads"] = result.threads;
  const double n = result.rows.empty() ? 1.0 : static_cast<double>(result.rows.size());
  json["cost"] = {{"build_seconds", result.cost.build},
                  {"operating_point_seconds", result.cost.operating_point},
                  {"modes_seconds", result.cost.modes},
                  {"static_seconds", result.cost.static_state},
                  {"sweep_seconds", result.cost.sweep},
                  {"per_variant_seconds", result.cost.total() / n},
                  {"wall_seconds", result.seconds}};
  json["notes"] = result.notes;
  return json;
}

}  // namespace emnet
