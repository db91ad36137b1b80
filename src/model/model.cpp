// Scene → Network: beam, DEA patches with their electrical loop and drive, loads, probes.
//
// DEA electrical loop, per DEA X:  source s_X —[electrode resistance]— e_X —[C₀ + transducer]— 0
// Drives (dea_drive):
//   antagonistic       A: 0/V square wave on for the first `duty` of each period, B the rest;
//                      A's on-time lengthened by `overlap` (both on together; < 0: a dead time).
//                      Static / at rest: A on (the sources at t = 0).
//   switched           one DEA: 0/V square wave on for the first `duty` of each period (how a
//                      unimorph is driven). Static / at rest: on.
//   bias_differential  V_A = V₀ + v·sin(2πft), V_B = V₀ − v·sin(2πft); AC input: v on A, −v on
//                      B, the network linearised at V₀ (moment exactly linear in v).
//   single             V = V₀ + v·sin(2πft) on one DEA; AC input v, linearised at V₀.
// AC input of the square-wave drives. A voltage switched between 0 and V is two-level, so its
// square is V times itself: the force k_F·V(t)² = k_F·V·V(t) is exactly a 0/k_F·V² square wave,
// linear in the switching function, with no linearisation about an operating voltage (which
// at 0 V would give no force and at V twice the swing). Its alternating part, ±k_F·V²/2 about
// the mean k_F·V²/2, is the AC input (one sinusoid of amplitude k_F·V²/2 per DEA; A and B in
// antiphase for the antagonistic pair, whose means cancel); the response to the square wave's
// fundamental is 4/π times the AC result. The input is this force applied directly, not
// through the RC loops, whatever drive.electrical_dynamics: through a loop the capacitor
// voltage is a first-order lag, and the force's fundamental is the same times 1/(1 + jωτ)
// (exactly at duty 0.5 for τ ≪ T: the square of the lagged wave differs from V times it only
// by equal pulses at both edges, which repeat every half period and have no fundamental); the
// AC result leaves this factor out, (ωτ)²/2 in amplitude and ωτ in phase. The network is
// linearised at the static state (the sources at t = 0), which matters only to the
// back-coupling gyrator K = 2·k_F·U₀ of a DEA that asks for it.
// A DEA not named by the drive has its source node tied to ground through its resistance.
//
// drive.electrical_dynamics = "auto": the RC loop (electrode resistance R_e, capacitance C₀)
// makes the capacitor voltage a first-order lag of the source, V_C = V_s/(1 + jωτ), τ = R_e·C₀.
// Its amplitude is |V_C/V_s| = 1/√(1 + (ωτ)²) ≈ 1 − (ωτ)²/2, so the ideal drive (V_C = V_s)
// overstates the voltage amplitude at ω by about (ωτ)²/2 relative (the phase lag ωτ is a
// delay of about τ, which shifts a periodic response in time but not its amplitude). The
// RC dynamics are kept when (a) a probe asks for dea_voltage or dea_current, or (b) this
// error at the band's top, (2π·f_high·τ)²/2 with the largest τ of the driven DEAs, exceeds
// model.tolerance; otherwise the ideal drive is built. (About a bias the force's alternating
// part 2k_F·V₀·v_C has the voltage's relative error; for a 0/V pulse, whose square follows
// (1 − e^(−t/τ))², each harmonic's error is of the same order.) The estimate counts the band
// only: a square wave's harmonics above f_high are not counted, and the note says so when
// f_high < 3f. Measured on the fish fin switched at 5 Hz, the ideal drive moves the periodic
// peaks by 8.3e-4 of the peak (tools/bench 5a), which an 8 Hz band's estimate, 9.1e-4, only
// just covers and a 6 Hz band's, 5.1e-4, does not.
//
// beam.segments = "auto": N from segment_selection (emnet/model/segment_selection.hpp) on the bare
// beam with the band of interest; with fluid loading, chosen again on the loaded beam.
#include "emnet/model/model.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "emnet/analysis/analysis.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/elements/voltage_source.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/model/segment_selection.hpp"
#include "emnet/core/units.hpp"

namespace emnet {

namespace {

constexpr double pi = 3.14159265358979323846;

std::string position_text(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "x = %.4g mm", x * 1e3);
  return buffer;
}

const DeaLayout* find_dea(const std::vector<DeaLayout>& deas, const std::string& name) {
  for (const auto& dea : deas)
    if (dea.name == name) return &dea;
  return nullptr;
}

// F(t) = k_F·V(t)² for a source waveform V, as waveforms: a pulse stays a pulse (0/V → 0/k_F·V²
// when its low level is 0); V0 + v·sin(ωt) squares to k_F·(V0² + v²/2) + 2k_F·V0·v·sin(ωt)
// − k_F·(v²/2)·cos(2ωt). The first waveform carries the AC input: `ac_force` for the
// antagonistic drive, the linearisation 2k_F·V0·v for sine drives.
std::vector<Waveform> squared_force(const Waveform& voltage, double force_constant,
                                    double ac_force) {
  if (voltage.shape == Waveform::Shape::sine) {
    Waveform fundamental = voltage;
    fundamental.dc =
        force_constant * (voltage.dc * voltage.dc + voltage.amplitude * voltage.amplitude / 2);
    fundamental.amplitude = 2 * force_constant * voltage.dc * voltage.amplitude;
    fundamental.ac_magnitude = 2 * force_constant * voltage.dc * voltage.ac_magnitude;
    Waveform harmonic = voltage;
    harmonic.dc = 0.0;
    harmonic.frequency = 2 * voltage.frequency;
    harmonic.amplitude = -force_constant * voltage.amplitude * voltage.amplitude / 2;
    harmonic.phase = 2 * voltage.phase + pi / 2;
    harmonic.ac_magnitude = 0.0;
    return {fundamental, harmonic};
  }
  Waveform force = voltage;  // pulse or constant with a zero low level
  force.dc = force_constant * voltage.dc * voltage.dc;
  force.pulse_high = force_constant * voltage.pulse_high * voltage.pulse_high;
  force.ac_magnitude = ac_force;
  force.ac_phase = 0.0;
  return {force};
}

// First undamped resonance [Hz] of the bare beam chain (no damping, no DEAs).
double first_beam_resonance(const Scene& scene, const BeamSpec& beam) {
  Network network;
  add_beam(network, beam, DampingSpec{});
  const System system = network.assemble();
  ModalOptions options;
  options.count = 1;
  options.keep_vectors = false;
  const ModalResult result = run_modes(system, Eigen::VectorXd::Zero(system.size()), options);
  if (!result.status.ok || result.modes.empty())
    throw InputError(
        scene.file, "environment.frequency",
        "the beam's first resonance, at which the fluid loading is evaluated, was "
        "not found (" +
            (result.status.ok ? std::string("no oscillatory mode") : result.status.message) +
            "); give environment.frequency");
  return result.modes.front().frequency_hz;
}

// [environment]: Sader's added mass m_a and damping c_a per length (emnet/model/fluid_loading.hpp),
// added to the beam's mass and viscous damping per length. Γ is taken at environment.frequency,
// or else at the first undamped resonance of the loaded beam, found by the fixed point
// f ← f₁(ρA + m_a(f)) from the bare beam's f₁ (it contracts fast: m_a varies with f only
// through Γ_r(Re), weakly; stops at a relative change of 1e-10).
Model::AppliedFluidLoading apply_fluid_loading(const Scene& scene, BeamSpec& beam,
                                               DampingSpec& damping,
                                               std::vector<std::string>& notes) {
  const EnvironmentSpec& environment = scene.environment;
  Model::AppliedFluidLoading applied;
  auto loading_at = [&](double frequency) {
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
  };
  std::string where;
  if (environment.frequency) {
    applied.loading = loading_at(*environment.frequency);
    where = "environment.frequency";
  } else {
    applied.vacuum_frequency = first_beam_resonance(scene, beam);
    double frequency = applied.vacuum_frequency;
    constexpr int kMaximumSteps = 100;
    constexpr double kRelativeChange = 1e-10;
    for (int step = 1; step <= kMaximumSteps; ++step) {
      BeamSpec loaded = beam;
      loaded.mass_per_length += loading_at(frequency).added_mass_per_length;
      const double next = first_beam_resonance(scene, loaded);
      applied.fixed_point_steps = step;
      const bool converged = std::abs(next - frequency) <= kRelativeChange * next;
      frequency = next;
      if (converged) break;
    }
    applied.loading = loading_at(frequency);
    where = "the loaded beam's first undamped resonance (fixed point in " +
            std::to_string(applied.fixed_point_steps) + " steps from the bare beam's " +
            format_number("%.4g", applied.vacuum_frequency) + " Hz)";
  }
  const FluidLoading& loading = applied.loading;
  notes.push_back(std::string("fluid loading, ") + fluid_name(environment.fluid) +
                  " (rho = " + format_number("%.5g", environment.density) +
                  " kg/m^3, eta = " + format_number("%.4g", environment.dynamic_viscosity) +
                  " Pa*s, plate width " + format_number("%.4g", environment.width * 1e3) +
                  " mm), Sader 1998: at " + format_number("%.5g", loading.frequency) + " Hz, " +
                  where + ": Re = " + format_number("%.4g", loading.reynolds) +
                  ", Gamma = " + format_number("%.5g", loading.hydrodynamic.real()) + " + " +
                  format_number("%.4g", loading.hydrodynamic.imag()) + "i; added mass " +
                  format_number("%.4g", loading.added_mass_per_length * 1e3) + " g/m (" +
                  format_number("%.3g", loading.added_mass_per_length / beam.mass_per_length) +
                  " x the beam's), damping " + format_number("%.4g", loading.damping_per_length) +
                  " N*s/m^2 to ground");
  if (loading.reynolds < kSaderCorrectionMinimumReynolds ||
      loading.reynolds > kSaderCorrectionMaximumReynolds)
    notes.push_back("fluid loading: Re = " + format_number("%.3g", loading.reynolds) +
                    " lies outside [1e-6, 1e4], where Sader's rectangular correction is fitted; "
                    "it is extrapolated");
  beam.mass_per_length += loading.added_mass_per_length;
  damping.viscous_per_length += loading.damping_per_length;
  return applied;
}

// beam.segments = "auto" on `beam` (bare or fluid-loaded): the chosen N into `beam`.
AutomaticChoice choose_segments(const Scene& scene, BeamSpec& beam, const std::string& what) {
  const BandOfInterest band = band_of_interest(scene, "beam.segments");
  SegmentSelection selection;
  try {
    selection = select_segments(beam, band.from, band.to, scene.model.tolerance);
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
        probe.quantity == ProbeQuantity::dea_current)
      asking = "probe " + probe.name + " asks for " + probe_quantity_name(probe.quantity);
  if (asking.empty() && electrical_probe_requested)
    asking = "a --probe asks for an electrical quantity";
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
          "; it matters to tran, sweep-switching --method shooting and the DEA probes; ac's "
          "input for this drive is the force k_F*V^2/2 applied directly, not through the RC "
          "loops, so ac changes with this choice only through dea[].back_coupling";
  }
  choice.value = keep ? "true" : "false";
  choice.reason = "drive.electrical_dynamics = \"auto\": RC dynamics " + choice.reason;
  choice.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return choice;
}

// The probe `spec` on `model`'s beam and DEAs; `dea` is the DEA an electrical probe names
// (nullptr when there is none of that name).
Probe make_probe_on(const Model& model, const ProbeSpec& spec, const DeaLayout* dea);

}  // namespace

DeaDrive dea_drive(const DriveSpec& drive, const std::string& dea_name) {
  DeaDrive driven;
  driven.voltage = Waveform::constant(0.0);
  const auto& names = drive.deas;
  const int role = names.empty()                                ? -1
                   : dea_name == names[0]                       ? 0
                   : (names.size() > 1 && dea_name == names[1]) ? 1
                                                                : -1;
  if (role < 0 || drive.kind == DriveKind::none) return driven;
  const double period = 1.0 / drive.frequency;
  Waveform& w = driven.voltage;
  switch (drive.kind) {
    case DriveKind::antagonistic:
      w = role == 0
              ? Waveform::square(0.0, drive.voltage, drive.frequency,
                                 drive.duty + drive.overlap * drive.frequency, 0.0, drive.rise_time)
              : Waveform::square(0.0, drive.voltage, drive.frequency, 1.0 - drive.duty,
                                 drive.duty * period, drive.rise_time);
      driven.ac_force_factor = role == 0 ? 0.5 : -0.5;  // × k_F·V²
      break;
    case DriveKind::switched:
      w = Waveform::square(0.0, drive.voltage, drive.frequency, drive.duty, 0.0, drive.rise_time);
      driven.ac_force_factor = 0.5;  // × k_F·V²: the force's ±level about its mean k_F·V²/2
      break;
    case DriveKind::bias_differential:
    case DriveKind::single:
      w.shape = Waveform::Shape::sine;
      w.dc = drive.bias;
      w.amplitude = role == 0 ? drive.amplitude : -drive.amplitude;
      w.frequency = drive.frequency;
      w.ac_magnitude = drive.amplitude;
      w.ac_phase = role == 0 ? 0.0 : pi;
      break;
    case DriveKind::none:
      break;
  }
  return driven;
}

double drive_time_constant(const Scene& scene, std::string* which) {
  double tau = 0.0;
  for (const DeaSpec& spec : scene.deas) {
    if (std::find(scene.drive.deas.begin(), scene.drive.deas.end(), spec.name) ==
        scene.drive.deas.end())
      continue;
    const double capacitance =
        dea_capacitance(spec.relative_permittivity, spec.dielectric_thickness, spec.electrode_width,
                        spec.to - spec.from);
    if (spec.electrode_resistance * capacitance > tau) {
      tau = spec.electrode_resistance * capacitance;
      if (which) *which = spec.name;
    }
  }
  return tau;
}

Model build_model(const Scene& scene, bool electrical_probe_requested) {
  Model model;
  model.scene = scene;
  Network& network = model.network;
  BeamSpec beam_spec = scene.beam;
  DampingSpec damping = scene.damping;
  model.automatic_choices = scene.automatic_choices;
  if (beam_spec.auto_segments) {
    model.automatic_choices.push_back(choose_segments(scene, beam_spec, ""));
    if (scene.environment.fluid != Fluid::none) {
      // The fluid's added mass moves the modes relative to the band: choose again on the
      // loaded beam (the loading itself was evaluated with the bare beam's N).
      model.fluid = apply_fluid_loading(scene, beam_spec, damping, model.notes);
      beam_spec.auto_segments = true;
      model.automatic_choices.back() =
          choose_segments(scene, beam_spec, " on the fluid-loaded beam");
    }
    model.scene.beam.segments = beam_spec.segments;
    model.scene.beam.auto_segments = false;
    model.scene.automatic_choices = model.automatic_choices;
  } else if (scene.environment.fluid != Fluid::none) {
    model.fluid = apply_fluid_loading(scene, beam_spec, damping, model.notes);
  }
  if (scene.drive.electrical_dynamics_auto) {
    model.automatic_choices.push_back(
        choose_electrical_dynamics(scene, electrical_probe_requested));
    // The choice into the model's scene, resolved: code that sets electrical_dynamics on a
    // copy of it (an ideal-drive variant) gets what it sets.
    model.scene.drive.electrical_dynamics = model.automatic_choices.back().value == "true";
    model.scene.drive.electrical_dynamics_auto = false;
  }
  for (const AutomaticChoice& choice : model.automatic_choices)
    model.notes.push_back(choice.reason);
  model.beam = add_beam(network, beam_spec, damping);
  const BeamLayout& beam = model.beam;

  // Point loads: consistent nodal loads from the Hermite shape functions, exact at the nodes.
  int load_index = 0;
  for (const LoadSpec& load : scene.loads) {
    const LinearTerms terms =
        load.kind == LoadKind::force ? beam.deflection_terms(load.at) : beam.slope_terms(load.at);
    for (const auto& [node, coefficient] : terms) {
      Waveform w = Waveform::constant(load.value * coefficient);
      w.ac_magnitude = load.value * coefficient;
      network.add<CurrentSource>(
          "load" + std::to_string(load_index) + "_" + network.node(node).name, ground, node, w);
    }
    ++load_index;
  }

  const DriveSpec& drive = model.scene.drive;
  for (const DeaSpec& spec : scene.deas) {
    DeaLayout layout;
    layout.name = spec.name;
    layout.electrode_resistance = spec.electrode_resistance;
    layout.capacitance = dea_capacitance(spec.relative_permittivity, spec.dielectric_thickness,
                                         spec.electrode_width, spec.to - spec.from);
    layout.force_constant =
        dea_force_constant(spec.relative_permittivity, spec.dielectric_thickness,
                           spec.force_thickness, spec.electrode_width);
    // Face elongation rate ẋ = s·z·(Ω(x1) − Ω(x0)), s = −1 on the top face, +1 on the bottom.
    const double sign = spec.face == Face::top ? -1.0 : 1.0;
    std::vector<Dea::Coupling> coupling;
    for (const auto& [node, c] : beam.slope_terms(spec.to))
      coupling.push_back({node, sign * spec.lever_arm * c});
    for (const auto& [node, c] : beam.slope_terms(spec.from))
      coupling.push_back({node, -sign * spec.lever_arm * c});
    const DeaDrive driven = dea_drive(drive, spec.name);
    const Waveform& source = driven.voltage;
    const double ac_force =
        driven.ac_force_factor * layout.force_constant * drive.voltage * drive.voltage;

    if (!drive.electrical_dynamics) {
      // Ideal voltage-driven force F(t) = k_F·V(t)², entered as through sources along the
      // coupling: a linear network.
      for (const Waveform& force : squared_force(source, layout.force_constant, ac_force))
        for (const auto& c : coupling)
          network.add<CurrentSource>("F_" + spec.name + "_" + network.node(c.node).name, ground,
                                     c.node, force.scaled(c.coefficient));
      model.deas.push_back(layout);
      continue;
    }
    layout.source_node = network.add_node("s_" + spec.name, Domain::electrical,
                                          "DEA " + spec.name + " source terminal [V]");
    layout.electrode_node = network.add_node("e_" + spec.name, Domain::electrical,
                                             "DEA " + spec.name + " capacitor voltage [V]");
    network.add<VoltageSource>("V_" + spec.name, layout.source_node, ground, source,
                               Domain::electrical);
    network.add<Conductance>("Re_" + spec.name, layout.source_node, layout.electrode_node,
                             1.0 / spec.electrode_resistance);
    network.add<Dea>("dea_" + spec.name, layout.electrode_node, ground, layout.capacitance,
                     layout.force_constant, coupling, spec.back_coupling, ac_force);
    model.deas.push_back(layout);
  }
  if (!drive.electrical_dynamics && !scene.deas.empty())
    model.notes.push_back(
        std::string("DEA electrical dynamics left out (drive.electrical_dynamics = ") +
        (scene.drive.electrical_dynamics_auto ? "\"auto\"" : "false") +
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
  return model;
}

Probe Model::make_probe(const ProbeSpec& spec) const {
  return make_probe_on(*this, spec, find_dea(deas, spec.dea));
}

namespace {

Probe make_probe_on(const Model& model, const ProbeSpec& spec, const DeaLayout* dea) {
  const BeamLayout& beam = model.beam;
  const std::vector<AutomaticChoice>& automatic_choices = model.automatic_choices;
  Probe probe;
  probe.name = spec.name;
  probe.quantity = spec.quantity;
  probe.unit = probe_unit(spec.quantity);
  const std::string where = position_text(spec.at);
  switch (spec.quantity) {
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
      if (!dea) throw InputError("probe " + spec.name, "dea", "no DEA named '" + spec.dea + "'");
      if (dea->electrode_node == ground)
        throw InputError("probe " + spec.name, "dea",
                         "DEA '" + spec.dea +
                             "' has no electrical model (drive.electrical_dynamics = " +
                             (std::any_of(automatic_choices.begin(), automatic_choices.end(),
                                          [](const AutomaticChoice& choice) {
                                            return choice.key == "drive.electrical_dynamics";
                                          })
                                  ? std::string("\"auto\" chose false")
                                  : "false") +
                             "; set it true, e.g. --set drive.electrical_dynamics=true)");
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
  for (ProbeQuantity q :
       {ProbeQuantity::deflection, ProbeQuantity::velocity, ProbeQuantity::rotation,
        ProbeQuantity::angular_velocity, ProbeQuantity::dea_voltage, ProbeQuantity::dea_current})
    if (quantity == probe_quantity_name(q)) {
      spec.quantity = q;
      known = true;
    }
  const bool electrical =
      spec.quantity == ProbeQuantity::dea_voltage || spec.quantity == ProbeQuantity::dea_current;
  if (!known || (electrical ? colon == std::string::npos : at_sign == std::string::npos))
    throw InputError("--probe", text,
                     "expected a probe name of the scene, QUANTITY@POSITION (e.g. "
                     "deflection@70mm, velocity@0.1) or dea_voltage:NAME / dea_current:NAME");
  if (electrical) {
    spec.dea = text.substr(colon + 1);
  } else {
    try {
      const std::string position = text.substr(at_sign + 1);
      size_t used = 0;
      double plain = 0.0;
      try {
        plain = std::stod(position, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      // A plain number is SI (metres); anything else must carry a length unit.
      spec.at = used == position.size() && std::isfinite(plain)
                    ? plain
                    : parse_quantity(position, dim::length);
    } catch (const std::exception& e) {
      throw InputError("--probe", text, e.what());
    }
    if (!(spec.at >= 0.0 && spec.at <= beam.length))
      throw InputError("--probe", text,
                       "position outside the beam [0, " + std::to_string(beam.length) + " m]");
  }
  return make_probe(spec);
}

}  // namespace emnet
