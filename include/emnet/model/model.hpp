// From a resolved Scene to a Network: the beam chain, the DEA patches and their drive, loads,
// probes, with a record of what each element is (emnet/model/structure.hpp).
//
// The beam: N equal massless segments of length l = L/N, each realised exactly as
//   - a rotational compliance n_R = l/EI between the rotation nodes r_k and r_k+1;
//   - a translational branch v_k → n_T = l³/(12·EI) → m_k → lever → v_k+1, the lever being an
//     ideal transformer whose secondary adds (l/2)·(Ω_k + Ω_k+1) and whose primaries feed the
//     branch force back as torques (l/2)·F into both rotation nodes.
// Its flexibility equals the cubic Hermite element's, so nodal statics are exact for every N.
// Mass lumping rule: half of each segment's mass ρA·l to each of its two end nodes (a
// capacitor from the velocity node to ground); optional rotary inertia ρI·l lumped the same
// way onto the rotation nodes. Damping: viscous damping to ground c·l (lumped like the mass)
// and/or Kelvin–Voigt material damping τ, realised as a damper τ/n in parallel with every
// compliance n (the inductor's parallel conductance, stamped as τ times the rate of the
// spring force: elements/inductor.hpp), which gives exactly the damping matrix τ·K.
// Ends: clamped (v = Ω = 0), pinned (v = 0), sliding (Ω = 0), free: tied to ground or left open.
//
// The model builder runs no analysis: the scene's "auto" keys (beam.segments, the fluid
// loading's resonance without environment.frequency, drive.electrical_dynamics) are resolved
// before it (resolve_scene or prepare_model, emnet/studies/resolve.hpp), and build_model refuses
// a scene that still has one.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "emnet/elements/dea.hpp"
#include "emnet/model/drive.hpp"
#include "emnet/model/fluid_loading.hpp"
#include "emnet/model/structure.hpp"
#include "emnet/network/network.hpp"
#include "emnet/network/output.hpp"
#include "emnet/network/waveform.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

struct BeamLayout {
  double length = 0.0;
  double segment_length = 0.0;
  std::vector<double> x;                 // node positions [m]
  std::vector<NodeId> velocity;          // translational node per position (ground if held)
  std::vector<NodeId> angular_velocity;  // rotational node per position (ground if held)
  // Cubic Hermite interpolation over the segment holding x:
  // w(x) = Σ c·(w, φ at the segment's ends); the same coefficients map v, Ω to v(x).
  LinearTerms deflection_terms(double x) const;
  // φ(x) = dw/dx from the derivatives of the same shape functions.
  LinearTerms slope_terms(double x) const;
};

// Adds the beam chain to `network`, and the record of each node and element to `structure`
// when given.
BeamLayout add_beam(Network& network, const BeamSpec& beam, const DampingSpec& damping,
                    ModelStructure* structure = nullptr);

struct DeaLayout {
  std::string name;
  NodeId source_node = ground;     // electrical node behind the source
  NodeId electrode_node = ground;  // capacitor node (after the electrode resistance)
  double electrode_resistance = 0.0;
  double capacitance = 0.0;
  double force_constant = 0.0;  // k_F [N/V²]
  // Face elongation rate per across value: ẋ = Σ c·y[node] (the slopes at the span's ends
  // times ∓ the lever arm), where its force enters the beam.
  std::vector<Dea::Coupling> coupling;
};

struct Model {
  Scene scene;  // the resolved scene it was built from
  Network network;
  ModelStructure structure;  // what each node and element of `network` is
  BeamLayout beam;
  std::vector<DeaLayout> deas;
  std::vector<Probe> probes;       // the scene's probes (a tip deflection probe if it has none)
  std::vector<std::string> notes;  // what was built and why, for the user
  std::vector<AutomaticChoice> automatic_choices;  // resolved "auto" keys, in the notes too
  // [environment] fluid loading as stamped: m_a added to the beam's mass per length, c_a to its
  // viscous damping per length (lumped like them); empty for environment.fluid = "none".
  struct AppliedFluidLoading {
    FluidLoading loading;
    double vacuum_frequency = 0.0;  // [Hz] first undamped resonance of the bare beam
    int fixed_point_steps = 0;      // 0 when environment.frequency is given
  };
  std::optional<AppliedFluidLoading> fluid;
  Probe make_probe(const ProbeSpec& spec) const;
  // Parses "deflection@70mm", "velocity@0.1", "dea_current:A" or a probe name of the scene.
  Probe parse_probe(const std::string& text) const;
  // The DEA named `name`; nullptr when there is none.
  const DeaLayout* find_dea(const std::string& name) const;
};

// The scene's "auto" keys that are not resolved yet, by their keys: "beam.segments",
// "environment.frequency" (fluid loading without a frequency whose resonance is not found, or
// was found for another beam or fluid: fluid_resonance_current), "drive.electrical_dynamics".
std::vector<std::string> unresolved_keys(const Scene& scene);
// Whether scene.environment.resonance was found for the scene's beam and fluid as they are.
bool fluid_resonance_current(const Scene& scene);

// Sader's loading (emnet/model/fluid_loading.hpp) of the scene's [environment] at `frequency`
// [Hz]; an InputError naming "environment" when the values overflow it.
FluidLoading scene_fluid_loading(const Scene& scene, double frequency);

// The [environment] fluid loading of a resolved scene (at environment.frequency, else at
// environment.resonance) applied to `beam` and `damping`: its added mass and damping per length
// added to them, its note(s) appended to `notes`.
Model::AppliedFluidLoading apply_fluid_loading(const Scene& scene, BeamSpec& beam,
                                               DampingSpec& damping,
                                               std::vector<std::string>& notes);

// drive.electrical_dynamics set to `on` in `scene`: "auto" cleared and the record of a choice
// made for it dropped (a model of the result says what was set, not what was once chosen).
void set_electrical_dynamics(Scene& scene, bool on);

// The network of a resolved scene (no "auto" left: unresolved_keys empty). Runs no analysis.
// Throws std::logic_error naming the unresolved keys otherwise, InputError for a scene that
// cannot be built (a probe of a DEA without an electrical model, a fluid loading that cannot
// be evaluated).
Model build_model(const Scene& resolved_scene);

}  // namespace emnet
