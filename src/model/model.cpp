// Resolved Scene → Network: beam, DEA patches with their electrical loop and drive, loads,
// probes (their terms: probes.cpp), each node and element recorded in the model's structure as
// it is added.
//
// DEA electrical loop, per DEA X:  source s_X —[electrode resistance]— e_X —[C₀ + transducer]— 0
// With drive.electrical_dynamics = false the loop is left out and the DEA's force k_F·V(t)² of
// its source voltage is entered directly along its coupling (a linear network). What each drive
// applies, and its AC input: emnet/model/drive.hpp. A DEA not named by the drive has its source
// node tied to ground through its resistance (a 0 V source), unless a [[circuit]] element ends on
// its terminal "dea.X": then the circuit drives s_X and no source is added there
// (emnet/model/circuit.hpp).
//
// [environment] fluid loading: Sader's added mass m_a and damping c_a per length
// (emnet/model/fluid_loading.hpp), added to the beam's mass and viscous damping per length, at
// environment.frequency or at the loaded beam's first undamped resonance that the resolve step
// found (EnvironmentSpec::resonance).
#include "emnet/model/model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "emnet/core/errors.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/units.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/elements/voltage_source.hpp"
#include "emnet/model/circuit.hpp"
#include "probes.hpp"

namespace emnet {

double mean_mass_per_length(const BeamSpec& beam) {
  if (beam.sections.empty()) return beam.mass_per_length;
  double mass = 0.0;
  for (const SectionSpec& section : beam.sections) mass += section.mass_per_length * section.length;
  return mass / beam.length;
}

void add_distributed_loading(BeamSpec& beam, DampingSpec& damping, double mass_per_length,
                             double damping_per_length) {
  beam.mass_per_length += mass_per_length;
  damping.viscous_per_length += damping_per_length;
  for (SectionSpec& section : beam.sections) {
    section.mass_per_length += mass_per_length;
    if (section.viscous_per_length) *section.viscous_per_length += damping_per_length;
  }
}

namespace {

bool chosen_automatically(const Scene& scene, const std::string& key) {
  return std::any_of(scene.automatic_choices.begin(), scene.automatic_choices.end(),
                     [&](const AutomaticChoice& choice) { return choice.key == key; });
}

// DEA `spec`'s layout on `beam`: capacitance, force constant and coupling.
DeaLayout dea_layout(const DeaSpec& spec, const BeamLayout& beam) {
  DeaLayout layout;
  layout.name = spec.name;
  layout.electrode_resistance = spec.electrode_resistance;
  layout.capacitance = dea_capacitance(spec.relative_permittivity, spec.dielectric_thickness,
                                       spec.electrode_width, spec.to - spec.from);
  layout.force_constant = dea_force_constant(spec.relative_permittivity, spec.dielectric_thickness,
                                             spec.force_thickness, spec.electrode_width);
  // Face elongation rate ẋ = s·z·(Ω(x1) − Ω(x0)), s = −1 on the top face, +1 on the bottom.
  const double sign = spec.face == Face::top ? -1.0 : 1.0;
  for (const auto& [node, c] : beam.slope_terms(spec.to))
    layout.coupling.push_back({node, sign * spec.lever_arm * c});
  for (const auto& [node, c] : beam.slope_terms(spec.from))
    layout.coupling.push_back({node, -sign * spec.lever_arm * c});
  return layout;
}

}  // namespace

Model::AppliedFluidLoading apply_fluid_loading(const Scene& scene, BeamSpec& beam,
                                               DampingSpec& damping,
                                               std::vector<std::string>& notes) {
  const EnvironmentSpec& environment = scene.environment;
  Model::AppliedFluidLoading applied;
  std::string where;
  if (environment.frequency) {
    applied.loading = scene_fluid_loading(scene, *environment.frequency);
    where = "environment.frequency";
  } else {
    if (!environment.resonance)
      throw std::logic_error("apply_fluid_loading: the fluid loading's resonance is not resolved");
    const EnvironmentSpec::Resonance& resonance = *environment.resonance;
    applied.vacuum_frequency = resonance.vacuum_frequency;
    applied.fixed_point_steps = resonance.fixed_point_steps;
    applied.loading = scene_fluid_loading(scene, resonance.frequency);
    where = "the loaded beam's first undamped resonance (fixed point in " +
            std::to_string(applied.fixed_point_steps) + " steps from the bare beam's " +
            format_number("%.4g", applied.vacuum_frequency) + " Hz)";
  }
  const FluidLoading& loading = applied.loading;
  notes.push_back(
      std::string("fluid loading, ") + fluid_name(environment.fluid) +
      " (rho = " + format_number("%.5g", environment.density) +
      " kg/m^3, eta = " + format_number("%.4g", environment.dynamic_viscosity) +
      " Pa*s, plate width " + format_number("%.4g", environment.width * 1e3) +
      " mm), Sader 1998: at " + format_number("%.5g", loading.frequency) + " Hz, " + where +
      ": Re = " + format_number("%.4g", loading.reynolds) +
      ", Gamma = " + format_number("%.5g", loading.hydrodynamic.real()) + " + " +
      format_number("%.4g", loading.hydrodynamic.imag()) + "i; added mass " +
      format_number("%.4g", loading.added_mass_per_length * 1e3) + " g/m (" +
      format_number("%.3g", loading.added_mass_per_length / mean_mass_per_length(beam)) +
      " x the beam's" + (beam.sections.empty() ? "" : " mean") + "), damping " +
      format_number("%.4g", loading.damping_per_length) + " N*s/m^2 to ground");
  if (loading.reynolds < kSaderCorrectionMinimumReynolds ||
      loading.reynolds > kSaderCorrectionMaximumReynolds)
    notes.push_back("fluid loading: Re = " + format_number("%.3g", loading.reynolds) +
                    " lies outside [1e-6, 1e4], where Sader's rectangular correction is fitted; "
                    "it is extrapolated");
  add_distributed_loading(beam, damping, loading.added_mass_per_length, loading.damping_per_length);
  return applied;
}

std::vector<std::string> unresolved_keys(const Scene& scene) {
  std::vector<std::string> keys;
  if (scene.beam.auto_segments) keys.push_back("beam.segments");
  if (scene.environment.fluid != Fluid::none && !scene.environment.frequency &&
      !fluid_resonance_current(scene))
    keys.push_back("environment.frequency");
  if (scene.drive.electrical_dynamics_auto) keys.push_back("drive.electrical_dynamics");
  if (scene.beam.kinematics_auto) keys.push_back("beam.kinematics");
  return keys;
}

bool fluid_resonance_current(const Scene& scene) {
  const EnvironmentSpec& environment = scene.environment;
  if (!environment.resonance) return false;
  const EnvironmentSpec::Resonance& resonance = *environment.resonance;
  return same_beam(resonance.beam, scene.beam) && resonance.fluid == environment.fluid &&
         resonance.density == environment.density &&
         resonance.dynamic_viscosity == environment.dynamic_viscosity &&
         resonance.width == environment.width;
}

FluidLoading scene_fluid_loading(const Scene& scene, double frequency) {
  const EnvironmentSpec& environment = scene.environment;
  try {
    return rectangular_beam_fluid_loading(environment.density, environment.dynamic_viscosity,
                                          environment.width, frequency);
  } catch (const std::invalid_argument& error) {
    // Values each in range can still overflow the Reynolds number rho*omega*b^2/(4*eta).
    throw InputError(scene.file, "environment",
                     "the fluid loading at " + format_number("%.4g", frequency) +
                         " Hz cannot be evaluated from environment.density, "
                         "dynamic_viscosity and width: " +
                         error.what());
  }
}

void set_electrical_dynamics(Scene& scene, bool on) {
  scene.drive.electrical_dynamics = on;
  scene.drive.electrical_dynamics_auto = false;
  auto& choices = scene.automatic_choices;
  choices.erase(std::remove_if(choices.begin(), choices.end(),
                               [](const AutomaticChoice& choice) {
                                 return choice.key == "drive.electrical_dynamics";
                               }),
                choices.end());
}

namespace {

// Throws std::logic_error when `scene` still has "auto" keys (a programming error: the front-ends
// resolve a scene before they build its model).
void require_resolved(const Scene& scene) {
  const std::vector<std::string> keys = unresolved_keys(scene);
  if (keys.empty()) return;
  std::string list;
  for (const auto& key : keys) list += (list.empty() ? "" : ", ") + key;
  throw std::logic_error("build_model: the scene" +
                         (scene.file.empty() ? std::string() : " " + scene.file) +
                         " has unresolved \"auto\" keys (" + list +
                         "); resolve them first (resolve_scene or prepare_model, "
                         "emnet/studies/resolve.hpp)");
}

// The note on a mesh that is not N equal segments.
void note_beam_mesh(Model& model) {
  const BeamLayout& beam = model.beam;
  if (beam.raised_from > 0)
    model.notes.push_back(
        "beam mesh: " + std::to_string(beam.x.size() - 1) +
        " segments, more than beam.segments = " + std::to_string(beam.raised_from) +
        ", so that every section boundary, mass, spring, DEA end and load" +
        (beam.kinematics == BeamKinematics::large ? std::string(" and probe") : std::string()) +
        " sits on a node");
  else if (!beam.uniform)
    model.notes.push_back(
        "beam mesh: " + std::to_string(beam.x.size() - 1) +
        " segments spread by length between the section boundaries, masses, "
        "springs, DEA ends and loads" +
        (beam.kinematics == BeamKinematics::large ? std::string(" and probes") : std::string()));
}

// Point loads: consistent nodal loads from the Hermite shape functions, exact at the nodes.
void add_point_loads(const Scene& scene, Model& model) {
  Network& network = model.network;
  const BeamLayout& beam = model.beam;
  int load_index = 0;
  for (const LoadSpec& load : scene.loads) {
    const LinearTerms terms =
        load.kind == LoadKind::force ? beam.deflection_terms(load.at) : beam.slope_terms(load.at);
    for (const auto& [node, coefficient] : terms) {
      Waveform w = Waveform::constant(load.value * coefficient);
      w.ac_magnitude = load.value * coefficient;
      ElementRecord record;
      record.component = Component::load;
      record.part = ElementPart::nodal_load;
      record.index = load_index;
      record.meaning = "load " + std::to_string(load_index) + "'s share on node " +
                       network.node(node).name + " [" + through_unit(network.node(node).domain) +
                       "]";
      add_recorded<CurrentSource>(
          network, &model.structure, std::move(record),
          "load" + std::to_string(load_index) + "_" + network.node(node).name, ground, node, w);
    }
    ++load_index;
  }
}

// Ideal voltage-driven force F(t) = k_F·V(t)² of DEA `spec`, entered as through sources along its
// coupling: a linear network.
void add_ideal_dea_force(const DriveSpec& drive, const DeaSpec& spec, const DeaLayout& layout,
                         Model& model) {
  Network& network = model.network;
  const size_t parts = squared_force(dea_drive(drive, spec.name).voltage, 1.0, 0.0).size();
  for (size_t part = 0; part < parts; ++part)
    for (size_t c = 0; c < layout.coupling.size(); ++c) {
      const NodeId node = layout.coupling[c].node;
      ElementRecord record;
      record.component = Component::drive_source;
      record.part = ElementPart::ideal_force;
      record.dea = spec.name;
      record.force_part = static_cast<int>(part);
      record.coupling = static_cast<int>(c);
      record.meaning = "DEA " + spec.name + "'s ideal force k_F*V(t)^2" +
                       (parts > 1 ? (part == 0 ? " (DC and f part)" : " (2f part)") : "") +
                       " on node " + network.node(node).name + " [" +
                       through_unit(network.node(node).domain) + "]";
      const Waveform force = drive_source_waveform(drive, layout, record);
      add_recorded<CurrentSource>(network, &model.structure, std::move(record),
                                  "F_" + spec.name + "_" + network.node(node).name, ground, node,
                                  force);
    }
}

// DEA `spec`'s electrical loop: its source (unless the circuit drives its terminal), electrode
// resistance and transducer; sets the layout's source and electrode nodes.
void add_dea_electrical_loop(const Scene& scene, const DeaSpec& spec, DeaLayout& layout,
                             Model& model) {
  Network& network = model.network;
  ModelStructure* structure = &model.structure;
  const DriveSpec& drive = scene.drive;
  NodeRecord source_node{NodeRole::dea_source, -1, spec.name};
  NodeRecord electrode_node{NodeRole::dea_electrode, -1, spec.name};
  layout.source_node =
      add_recorded_node(network, structure, source_node, "s_" + spec.name, Domain::electrical,
                        "DEA " + spec.name + " source terminal [V]");
  layout.electrode_node =
      add_recorded_node(network, structure, electrode_node, "e_" + spec.name, Domain::electrical,
                        "DEA " + spec.name + " capacitor voltage [V]");
  if (!circuit_drives_dea(scene, spec.name)) {
    ElementRecord source{Component::drive_source,
                         ElementPart::source_voltage,
                         -1,
                         spec.name,
                         -1,
                         -1,
                         "DEA " + spec.name + "'s source voltage V(t) [V]"};
    const Waveform voltage = drive_source_waveform(drive, layout, source);
    add_recorded<VoltageSource>(network, structure, std::move(source), "V_" + spec.name,
                                layout.source_node, ground, voltage, Domain::electrical);
  }
  add_recorded<Conductance>(network, structure,
                            {Component::dea, ElementPart::electrode_resistance, -1, spec.name, -1,
                             -1, "DEA " + spec.name + "'s electrode resistance R_e [Ohm]"},
                            "Re_" + spec.name, layout.source_node, layout.electrode_node,
                            1.0 / spec.electrode_resistance);
  add_recorded<Dea>(network, structure,
                    {Component::dea, ElementPart::transducer, -1, spec.name, -1, -1,
                     "DEA " + spec.name + "'s capacitor C0 and force k_F*u^2 [F, N/V^2]"},
                    "dea_" + spec.name, layout.electrode_node, ground, layout.capacitance,
                    layout.force_constant, layout.coupling, spec.back_coupling,
                    dea_ac_force(drive, layout));
}

// Every DEA: its layout on the beam, and its electrical loop or, without electrical dynamics,
// its ideal force.
void add_deas(const Scene& scene, Model& model) {
  const DriveSpec& drive = scene.drive;
  if (!scene.circuit.empty() && !drive.electrical_dynamics)
    throw InputError(scene.file, "drive.electrical_dynamics",
                     "is false, but the scene has [[circuit]] elements, which act through the "
                     "DEAs' electrical loops: a circuit needs drive.electrical_dynamics = true");
  for (const DeaSpec& spec : scene.deas) {
    DeaLayout layout = dea_layout(spec, model.beam);
    if (drive.electrical_dynamics)
      add_dea_electrical_loop(scene, spec, layout, model);
    else
      add_ideal_dea_force(drive, spec, layout, model);
    model.deas.push_back(layout);
  }
}

// The [[circuit]] elements around the DEAs' terminals, and their note.
void add_scene_circuit(const Scene& scene, Model& model) {
  if (scene.circuit.empty()) return;
  std::map<std::string, NodeId> terminals;
  for (const DeaLayout& layout : model.deas) terminals.emplace(layout.name, layout.source_node);
  model.circuit_nodes = add_circuit(model.network, &model.structure, scene, terminals);
  std::string driven;
  for (const std::string& name : circuit_driven_deas(scene)) driven += " " + name;
  model.notes.push_back("circuit: " + std::to_string(scene.circuit.size()) + " element(s), " +
                        std::to_string(model.circuit_nodes.size()) + " node(s) of its own" +
                        (driven.empty() ? std::string("; it drives no DEA")
                                        : "; it drives DEA(s)" + driven + " at their terminals"));
}

// The notes on what the DEAs' model leaves out: the electrical dynamics, the back-coupling, the
// linear response of a single DEA at zero bias.
void note_dea_simplifications(const Scene& scene, Model& model) {
  const DriveSpec& drive = scene.drive;
  if (!drive.electrical_dynamics && !scene.deas.empty())
    model.notes.push_back(
        std::string("DEA electrical dynamics left out (drive.electrical_dynamics = ") +
        (chosen_automatically(scene, "drive.electrical_dynamics") ? "\"auto\"" : "false") +
        "): each DEA is an ideal force k_F*V(t)^2 of its source voltage");
  // One note for the back-coupling i += V*dC/dt, whichever DEAs leave it out.
  std::string without, asked;
  for (const DeaSpec& spec : scene.deas)
    (spec.back_coupling ? asked : without) += (std::string(" ") + spec.name);
  if (!drive.electrical_dynamics && !asked.empty())
    model.notes.push_back(
        "DEA back-coupling left out: the ideal drive has no electrical loop "
        "to carry it (asked by dea[].back_coupling for DEA(s)" +
        asked + ")");
  else if (!without.empty())
    model.notes.push_back(std::string("DEA back-coupling left out") +
                          (asked.empty() ? "" : " for DEA(s)" + without) +
                          ": not asked (dea[].back_coupling)");

  if (drive.kind == DriveKind::single && drive.bias == 0.0)
    model.notes.push_back(
        "single DEA at zero bias: the linearised (AC) response is zero; a V² drive acts at 0 "
        "and 2f");
}

// The scene's probes, or the tip's deflection when it names none.
void add_probes(const Scene& scene, Model& model) {
  // Each probe's DEA by name: one lookup per probe, not a scan of the DEAs.
  std::map<std::string, const DeaLayout*> dea_by_name;
  for (const DeaLayout& layout : model.deas) dea_by_name.emplace(layout.name, &layout);
  for (const ProbeSpec& spec : scene.probes) {
    const auto found = dea_by_name.find(spec.dea);
    model.probes.push_back(
        make_probe_on(model, spec, found == dea_by_name.end() ? nullptr : found->second));
  }
  if (model.probes.empty()) {
    ProbeSpec tip;
    tip.name = "tip";
    tip.quantity = ProbeQuantity::deflection;
    tip.at = scene.beam.length;
    model.probes.push_back(model.make_probe(tip));
  }
}

// Large kinematics: an inextensible beam whose two ends both hold x (clamped, pinned or sliding)
// cannot deflect at all (any deflection would lengthen it), and its axial force is not
// determined: refused, naming the key that makes it extensible.
// Nothing holds a beam with two free ends along x (springs act along y or on the rotation): it
// is refused too, naming the end condition.
void require_deflectable(const Scene& scene) {
  const BeamSpec& beam = scene.beam;
  if (beam.kinematics != BeamKinematics::large) return;
  const bool held_along_x =
      std::any_of(beam.springs.begin(), beam.springs.end(),
                  [](const SpringSpec& spring) { return spring.kind == SpringKind::axial; });
  if (beam.left == EndCondition::free && beam.right == EndCondition::free && !held_along_x)
    throw InputError(scene.file, "beam.left",
                     "is free, and so is beam.right: with beam.kinematics = \"large\" nothing "
                     "would hold the beam along x; hold one end (clamped, pinned or sliding) or "
                     "give a [[spring]] of kind \"axial\"");
  if (beam.left == EndCondition::free || beam.right == EndCondition::free) return;
  if (!extensible(beam))
    throw InputError(scene.file, "beam.axial_stiffness",
                     "is needed: with beam.kinematics = \"large\" both ends hold the beam along "
                     "x (" +
                         std::string(end_condition_name(beam.left)) + " and " +
                         end_condition_name(beam.right) +
                         "), and an inextensible beam between them cannot deflect; give the "
                         "axial stiffness EA (here or for every section)");
}

// The ends at which the scene's [[probe]] entries ask for a reaction force (large kinematics
// carries it as unknowns of the end segment only there).
ReactionEnds reaction_force_ends(const Scene& scene) {
  ReactionEnds ends;
  for (const ProbeSpec& probe : scene.probes)
    if (probe.quantity == ProbeQuantity::reaction_force ||
        probe.quantity == ProbeQuantity::axial_reaction_force)
      (probe.at < 0.5 * scene.beam.length ? ends.left : ends.right) = true;
  return ends;
}

}  // namespace

Model build_model(const Scene& scene) {
  require_resolved(scene);
  require_deflectable(scene);
  Model model;
  model.scene = scene;
  BeamSpec beam_spec = scene.beam;
  DampingSpec damping = scene.damping;
  model.automatic_choices = scene.automatic_choices;
  if (scene.environment.fluid != Fluid::none)
    model.fluid = apply_fluid_loading(scene, beam_spec, damping, model.notes);
  for (const AutomaticChoice& choice : model.automatic_choices)
    model.notes.push_back(choice.reason);
  model.beam = add_beam(model.network, beam_spec, damping, scene_attachment_points(scene),
                        &model.structure, reaction_force_ends(scene));
  note_beam_mesh(model);
  add_point_loads(scene, model);
  add_deas(scene, model);
  add_scene_circuit(scene, model);
  note_dea_simplifications(scene, model);
  add_probes(scene, model);
  return model;
}

const DeaLayout* Model::find_dea(const std::string& name) const {
  for (const auto& dea : deas)
    if (dea.name == name) return &dea;
  return nullptr;
}

}  // namespace emnet
