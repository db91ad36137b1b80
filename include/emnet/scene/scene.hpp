// A scene: what the user writes in netlists/*.toml, read into plain SI data.
//
// The reader (src/scene/scene_reader.cpp) turns a TOML file plus `--set key=value` overrides into
// a Scene, checking every key, unit and range; the resolve step (src/studies/resolve.cpp) makes
// its "auto" choices; the model builder (src/model/) turns the resolved Scene into a Network.
// Every quantity here is SI; the comments name the scene key. The syntax of [[circuit]]
// elements and their source waveforms is written out at CircuitSpec below.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "emnet/core/quantity.hpp"

namespace emnet {

/// beam.left, beam.right: how an end of the beam is held.
enum class EndCondition { clamped, free, pinned, sliding };
/// The name a scene file writes for `end`.
const char* end_condition_name(EndCondition end);

/// beam.theory: what one segment realises. Euler–Bernoulli: bending only; Timoshenko: bending
/// plus the shear compliance l/(κGA) of each segment (emnet/model/model.hpp).
enum class BeamTheory { euler_bernoulli, timoshenko };
/// The name a scene file writes for `theory`.
const char* beam_theory_name(BeamTheory theory);

/// beam.kinematics: small deflections (the linear beam network), or large ones (planar,
/// geometrically exact co-rotational segments; docs/model.md, Large deflection).
enum class BeamKinematics { small, large };
/// The name a scene file writes for `kinematics`.
const char* beam_kinematics_name(BeamKinematics kinematics);

/// [[section]]: a uniform stretch of the beam, in order from x = 0; the sections' lengths add up
/// to beam.length. A beam without sections is one uniform section of the [beam] values.
struct SectionSpec {
  double length = 0.0;                     ///< section[].length [m]
  double bending_stiffness = 0.0;          ///< section[].bending_stiffness EI [N·m²]
  double mass_per_length = 0.0;            ///< section[].mass_per_length ρA [kg/m]
  double rotary_inertia_per_length = 0.0;  ///< section[].rotary_inertia_per_length ρI [kg·m]
  /// section[].shear_stiffness κGA [N] (Timoshenko); unset: beam.shear_stiffness.
  std::optional<double> shear_stiffness;
  /// section[].axial_stiffness EA [N] (large kinematics); unset: beam.axial_stiffness.
  std::optional<double> axial_stiffness;
  /// section[].viscous_per_length [N·s/m²] and section[].kelvin_voigt_time τ [s]; unset: the
  /// [damping] table's.
  std::optional<double> viscous_per_length;
  std::optional<double> kelvin_voigt_time;
  /// section[].segments: this section's own segment count; 0 (unset or "auto"): a share of
  /// beam.segments by length.
  int segments = 0;
};

/// [[mass]]: a rigid point mass fixed to the beam at `at` (a capacitor to ground on the velocity
/// node there; its rotary inertia one on the rotation node).
struct MassSpec {
  std::string name;             ///< mass[].name (optional; "" addresses it by index)
  double at = 0.0;              ///< mass[].at [m]
  double mass = 0.0;            ///< mass[].mass [kg]
  double rotary_inertia = 0.0;  ///< mass[].rotary_inertia [kg·m²]
};

/// [[spring]]: a linear spring (and dashpot in parallel) from the beam at `at` to ground, or to
/// the beam at `to`. Translational: a force k·(w(at) − w(to)); rotational: a moment
/// k·(φ(at) − φ(to)); axial (beam.kinematics = "large" only): a force along the fixed frame's x,
/// k·(u(at) − u(to)). An elastic clamp is a free (or pinned) end with springs at x = 0.
enum class SpringKind { translational, rotational, axial };
/// A [[spring]] entry (see SpringKind).
struct SpringSpec {
  std::string name;                             ///< spring[].name (optional)
  double at = 0.0;                              ///< spring[].at [m]
  SpringKind kind = SpringKind::translational;  ///< spring[].kind
  double stiffness = 0.0;                       ///< spring[].stiffness k [N/m] or [N·m/rad]
  double damping = 0.0;                         ///< spring[].damping [N·s/m] or [N·m·s/rad]
  std::optional<double> to;                     ///< spring[].to [m]; unset: ground
};

/// [beam]: the beam's length, mesh, uniform properties and ends, and the structure on it.
struct BeamSpec {
  double length = 0.0;  ///< beam.length [m]
  int segments = 0;     ///< beam.segments [-]
  /// beam.segments = "auto": the resolve step chooses N from [model] (segments is 0 until
  /// then; emnet/studies/segment_selection.hpp). An integer, or --segments N, sets it false.
  bool auto_segments = false;
  /// Not a scene key: each segment of the mesh of `segments` is cut into this many equal ones
  /// (emnet/model/mesh.hpp rule 3). 2 gives the N/2N error estimates their nested 2N mesh.
  int refinement = 1;
  double bending_stiffness = 0.0;                   ///< beam.bending_stiffness EI [N·m²]
  double mass_per_length = 0.0;                     ///< beam.mass_per_length ρA [kg/m]
  double rotary_inertia_per_length = 0.0;           ///< beam.rotary_inertia_per_length ρI [kg·m]
  EndCondition left = EndCondition::clamped;        ///< beam.left  (x = 0)
  EndCondition right = EndCondition::free;          ///< beam.right (x = length)
  BeamTheory theory = BeamTheory::euler_bernoulli;  ///< beam.theory
  double shear_stiffness = 0.0;  ///< beam.shear_stiffness κGA [N] (Timoshenko); 0: not given
  BeamKinematics kinematics = BeamKinematics::small;  ///< beam.kinematics
  /// beam.kinematics = "auto": resolve_scene chooses `kinematics` (small until it does).
  bool kinematics_auto = false;
  /// beam.axial_stiffness EA [N] (large kinematics); 0: not given, the beam is inextensible.
  double axial_stiffness = 0.0;
  /// The structure on the beam, read from [[section]], [[mass]] and [[spring]]. With sections,
  /// bending_stiffness, mass_per_length and rotary_inertia_per_length above are unused (0).
  std::vector<SectionSpec> sections;
  std::vector<MassSpec> masses;
  std::vector<SpringSpec> springs;
};

/// The beam's sections as built: its [[section]] entries, or one section of the [beam] values
/// (with the [damping] table's defaults left unset).
std::vector<SectionSpec> effective_sections(const BeamSpec& beam);
/// EA [N] of `section` of `beam`: its own, else beam.axial_stiffness; 0 when neither is given.
double effective_axial_stiffness(const BeamSpec& beam, const SectionSpec& section);
/// Whether every section of `beam` has an axial stiffness (effective_axial_stiffness > 0): with
/// large kinematics, whether no segment is inextensible.
bool extensible(const BeamSpec& beam);
/// Whether two beams are the same structure (every field, sections, masses and springs).
bool same_beam(const BeamSpec& a, const BeamSpec& b);

/// [damping]: the beam's viscous and Kelvin–Voigt damping.
struct DampingSpec {
  double viscous_per_length = 0.0;  ///< damping.viscous_per_length [N·s/m²], to ground
  double kelvin_voigt_time = 0.0;   ///< damping.kelvin_voigt_time τ [s]: M = EI(κ + τ·κ')
  /// damping.loss_factor η at damping.loss_factor_frequency f: τ = η/(2π f). Either this pair
  /// or kelvin_voigt_time, not both (the reader enforces it).
  std::optional<double> loss_factor;
  std::optional<double> loss_factor_frequency;  ///< [Hz]
  /// τ [s]: η/(2π f) when loss_factor is given, else kelvin_voigt_time.
  double effective_kelvin_voigt_time() const;
};

/// Default dea[].breakdown_field: 80 V/µm, the dielectric breakdown strength in the data sheet
/// of WACKER ELASTOSIL Film 2030 (ASTM D 3755), the silicone film of the paper's DEAs. The data
/// sheet gives it for the film as supplied; the paper pre-stretches its film (to 51 µm), which
/// it says raises the breakdown strength, by how much it does not say.
inline constexpr double kDefaultBreakdownField = 80e6;

/// A face of the beam: top = +w side; an energised DEA there bends toward −w.
enum class Face { top, bottom };

/// A [[dea]] entry: one DEA on a face of the beam, over [from, to].
struct DeaSpec {
  std::string name;                    ///< dea[].name
  double from = 0.0;                   ///< dea[].from x0 [m]
  double to = 0.0;                     ///< dea[].to   x1 [m]
  Face face = Face::top;               ///< dea[].face
  double lever_arm = 0.0;              ///< dea[].lever_arm z [m] from the neutral plane
  double relative_permittivity = 0.0;  ///< dea[].relative_permittivity ε_r [-]
  double dielectric_thickness = 0.0;   ///< dea[].dielectric_thickness d [m]
  double force_thickness = 0.0;        ///< dea[].force_thickness d' [m] (paper Eq. 16)
  double electrode_width = 0.0;        ///< dea[].electrode_width [m]
  double electrode_resistance = 0.0;   ///< dea[].electrode_resistance [Ω]
  bool back_coupling = false;          ///< dea[].back_coupling: i += V·dC/dt
  /// dea[].breakdown_field [V/m]: the field V/d across the film above which a result is flagged
  /// as outside the model (emnet/model/validity.hpp); default kDefaultBreakdownField.
  double breakdown_field = kDefaultBreakdownField;
};

/// drive.kind: what the DEAs are driven with (src/model/model.cpp builds the sources):
///   antagonistic       0/V square wave on DEA A for the first `duty` of each period, on B for
///                      the rest (keys deas = [A, B], voltage, frequency, duty, rise_time,
///                      overlap);
///   switched           0/V square wave on one DEA, on for the first `duty` of each period
///                      (deas = [A], voltage, frequency, duty, rise_time);
///   bias_differential  V_A = V0 + v·sin(2πft), V_B = V0 − v·sin(2πft) (deas = [A, B], bias,
///                      amplitude, frequency);
///   single             V = V0 + v·sin(2πft) on one DEA (deas = [A], bias, amplitude, frequency);
///   none               no DEA driven: the scene's loads only (frequency, if given, is only the
///                      period of `tran --periods`).
/// drive.electrical_dynamics applies to every kind. The reader refuses a key the kind does not use.
enum class DriveKind { none, antagonistic, bias_differential, single, switched };
/// The name a scene file writes for `kind`.
const char* drive_kind_name(DriveKind kind);

/// [drive]: what the DEAs are driven with (see DriveKind).
struct DriveSpec {
  DriveKind kind = DriveKind::none;  ///< drive.kind
  std::vector<std::string> deas;     ///< drive.deas: [A, B] (antagonistic, bias_differential), [A]
  double voltage = 0.0;              ///< drive.voltage [V]: switched level (antagonistic, switched)
  double bias = 0.0;                 ///< drive.bias V0 [V] (bias_differential, single)
  double amplitude = 0.0;            ///< drive.amplitude v [V] (bias_differential, single)
  double frequency = 0.0;            ///< drive.frequency [Hz]: switching / sine frequency
  double rise_time = 0.0;            ///< drive.rise_time [s] (antagonistic, switched)
  double duty = 0.5;  ///< drive.duty [-]: fraction of the period A is on (antagonistic, switched)
  /// drive.overlap [s] (antagonistic): A stays on this long after B has switched on, both on
  /// together; negative, a dead time: A switches off this long before B switches on.
  double overlap = 0.0;
  /// drive.electrical_dynamics: true = each DEA is its capacitor behind its electrode
  /// resistance and its force follows the capacitor voltage (nonlinear); false = an ideal
  /// voltage-driven force k_F·V(t)² from the source (a linear network: exact transient).
  bool electrical_dynamics = true;
  /// drive.electrical_dynamics = "auto": the resolve step keeps the RC dynamics only when a
  /// probe asks for an electrical quantity or the RC lag matters in [model]'s band to its
  /// tolerance (emnet/studies/resolve.hpp). A resolved scene holds the choice in
  /// electrical_dynamics, with this flag cleared; code that sets electrical_dynamics on a scene
  /// clears it too (set_electrical_dynamics, emnet/model/model.hpp, also drops the choice's
  /// record).
  bool electrical_dynamics_auto = false;
};

/// [[circuit]]: an electrical network around the DEAs, written element by element.
///
///   [[circuit]]
///   name = "amp"              # required, unique (it names the element in SPICE decks)
///   kind = "voltage_source"   # resistor | capacitor | inductor | voltage_source | current_source
///   from = "out"              # node names: any identifier is a node of the circuit; "ground"
///   to = "ground"             #   (or "0") is ground; "dea.A" is DEA A's terminal s_A, in
///                             #   front of its electrode resistance
///   value = "10 MOhm"         # resistor [Ohm], capacitor [F], inductor [H]; a source's
///                             #   constant value [V or A] with waveform = "dc"
///   waveform = "square"       # sources only: dc (default) | sine | square | pulse | pwl
///   ac = "1 V"                # sources only: the AC analysis' magnitude (default 0)
///
/// Waveform keys (a key the waveform does not use is refused, with the waveforms that use it);
/// levels are V for a voltage source, A for a current source:
///   square  low, high, frequency, duty (0.5), rise (0), fall (= rise), delay (0): high for the
///           first duty/frequency of each period from `delay` (rise included), then low;
///   pulse   low, high, delay, rise, fall, width, period (SPICE PULSE; period 0: one pulse);
///   sine    offset, amplitude, frequency, phase [degrees, a plain number] (0), delay (0):
///           offset + amplitude*sin(2*pi*frequency*(t - delay) + phase);
///   pwl     points = [["0 s", "0 V"], ["1 ms", "3 kV"]] (times increasing; constant before the
///           first and after the last), or file = "drive.csv": two columns, time [s] and value
///           [SI], separated by a comma (or spaces), one header line allowed, relative to the
///           scene file's folder.
/// Signs: a voltage source holds V(from) - V(to) = value(t); a current source drives value(t)
/// out of node `from`, through itself, into node `to` (SPICE's I from to).
/// Rules (the reader's): every node other than ground is touched by at least two element ends
/// (a DEA terminal counts its DEA); every node has a DC path to ground through resistors,
/// inductors and voltage sources, and voltage sources with inductors form no loop (else the
/// static state is undefined); "dea.X" names a DEA the [drive] does not drive; a circuit needs
/// drive.electrical_dynamics = true ("auto" keeps it).
enum class CircuitKind { resistor, capacitor, inductor, voltage_source, current_source };
/// The name a scene file writes for `kind`.
const char* circuit_kind_name(CircuitKind kind);
/// Whether `kind` is a voltage or current source.
bool is_source(CircuitKind kind);

/// circuit[].waveform: a source's time function (see CircuitKind).
enum class WaveformKind { dc, sine, square, pulse, pwl };
/// The name a scene file writes for `kind`.
const char* waveform_kind_name(WaveformKind kind);

/// A source's time function, as the scene gives it (circuit[].waveform and its keys), SI.
struct WaveformSpec {
  WaveformKind kind = WaveformKind::dc;  ///< circuit[].waveform
  double low = 0.0;            ///< square, pulse: the level before and between pulses [V or A]
  double high = 0.0;           ///< square, pulse: the pulse's level
  double frequency = 0.0;      ///< square, sine [Hz]
  double duty = 0.5;           ///< square: fraction of the period at `high` (rise included) [-]
  double rise = 0.0;           ///< square, pulse [s]
  std::optional<double> fall;  ///< square, pulse [s]; unset: square's rise, pulse's 0
  double delay = 0.0;          ///< square, pulse, sine [s]
  double width = 0.0;          ///< pulse: time at `high` [s]
  double period = 0.0;         ///< pulse [s]; 0: a single pulse
  double offset = 0.0;         ///< sine [V or A]
  double amplitude = 0.0;      ///< sine [V or A]
  double phase_degrees = 0.0;  ///< sine [deg]
  std::vector<std::pair<double, double>> points;  ///< pwl: (time [s], value) pairs
  std::string file;  ///< pwl: the CSV file as written in the scene ("" for inline points)
  /// The fall time [s]: `fall`, else the square wave's rise or the pulse's 0.
  double fall_time() const { return fall.value_or(kind == WaveformKind::square ? rise : 0.0); }
};

/// A [[circuit]] element (see CircuitKind).
struct CircuitSpec {
  std::string name;                          ///< circuit[].name
  CircuitKind kind = CircuitKind::resistor;  ///< circuit[].kind
  std::string from;                          ///< circuit[].from, a node name as written
  std::string to;                            ///< circuit[].to
  double value = 0.0;                        ///< circuit[].value [Ohm, F, H; V or A]
  WaveformSpec waveform;                     ///< circuit[].waveform and its keys
  double ac = 0.0;                           ///< circuit[].ac [V or A]
};

/// Circuit node names: ground ("ground" or "0"), a DEA terminal ("dea.X": the DEA's name, else
/// ""), any other name is a node of the circuit.
bool is_ground_node_name(const std::string& node);
/// "X" for "dea.X", else "".
std::string dea_of_node_name(const std::string& node);

/// load[].kind.
enum class LoadKind { force, moment };
/// A [[load]] entry: a force [N] or moment [N·m] on the beam at `at`.
struct LoadSpec {
  LoadKind kind = LoadKind::force;  ///< load[].kind
  double at = 0.0;                  ///< load[].at [m]
  double value = 0.0;               ///< load[].value [N] or [N·m]; also its AC amplitude
};

/// A [[probe]] entry: a quantity the analyses report, and where it is taken.
struct ProbeSpec {
  std::string name;                                    ///< probe[].name
  ProbeQuantity quantity = ProbeQuantity::deflection;  ///< probe[].quantity
  double at = 0.0;        ///< probe[].at [m] (beam quantities; a reaction: 0 or beam.length)
  std::string dea;        ///< probe[].dea (dea_voltage, dea_current, dea_force)
  std::string spring;     ///< probe[].spring (spring_force): a spring's name, or its index
  Face face = Face::top;  ///< probe[].face (strain)
  double distance = 0.0;  ///< probe[].distance z [m] from the neutral plane (strain)
};

/// [ac]: the AC sweep's frequency grid.
struct AcSpec {
  double from = 0.1;   ///< ac.from [Hz]
  double to = 10.0;    ///< ac.to [Hz]
  int points = 200;    ///< ac.points
  bool log = false;    ///< ac.scale = "lin" | "log"
  bool given = false;  ///< the scene has an [ac] table (its upper end then bounds the default band)
};

/// [model]: what the scene wants to know, for the automatic choices (beam.segments = "auto",
/// drive.electrical_dynamics = "auto"). model.band = ["0 Hz", "130 Hz"] or "130 Hz" (from 0);
/// unset, the band is 0 to the larger of ac.to (with an [ac] table) and 10 x drive.frequency
/// (emnet/studies/segment_selection.hpp, band_of_interest).
struct ModelSpec {
  std::optional<double> band_from;  ///< model.band lower end [Hz]
  std::optional<double> band_to;    ///< model.band upper end [Hz]
  double tolerance = 1e-3;          ///< model.tolerance: relative accuracy of the band's resonances
  /// model.deflection_limit: the largest |deflection| a small-deflection linear beam is trusted
  /// with, as a fraction of beam.length; a result beyond it is flagged (emnet/model/validity.hpp).
  double deflection_limit = 0.1;
};

/// [environment]: the fluid around the beam (fluid loading, emnet/model/fluid_loading.hpp).
enum class Fluid { none, air, water };
/// The name a scene file writes for `fluid`.
const char* fluid_name(Fluid fluid);

/// [environment]: the fluid's keys, and the resonance its loading is evaluated at.
struct EnvironmentSpec {
  Fluid fluid = Fluid::none;  ///< environment.fluid
  double density = 0.0;       ///< environment.density ρ [kg/m³] (default: the fluid's, 20 °C)
  double dynamic_viscosity = 0.0;  ///< environment.dynamic_viscosity η [Pa·s] (default as density)
  double width = 0.0;              ///< environment.width b [m]: the plate's width across the motion
  /// environment.frequency [Hz] at which the hydrodynamic function is evaluated; unset: the
  /// first resonance of the loaded beam, found by fixed-point iteration.
  std::optional<double> frequency;
  /// That resonance, once found (the resolve step, emnet/studies/resolve.hpp): the fixed point
  /// and the beam and fluid it was found for. The model builder evaluates the loading there; a
  /// scene whose beam or fluid no longer matches (changed since) has it unresolved again.
  struct Resonance {
    double frequency = 0.0;         ///< [Hz] the loaded beam's first undamped resonance
    double vacuum_frequency = 0.0;  ///< [Hz] the bare beam's, where the fixed point started
    int fixed_point_steps = 0;
    BeamSpec beam;  ///< the beam it resolves (N as the model is built)
    Fluid fluid = Fluid::none;
    double density = 0.0, dynamic_viscosity = 0.0, width = 0.0;
  };
  std::optional<Resonance> resonance;
};

/// A choice made for the scene's "auto" keys by the resolve step (emnet/studies/resolve.hpp):
/// what, why, at what estimated error and cost; printed in every command's notes and as
/// "automatic_choices" in --json.
struct AutomaticChoice {
  std::string key;               ///< "beam.segments", "drive.electrical_dynamics"
  std::string value;             ///< "38", "false"
  std::string reason;            ///< one line, with the numbers
  double estimated_error = 0.0;  ///< relative, the criterion's estimate of what the choice costs
  double tolerance = 0.0;        ///< model.tolerance it was held to
  double band_from_hz = 0.0;     ///< the band of interest it was made for
  double band_to_hz = 0.0;
  double seconds = 0.0;  ///< time spent choosing
};

/// A scene file's contents, in SI (see the header comment).
struct Scene {
  std::string file;   ///< path it was read from
  std::string name;   ///< scene.name
  std::string title;  ///< scene.title
  BeamSpec beam;
  DampingSpec damping;
  std::vector<DeaSpec> deas;
  DriveSpec drive;
  std::vector<LoadSpec> loads;
  std::vector<ProbeSpec> probes;
  std::vector<CircuitSpec> circuit;  ///< [[circuit]] elements, in the file's order
  AcSpec ac;
  EnvironmentSpec environment;
  ModelSpec model;
  std::map<std::string, std::string> provenance;  ///< [provenance] "dotted.key" = "paper: …"
  /// Choices already made for this scene (a resolved scene, and so a model's, has its "auto"
  /// keys resolved and carries the choices here, so a model rebuilt from it keeps the same N and
  /// drive and says why).
  std::vector<AutomaticChoice> automatic_choices;
};

}  // namespace emnet
