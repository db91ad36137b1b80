// Time functions of independent sources, and their small-signal (AC) excitation.
//
// A source's value is value(t) in its own unit (A or V in the network; N, N·m, m/s or rad/s
// by the Firestone analogy). The DC value is value at t = 0 before any edge; the AC phasor
// is ac_magnitude·exp(j·ac_phase) and is used only by the AC analysis.
#pragma once

#include <complex>
#include <string>
#include <vector>

namespace emnet {

/// The time function of an independent source and its AC excitation.
struct Waveform {
  /// Which fields below define the time function.
  enum class Shape { dc, pulse, sine, pwl };
  Shape shape = Shape::dc;

  double dc = 0.0;  ///< dc: value; pulse: low level (v1); sine: offset

  /// pulse (SPICE PULSE semantics): v1 -> v2 after delay, rise, width, fall, period.
  double pulse_high = 0.0;
  double delay = 0.0;
  double rise = 0.0;
  double fall = 0.0;
  double width = 0.0;
  double period = 0.0;  ///< 0: a single pulse

  /// sine: dc + amplitude·sin(2π·frequency·(t − delay) + phase)
  double amplitude = 0.0;
  double frequency = 0.0;
  double phase = 0.0;  ///< rad

  /// pwl: (time, value) pairs, times strictly increasing; constant outside.
  std::vector<std::pair<double, double>> points;

  /// Small-signal excitation of the AC analysis.
  double ac_magnitude = 0.0;
  double ac_phase = 0.0;  ///< rad

  /// The value at time t [s], taken from the right at a breakpoint.
  double value(double t) const;
  /// d value/dt on the piece that holds t, taken from the right at a breakpoint as value() is
  /// (0 on constant pieces, so that a piecewise-constant source has slope 0 exactly). For dc,
  /// pulse and pwl the value is affine between breakpoints: value(t) = value(t₀) + slope·(t − t₀).
  double slope(double t) const;
  /// Affine between breakpoints (dc, pulse, pwl); a sine is not.
  bool piecewise_linear() const { return shape != Shape::sine; }
  /// value(0).
  double value_at_rest() const { return value(0.0); }
  /// ac_magnitude·exp(j·ac_phase).
  std::complex<double> ac_phasor() const { return std::polar(ac_magnitude, ac_phase); }
  /// Instants in (t_begin, t_end] where the value or its slope jumps.
  void breakpoints(double t_begin, double t_end, std::vector<double>& out) const;

  /// The same time function multiplied by `factor` (levels, amplitude, AC magnitude).
  Waveform scaled(double factor) const;
  /// A dc waveform of `value`.
  static Waveform constant(double value);
  /// A periodic pulse from `low` to `high` with equal rise and fall times.
  /// @param frequency  [Hz]
  /// @param duty       the fraction of the period from the start of the rise to the start of the
  ///                   fall
  /// @param delay      [s]
  /// @param rise_time  the rise and the fall [s]
  static Waveform square(double low, double high, double frequency, double duty, double delay,
                         double rise_time);
};

}  // namespace emnet
