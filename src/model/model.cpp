// Resolved Scene → Network: beam, DEA patches with their electrical loop and drive, loads,
// probes, each node and element recorded in the model's structure as it is added.
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

std::string position_text(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "x = %.4g mm", x * 1e3);
  return buffer;
}

bool chosen_automatically(const Scene& scene, const std::string& key) {
  return std::any_of(scene.automatic_choices.begin(), scene.automatic_choices.end(),
                     [&](const AutomaticChoice& choice) { return choice.key == key; });
}

// The probe `spec` on `model`'s beam and DEAs; `dea` is the DEA an electrical probe names
// (nullptr when there is none of that name).
Probe make_probe_on(const Model& model, const ProbeSpec& spec, const DeaLayout* dea);

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
  model.beam =
      add_beam(model.network, beam_spec, damping, scene_attachment_points(scene), &model.structure);
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

Probe Model::make_probe(const ProbeSpec& spec) const {
  return make_probe_on(*this, spec, find_dea(spec.dea));
}

namespace {

// The index in Network::elements() of the element recorded as (component, part, index); -1 when
// there is none (a spring between two held nodes is left out).
int recorded_element(const Model& model, Component component, ElementPart part, int index) {
  const std::vector<ElementRecord>& records = model.structure.elements;
  for (std::size_t e = 0; e < records.size(); ++e)
    if (records[e].component == component && records[e].part == part && records[e].index == index)
      return static_cast<int>(e);
  return -1;
}

// The first branch unknown (its index in y) of the element recorded as (component, part, index).
int recorded_branch(const Model& model, Component component, ElementPart part, int index) {
  const int element = recorded_element(model, component, part, index);
  if (element < 0)
    throw std::logic_error(std::string("make_probe: no ") + component_name(component) + " " +
                           element_part_name(part) + " " + std::to_string(index));
  return model.network.branch_unknown_index(static_cast<std::size_t>(element));
}

std::string electrical_dynamics_missing(const Model& model, const std::string& what) {
  const bool automatic = std::any_of(
      model.automatic_choices.begin(), model.automatic_choices.end(),
      [](const AutomaticChoice& choice) { return choice.key == "drive.electrical_dynamics"; });
  return what + " (drive.electrical_dynamics = " +
         (automatic ? std::string("\"auto\" chose false") : "false") + "; set it true)";
}

// The spring probe[].spring names: by its name, else by its index.
int spring_index(const Model& model, const ProbeSpec& spec) {
  const std::vector<SpringSpec>& springs = model.scene.beam.springs;
  for (std::size_t n = 0; n < springs.size(); ++n)
    if (!springs[n].name.empty() && springs[n].name == spec.spring) return static_cast<int>(n);
  for (std::size_t n = 0; n < springs.size(); ++n)
    if (spec.spring == std::to_string(n)) return static_cast<int>(n);
  throw InputError("probe " + spec.name, "spring",
                   "no spring named '" + spec.spring + "' (nor of that index)");
}

// The through quantity a spring element of record index n sends from the held node `held`
// into the rest of the network, for the reaction at `held` (see reaction_terms).
void add_spring_share(const Model& model, int n, double end_x, Domain domain, Probe& probe) {
  const SpringSpec& spring = model.scene.beam.springs[static_cast<std::size_t>(n)];
  const bool rotational = spring.kind == SpringKind::rotational;
  if (rotational != (domain == Domain::rotational)) return;
  const int node_index = model.beam.node_at(end_x);
  const bool at_held = model.beam.node_at(spring.at) == node_index;
  const bool to_held = spring.to && model.beam.node_at(*spring.to) == node_index;
  if (!at_held && !to_held) return;
  const int element = recorded_element(model, Component::spring, ElementPart::spring_compliance, n);
  if (element < 0) return;  // both ends held: left out, carries nothing
  const auto& inductor =
      static_cast<const Inductor&>(*model.network.elements()[static_cast<std::size_t>(element)]);
  // Through quantity a → b: j + c·(y_a − y_b); the held end's row gets +that at a, −that at b.
  const double sign = at_held ? 1.0 : -1.0;
  const NodeId other = at_held ? inductor.b() : inductor.a();
  probe.terms.emplace_back(model.network.branch_unknown_index(static_cast<std::size_t>(element)),
                           sign);
  if (spring.damping > 0.0 && other != ground) probe.terms.emplace_back(other, -spring.damping);
}

// The support's force (translational) or moment (rotational) on the beam at the held end x = 0
// or L: the through quantities of the elements attached to the held node, which the support
// takes (R = Σ through quantities leaving the held node into elements − loads on it; see
// docs/model.md, Outputs).
//   force, left end:   R = −j_lever,0   (the lever's current is −(j + τ·j') of the segment's
//                                        translational compliance: the whole segment force)
//   force, right end:  R = +j_lever,N−1
//   moment, left end:  M = j_R,0 − g_p·Ω₁ − (l/2)·j_lever,0
//   moment, right end: M = −j_R,N−1 − g_p·Ω_N−1 − (l/2)·j_lever,N−1
// with g_p = τ/n_R the Kelvin–Voigt damper across the rotational compliance, whose through
// quantity g_p·(y_a − y_b) is entered from the across values (the held one is zero); springs with
// an end on the held node add their force; a DEA with an end on the held rotation node adds
// −c_H·k_F·u² (c_H = ∓z, its coupling there), a square.
void reaction_terms(const Model& model, const ProbeSpec& spec, Probe& probe) {
  const BeamLayout& beam = model.beam;
  const BeamSpec& beam_spec = model.scene.beam;
  const bool moment = spec.quantity == ProbeQuantity::reaction_moment;
  const int node = beam.node_at(spec.at);
  const int last = static_cast<int>(beam.x.size()) - 1;
  if (node != 0 && node != last)
    throw InputError("probe " + spec.name, "at",
                     std::string("a reaction is measured at a held end: at = 0 or beam.length (") +
                         format_number("%.6g", beam.length) + " m), not at " +
                         position_text(spec.at));
  const bool left = node == 0;
  const EndCondition end = left ? beam_spec.left : beam_spec.right;
  const std::string end_key = left ? "beam.left" : "beam.right";
  const std::string end_name = end_condition_name(end);
  const bool holds = moment ? end == EndCondition::clamped || end == EndCondition::sliding
                            : end == EndCondition::clamped || end == EndCondition::pinned;
  if (!holds) {
    std::string why = "the end at " + position_text(spec.at) + " is " + end_name + " (" + end_key +
                      "): its support takes no " + (moment ? "moment" : "force");
    if (end == EndCondition::free)
      why += "; a spring support there carries it: probe quantity spring_force with probe[].spring";
    throw InputError("probe " + spec.name, "quantity", why);
  }
  const std::string kind = moment ? "moment" : "force";
  int load_index = 0;
  for (const LoadSpec& load : model.scene.loads) {
    if ((load.kind == LoadKind::moment) == moment && load.value != 0.0 &&
        beam.node_at(load.at) == node)
      throw InputError("probe " + spec.name, "at",
                       "load " + std::to_string(load_index) + " (a " + kind + " at " +
                           position_text(load.at) +
                           ") acts on the held end and goes straight into the support; the "
                           "reaction probe leaves such loads out: move the load off the end");
    ++load_index;
  }
  const int segment = left ? 0 : last - 1;
  const int lever = recorded_branch(model, Component::beam_segment, ElementPart::lever, segment);
  const double half = 0.5 * beam.segment_lengths[static_cast<std::size_t>(segment)];
  const Domain domain = moment ? Domain::rotational : Domain::translational;
  if (!moment) {
    probe.terms.emplace_back(lever, left ? -1.0 : 1.0);
  } else {
    const int element = recorded_element(model, Component::beam_segment,
                                         ElementPart::rotational_compliance, segment);
    const auto& compliance =
        static_cast<const Inductor&>(*model.network.elements()[static_cast<std::size_t>(element)]);
    probe.terms.emplace_back(model.network.branch_unknown_index(static_cast<std::size_t>(element)),
                             left ? 1.0 : -1.0);
    const NodeId other = left ? compliance.b() : compliance.a();
    if (compliance.parallel_conductance() != 0.0 && other != ground)
      probe.terms.emplace_back(other, -compliance.parallel_conductance());
    probe.terms.emplace_back(lever, -half);
  }
  for (std::size_t n = 0; n < beam_spec.springs.size(); ++n)
    add_spring_share(model, static_cast<int>(n), spec.at, domain, probe);
  if (moment)
    for (const DeaSpec& dea : model.scene.deas) {
      const bool from_here = beam.node_at(dea.from) == node, to_here = beam.node_at(dea.to) == node;
      if (!from_here && !to_here) continue;
      const DeaLayout* layout = model.find_dea(dea.name);
      if (!layout || layout->electrode_node == ground)
        throw InputError("probe " + spec.name, "quantity",
                         electrical_dynamics_missing(
                             model, "DEA '" + dea.name +
                                        "' ends on the held end; its moment there is the "
                                        "ideal drive's k_F*V(t)^2, no output of the network"));
      // Coupling at the held rotation node (ψ there has coefficient 1): −s·z at `from`, +s·z at
      // `to`, s = −1 on the top face (model.cpp dea_layout).
      const double face_sign = dea.face == Face::top ? -1.0 : 1.0;
      const double coupling = (to_here ? 1.0 : -1.0) * face_sign * dea.lever_arm;
      probe.squares.push_back(
          {-coupling * layout->force_constant, {{layout->electrode_node, 1.0}}});
    }
  probe.description = std::string("reaction ") + kind + " of the " + end_name + " support at " +
                      position_text(spec.at) + " on the beam (" +
                      (moment ? "positive as +psi" : "positive along +w") + ")";
}

// A spring's force (a rotational spring: its moment) for probe[].spring: its compliance's branch
// current plus its dashpot's c*(y_a - y_b).
void spring_force_terms(const Model& model, const ProbeSpec& spec, Probe& probe) {
  const int n = spring_index(model, spec);
  const SpringSpec& spring = model.scene.beam.springs[static_cast<std::size_t>(n)];
  const bool rotational = spring.kind == SpringKind::rotational;
  probe.unit = rotational ? "N*m" : "N";
  const std::string id = spring.name.empty() ? std::to_string(n) : spring.name;
  const std::string what = rotational ? "moment" : "force";
  const std::string to = spring.to ? position_text(*spring.to) : std::string("ground");
  probe.description = "spring " + id + "'s " + what + " k*(" + (rotational ? "phi" : "w") + "(" +
                      position_text(spring.at) + ") - " + (rotational ? "phi" : "w") + "(" + to +
                      ")) + c*rate: positive stretched along +" + (rotational ? "psi" : "w") +
                      " at its 'at' end, which it pulls back";
  const int element = recorded_element(model, Component::spring, ElementPart::spring_compliance, n);
  if (element < 0) {
    probe.description += " (both ends held: it carries nothing)";
    return;
  }
  probe.terms.emplace_back(model.network.branch_unknown_index(static_cast<std::size_t>(element)),
                           1.0);
  const int damper = recorded_element(model, Component::spring, ElementPart::spring_damper, n);
  if (damper >= 0) {
    const auto& inductor =
        static_cast<const Inductor&>(*model.network.elements()[static_cast<std::size_t>(element)]);
    if (inductor.a() != ground) probe.terms.emplace_back(inductor.a(), spring.damping);
    if (inductor.b() != ground) probe.terms.emplace_back(inductor.b(), -spring.damping);
  }
}

// With large kinematics a beam quantity reads the nodes' own unknowns: the probe must sit on a
// node (the mesher puts one at every scene probe) and be one the co-rotational network carries.
// Returns true when it filled `probe`; false for quantities that are not the beam's.
// @throws InputError for a position between nodes or a quantity not yet carried
bool large_kinematics_probe(const BeamLayout& beam, const ProbeSpec& spec, Probe& probe) {
  const std::string who = "probe " + spec.name;
  if (spec.quantity == ProbeQuantity::strain || spec.quantity == ProbeQuantity::reaction_force ||
      spec.quantity == ProbeQuantity::reaction_moment ||
      spec.quantity == ProbeQuantity::spring_force)
    throw InputError(who, "quantity",
                     std::string("'") + probe_quantity_name(spec.quantity) +
                         "' is not available with beam.kinematics = \"large\" yet (deflection, "
                         "axial_displacement, rotation and their rates are)");
  if (!is_beam_motion(spec.quantity)) return false;
  const int node = beam.node_at(spec.at);
  if (node < 0)
    throw InputError(who, "at",
                     "is between the beam's nodes; with beam.kinematics = \"large\" a probe reads "
                     "a node: name it in the scene's [[probe]] entries, which get a node each");
  const size_t k = static_cast<size_t>(node);
  const bool axial = spec.quantity == ProbeQuantity::axial_displacement;
  const bool rotational =
      spec.quantity == ProbeQuantity::rotation || spec.quantity == ProbeQuantity::angular_velocity;
  const NodeId id =
      axial ? beam.axial_velocity[k] : (rotational ? beam.angular_velocity[k] : beam.velocity[k]);
  if (id != ground) probe.terms = {{id, 1.0}};
  probe.integrations =
      spec.quantity == ProbeQuantity::velocity || spec.quantity == ProbeQuantity::angular_velocity
          ? 0
          : 1;
  probe.description = std::string(probe_quantity_name(spec.quantity)) + " at " +
                      position_text(spec.at) + " (fixed frame)";
  return true;
}

Probe make_probe_on(const Model& model, const ProbeSpec& spec, const DeaLayout* dea) {
  const BeamLayout& beam = model.beam;
  Probe probe;
  probe.name = spec.name;
  probe.quantity = spec.quantity;
  probe.unit = probe_unit(spec.quantity);
  const std::string where = position_text(spec.at);
  auto electrical_dea = [&]() {
    if (!dea) throw InputError("probe " + spec.name, "dea", "no DEA named '" + spec.dea + "'");
    if (dea->electrode_node == ground)
      throw InputError(
          "probe " + spec.name, "dea",
          electrical_dynamics_missing(
              model, "DEA '" + spec.dea + "' has no electrical model" +
                         (spec.quantity == ProbeQuantity::dea_force
                              ? ": its force is the ideal drive's k_F*V(t)^2 of its source "
                                "voltage, not an output of the network"
                              : "")));
  };
  if (beam.kinematics == BeamKinematics::large && large_kinematics_probe(beam, spec, probe))
    return probe;
  switch (spec.quantity) {
    case ProbeQuantity::axial_displacement:
      throw InputError("probe " + spec.name, "quantity",
                       "'axial_displacement' needs beam.kinematics = \"large\": with small "
                       "deflections the beam has no axial motion (it is of second order in the "
                       "rotations)");
    case ProbeQuantity::deflection:
    case ProbeQuantity::velocity:
      probe.terms = beam.deflection_terms(spec.at);
      probe.integrations = spec.quantity == ProbeQuantity::deflection ? 1 : 0;
      probe.description = std::string(probe_quantity_name(spec.quantity)) + " at " + where;
      break;
    case ProbeQuantity::rotation:
    case ProbeQuantity::angular_velocity:
      probe.terms = beam.slope_terms(spec.at);
      probe.integrations = spec.quantity == ProbeQuantity::rotation ? 1 : 0;
      probe.description = std::string(probe_quantity_name(spec.quantity)) + " at " + where;
      break;
    case ProbeQuantity::dea_voltage:
    case ProbeQuantity::dea_current: {
      electrical_dea();
      if (spec.quantity == ProbeQuantity::dea_voltage) {
        probe.terms = {{dea->electrode_node, 1.0}};
        probe.description = "capacitor voltage of DEA " + spec.dea;
      } else {
        const double g = 1.0 / dea->electrode_resistance;
        probe.terms = {{dea->source_node, g}, {dea->electrode_node, -g}};
        probe.description = "current into DEA " + spec.dea;
      }
      break;
    }
    case ProbeQuantity::dea_force:
      electrical_dea();
      probe.squares.push_back({dea->force_constant, {{dea->electrode_node, 1.0}}});
      probe.description = "force k_F*u^2 of DEA " + spec.dea +
                          " on its face (k_F = " + format_number("%.6g", dea->force_constant) +
                          " N/V^2)";
      break;
    case ProbeQuantity::reaction_force:
    case ProbeQuantity::reaction_moment:
      reaction_terms(model, spec, probe);
      break;
    case ProbeQuantity::spring_force:
      spring_force_terms(model, spec, probe);
      break;
    case ProbeQuantity::strain: {
      // ε = ∓z·dψ/dx: −z on the top face (+w side), +z on the bottom; the time integral of the
      // curvature rate from the velocities.
      const double z = spec.face == Face::top ? -spec.distance : spec.distance;
      for (const auto& [node, c] : beam.curvature_terms(spec.at))
        probe.terms.emplace_back(node, z * c);
      probe.integrations = 1;
      probe.description = std::string("strain of the ") +
                          (spec.face == Face::top ? "top" : "bottom") + " face at " + where +
                          ", z = " + format_number("%.4g", spec.distance * 1e3) +
                          " mm from the neutral plane (positive stretched)";
      break;
    }
  }
  return probe;
}

}  // namespace

Probe Model::parse_probe(const std::string& text) const {
  for (const Probe& probe : probes)
    if (probe.name == text) return probe;
  ProbeSpec spec;
  spec.name = text;
  const auto at_sign = text.find('@');
  const auto colon = text.find(':');
  const std::string quantity = text.substr(0, std::min(at_sign, colon));
  bool known = false;
  for (ProbeQuantity q : probe_quantities())
    if (quantity == probe_quantity_name(q)) {
      spec.quantity = q;
      known = true;
    }
  const bool named =
      spec.quantity == ProbeQuantity::dea_voltage || spec.quantity == ProbeQuantity::dea_current ||
      spec.quantity == ProbeQuantity::dea_force || spec.quantity == ProbeQuantity::spring_force;
  if (!known || (named ? colon == std::string::npos || colon + 1 == text.size()
                       : at_sign == std::string::npos))
    throw OptionError("probe",
                      "expected a probe name of the scene, QUANTITY@POSITION (e.g. "
                      "deflection@70mm, velocity@0.1, reaction_force@0, reaction_moment@0), "
                      "strain@POSITION,FACE,DISTANCE (e.g. strain@20mm,top,1.5mm), "
                      "dea_voltage:NAME / dea_current:NAME / dea_force:NAME or "
                      "spring_force:NAME (a spring's name or index)",
                      text);
  // A plain number is SI (metres); anything else must carry a length unit.
  auto length = [&](const std::string& written) {
    try {
      size_t used = 0;
      double plain = 0.0;
      try {
        plain = std::stod(written, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      return used == written.size() && std::isfinite(plain) ? plain
                                                            : parse_quantity(written, dim::length);
    } catch (const std::exception& e) {
      throw OptionError("probe", e.what(), text);
    }
  };
  if (named) {
    (spec.quantity == ProbeQuantity::spring_force ? spec.spring : spec.dea) =
        text.substr(colon + 1);
  } else {
    std::string position = text.substr(at_sign + 1);
    if (spec.quantity == ProbeQuantity::strain) {
      const auto first = position.find(','), second = position.find(',', first + 1);
      if (first == std::string::npos || second == std::string::npos)
        throw OptionError("probe",
                          "a strain needs its face and its distance from the neutral plane: "
                          "strain@POSITION,FACE,DISTANCE (e.g. strain@20mm,top,1.5mm)",
                          text);
      const std::string face = position.substr(first + 1, second - first - 1);
      if (face != "top" && face != "bottom")
        throw OptionError("probe", "the face must be top or bottom, got '" + face + "'", text);
      spec.face = face == "top" ? Face::top : Face::bottom;
      spec.distance = length(position.substr(second + 1));
      if (!(spec.distance > 0.0))
        throw OptionError("probe", "the distance from the neutral plane must be > 0", text);
      position = position.substr(0, first);
    }
    spec.at = length(position);
    if (!(spec.at >= 0.0 && spec.at <= beam.length))
      throw OptionError(
          "probe", "position outside the beam [0, " + std::to_string(beam.length) + " m]", text);
  }
  return make_probe(spec);
}

}  // namespace emnet
