// The resolve step: beam.segments, the fluid loading's resonance and
// drive.electrical_dynamics chosen for a scene (see include/emnet/studies/resolve.hpp).
#include "emnet/studies/resolve.hpp"

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "emnet/analysis/analysis.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/units.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "kinematics_choice.hpp"

namespace emnet {

namespace {

constexpr double pi = 3.14159265358979323846;

// First undamped resonance [Hz] of the bare beam chain (no damping, no DEAs).
double first_beam_resonance(const Scene& scene, const BeamSpec& beam) {
  Network network;
  BeamSpec small = beam;  // the linear chain: its resonance at rest is the same
  small.kinematics = BeamKinematics::small;
  add_beam(network, small, DampingSpec{}, scene_attachment_points(scene));
  const System system = network.assemble();
  ModalOptions options;
  options.count = 1;
  options.keep_vectors = false;
  const ModalResult result = run_modes(system, Eigen::VectorXd::Zero(system.size()), options);
  if (!result.status.ok() || result.modes.empty())
    throw InputError(
        scene.file, "environment.frequency",
        "the beam's first resonance, at which the fluid loading is evaluated, was "
        "not found (" +
            (result.status.ok() ? std::string("no oscillatory mode") : result.status.message) +
            "); give environment.frequency");
  return result.modes.front().frequency_hz;
}

// The loaded beam's first undamped resonance on `beam` (its N), by the fixed point
// f ← f₁(ρA + m_a(f)) from the bare beam's f₁; stops at a relative change of 1e-10.
EnvironmentSpec::Resonance find_fluid_resonance(const Scene& scene, const BeamSpec& beam) {
  const EnvironmentSpec& environment = scene.environment;
  EnvironmentSpec::Resonance resonance;
  resonance.vacuum_frequency = first_beam_resonance(scene, beam);
  double frequency = resonance.vacuum_frequency;
  constexpr int kMaximumSteps = 100;
  constexpr double kRelativeChange = 1e-10;
  for (int step = 1; step <= kMaximumSteps; ++step) {
    BeamSpec loaded = beam;
    DampingSpec no_damping;
    add_distributed_loading(loaded, no_damping,
                            scene_fluid_loading(scene, frequency).added_mass_per_length, 0.0);
    const double next = first_beam_resonance(scene, loaded);
    resonance.fixed_point_steps = step;
    const bool converged = std::abs(next - frequency) <= kRelativeChange * next;
    frequency = next;
    if (converged) break;
  }
  resonance.frequency = frequency;
  resonance.beam = beam;
  resonance.fluid = environment.fluid;
  resonance.density = environment.density;
  resonance.dynamic_viscosity = environment.dynamic_viscosity;
  resonance.width = environment.width;
  return resonance;
}

// beam.segments = "auto" on `beam` (bare or fluid-loaded): the chosen N into `beam`.
AutomaticChoice choose_segments(const Scene& scene, BeamSpec& beam, const std::string& what) {
  const BandOfInterest band = band_of_interest(scene, "beam.segments");
  SegmentSelection selection;
  try {
    selection = select_segments(beam, band.from, band.to, scene.model.tolerance, 20000,
                                scene_attachment_points(scene));
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& error) {
    throw InputError(scene.file, "beam.segments", error.what());
  }
  beam.segments = selection.segments;
  beam.auto_segments = false;
  AutomaticChoice choice;
  choice.key = "beam.segments";
  choice.value = std::to_string(selection.segments);
  choice.estimated_error = selection.estimated_error;
  choice.tolerance = scene.model.tolerance;
  choice.band_from_hz = band.from;
  choice.band_to_hz = band.to;
  choice.seconds = selection.seconds;
  choice.reason = "beam.segments = \"auto\"" + what + ": " + selection.summary() +
                  "; the smallest N meeting model.tolerance " +
                  format_number("%.3g", scene.model.tolerance) + " in the band " +
                  format_number("%.5g", band.from) + " to " + format_number("%.5g", band.to) +
                  " Hz (" + band.source + ")";
  return choice;
}

// drive.electrical_dynamics = "auto" (see the top comment): true keeps the RC dynamics.
AutomaticChoice choose_electrical_dynamics(const Scene& scene, bool electrical_probe_requested) {
  const auto start = std::chrono::steady_clock::now();
  AutomaticChoice choice;
  choice.key = "drive.electrical_dynamics";
  choice.tolerance = scene.model.tolerance;
  std::string asking;
  for (const ProbeSpec& probe : scene.probes)
    if (probe.quantity == ProbeQuantity::dea_voltage ||
        probe.quantity == ProbeQuantity::dea_current || probe.quantity == ProbeQuantity::dea_force)
      asking = "probe " + probe.name + " asks for " + probe_quantity_name(probe.quantity);
  if (asking.empty() && electrical_probe_requested)
    asking = "a probe asks for an electrical quantity";
  if (!scene.circuit.empty())  // a circuit acts through the electrical loops only
    asking = "the scene has [[circuit]] elements (" + std::to_string(scene.circuit.size()) +
             "), which act through the DEAs' electrical loops";
  bool keep = false;
  if (!asking.empty()) {
    keep = true;
    choice.reason = "kept: " + asking;
  } else if (scene.drive.kind == DriveKind::none || scene.deas.empty()) {
    choice.reason = "left out: no DEA is driven (drive.kind = none), the RC loop carries nothing";
  } else {
    const BandOfInterest band = band_of_interest(scene, "drive.electrical_dynamics");
    choice.band_from_hz = band.from;
    choice.band_to_hz = band.to;
    std::string which;
    const double tau = drive_time_constant(scene, &which);
    const double omega_tau = 2 * pi * band.to * tau;
    choice.estimated_error = omega_tau * omega_tau / 2;
    keep = choice.estimated_error > scene.model.tolerance;
    choice.reason = std::string(keep ? "kept" : "left out") +
                    ": RC time constant tau = R_e*C0 = " + format_number("%.4g", tau * 1e3) +
                    " ms (DEA " + which + "), band top f_high = " + format_number("%.5g", band.to) +
                    " Hz (" + band.source +
                    "): the ideal drive's amplitude error (2*pi*f_high*tau)^2/2 = " +
                    format_number("%.3g", choice.estimated_error) + (keep ? " > " : " <= ") +
                    "model.tolerance " + format_number("%.3g", scene.model.tolerance) +
                    " (phase lag 2*pi*f_high*tau = " + format_number("%.3g", omega_tau) + " rad)";
    const bool square_wave =
        scene.drive.kind == DriveKind::antagonistic || scene.drive.kind == DriveKind::switched;
    if (square_wave && band.to < 3 * scene.drive.frequency)
      choice.reason += "; the square wave's harmonics from 3f = " +
                       format_number("%.4g", 3 * scene.drive.frequency) +
                       " Hz lie above the band and are not counted";
    // What the choice changes: the time-domain analyses and the electrical probes; the ac
    // input of a square-wave drive is its force level applied directly, never through the loops.
    if (square_wave)
      choice.reason +=
          "; it matters to the time-domain analyses (tran, and the shooting method of the "
          "switching sweep) and to the DEA probes; ac's "
          "input for this drive is the force k_F*V^2/2 applied directly, not through the RC "
          "loops, so ac changes with this choice only through dea[].back_coupling";
  }
  choice.value = keep ? "true" : "false";
  choice.reason = "drive.electrical_dynamics = \"auto\": RC dynamics " + choice.reason;
  choice.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return choice;
}

}  // namespace

ResolvedScene resolve_scene(const Scene& scene, const ResolveOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ResolvedScene resolved;
  resolved.scene = scene;
  Scene& out = resolved.scene;
  const bool fluid = scene.environment.fluid != Fluid::none;
  const bool resonance_wanted = options.fluid_resonance && fluid && !scene.environment.frequency &&
                                !fluid_resonance_current(scene);
  bool resonance_found = false;
  if (options.segments && scene.beam.auto_segments) {
    BeamSpec beam = scene.beam;
    resolved.automatic_choices.push_back(choose_segments(scene, beam, ""));
    if (fluid) {
      // The fluid's added mass moves the modes relative to the band: choose again on the
      // loaded beam (the loading itself evaluated with the bare beam's N).
      double frequency = 0.0;
      std::optional<EnvironmentSpec::Resonance> resonance;
      if (scene.environment.frequency) {
        frequency = *scene.environment.frequency;
      } else {
        resonance = find_fluid_resonance(scene, beam);
        frequency = resonance->frequency;
      }
      BeamSpec loaded = beam;
      DampingSpec no_damping;
      add_distributed_loading(loaded, no_damping,
                              scene_fluid_loading(scene, frequency).added_mass_per_length, 0.0);
      loaded.auto_segments = true;
      resolved.automatic_choices.back() =
          choose_segments(scene, loaded, " on the fluid-loaded beam");
      beam.segments = loaded.segments;
      if (resonance && resonance_wanted) {
        // Found at the bare beam's N, it resolves the beam as built (the chosen N).
        resonance->beam = scene.beam;
        resonance->beam.segments = beam.segments;
        resonance->beam.auto_segments = false;
        out.environment.resonance = resonance;
        resonance_found = true;
      }
    }
    out.beam.segments = beam.segments;
    out.beam.auto_segments = false;
  } else if (resonance_wanted) {
    out.environment.resonance = find_fluid_resonance(scene, scene.beam);
    resonance_found = true;
  }
  if (options.electrical_dynamics && scene.drive.electrical_dynamics_auto) {
    resolved.automatic_choices.push_back(
        choose_electrical_dynamics(scene, options.electrical_probe_requested));
    out.drive.electrical_dynamics = resolved.automatic_choices.back().value == "true";
    out.drive.electrical_dynamics_auto = false;
  }
  if (options.kinematics && scene.beam.kinematics_auto && !out.beam.auto_segments &&
      !out.drive.electrical_dynamics_auto) {
    resolved.automatic_choices.push_back(choose_kinematics(out, options.large_kinematics));
    out.beam.kinematics = resolved.automatic_choices.back().value == "large"
                              ? BeamKinematics::large
                              : BeamKinematics::small;
    out.beam.kinematics_auto = false;
  }
  for (const AutomaticChoice& choice : resolved.automatic_choices)
    out.automatic_choices.push_back(choice);
  if (resonance_found) {  // its note(s), as the model prints them
    BeamSpec beam = out.beam;
    DampingSpec damping = out.damping;
    apply_fluid_loading(out, beam, damping, resolved.notes);
  }
  for (const AutomaticChoice& choice : resolved.automatic_choices)
    resolved.notes.push_back(choice.reason);
  resolved.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return resolved;
}

Scene resolve_segments(const Scene& scene) {
  if (!scene.beam.auto_segments) return scene;
  ResolveOptions segments_only;
  segments_only.fluid_resonance = false;
  segments_only.electrical_dynamics = false;
  return resolve_scene(scene, segments_only).scene;
}

Scene resolve_kinematics(const Scene& scene, LargeKinematicsUse use,
                         std::vector<std::string>* notes) {
  if (!scene.beam.kinematics_auto) return scene;
  // The choice needs the rest resolved (it runs the small network); only it is kept.
  ResolveOptions everything;
  everything.large_kinematics = use;
  const ResolvedScene resolved = resolve_scene(scene, everything);
  Scene chosen = scene;
  for (const AutomaticChoice& choice : resolved.automatic_choices)
    if (choice.key == "beam.kinematics") {
      chosen.beam.kinematics = resolved.scene.beam.kinematics;
      chosen.beam.kinematics_auto = false;
      chosen.automatic_choices.push_back(choice);
      if (notes) notes->push_back(choice.reason);
    }
  return chosen;
}

bool asks_for_dea_electrics(const std::string& probe_text) {
  return probe_text.rfind("dea_voltage", 0) == 0 || probe_text.rfind("dea_current", 0) == 0;
}

bool asks_for_dea_electrics(const std::vector<std::string>& probe_texts) {
  for (const auto& text : probe_texts)
    if (asks_for_dea_electrics(text)) return true;
  return false;
}

namespace {

// Refuses a large-kinematics scene the analysis does not serve (LargeKinematicsUse).
void require_served_kinematics(const Scene& scene, LargeKinematicsUse use) {
  if (scene.beam.kinematics != BeamKinematics::large) return;
  if (use == LargeKinematicsUse::refused)
    throw InputError(scene.file, "beam.kinematics",
                     "is \"large\", a nonlinear network, which this analysis does not serve "
                     "(the exact transient needs a linear one: IDA serves it)");
  if (use == LargeKinematicsUse::dynamics && !extensible(scene.beam))
    throw InputError(scene.file, "beam.axial_stiffness",
                     "is needed for modes, AC and transients with beam.kinematics = \"large\": "
                     "an inextensible beam with masses is a constrained mechanism (a DAE of index "
                     "3); give the axial stiffness EA (the static analysis takes an inextensible "
                     "beam)");
}

}  // namespace

PrepareOptions prepare_options_for_probes(const std::vector<std::string>& probe_texts) {
  PrepareOptions prepare;
  prepare.electrical_probe_requested = asks_for_dea_electrics(probe_texts);
  return prepare;
}

Model prepare_model(const Scene& scene, const PrepareOptions& options) {
  require_served_kinematics(scene, options.large_kinematics);
  ResolveOptions resolve;
  resolve.electrical_probe_requested = options.electrical_probe_requested;
  resolve.large_kinematics = options.large_kinematics;
  return build_model(resolve_scene(scene, resolve).scene);
}

}  // namespace emnet
