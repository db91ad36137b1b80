// From a resolved Scene to a Network: the beam chain, the DEA patches and their drive, loads,
// probes, with a record of what each element is (emnet/model/structure.hpp).
//
// The beam: N massless segments between the nodes the mesher places (emnet/model/mesh.hpp: a
// node at every section boundary, point mass, spring end, DEA end and load; equal segments
// when nothing needs another grid). Segment k of length l, in section s (EI, ρA, ρI, κGA), is
// realised exactly as
//   - a rotational compliance n_R = l/EI between the rotation nodes r_k and r_k+1;
//   - a translational branch v_k → n_T → m_k → lever → v_k+1, the lever being an ideal
//     transformer whose secondary adds (l/2)·(Ω_k + Ω_k+1) and whose primaries feed the branch
//     force back as torques (l/2)·F into both rotation nodes;
//   - n_T = l³/(12·EI) (beam.theory = "euler_bernoulli"), or n_T = l³/(12·EI) + l/(κGA)
//     ("timoshenko": the shear compliance of the segment, a pure shear term in the cantilever
//     flexibility w = l³/(3EI)·F + l²/(2EI)·M + l/(κGA)·F with φ unchanged).
// Its flexibility equals the cubic Hermite element's (Timoshenko: the shear-corrected
// element's), so nodal statics are exact for every N. The rotation nodes carry the
// cross-section rotation ψ (= dw/dx for Euler–Bernoulli).
// Mass lumping rule: half of each segment's mass ρA·l to each of its two end nodes (a
// capacitor from the velocity node to ground); optional rotary inertia ρI·l lumped the same
// way onto the rotation nodes. Damping: viscous damping to ground c·l (lumped like the mass)
// and/or Kelvin–Voigt material damping τ, realised as a damper τ/n in parallel with every
// compliance n (the inductor's parallel conductance, stamped as τ times the rate of the
// spring force: elements/inductor.hpp), which gives exactly the damping matrix τ·K; a section
// may set its own c and τ.
// Ends: clamped (v = Ω = 0), pinned (v = 0), sliding (Ω = 0), free: tied to ground or left open.
// Point masses ([[mass]]): m on the velocity node, J on the rotation node at their position.
// Springs ([[spring]]): an inductor of compliance 1/k (with its dashpot as a conductance in
// parallel) between the node at `at` and ground or the node at `to`; translational between
// velocity nodes, rotational between rotation nodes. An end held by its support holds the
// spring's end there too (a spring between two held nodes does nothing and is left out).
//
// The model builder runs no analysis: the scene's "auto" keys (beam.segments, the fluid
// loading's resonance without environment.frequency, drive.electrical_dynamics) are resolved
// before it (resolve_scene or prepare_model, emnet/studies/resolve.hpp), and build_model refuses
// a scene that still has one.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "emnet/elements/dea.hpp"
#include "emnet/model/drive.hpp"
#include "emnet/model/fluid_loading.hpp"
#include "emnet/model/mesh.hpp"
#include "emnet/model/structure.hpp"
#include "emnet/network/network.hpp"
#include "emnet/network/output.hpp"
#include "emnet/network/waveform.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

/// The beam as add_beam built it: its mesh, nodes and shape functions.
struct BeamLayout {
  double length = 0.0;  ///< L [m]
  /// The uniform grid's segment length L/N (every segment's, when `uniform`); the mean otherwise.
  double segment_length = 0.0;
  bool uniform = true;                  ///< BeamMesh::uniform
  std::vector<double> x;                ///< node positions [m]
  std::vector<double> segment_lengths;  ///< per segment [m]
  std::vector<int> segment_section;     ///< per segment: its index in effective_sections(beam)
  /// Per segment: Φ = 12·EI/(κGA·l²), the shear parameter of its shape functions (0: Euler–
  /// Bernoulli).
  std::vector<double> shear_parameter;
  std::vector<NodeId> velocity;          ///< translational node per position (ground if held)
  std::vector<NodeId> angular_velocity;  ///< rotational node per position (ground if held)
  /// beam.kinematics: with large kinematics `velocity` is the fixed-frame y velocity and
  /// `axial_velocity` the x velocity per position (ground if held); empty for small.
  BeamKinematics kinematics = BeamKinematics::small;
  std::vector<NodeId> axial_velocity;
  int raised_from = 0;  ///< BeamMesh::raised_from
  /// The segment's shape functions over the segment holding x (cubic Hermite; with shear the
  /// shear-corrected cubics of the same exact massless segment):
  /// w(x) = Σ c·(w, ψ at the segment's ends); the same coefficients map v, Ω to v(x).
  LinearTerms deflection_terms(double x) const;
  /// ψ(x), the cross-section rotation (dw/dx without shear), from the same segment's solution.
  LinearTerms slope_terms(double x) const;
  /// dψ/dx, the curvature: the face strain is ∓z·dψ/dx.
  LinearTerms curvature_terms(double x) const;
  /// The node at x (to 1e-9 of the beam length); -1 when x is inside a segment.
  int node_at(double x) const;
};

/// The held ends whose reaction force is an output: with large kinematics their end segment
/// carries the force it draws from the end as two unknowns (corotational_segment.hpp), which the
/// reaction probes read; other networks have no such unknowns.
struct ReactionEnds {
  bool left = false, right = false;
};

/// Adds the beam chain, its point masses and springs to `network` (nodes from mesh_beam(beam,
/// attachments)), and the record of each node and element to `structure` when given.
/// @param attachments  positions along the beam that get a node [m]
/// @param reactions    large kinematics: the ends whose reaction force is an output
/// @throws std::logic_error as mesh_beam does
BeamLayout add_beam(Network& network, const BeamSpec& beam, const DampingSpec& damping,
                    const std::vector<double>& attachments = {},
                    ModelStructure* structure = nullptr, ReactionEnds reactions = {});

/// A DEA as the model builder built it: its nodes, values and coupling to the beam.
struct DeaLayout {
  std::string name;
  NodeId source_node = ground;        ///< electrical node behind the source
  NodeId electrode_node = ground;     ///< capacitor node (after the electrode resistance)
  double electrode_resistance = 0.0;  ///< R_e [Ω]
  double capacitance = 0.0;           ///< C₀ [F]
  double force_constant = 0.0;        ///< k_F [N/V²]
  /// Face elongation rate per across value: ẋ = Σ c·y[node] (the slopes at the span's ends
  /// times ∓ the lever arm), where its force enters the beam.
  std::vector<Dea::Coupling> coupling;
};

/// The network built from a resolved scene, with what each part of it stands for.
struct Model {
  Scene scene;                  ///< the resolved scene it was built from
  Network network;              ///< the network built
  ModelStructure structure;     ///< what each node and element of `network` is
  BeamLayout beam;              ///< the beam as built
  std::vector<DeaLayout> deas;  ///< the DEAs as built
  /// The [[circuit]]'s own nodes by their scene names (emnet/model/circuit.hpp); ground and the
  /// DEA terminals "dea.X" are not in it.
  std::map<std::string, NodeId> circuit_nodes;
  std::vector<Probe> probes;       ///< the scene's probes (a tip deflection probe if it has none)
  std::vector<std::string> notes;  ///< what was built and why, for the user
  std::vector<AutomaticChoice> automatic_choices;  ///< resolved "auto" keys, in the notes too
  /// [environment] fluid loading as stamped: m_a added to the beam's mass per length, c_a to its
  /// viscous damping per length (lumped like them); empty for environment.fluid = "none".
  struct AppliedFluidLoading {
    FluidLoading loading;           ///< as evaluated
    double vacuum_frequency = 0.0;  ///< [Hz] first undamped resonance of the bare beam
    int fixed_point_steps = 0;      ///< 0 when environment.frequency is given
  };
  std::optional<AppliedFluidLoading> fluid;  ///< see AppliedFluidLoading
  /// The probe `spec` describes, on this model's network.
  /// @throws InputError naming the probe when `spec` does not fit the model
  Probe make_probe(const ProbeSpec& spec) const;
  /// Parses "deflection@70mm", "velocity@0.1", "dea_current:A" or a probe name of the scene.
  /// @throws OptionError (emnet/core/option_error.hpp) naming the field "probe" and the text
  Probe parse_probe(const std::string& text) const;
  /// The DEA named `name`; nullptr when there is none.
  const DeaLayout* find_dea(const std::string& name) const;
};

/// The scene's "auto" keys that are not resolved yet, by their keys: "beam.segments",
/// "environment.frequency" (fluid loading without a frequency whose resonance is not found, or
/// was found for another beam or fluid: fluid_resonance_current), "drive.electrical_dynamics".
std::vector<std::string> unresolved_keys(const Scene& scene);
/// Whether scene.environment.resonance was found for the scene's beam and fluid as they are.
bool fluid_resonance_current(const Scene& scene);

/// Sader's loading (emnet/model/fluid_loading.hpp) of the scene's [environment] at `frequency`
/// [Hz].
/// @throws InputError naming "environment" when the values overflow it
FluidLoading scene_fluid_loading(const Scene& scene, double frequency);

/// The beam's mass per length averaged over its length (its sections').
double mean_mass_per_length(const BeamSpec& beam);
/// A load spread along the whole beam: mass and viscous damping per length added to the beam's
/// and every section's (a section's own viscous damping, where it has one, too).
/// @param mass_per_length     [kg/m]
/// @param damping_per_length  [N·s/m²]
void add_distributed_loading(BeamSpec& beam, DampingSpec& damping, double mass_per_length,
                             double damping_per_length);

/// The [environment] fluid loading of a resolved scene (at environment.frequency, else at
/// environment.resonance) applied to `beam` and `damping`: its added mass and damping per length
/// added to them, its note(s) appended to `notes`.
/// @throws InputError naming "environment" when the values overflow Sader's loading
/// @throws std::logic_error when neither environment.frequency nor environment.resonance is set
Model::AppliedFluidLoading apply_fluid_loading(const Scene& scene, BeamSpec& beam,
                                               DampingSpec& damping,
                                               std::vector<std::string>& notes);

/// drive.electrical_dynamics set to `on` in `scene`: "auto" cleared and the record of a choice
/// made for it dropped (a model of the result says what was set, not what was once chosen).
void set_electrical_dynamics(Scene& scene, bool on);

/// The network of a resolved scene (no "auto" left: unresolved_keys empty). Runs no analysis.
/// @throws std::logic_error naming the unresolved keys otherwise
/// @throws InputError for a scene that cannot be built (a probe of a DEA without an electrical
///         model, a fluid loading that cannot be evaluated)
Model build_model(const Scene& resolved_scene);

}  // namespace emnet
