// The resolve step: a scene's "auto" keys chosen, before the model builder (which runs no
// analysis) turns the resolved scene into a network.
//
// What it resolves, each recorded in the resolved scene (Scene::automatic_choices and
// EnvironmentSpec::resonance) so that a model rebuilt from it is the same:
//
// beam.segments = "auto": N from select_segments (emnet/studies/segment_selection.hpp) on the
// bare beam with the band of interest; with fluid loading, chosen again on the loaded beam (the
// loading evaluated with the bare beam's N, see below).
//
// The fluid loading's frequency ([environment] without environment.frequency): Sader's
// hydrodynamic function is taken at the loaded beam's first undamped resonance, found by the
// fixed point f ← f₁(ρA + m_a(f)) from the bare beam's f₁ (it contracts fast: m_a varies with f
// only through Γ_r(Re), weakly; stops at a relative change of 1e-10), each f₁ a modal solve of
// the bare beam chain (no damping, no DEAs) at the scene's N.
//
// drive.electrical_dynamics = "auto": the RC loop (electrode resistance R_e, capacitance C₀)
// makes the capacitor voltage a first-order lag of the source, V_C = V_s/(1 + jωτ), τ = R_e·C₀.
// Its amplitude is |V_C/V_s| = 1/√(1 + (ωτ)²) ≈ 1 − (ωτ)²/2, so the ideal drive (V_C = V_s)
// overstates the voltage amplitude at ω by about (ωτ)²/2 relative (the phase lag ωτ is a
// delay of about τ, which shifts a periodic response in time but not its amplitude). The
// RC dynamics are kept when the scene has [[circuit]] elements (they act through the loops
// only), when (a) a probe asks for dea_voltage, dea_current or dea_force, or (b) this
// error at the band's top, (2π·f_high·τ)²/2 with the largest τ of the driven DEAs, exceeds
// model.tolerance; otherwise the ideal drive is built. (About a bias the force's alternating
// part 2k_F·V₀·v_C has the voltage's relative error; for a 0/V pulse, whose square follows
// (1 − e^(−t/τ))², each harmonic's error is of the same order.) The estimate counts the band
// only: a square wave's harmonics above f_high are not counted, and the note says so when
// f_high < 3f. Measured on the fish fin switched at 5 Hz, the ideal drive moves the periodic
// peaks by 8.3e-4 of the peak (tools/bench 5a), which an 8 Hz band's estimate, 9.1e-4, only
// just covers and a 6 Hz band's, 5.1e-4, does not.
#pragma once

#include <string>
#include <vector>

#include "emnet/model/model.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

/// What the analysis a model is prepared for does with beam.kinematics = "large" (docs/model.md,
/// Large deflection): prepare_model refuses a scene the analysis does not serve, naming the key,
/// so that no analysis runs the co-rotational network it has not been checked on.
enum class LargeKinematicsUse {
  refused,       ///< not served (the exact transient: it needs a linear network)
  static_state,  ///< the static analysis: any beam, inextensible included
  /// modes, AC and IDA transients: every segment needs an axial stiffness EA, because an
  /// inextensible beam with masses is a constrained mechanism (a DAE of index 3) that the time
  /// integration and the poles' error bounds do not take
  dynamics,
};

struct ResolveOptions {
  // A probe outside the scene (the command line's --probe) asks for dea_voltage, dea_current or
  // dea_force, which drive.electrical_dynamics = "auto" must then keep.
  bool electrical_probe_requested = false;
  // What to resolve; a key left out keeps its "auto" (a later resolve chooses it for the scene
  // as it is then: the command line fixes N once per command, and chooses the rest for each
  // scene it builds, after its own changes to the scene).
  bool segments = true;
  bool fluid_resonance = true;
  bool electrical_dynamics = true;
  bool kinematics = true;
  // What the analysis serves, for beam.kinematics = "auto" (small where large is refused).
  LargeKinematicsUse large_kinematics = LargeKinematicsUse::refused;
};

struct ResolvedScene {
  // The scene with the asked "auto" keys resolved; its automatic_choices are the scene's
  // earlier ones followed by those made here.
  Scene scene;
  std::vector<AutomaticChoice> automatic_choices;  // made here, in order
  // What was resolved, in words, as the model built from `scene` prints it: the fluid loading's
  // note(s) when its frequency was resolved here, then each new choice's reason.
  std::vector<std::string> notes;
  double seconds = 0.0;
};

// Throws InputError naming the key when a choice cannot be made (no band for "auto", a modal
// solve that fails, the fluid's resonance not found).
ResolvedScene resolve_scene(const Scene& scene, const ResolveOptions& options = {});

/// The scene with beam.segments = "auto" chosen and nothing else resolved: what a front-end
/// does once per run, so that every model it then builds from the scene (sweeps, fits, finite
/// differences, variants) has the same N; the fluid loading's resonance and
/// drive.electrical_dynamics = "auto" stay to be chosen for each scene built. A scene without
/// "auto" segments is returned as it is.
/// @throws InputError as resolve_scene, when N cannot be chosen
Scene resolve_segments(const Scene& scene);

/// The scene with beam.kinematics = "auto" chosen for an analysis that serves `use` and nothing
/// else resolved: what a study does once on its nominal scene, so that every scene it derives
/// (finite differences, variants, fits) keeps the same network instead of choosing again near
/// the threshold. A scene without "auto" kinematics is returned as it is.
/// @param notes  when given, the choice's reason is appended
/// @throws InputError as resolve_scene
Scene resolve_kinematics(const Scene& scene, LargeKinematicsUse use,
                         std::vector<std::string>* notes = nullptr);

/// Whether a probe text asks for a DEA's electrical quantity, "dea_voltage…" or "dea_current…"
/// (emnet/model/model.hpp, Model::parse_probe): the RC loop of the DEA must then be modelled.
bool asks_for_dea_electrics(const std::string& probe_text);
/// Whether any of `probe_texts` does.
bool asks_for_dea_electrics(const std::vector<std::string>& probe_texts);

struct PrepareOptions {
  bool electrical_probe_requested = false;                            // as ResolveOptions
  LargeKinematicsUse large_kinematics = LargeKinematicsUse::refused;  ///< see LargeKinematicsUse
};

/// The PrepareOptions of an analysis that serves large kinematics as `use`, the rest default.
inline PrepareOptions serving_large_kinematics(LargeKinematicsUse use) {
  PrepareOptions prepare;
  prepare.large_kinematics = use;
  return prepare;
}

/// The PrepareOptions of a run that asks for `probe_texts`: the RC dynamics kept when one of
/// them asks for a DEA's electrical quantity (asks_for_dea_electrics).
PrepareOptions prepare_options_for_probes(const std::vector<std::string>& probe_texts);

/// resolve_scene (everything) then build_model: the model of any read scene.
/// @throws InputError naming beam.kinematics for a large-kinematics scene the analysis does not
///   serve (options.large_kinematics), beam.axial_stiffness for an inextensible one it serves
///   only with EA, and as resolve_scene and build_model
Model prepare_model(const Scene& scene, const PrepareOptions& options = {});

}  // namespace emnet
