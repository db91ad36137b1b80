// The scene's drive on each DEA, its drive sources' waveforms, and the drive's excitation at
// another frequency: see include/emnet/model/drive.hpp.
#include "emnet/model/drive.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "emnet/core/constants.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/units.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/model/circuit.hpp"
#include "emnet/model/model.hpp"

namespace emnet {

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
      w.ac_phase = role == 0 ? 0.0 : kPi;
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
    harmonic.phase = 2 * voltage.phase + kPi / 2;
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

namespace {

// `assembled` with each waveform that an element of `component` stamped made again by
// remake(its record, the element's index): the one walk of drive_excitation and
// circuit_excitation. `caller` names the function in a logic error.
template <class Remake>
Excitation with_waveforms_remade(const Model& model, const Excitation& assembled,
                                 Component component, const std::string& caller,
                                 const Remake& remake) {
  Excitation excitation = assembled;
  if (excitation.waveform_element.size() != excitation.waveforms.size())
    throw std::logic_error(caller +
                           ": the excitation does not say which element stamped each waveform");
  for (size_t w = 0; w < excitation.waveforms.size(); ++w) {
    const int element = excitation.waveform_element[w];
    const ElementRecord* record = model.structure.element(static_cast<size_t>(element));
    if (record && record->component == component)
      excitation.waveforms[w] = remake(*record, element);
  }
  return excitation;
}

}  // namespace

Excitation drive_excitation(const Model& model, const Excitation& assembled, double frequency) {
  DriveSpec drive = model.scene.drive;
  drive.frequency = frequency;
  std::vector<int> owned(model.structure.elements.size(), 0);
  Excitation excitation = with_waveforms_remade(
      model, assembled, Component::drive_source, "drive_excitation",
      [&](const ElementRecord& record, int element) {
        const DeaLayout* dea = model.find_dea(record.dea);
        if (!dea) throw std::logic_error("drive_excitation: no DEA named " + record.dea);
        ++owned[static_cast<size_t>(element)];
        return drive_source_waveform(drive, *dea, record);
      });
  for (size_t k = 0; k < owned.size(); ++k)
    if (model.structure.elements[k].component == Component::drive_source && owned[k] != 1)
      throw std::logic_error("drive_excitation: drive source " + std::to_string(k) + " owns " +
                             std::to_string(owned[k]) +
                             " waveforms of the excitation (one expected): an excitation of "
                             "another network");
  return excitation;
}

Excitation circuit_excitation(const Model& model, const Scene& scene, const Excitation& assembled) {
  return with_waveforms_remade(
      model, assembled, Component::circuit, "circuit_excitation",
      [&](const ElementRecord& record, int) {
        if (record.index < 0 || static_cast<size_t>(record.index) >= scene.circuit.size())
          throw std::logic_error("circuit_excitation: no circuit entry " +
                                 std::to_string(record.index) + " in the scene");
        return circuit_waveform(scene.circuit[static_cast<size_t>(record.index)]);
      });
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

void check_overlap_fits(const Scene& scene, double frequency_hz, const std::string& field) {
  const auto& drive = scene.drive;
  if (drive.overlap == 0.0) return;
  const double period = 1.0 / frequency_hz, on_time = drive.duty * period + drive.overlap;
  if (!(on_time > 2.0 * drive.rise_time && on_time < period - 2.0 * drive.rise_time))
    throw OptionError::in_file(field, scene.file, "drive.overlap",
                               format_number("%.6g s", drive.overlap) +
                                   " makes DEA A's on-time leave the period " +
                                   format_number("%.6g s", period) + " at " +
                                   format_number("%.6g Hz", frequency_hz) + " ({" + field + "})");
}

namespace {

bool is_periodic(const WaveformSpec& w) {
  switch (w.kind) {
    case WaveformKind::square:
    case WaveformKind::sine:
      return w.frequency > 0.0;
    case WaveformKind::pulse:
      return w.period > 0.0;
    case WaveformKind::dc:
    case WaveformKind::pwl:
      return false;
  }
  return false;
}

double own_frequency(const WaveformSpec& w) {
  return w.kind == WaveformKind::pulse ? 1.0 / w.period : w.frequency;
}

}  // namespace

std::vector<size_t> switched_sources(const Scene& scene, const std::vector<std::string>& names) {
  std::vector<size_t> switched;
  for (const std::string& name : names) {
    auto found = std::find_if(scene.circuit.begin(), scene.circuit.end(),
                              [&](const CircuitSpec& c) { return c.name == name; });
    if (found == scene.circuit.end() || !is_source(found->kind))
      throw InputError(scene.file, "circuit",
                       "the switched source \"" + name + "\" is not a [[circuit]] source");
    if (!is_periodic(found->waveform))
      throw InputError(scene.file, "circuit." + name + ".waveform",
                       "the switched source \"" + name + "\" has the non-periodic waveform \"" +
                           waveform_kind_name(found->waveform.kind) +
                           "\": only square, sine and pulse with a period switch");
    const size_t index = static_cast<size_t>(found - scene.circuit.begin());
    if (std::find(switched.begin(), switched.end(), index) == switched.end())
      switched.push_back(index);
  }
  if (names.empty())
    for (size_t k = 0; k < scene.circuit.size(); ++k)
      if (is_source(scene.circuit[k].kind) && is_periodic(scene.circuit[k].waveform))
        switched.push_back(k);
  return switched;
}

std::vector<std::string> set_switching_frequency(Scene& scene, double frequency_hz,
                                                 const std::vector<std::string>& sources) {
  if (!(frequency_hz > 0.0) || !std::isfinite(frequency_hz))
    throw InputError(scene.file, "drive.frequency",
                     "a switching frequency must be finite and > 0 Hz, not " +
                         format_number("%.6g", frequency_hz));
  const std::vector<size_t> switched = switched_sources(scene, sources);
  if (switched.empty() && !scene.circuit.empty() && scene.drive.kind == DriveKind::none)
    throw InputError(scene.file, "circuit",
                     "nothing switches: drive.kind is \"none\" and no [[circuit]] source has a "
                     "periodic waveform (square, sine, pulse with a period)");
  std::vector<std::string> notes;
  scene.drive.frequency = frequency_hz;
  const double period = 1.0 / frequency_hz;
  std::vector<double> own;
  for (size_t k : switched) {
    CircuitSpec& source = scene.circuit[k];
    WaveformSpec& w = source.waveform;
    const double old_period = 1.0 / own_frequency(w);
    own.push_back(own_frequency(w));
    w.delay *= period / old_period;
    if (w.kind == WaveformKind::pulse) {
      w.width *= period / old_period;
      w.period = period;
    } else {
      w.frequency = frequency_hz;
    }
    const double edges = w.kind == WaveformKind::sine ? 0.0 : w.rise + w.fall_time();
    const double on = w.kind == WaveformKind::pulse ? w.width : 0.0;
    if (!(edges + on < period))
      throw InputError(scene.file, "circuit." + source.name + ".rise",
                       "the rise and fall" + std::string(on > 0.0 ? " and the width" : "") +
                           " of source \"" + source.name + "\" (" +
                           format_with_unit(edges + on, "s") + ") do not fit in the period " +
                           format_with_unit(period, "s") + " at " +
                           format_with_unit(frequency_hz, "Hz"));
  }
  if (!own.empty() &&
      *std::min_element(own.begin(), own.end()) != *std::max_element(own.begin(), own.end()))
    notes.push_back("the switched sources had different frequencies (" +
                    format_with_unit(*std::min_element(own.begin(), own.end()), "Hz") + " to " +
                    format_with_unit(*std::max_element(own.begin(), own.end()), "Hz") +
                    "): all are set to the switching frequency");
  for (size_t k = 0; k < scene.circuit.size(); ++k)
    if (is_source(scene.circuit[k].kind) &&
        std::find(switched.begin(), switched.end(), k) == switched.end())
      notes.push_back("source " + scene.circuit[k].name + " (" +
                      waveform_kind_name(scene.circuit[k].waveform.kind) +
                      (is_periodic(scene.circuit[k].waveform) ? ", not named" : ", not periodic") +
                      ") keeps its own waveform");
  return notes;
}

}  // namespace emnet
