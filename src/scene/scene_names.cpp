// Names of the scene enumerations (as written in scene files) and small Scene helpers.
#include "emnet/core/constants.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

const char* end_condition_name(EndCondition end) {
  switch (end) {
    case EndCondition::clamped:
      return "clamped";
    case EndCondition::free:
      return "free";
    case EndCondition::pinned:
      return "pinned";
    case EndCondition::sliding:
      return "sliding";
  }
  return "?";
}

const char* beam_theory_name(BeamTheory theory) {
  return theory == BeamTheory::timoshenko ? "timoshenko" : "euler_bernoulli";
}

const char* beam_kinematics_name(BeamKinematics kinematics) {
  return kinematics == BeamKinematics::large ? "large" : "small";
}

std::vector<SectionSpec> effective_sections(const BeamSpec& beam) {
  if (!beam.sections.empty()) return beam.sections;
  SectionSpec uniform;
  uniform.length = beam.length;
  uniform.bending_stiffness = beam.bending_stiffness;
  uniform.mass_per_length = beam.mass_per_length;
  uniform.rotary_inertia_per_length = beam.rotary_inertia_per_length;
  return {uniform};
}

double effective_axial_stiffness(const BeamSpec& beam, const SectionSpec& section) {
  return section.axial_stiffness.value_or(beam.axial_stiffness);
}

bool extensible(const BeamSpec& beam) {
  for (const SectionSpec& section : effective_sections(beam))
    if (!(effective_axial_stiffness(beam, section) > 0.0)) return false;
  return true;
}

namespace {

bool same_section(const SectionSpec& a, const SectionSpec& b) {
  return a.length == b.length && a.bending_stiffness == b.bending_stiffness &&
         a.mass_per_length == b.mass_per_length &&
         a.rotary_inertia_per_length == b.rotary_inertia_per_length &&
         a.shear_stiffness == b.shear_stiffness && a.axial_stiffness == b.axial_stiffness &&
         a.viscous_per_length == b.viscous_per_length &&
         a.kelvin_voigt_time == b.kelvin_voigt_time && a.segments == b.segments;
}

bool same_mass(const MassSpec& a, const MassSpec& b) {
  return a.at == b.at && a.mass == b.mass && a.rotary_inertia == b.rotary_inertia;
}

bool same_spring(const SpringSpec& a, const SpringSpec& b) {
  return a.at == b.at && a.kind == b.kind && a.stiffness == b.stiffness && a.damping == b.damping &&
         a.to == b.to;
}

template <typename Item, typename Same>
bool same_lists(const std::vector<Item>& a, const std::vector<Item>& b, Same same) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (!same(a[k], b[k])) return false;
  return true;
}

}  // namespace

bool same_beam(const BeamSpec& a, const BeamSpec& b) {
  return a.length == b.length && a.segments == b.segments && a.auto_segments == b.auto_segments &&
         a.bending_stiffness == b.bending_stiffness && a.mass_per_length == b.mass_per_length &&
         a.rotary_inertia_per_length == b.rotary_inertia_per_length && a.left == b.left &&
         a.right == b.right && a.theory == b.theory && a.shear_stiffness == b.shear_stiffness &&
         a.kinematics == b.kinematics && a.kinematics_auto == b.kinematics_auto &&
         a.axial_stiffness == b.axial_stiffness &&
         same_lists(a.sections, b.sections, same_section) &&
         same_lists(a.masses, b.masses, same_mass) && same_lists(a.springs, b.springs, same_spring);
}

const char* fluid_name(Fluid fluid) {
  switch (fluid) {
    case Fluid::none:
      return "none";
    case Fluid::air:
      return "air";
    case Fluid::water:
      return "water";
  }
  return "?";
}

const char* drive_kind_name(DriveKind kind) {
  switch (kind) {
    case DriveKind::none:
      return "none";
    case DriveKind::antagonistic:
      return "antagonistic";
    case DriveKind::bias_differential:
      return "bias_differential";
    case DriveKind::single:
      return "single";
    case DriveKind::switched:
      return "switched";
  }
  return "?";
}

const char* circuit_kind_name(CircuitKind kind) {
  switch (kind) {
    case CircuitKind::resistor:
      return "resistor";
    case CircuitKind::capacitor:
      return "capacitor";
    case CircuitKind::inductor:
      return "inductor";
    case CircuitKind::voltage_source:
      return "voltage_source";
    case CircuitKind::current_source:
      return "current_source";
  }
  return "?";
}

bool is_source(CircuitKind kind) {
  return kind == CircuitKind::voltage_source || kind == CircuitKind::current_source;
}

const char* waveform_kind_name(WaveformKind kind) {
  switch (kind) {
    case WaveformKind::dc:
      return "dc";
    case WaveformKind::sine:
      return "sine";
    case WaveformKind::square:
      return "square";
    case WaveformKind::pulse:
      return "pulse";
    case WaveformKind::pwl:
      return "pwl";
  }
  return "?";
}

bool is_ground_node_name(const std::string& node) {
  return node == "ground" || node == "0";
}

std::string dea_of_node_name(const std::string& node) {
  const std::string prefix = "dea.";
  return node.compare(0, prefix.size(), prefix) == 0 ? node.substr(prefix.size()) : std::string();
}

double DampingSpec::effective_kelvin_voigt_time() const {
  if (!loss_factor.has_value()) return kelvin_voigt_time;
  const double frequency = loss_factor_frequency.value_or(0.0);
  if (!(frequency > 0.0)) return kelvin_voigt_time;  // the reader never lets this happen
  return *loss_factor / (kTwoPi * frequency);
}

}  // namespace emnet
