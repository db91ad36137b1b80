// The scene's drive on each DEA, its drive sources' waveforms, and the drive's excitation at
// another frequency: see include/emnet/model/drive.hpp.
#include "emnet/model/drive.hpp"

#include <algorithm>
#include <stdexcept>

#include "emnet/core/errors.hpp"
#include "emnet/core/units.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/model/model.hpp"

namespace emnet {

namespace {

constexpr double pi = 3.14159265358979323846;

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

double dea_ac_force(const DriveSpec& drive, const DeaLayout& dea) {
  return dea_drive(drive, dea.name).ac_force_factor * dea.force_constant * drive.voltage *
         drive.voltage;
}

Waveform drive_source_waveform(const DriveSpec& drive, const DeaLayout& dea,
                               const ElementRecord& record) {
  if (record.component != Component::drive_source)
    throw std::logic_error("drive_source_waveform: element is no drive source");
  const DeaDrive driven = dea_drive(drive, dea.name);
  if (record.part == ElementPart::source_voltage) return driven.voltage;
  const std::vector<Waveform> parts =
      squared_force(driven.voltage, dea.force_constant, dea_ac_force(drive, dea));
  if (record.force_part < 0 || record.force_part >= static_cast<int>(parts.size()) ||
      record.coupling < 0 || record.coupling >= static_cast<int>(dea.coupling.size()))
    throw std::logic_error("drive_source_waveform: no force part " +
                           std::to_string(record.force_part) + " on coupling node " +
                           std::to_string(record.coupling) + " of DEA " + dea.name);
  return parts[static_cast<size_t>(record.force_part)].scaled(
      dea.coupling[static_cast<size_t>(record.coupling)].coefficient);
}

Excitation drive_excitation(const Model& model, const Excitation& assembled, double frequency) {
  DriveSpec drive = model.scene.drive;
  drive.frequency = frequency;
  Excitation excitation = assembled;
  if (excitation.waveform_element.size() != excitation.waveforms.size())
    throw std::logic_error(
        "drive_excitation: the excitation does not say which element stamped "
        "each waveform");
  std::vector<int> owned(model.structure.elements.size(), 0);
  for (size_t w = 0; w < excitation.waveforms.size(); ++w) {
    const int element = excitation.waveform_element[w];
    const ElementRecord* record = model.structure.element(static_cast<size_t>(element));
    if (!record || record->component != Component::drive_source) continue;
    const DeaLayout* dea = model.find_dea(record->dea);
    if (!dea) throw std::logic_error("drive_excitation: no DEA named " + record->dea);
    excitation.waveforms[w] = drive_source_waveform(drive, *dea, *record);
    ++owned[static_cast<size_t>(element)];
  }
  for (size_t k = 0; k < owned.size(); ++k)
    if (model.structure.elements[k].component == Component::drive_source && owned[k] != 1)
      throw std::logic_error("drive_excitation: drive source " + std::to_string(k) + " owns " +
                             std::to_string(owned[k]) +
                             " waveforms of the excitation (one expected): an excitation of "
                             "another network");
  return excitation;
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

void check_overlap_fits(const Scene& scene, double frequency_hz, const std::string& where) {
  const auto& drive = scene.drive;
  if (drive.overlap == 0.0) return;
  const double period = 1.0 / frequency_hz, on_time = drive.duty * period + drive.overlap;
  if (!(on_time > 2.0 * drive.rise_time && on_time < period - 2.0 * drive.rise_time))
    throw InputError(scene.file, "drive.overlap",
                     format_number("%.6g s", drive.overlap) +
                         " makes DEA A's on-time leave the period " +
                         format_number("%.6g s", period) + " at " +
                         format_number("%.6g Hz", frequency_hz) + " (" + where + ")");
}

}  // namespace emnet
