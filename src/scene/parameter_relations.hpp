// Conditions between scene keys (a position on the beam, a DEA's span, the rise time within half
// a period, ...), each with the reader's message, so that the scene reader and set_parameter
// say the same thing about the same value.
#pragma once

#include <optional>
#include <string>

#include "emnet/core/units.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

// Positions within this fraction of the beam length outside [0, L] are taken as the beam end.
inline constexpr double kBeamEndTolerance = 1e-9;

// A message about one key: `name` is the key within its table ("to"), or a whole key.
struct KeyMessage {
  std::string name;
  std::string message;
};

// "must be 0 or at least 2.2e-308 m in magnitude (...)": a subnormal value has lost its precision,
// and a length of one cut into segments underflows to zero. For a value that is 0 or normal, "".
std::string subnormal_violation(double value, const Dimension& dimension);

// "" for a position on the beam [0, L] (to kBeamEndTolerance), else "must lie on the beam ...".
std::string beam_position_violation(double position, double beam_length);
// A DEA's span [from, to] off the beam or empty: the key it is reported on ("from" or "to").
std::optional<KeyMessage> dea_span_violation(const std::string& dea_name, double from, double to,
                                             double beam_length);
// "" when the beam has no sections or their lengths add up to beam.length (to kBeamEndTolerance).
std::string sections_length_violation(const BeamSpec& beam);
// "" for a spring to ground or to another point; the message for spring[].to at its own `at`.
std::string spring_ends_violation(const SpringSpec& spring, double beam_length);
// drive.rise_time at least half a period of drive.frequency; "" otherwise.
std::string rise_time_violation(double rise_time, double frequency);
// drive.overlap that makes DEA A's on-time leave the period (with the rise time at both
// edges); "" otherwise, and for overlap 0.
std::string overlap_violation(double duty, double overlap, double frequency, double rise_time);
// ac.from on a log scale must be > 0; "" otherwise.
std::string ac_log_from_violation(bool log, double from);
// ac.to must be above ac.from; `default_to`: ac.to was not given.
std::string ac_to_violation(double from, double to, bool default_to);

// A [[circuit]] element's value and waveform: a resistor, capacitor or inductor value > 0; a
// square wave's edges inside its period (rise <= duty/frequency, duty/frequency + fall <=
// 1/frequency); a pulse's period 0 or at least rise + width + fall; a pwl's times increasing
// (from at least one point). The key it is reported on ("value", "rise", ...), or nullopt.
std::optional<KeyMessage> circuit_element_violation(const CircuitSpec& element);

// The first of these conditions `scene` breaks, named by its canonical key ("dea[A].to",
// "probe[tip].at", "drive.rise_time"), or nullopt.
std::optional<KeyMessage> scene_relation_violation(const Scene& scene);

}  // namespace emnet
