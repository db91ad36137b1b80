// From a Scene to a Network: the beam chain, the DEA patches and their drive, loads, probes.
//
// The beam (DESIGN §2): N equal massless segments of length l = L/N, each realised exactly as
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
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "emnet/model/fluid_loading.hpp"
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
  // Cubic Hermite interpolation over the segment holding x (DESIGN §5):
  // w(x) = Σ c·(w, φ at the segment's ends); the same coefficients map v, Ω to v(x).
  LinearTerms deflection_terms(double x) const;
  // φ(x) = dw/dx from the derivatives of the same shape functions.
  LinearTerms slope_terms(double x) const;
};

// Adds the beam chain to `network`.
BeamLayout add_beam(Network& network, const BeamSpec& beam, const DampingSpec& damping);

struct DeaLayout {
  std::string name;
  NodeId source_node = ground;     // electrical node behind the source
  NodeId electrode_node = ground;  // capacitor node (after the electrode resistance)
  double electrode_resistance = 0.0;
  double capacitance = 0.0;
  double force_constant = 0.0;  // k_F [N/V²]
};

struct Model {
  Scene scene;
  Network network;
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
};

// What a drive applies to DEA `dea_name` (src/model/model.cpp says why): its source voltage
// (constant 0 for a DEA the drive does not name) and, for the square-wave drives, the factor f
// of its AC force input f·k_F·V² (±1/2; 0 for the sine drives, whose AC input is the source's
// own amplitude v).
struct DeaDrive {
  Waveform voltage;
  double ac_force_factor = 0.0;
};
DeaDrive dea_drive(const DriveSpec& drive, const std::string& dea_name);

// The largest RC time constant R_e·C₀ [s] of the DEAs the drive names (0 when it names none);
// `which`, when given, receives that DEA's name.
double drive_time_constant(const Scene& scene, std::string* which = nullptr);

// `electrical_probe_requested`: a probe outside the scene (the command line's --probe) asks for
// dea_voltage or dea_current, which drive.electrical_dynamics = "auto" must then keep.
Model build_model(const Scene& scene, bool electrical_probe_requested = false);

}  // namespace emnet
