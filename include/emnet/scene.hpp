// A scene: what the user writes in netlists/*.toml, read into plain SI data.
//
// The reader (src/io/scene_reader.cpp) turns a TOML file plus `--set key=value` overrides into
// a Scene, checking every key, unit and range; the model builder (src/model/) turns a Scene
// into a Network. Every quantity here is SI; the comments name the scene key.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace emnet {

enum class EndCondition { clamped, free, pinned, sliding };
const char* end_condition_name(EndCondition end);

struct BeamSpec {
  double length = 0.0;                        // beam.length [m]
  int segments = 0;                           // beam.segments [-]
  double bending_stiffness = 0.0;             // beam.bending_stiffness EI [N·m²]
  double mass_per_length = 0.0;               // beam.mass_per_length ρA [kg/m]
  double rotary_inertia_per_length = 0.0;     // beam.rotary_inertia_per_length ρI [kg·m]
  EndCondition left = EndCondition::clamped;  // beam.left  (x = 0)
  EndCondition right = EndCondition::free;    // beam.right (x = length)
};

struct DampingSpec {
  double viscous_per_length = 0.0;  // damping.viscous_per_length [N·s/m²], to ground
  double kelvin_voigt_time = 0.0;   // damping.kelvin_voigt_time τ [s]: M = EI(κ + τ·κ')
  // damping.loss_factor η at damping.loss_factor_frequency f: τ = η/(2π f). Either this pair
  // or kelvin_voigt_time, not both (the reader enforces it).
  std::optional<double> loss_factor;
  std::optional<double> loss_factor_frequency;  // [Hz]
  double effective_kelvin_voigt_time() const;
};

enum class Face { top, bottom };  // top = +w side; an energised DEA there bends toward −w

struct DeaSpec {
  std::string name;                    // dea[].name
  double from = 0.0;                   // dea[].from x0 [m]
  double to = 0.0;                     // dea[].to   x1 [m]
  Face face = Face::top;               // dea[].face
  double lever_arm = 0.0;              // dea[].lever_arm z [m] from the neutral plane
  double relative_permittivity = 0.0;  // dea[].relative_permittivity ε_r [-]
  double dielectric_thickness = 0.0;   // dea[].dielectric_thickness d [m]
  double force_thickness = 0.0;        // dea[].force_thickness d' [m] (paper Eq. 16)
  double electrode_width = 0.0;        // dea[].electrode_width [m]
  double electrode_resistance = 0.0;   // dea[].electrode_resistance [Ω]
  bool back_coupling = false;          // dea[].back_coupling: i += V·dC/dt
};

enum class DriveKind { none, antagonistic, bias_differential, single };
const char* drive_kind_name(DriveKind kind);

struct DriveSpec {
  DriveKind kind = DriveKind::none;  // drive.kind
  std::vector<std::string> deas;     // drive.deas: [A, B] (antagonistic, bias_differential), [A]
  double voltage = 0.0;              // drive.voltage [V]: switched level (antagonistic, single)
  double bias = 0.0;                 // drive.bias V0 [V] (bias_differential, single)
  double amplitude = 0.0;            // drive.amplitude v [V] (bias_differential, single)
  double frequency = 0.0;            // drive.frequency [Hz]: switching / sine frequency
  double rise_time = 0.0;            // drive.rise_time [s]
  double duty = 0.5;                 // drive.duty [-]: fraction of the period A is on
  // drive.overlap [s] (antagonistic): A stays on this long after B has switched on, both on
  // together; negative, a dead time: A switches off this long before B switches on.
  double overlap = 0.0;
  // drive.electrical_dynamics: true = each DEA is its capacitor behind its electrode
  // resistance and its force follows the capacitor voltage (nonlinear); false = an ideal
  // voltage-driven force k_F·V(t)² from the source (a linear network: exact transient).
  bool electrical_dynamics = true;
};

enum class LoadKind { force, moment };
struct LoadSpec {
  LoadKind kind = LoadKind::force;  // load[].kind
  double at = 0.0;                  // load[].at [m]
  double value = 0.0;               // load[].value [N] or [N·m]; also its AC amplitude
};

enum class ProbeQuantity {
  deflection,
  velocity,
  rotation,
  angular_velocity,
  dea_voltage,
  dea_current
};
const char* probe_quantity_name(ProbeQuantity quantity);
const char* probe_unit(ProbeQuantity quantity);

struct ProbeSpec {
  std::string name;                                    // probe[].name
  ProbeQuantity quantity = ProbeQuantity::deflection;  // probe[].quantity
  double at = 0.0;                                     // probe[].at [m] (beam quantities)
  std::string dea;                                     // probe[].dea (dea_voltage, dea_current)
};

struct AcSpec {
  double from = 0.1;  // ac.from [Hz]
  double to = 10.0;   // ac.to [Hz]
  int points = 200;   // ac.points
  bool log = false;   // ac.scale = "lin" | "log"
};

// [environment]: the fluid around the beam (fluid loading, emnet/fluid_loading.hpp).
enum class Fluid { none, air, water };
const char* fluid_name(Fluid fluid);

struct EnvironmentSpec {
  Fluid fluid = Fluid::none;       // environment.fluid
  double density = 0.0;            // environment.density ρ [kg/m³] (default: the fluid's, 20 °C)
  double dynamic_viscosity = 0.0;  // environment.dynamic_viscosity η [Pa·s] (default as density)
  double width = 0.0;              // environment.width b [m]: the plate's width across the motion
  // environment.frequency [Hz] at which the hydrodynamic function is evaluated; unset: the
  // first resonance of the loaded beam, found by fixed-point iteration.
  std::optional<double> frequency;
};

struct Scene {
  std::string file;   // path it was read from
  std::string name;   // scene.name
  std::string title;  // scene.title
  BeamSpec beam;
  DampingSpec damping;
  std::vector<DeaSpec> deas;
  DriveSpec drive;
  std::vector<LoadSpec> loads;
  std::vector<ProbeSpec> probes;
  AcSpec ac;
  EnvironmentSpec environment;
  std::map<std::string, std::string> provenance;  // [provenance] "dotted.key" = "paper: …"
};

}  // namespace emnet
