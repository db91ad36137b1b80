// Speckle-point differences, DEA outputs and the two output lists: see
// include/emnet/model/outputs.hpp.
#include "emnet/model/outputs.hpp"

#include "emnet/model/circuit.hpp"

namespace emnet {

int speckle_point_reference(const Model& model) {
  int reference = -1;
  for (size_t k = 0; k < model.probes.size(); ++k)
    if (model.probes[k].name == "P1") reference = static_cast<int>(k);
  return reference;
}

std::vector<ModelOutput> speckle_point_differences(const Model& model) {
  std::vector<ModelOutput> differences;
  const int reference = speckle_point_reference(model);
  if (reference < 0) return differences;
  const Probe& p1 = model.probes[static_cast<size_t>(reference)];
  for (size_t k = 0; k < model.probes.size(); ++k) {
    const Probe& probe = model.probes[k];
    if (static_cast<int>(k) == reference || probe.name.size() < 2 || probe.name[0] != 'P' ||
        probe.quantity != p1.quantity)
      continue;
    ModelOutput difference;
    difference.origin = OutputOrigin::speckle_point_difference;
    difference.probe_index = static_cast<int>(k);
    difference.reference_index = reference;
    difference.probe = probe;
    difference.probe.name = "dx" + probe.name.substr(1);
    difference.probe.description = probe.name + " - P1";
    for (const auto& [index, c] : p1.terms) difference.probe.terms.emplace_back(index, -c);
    differences.push_back(std::move(difference));
  }
  return differences;
}

std::vector<ModelOutput> dea_electrical_outputs(const Model& model) {
  std::vector<ModelOutput> outputs;
  for (const auto& dea : model.deas)
    if (dea.electrode_node != ground) {
      ModelOutput voltage{model.parse_probe("dea_voltage:" + dea.name), OutputOrigin::dea_voltage,
                          -1, -1, dea.name};
      voltage.probe.name = "u_" + dea.name;
      ModelOutput current{model.parse_probe("dea_current:" + dea.name), OutputOrigin::dea_current,
                          -1, -1, dea.name};
      current.probe.name = "i_" + dea.name;
      outputs.push_back(std::move(voltage));
      outputs.push_back(std::move(current));
    }
  return outputs;
}

std::vector<CircuitDeaVoltageProbe> circuit_dea_voltage_probes(const Model& model) {
  std::vector<CircuitDeaVoltageProbe> probes;
  for (const std::string& name : circuit_driven_deas(model.scene))
    for (const DeaLayout& dea : model.deas)
      if (dea.name == name && dea.electrode_node != ground)
        probes.push_back({name, model.parse_probe("dea_voltage:" + name)});
  return probes;
}

namespace {

ModelOutput scene_probe_output(const Model& model, size_t k) {
  ModelOutput output;
  output.probe = model.probes[k];
  output.probe_index = static_cast<int>(k);
  return output;
}

// A DEA's u_X or i_X that a scene probe already shows (the same quantity of the same DEA,
// whatever the probe's name), so that no output is listed twice.
bool shown_by_a_scene_probe(const Model& model, const ModelOutput& output) {
  for (const Probe& probe : model.probes)
    if (probe.quantity == output.probe.quantity && probe.terms == output.probe.terms &&
        probe.integrations == output.probe.integrations)
      return true;
  return false;
}

void append_dea_electrical_outputs(const Model& model, std::vector<ModelOutput>& outputs) {
  for (ModelOutput& output : dea_electrical_outputs(model))
    if (!shown_by_a_scene_probe(model, output)) outputs.push_back(std::move(output));
}

}  // namespace

std::vector<ModelOutput> transient_output_list(const Model& model) {
  const std::vector<ModelOutput> differences = speckle_point_differences(model);
  const int reference = speckle_point_reference(model);
  std::vector<ModelOutput> outputs;
  for (size_t k = 0; k < model.probes.size(); ++k) {
    if (static_cast<int>(k) == reference) continue;  // P1 itself: the reference of dx_k
    const ModelOutput* replacing = nullptr;
    for (const ModelOutput& difference : differences)
      if (difference.probe_index == static_cast<int>(k)) replacing = &difference;
    outputs.push_back(replacing ? *replacing : scene_probe_output(model, k));
  }
  append_dea_electrical_outputs(model, outputs);
  return outputs;
}

std::vector<ModelOutput> deck_output_list(const Model& model) {
  std::vector<ModelOutput> outputs;
  for (size_t k = 0; k < model.probes.size(); ++k)
    if (deck_exports(model, model.probes[k])) outputs.push_back(scene_probe_output(model, k));
  for (ModelOutput& output : speckle_point_differences(model)) outputs.push_back(std::move(output));
  append_dea_electrical_outputs(model, outputs);
  return outputs;
}

const ModelOutput* default_deflection_output(const std::vector<ModelOutput>& outputs) {
  const ModelOutput* last_difference = nullptr;
  const ModelOutput* last_deflection = nullptr;
  for (const ModelOutput& output : outputs) {
    if (output.probe.quantity != ProbeQuantity::deflection) continue;
    last_deflection = &output;
    if (output.origin == OutputOrigin::speckle_point_difference) last_difference = &output;
  }
  return last_difference ? last_difference : last_deflection;
}

std::vector<Probe> probes_of(const std::vector<ModelOutput>& outputs) {
  std::vector<Probe> probes;
  probes.reserve(outputs.size());
  for (const ModelOutput& output : outputs) probes.push_back(output.probe);
  return probes;
}

std::string deck_export_refusal(const Model& model, const Probe& probe) {
  if (!is_linear(probe))
    return "it squares a voltage (k_F*u^2), which the deck's G sources cannot weigh";
  const int nodes = static_cast<int>(model.network.nodes().size());
  for (const auto& [index, c] : probe.terms)
    if (index < 0 || index >= nodes)
      return "it takes a branch through quantity (a compliance's or a lever's current), which "
             "the deck does not carry as a node voltage";
  return "";
}

bool deck_exports(const Model& model, const Probe& probe) {
  return deck_export_refusal(model, probe).empty();
}

std::vector<std::string> deck_left_out_notes(const Model& model) {
  std::vector<std::string> notes;
  for (const Probe& probe : model.probes)
    if (const std::string why = deck_export_refusal(model, probe); !why.empty())
      notes.push_back("probe " + probe.name + " (" + probe_quantity_name(probe.quantity) +
                      ") is not exported to SPICE decks and not cross-checked: " + why);
  return notes;
}

}  // namespace emnet
