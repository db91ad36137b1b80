// Conditions between scene keys with the reader's messages; see parameter_relations.hpp.
#include "parameter_relations.hpp"

#include <cmath>
#include <limits>

#include "emnet/core/units.hpp"
#include "scene_text.hpp"

namespace emnet {

std::string subnormal_violation(double value, const Dimension& dimension) {
  if (value == 0.0 || std::abs(value) >= std::numeric_limits<double>::min()) return "";
  return "must be 0 or at least " + format_quantity(std::numeric_limits<double>::min(), dimension) +
         " in magnitude (a normal floating-point number), got " + format_quantity(value, dimension);
}

std::string beam_position_violation(double position, double beam_length) {
  const double tolerance = kBeamEndTolerance * beam_length;
  if (position < -tolerance || position > beam_length + tolerance) {
    return "must lie on the beam [0, " + format_quantity(beam_length, dim::length) + "], got " +
           format_quantity(position, dim::length);
  }
  return "";
}

std::optional<KeyMessage> dea_span_violation(const std::string& dea_name, double from, double to,
                                             double beam_length) {
  const double tolerance = kBeamEndTolerance * beam_length;
  const std::string span = "DEA '" + dea_name + "' spans [" + format_quantity(from, dim::length) +
                           ", " + format_quantity(to, dim::length) + "]";
  const std::string beam_span = "the beam [0, " + format_quantity(beam_length, dim::length) + "]";
  if (from < -tolerance) return KeyMessage{"from", span + ", outside " + beam_span};
  if (to > beam_length + tolerance) return KeyMessage{"to", span + ", outside " + beam_span};
  if (!(from < to)) return KeyMessage{"to", span + ": 'to' must be greater than 'from'"};
  return std::nullopt;
}

std::string rise_time_violation(double rise_time, double frequency) {
  if (rise_time < 0.5 / frequency) return "";
  return "must be shorter than half a period (" + format_quantity(0.5 / frequency, dim::time) +
         " at " + format_quantity(frequency, dim::frequency) + "), got " +
         format_quantity(rise_time, dim::time);
}

std::string overlap_violation(double duty, double overlap, double frequency, double rise_time) {
  if (overlap == 0.0) return "";
  // A's on-time (duty·T + overlap) must stay inside (rise time, T − rise time).
  const double period = 1.0 / frequency;
  const double on_time = duty * period + overlap;
  if (on_time > 2.0 * rise_time && on_time < period - 2.0 * rise_time) return "";
  return "makes DEA A's on-time " + format_quantity(on_time, dim::time) + " leave the period " +
         format_quantity(period, dim::time) + " (with the rise time at both edges)";
}

std::string ac_log_from_violation(bool log, double from) {
  if (!log || from > 0.0) return "";
  return "must be > 0 for a log scale, got " + format_quantity(from, dim::frequency);
}

std::string ac_to_violation(double from, double to, bool default_to) {
  if (to > from) return "";
  return "must be greater than ac.from (" + format_quantity(from, dim::frequency) + "), got " +
         format_quantity(to, dim::frequency) + (default_to ? " (the default)" : "");
}

std::optional<KeyMessage> circuit_element_violation(const CircuitSpec& element) {
  const WaveformSpec& waveform = element.waveform;
  switch (element.kind) {
    case CircuitKind::resistor:
    case CircuitKind::capacitor:
    case CircuitKind::inductor: {
      const Dimension unit = element.kind == CircuitKind::resistor    ? dim::resistance
                             : element.kind == CircuitKind::capacitor ? dim::capacitance
                                                                      : dim::inductance;
      if (!(element.value > 0.0))
        return KeyMessage{"value", std::string("must be > 0 for a ") +
                                       circuit_kind_name(element.kind) + ", got " +
                                       format_quantity(element.value, unit)};
      return std::nullopt;
    }
    case CircuitKind::voltage_source:
    case CircuitKind::current_source:
      break;
  }
  const double fall = waveform.fall_time();
  switch (waveform.kind) {
    case WaveformKind::square: {
      if (!(waveform.frequency > 0.0)) return std::nullopt;  // the key's range says why
      const double period = 1.0 / waveform.frequency, on_time = waveform.duty * period;
      if (waveform.rise > on_time)
        return KeyMessage{"rise", "must fit the high part of the period (duty/frequency = " +
                                      format_quantity(on_time, dim::time) + "), got " +
                                      format_quantity(waveform.rise, dim::time)};
      if (on_time + fall > period)
        return KeyMessage{"fall", "must fit the low part of the period ((1 - duty)/frequency = " +
                                      format_quantity(period - on_time, dim::time) + "), got " +
                                      format_quantity(fall, dim::time)};
      return std::nullopt;
    }
    case WaveformKind::pulse: {
      const double length = waveform.rise + waveform.width + fall;
      if (waveform.period != 0.0 && waveform.period < length)
        return KeyMessage{"period", "must be 0 (one pulse) or at least rise + width + fall = " +
                                        format_quantity(length, dim::time) + ", got " +
                                        format_quantity(waveform.period, dim::time)};
      return std::nullopt;
    }
    case WaveformKind::pwl: {
      const std::string key = waveform.file.empty() ? "points" : "file";
      if (waveform.points.empty()) return KeyMessage{key, "has no points"};
      for (std::size_t k = 1; k < waveform.points.size(); ++k)
        if (!(waveform.points[k].first > waveform.points[k - 1].first))
          return KeyMessage{key, "point " + std::to_string(k + 1) + "'s time " +
                                     format_quantity(waveform.points[k].first, dim::time) +
                                     " is not after the previous point's " +
                                     format_quantity(waveform.points[k - 1].first, dim::time) +
                                     " (times must increase)"};
      return std::nullopt;
    }
    case WaveformKind::dc:
    case WaveformKind::sine:
      return std::nullopt;
  }
  return std::nullopt;
}

namespace {

// "dea[A]", "load[0]": how the reader names an entry (by its name where it is one).
std::string entry_prefix(const std::string& table, const std::string& name, std::size_t index) {
  return table + "[" + (scene_text::is_identifier(name) ? name : std::to_string(index)) + "]";
}

bool beam_quantity(ProbeQuantity quantity) {
  return quantity != ProbeQuantity::dea_voltage && quantity != ProbeQuantity::dea_current &&
         quantity != ProbeQuantity::dea_force && quantity != ProbeQuantity::spring_force;
}

}  // namespace

std::string sections_length_violation(const BeamSpec& beam) {
  if (beam.sections.empty()) return "";
  double total = 0.0;
  for (const SectionSpec& section : beam.sections) total += section.length;
  if (std::abs(total - beam.length) <= kBeamEndTolerance * beam.length) return "";
  return "the " + std::to_string(beam.sections.size()) + " [[section]] lengths add up to " +
         format_quantity(total, dim::length) +
         ", not beam.length = " + format_quantity(beam.length, dim::length);
}

std::string spring_ends_violation(const SpringSpec& spring, double beam_length) {
  if (!spring.to) return "";
  if (std::abs(*spring.to - spring.at) <= kBeamEndTolerance * beam_length)
    return "is the spring's own position at = " + format_quantity(spring.at, dim::length) +
           " (a spring to ground leaves spring[].to out)";
  return "";
}

std::optional<KeyMessage> scene_relation_violation(const Scene& scene) {
  const double length = scene.beam.length;
  if (std::string why = sections_length_violation(scene.beam); !why.empty())
    return KeyMessage{"beam.length", why};
  for (std::size_t k = 0; k < scene.beam.masses.size(); ++k)
    if (std::string why = beam_position_violation(scene.beam.masses[k].at, length); !why.empty())
      return KeyMessage{entry_prefix("mass", scene.beam.masses[k].name, k) + ".at", why};
  for (std::size_t k = 0; k < scene.beam.springs.size(); ++k) {
    const SpringSpec& spring = scene.beam.springs[k];
    const std::string prefix = entry_prefix("spring", spring.name, k);
    if (std::string why = beam_position_violation(spring.at, length); !why.empty())
      return KeyMessage{prefix + ".at", why};
    if (spring.to) {
      if (std::string why = beam_position_violation(*spring.to, length); !why.empty())
        return KeyMessage{prefix + ".to", why};
      if (std::string why = spring_ends_violation(spring, length); !why.empty())
        return KeyMessage{prefix + ".to", why};
    }
  }
  for (std::size_t k = 0; k < scene.deas.size(); ++k) {
    const DeaSpec& dea = scene.deas[k];
    if (auto violation = dea_span_violation(dea.name, dea.from, dea.to, length))
      return KeyMessage{entry_prefix("dea", dea.name, k) + "." + violation->name,
                        violation->message};
  }
  const DriveSpec& drive = scene.drive;
  if (drive.frequency > 0.0) {
    if (std::string why = rise_time_violation(drive.rise_time, drive.frequency); !why.empty())
      return KeyMessage{"drive.rise_time", why};
    if (std::string why =
            overlap_violation(drive.duty, drive.overlap, drive.frequency, drive.rise_time);
        !why.empty())
      return KeyMessage{"drive.overlap", why};
  }
  for (std::size_t k = 0; k < scene.loads.size(); ++k)
    if (std::string why = beam_position_violation(scene.loads[k].at, length); !why.empty())
      return KeyMessage{entry_prefix("load", "", k) + ".at", why};
  for (std::size_t k = 0; k < scene.probes.size(); ++k) {
    const ProbeSpec& probe = scene.probes[k];
    if (!beam_quantity(probe.quantity)) continue;
    if (std::string why = beam_position_violation(probe.at, length); !why.empty())
      return KeyMessage{entry_prefix("probe", probe.name, k) + ".at", why};
  }
  for (std::size_t k = 0; k < scene.circuit.size(); ++k)
    if (auto violation = circuit_element_violation(scene.circuit[k]))
      return KeyMessage{entry_prefix("circuit", scene.circuit[k].name, k) + "." + violation->name,
                        violation->message};
  if (std::string why = ac_log_from_violation(scene.ac.log, scene.ac.from); !why.empty())
    return KeyMessage{"ac.from", why};
  if (std::string why = ac_to_violation(scene.ac.from, scene.ac.to, false); !why.empty())
    return KeyMessage{"ac.to", why};
  return std::nullopt;
}

}  // namespace emnet
