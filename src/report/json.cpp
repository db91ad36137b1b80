// JSON of results (emnet/report/json.hpp).
#include "emnet/report/json.hpp"

#include <cmath>

#include "emnet/core/constants.hpp"
#include "emnet/studies/static_study.hpp"

namespace emnet {

std::string json_text(const Json& json) {
  return json.dump(2, ' ', false, Json::error_handler_t::replace);
}

Json to_json(const DeformedShape& shape) {
  return {{"frequency_hz", shape.frequency},
          {"period_s", shape.period()},
          {"times_s", shape.times},
          {"reference_x_m", shape.reference_x},
          {"x_m", shape.x},
          {"y_m", shape.y}};
}

Json to_json(const Validity& validity) {
  Json violations = Json::array();
  for (const auto& v : validity.violations)
    violations.push_back({{"check", validity_check_name(v.check)},
                          {"subject", v.subject},
                          {"key", v.key},
                          {"value", v.value},
                          {"limit", v.limit},
                          {"message", v.message}});
  return {{"status", validity.within() ? "within" : "OUTSIDE"},
          {"summary", validity.summary},
          {"deflection_fraction_of_limit", validity.deflection_fraction},
          {"field_fraction_of_breakdown", validity.field_fraction},
          {"geometric_error_estimate", validity.geometric_error},
          {"largest_rotation_rad", validity.largest_rotation},
          {"violations", violations}};
}

Json to_json(const std::vector<AutomaticChoice>& automatic_choices) {
  Json choices = Json::array();
  for (const auto& choice : automatic_choices)
    choices.push_back({{"key", choice.key},
                       {"value", choice.value},
                       {"reason", choice.reason},
                       {"estimated_error", choice.estimated_error},
                       {"tolerance", choice.tolerance},
                       {"band_hz", {choice.band_from_hz, choice.band_to_hz}},
                       {"seconds", choice.seconds}});
  return choices;
}

void add_mesh_json(Json& out, const Model& model) {
  out["segments"] = static_cast<int>(model.beam.segment_lengths.size());
  if (model.beam.raised_from > 0) out["segments_asked"] = model.beam.raised_from;
}

Json to_json(const ModalReduction& m, bool tolerance_met) {
  return {{"status", tolerance_met ? "met" : "NOT MET"},
          {"tolerance", m.tolerance},
          {"band_hz", m.band_hz},
          {"cutoff_hz", m.cutoff_hz},
          {"kept_modes", m.kept_modes},
          {"kept_real_poles", m.kept_real_poles},
          {"truncated_poles", m.truncated_poles},
          {"full_unknowns", m.full_unknowns},
          {"modal_method", method_name(m.modal_method)}};
}

Json to_json(const ModesStudyResult& result, const std::vector<Probe>& probes,
             double total_seconds) {
  const Model& model = result.model;
  Json out;
  out["scene"] = model.scene.name;
  out["automatic_choices"] = to_json(model.automatic_choices);
  add_mesh_json(out, model);
  out["modes"] = Json::array();
  for (const auto& entry : result.modes) {
    const Mode& m = entry.mode;
    Json mode = {{"frequency_hz", m.frequency_hz},
                 {"damping_ratio", m.damping_ratio},
                 {"natural_frequency_hz", m.natural_frequency_hz},
                 {"pole", {m.pole.real(), m.pole.imag()}},
                 {"relative_residual", m.relative_residual},
                 {"error_bounded", m.error_bounded}};
    if (m.error_bounded) {
      mode["pole_error_bound"] = m.pole_error;
      mode["frequency_error_bound_hz"] = m.pole_error / (2 * kPi);
      mode["damping_ratio_error_bound"] = m.pole_error / std::abs(m.pole);
    } else {
      mode["unbounded_reason"] = m.unbounded_reason;
    }
    if (entry.discretisation_error_estimated) {
      mode["discretisation_error_estimate"] = entry.discretisation_error;
      mode["shape_correlation_2n"] = entry.shape_correlation;
    }
    if (!entry.shape.x_m.empty()) {
      Json nodes = Json::array();
      for (size_t i = 0; i < entry.shape.x_m.size(); ++i)
        nodes.push_back({{"x_m", entry.shape.x_m[i]},
                         {"deflection", entry.shape.deflection[i].real()},
                         {"deflection_imag", entry.shape.deflection[i].imag()}});
      mode["shape"] = nodes;
    }
    if (!probes.empty()) {
      Json at = Json::array();
      const std::vector<std::complex<double>> values = mode_probe_values(model, m, probes);
      for (size_t k = 0; k < probes.size(); ++k) {
        const Probe& probe = probes[k];
        const std::complex<double> value = values[k];
        at.push_back({{"name", probe.name},
                      {"description", probe.description},
                      {"value", value.real()},
                      {"value_imag", value.imag()},
                      {"unit", probe.unit + " per unit largest deflection"}});
      }
      mode["probes"] = at;
    }
    out["modes"].push_back(mode);
  }
  out["real_poles"] = Json::array();
  for (const auto& pole : result.modal.real_poles) {
    Json entry = {{"pole", pole.pole.real()},
                  {"time_constant_s", -1.0 / pole.pole.real()},
                  {"error_bounded", pole.error_bounded}};
    if (pole.error_bounded)
      entry["pole_error_bound"] = pole.pole_error;
    else
      entry["unbounded_reason"] = pole.unbounded_reason;
    out["real_poles"].push_back(entry);
  }
  out["mode_rule"] = kModeRule;
  out["overdamped_pairs"] = Json::array();
  for (const auto& pair : result.modal.overdamped_pairs) {
    Json entry = {{"frequency_hz", pair.frequency_hz},
                  {"damping_ratio", pair.damping_ratio},
                  {"natural_frequency_hz", pair.natural_frequency_hz},
                  {"pole_real", pair.pole.real()},
                  {"pole_imag", pair.pole.imag()},
                  {"error_bounded", pair.error_bounded}};
    if (pair.error_bounded) entry["pole_error_bound"] = pair.pole_error;
    out["overdamped_pairs"].push_back(entry);
  }
  out["rigid_body_modes"] = Json::array();
  for (const auto& name : result.rigid_body_motions) out["rigid_body_modes"].push_back(name);
  out["method"] = method_name(result.modal.method);
  out["complete"] = result.modal.complete;
  out["pencil_size"] = result.modal.pencil_size;
  out["cost"] = {{"modal_seconds", result.modal.seconds},
                 {"error_bound_seconds", result.modal.bound_seconds},
                 {"error_estimate_seconds", result.seconds_error_estimate},
                 {"total_seconds", total_seconds}};
  if (!result.unbounded.empty()) out["status"] = "NOT BOUNDED";
  return out;
}

Json to_json(const SensitivityResult& result, const Scene& scene, bool with_check,
             double total_seconds) {
  Json out;
  out["scene"] = scene.name;
  out["automatic_choices"] = to_json(scene.automatic_choices);
  out["segments"] = scene.beam.segments;
  out["modes"] = Json::array();
  for (const auto& mode : result.modes)
    out["modes"].push_back({{"frequency_hz", mode.frequency_hz},
                            {"natural_frequency_hz", mode.natural_frequency_hz},
                            {"pole", {mode.pole.real(), mode.pole.imag()}}});
  out["parameters"] = Json::array();
  for (const auto& parameter : result.parameters) {
    Json entry = {{"key", parameter.parameter.key},
                  {"value", parameter.parameter.value},
                  {"unit", parameter.parameter.unit},
                  {"modes", Json::array()}};
    for (const auto& s : parameter.modes) {
      Json mode = {{"pole_derivative", {s.pole_derivative.real(), s.pole_derivative.imag()}},
                   {"frequency_derivative", s.frequency_derivative},
                   {"natural_frequency_derivative", s.natural_frequency_derivative},
                   {"normalised", s.normalised},
                   {"normalised_natural", s.normalised_natural}};
      if (with_check) {
        mode["finite_difference_pole_derivative"] = {s.finite_difference_pole_derivative.real(),
                                                     s.finite_difference_pole_derivative.imag()};
        mode["check_difference"] = s.check_difference;
        mode["check_error_estimate"] = s.check_error_estimate;
      }
      entry["modes"].push_back(mode);
    }
    out["parameters"].push_back(entry);
  }
  out["left_vector_residual"] = result.left_vector_residual;
  if (!result.notes.empty()) out["notes"] = result.notes;
  out["cost"] = {{"sensitivity_seconds", result.seconds - result.check_seconds},
                 {"check_seconds", result.check_seconds},
                 {"total_seconds", total_seconds}};
  return out;
}

Json to_json(const Model& model, const StaticResult& rest,
             const std::vector<std::vector<double>>& nodes, const std::vector<Probe>& probes,
             const std::vector<double>& probe_values, const Validity& validity,
             double total_seconds) {
  Json out;
  out["scene"] = model.scene.name;
  out["automatic_choices"] = to_json(model.automatic_choices);
  add_mesh_json(out, model);
  out["nodes"] = Json::array();
  const std::vector<std::string> columns = static_node_columns(model);
  for (const auto& row : nodes) {
    Json node = Json::object();
    for (size_t c = 0; c < columns.size() && c < row.size(); ++c) node[columns[c]] = row[c];
    out["nodes"].push_back(std::move(node));
  }
  out["probes"] = Json::array();
  for (size_t k = 0; k < probes.size(); ++k)
    out["probes"].push_back({{"name", probes[k].name},
                             {"description", probes[k].description},
                             {"unit", probes[k].unit},
                             {"value", probe_values[k]}});
  out["accuracy"] = {{"relative_residual", rest.relative_residual},
                     {"newton_iterations", rest.newton_iterations},
                     {"load_steps", rest.load_steps},
                     {"discretisation", static_discretisation(model)}};
  out["cost"] = {{"solve_seconds", rest.seconds}, {"total_seconds", total_seconds}};
  out["validity"] = to_json(validity);
  return out;
}

}  // namespace emnet
