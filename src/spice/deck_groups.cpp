// The SPICE deck's groups of elements: each element is written under the title of the scene
// component it realises (a beam segment, the lumped node elements, a load, a point mass, a
// spring, the circuit, a DEA), read from the model's record of its elements (Model::structure),
// never from element names. The titles come from one table by component (group_titles below):
// a new component is one title function and one line in that table. Elements without a record,
// or of a component without a title, go to the group "other elements".
#include "deck_writer.hpp"
#include "emnet/model/circuit.hpp"

namespace emnet::spice_deck {

namespace {

GroupTitle beam_segment_title(const ElementRecord& record, const Model& model) {
  const Scene& scene = model.scene;
  const BeamLayout& beam = model.beam;
  const size_t k = static_cast<size_t>(record.index);
  const std::string id = std::to_string(record.index);
  GroupTitle title{"segment " + id, {}, {}};
  const std::vector<SectionSpec> sections = effective_sections(scene.beam);
  const double default_tau = scene.damping.effective_kelvin_voigt_time();
  const bool known = k < beam.segment_lengths.size() && k < beam.segment_section.size();
  if (!known || k + 1 >= beam.x.size()) return title;
  const SectionSpec& section = sections[static_cast<size_t>(beam.segment_section[k])];
  const double l = beam.segment_lengths[k];
  const double tau = section.kelvin_voigt_time.value_or(default_tau);
  const bool sheared = beam.shear_parameter[k] > 0.0;
  title.lines = {
      "segment " + id + ": x = " + millimetres(beam.x[k]) + " .. " + millimetres(beam.x[k + 1]) +
          ", l = " + number(l) + " m, EI = " + number(section.bending_stiffness) + " N*m^2",
      std::string("  nR: rotational compliance n_R = l/EI [rad/(N*m)] between the "
                  "rotation nodes; nT: translational compliance n_T = l^3/(12*EI)") +
          (sheared ? " + l/(kappa*G*A), kappa*G*A = " +
                         number(section.shear_stiffness.value_or(scene.beam.shear_stiffness)) +
                         " N (Timoshenko)"
                   : std::string()) +
          " [m/N]",
      model.scene.beam.kinematics == BeamKinematics::large
          ? "  co-rotational: the chord's change, angle and forces as B sources in the chord's "
            "frame (its own comment below)"
          : "  lever: ideal transformer, v_right - m = (l/2)*(Omega_left + Omega_right); "
            "its force F returns as torques (l/2)*F into both rotation nodes"};
  if (tau > 0.0)
    title.lines.push_back(
        "  Kelvin-Voigt damping: a resistor n/tau (a damper tau/n) across each "
        "compliance, tau = " +
        number(tau) + " s");
  return title;
}

GroupTitle beam_node_title(const ElementRecord&, const Model&) {
  return {"nodes",
          {"lumped at the beam nodes (half of each segment's share to each end node): "
           "masses rhoA*l [kg] and rotary inertias [kg*m^2] as capacitors to ground, viscous "
           "dampers [N*s/m] as resistors to ground"},
          {}};
}

GroupTitle load_title(const ElementRecord& record, const Model& model) {
  const size_t k = static_cast<size_t>(record.index);
  const std::string id = std::to_string(record.index);
  GroupTitle title{"load " + id, {}, {}};
  if (k >= model.scene.loads.size()) return title;
  const LoadSpec& load = model.scene.loads[k];
  title.lines = {"load " + id + ": " +
                 (load.kind == LoadKind::force ? "force " + number(load.value) + " N"
                                               : "moment " + number(load.value) + " N*m") +
                 " at x = " + millimetres(load.at) +
                 ", as consistent nodal loads from the Hermite shape functions"};
  return title;
}

GroupTitle point_mass_title(const ElementRecord& record, const Model& model) {
  const size_t k = static_cast<size_t>(record.index);
  GroupTitle title{"mass " + std::to_string(record.index), {}, {}};
  if (k >= model.scene.beam.masses.size()) return title;
  const MassSpec& mass = model.scene.beam.masses[k];
  title.lines = {"point mass " + (mass.name.empty() ? std::to_string(k) : mass.name) + ": " +
                 number(mass.mass) + " kg, rotary inertia " + number(mass.rotary_inertia) +
                 " kg*m^2 at x = " + millimetres(mass.at) + ", capacitors to ground"};
  return title;
}

GroupTitle spring_title(const ElementRecord& record, const Model& model) {
  const size_t k = static_cast<size_t>(record.index);
  GroupTitle title{"spring " + std::to_string(record.index), {}, {}};
  if (k >= model.scene.beam.springs.size()) return title;
  const SpringSpec& spring = model.scene.beam.springs[k];
  const bool rotational = spring.kind == SpringKind::rotational;
  title.lines = {std::string(rotational ? "rotational" : "translational") + " spring " +
                 (spring.name.empty() ? std::to_string(k) : spring.name) +
                 ": k = " + number(spring.stiffness) + (rotational ? " N*m/rad" : " N/m") +
                 ", damping " + number(spring.damping) + (rotational ? " N*m*s/rad" : " N*s/m") +
                 ", x = " + millimetres(spring.at) + " to " +
                 (spring.to ? "x = " + millimetres(*spring.to) : std::string("ground")) +
                 "; an inductor 1/k with a resistor 1/damping across it"};
  return title;
}

// One group for the whole circuit, with a line of its own for each entry.
GroupTitle circuit_title(const ElementRecord& record, const Model& model) {
  const size_t k = static_cast<size_t>(record.index);
  GroupTitle title{
      "circuit",
      {"circuit ([[circuit]] entries): electrical elements between named nodes, ground "
       "(0) and the DEAs' source terminals s_X; a voltage source holds V(from) - V(to), a "
       "current source drives its current from its first node through itself into its second"},
      {}};
  if (k >= model.scene.circuit.size()) return title;
  const CircuitSpec& element = model.scene.circuit[k];
  title.element_line = "  " + element.name + ": " + circuit_kind_name(element.kind) + " from " +
                       element.from + " to " + element.to +
                       (is_source(element.kind)
                            ? std::string(", waveform ") + waveform_kind_name(element.waveform.kind)
                            : std::string());
  return title;
}

// A DEA's electrical loop and what the drive applies to it, under one title.
GroupTitle dea_title(const ElementRecord& record, const Model& model) {
  const Scene& scene = model.scene;
  const std::string& n = record.dea;
  const DeaLayout* dea = model.find_dea(n);
  const DeaSpec* spec = nullptr;
  for (const DeaSpec& s : scene.deas)
    if (s.name == n) spec = &s;
  GroupTitle title{"dea " + n, {}, {}};
  title.lines.push_back("DEA " + n +
                        (spec ? std::string(": ") + (spec->face == Face::top ? "top" : "bottom") +
                                    " face, x = " + millimetres(spec->from) + " .. " +
                                    millimetres(spec->to) +
                                    ", lever arm z = " + millimetres(spec->lever_arm)
                              : std::string()));
  if (!dea) return title;
  title.lines.push_back("  force F = k_F*u^2, k_F = " + number(dea->force_constant) +
                        " N/V^2 (paper Eq. 16), as the moment pair -/+z*F at the span's ends");
  if (scene.drive.electrical_dynamics && circuit_drives_dea(scene, n))
    title.lines.push_back("  electrical: driven by the circuit at its terminal s_" + n +
                          ", electrode resistance " + number(dea->electrode_resistance) +
                          " Ohm, capacitor C0 = " + number(dea->capacitance) +
                          " F; the force follows the capacitor voltage u = V(e_" + n + ")");
  else if (scene.drive.electrical_dynamics)
    title.lines.push_back("  electrical: source V_V_" + n + ", electrode resistance " +
                          number(dea->electrode_resistance) +
                          " Ohm, capacitor C0 = " + number(dea->capacitance) +
                          " F; the force follows the capacitor voltage u = V(e_" + n + ")");
  else
    title.lines.push_back(
        "  ideal drive (drive.electrical_dynamics = false): the force "
        "k_F*V(t)^2 of the source voltage, as current sources");
  return title;
}

struct GroupTitleEntry {
  Component component;
  GroupTitle (*title)(const ElementRecord& record, const Model& model);
};

// The group titles by component: one line per component.
const GroupTitleEntry group_titles[] = {
    {Component::beam_segment, beam_segment_title},
    {Component::beam_node, beam_node_title},
    {Component::load, load_title},
    {Component::point_mass, point_mass_title},
    {Component::spring, spring_title},
    {Component::circuit, circuit_title},
    {Component::dea, dea_title},
    {Component::drive_source, dea_title},
};

}  // namespace

GroupTitle DeckWriter::group_title(const ElementRecord* record) const {
  if (!record) return {};
  for (const GroupTitleEntry& entry : group_titles)
    if (entry.component == record->component) return entry.title(*record, model_);
  return {};
}

std::vector<Group> DeckWriter::groups() const {
  std::vector<Group> list;
  const auto& elements = network_.elements();
  for (size_t e = 0; e < elements.size(); ++e) {
    GroupTitle title = group_title(model_.structure.element(e));
    auto group =
        std::find_if(list.begin(), list.end(), [&](const Group& g) { return g.key == title.key; });
    if (group == list.end()) group = list.insert(list.end(), Group{title.key, {}, {}});
    const bool first_title = group->title.empty();
    if (first_title) group->title = title.lines;
    if (!title.element_line.empty())
      group->title.push_back(title.element_line);  // one line per element
    group->elements.push_back(elements[e].get());
  }
  for (Group& g : list)
    if (g.title.empty()) g.title = {g.key == "other" ? "other elements" : g.key};
  return list;
}

}  // namespace emnet::spice_deck
