// Waveform evaluation: DC, SPICE-style PULSE, sine and piecewise-linear time functions.
#include "emnet/network/waveform.hpp"

#include <algorithm>
#include <cmath>

#include "emnet/core/constants.hpp"

namespace emnet {

double Waveform::value(double t) const {
  switch (shape) {
    case Shape::dc:
      return dc;
    case Shape::sine:
      if (t < delay) return dc + amplitude * std::sin(phase);
      return dc + amplitude * std::sin(kTwoPi * frequency * (t - delay) + phase);
    case Shape::pwl: {
      if (points.empty()) return dc;
      if (t <= points.front().first) return points.front().second;
      if (t >= points.back().first) return points.back().second;
      auto upper = std::upper_bound(points.begin(), points.end(), t,
                                    [](double time, const auto& p) { return time < p.first; });
      auto lower = upper - 1;
      const double fraction = (t - lower->first) / (upper->first - lower->first);
      return lower->second + fraction * (upper->second - lower->second);
    }
    case Shape::pulse: {
      if (t < delay) return dc;
      double local = t - delay;
      if (period > 0.0) local = std::fmod(local, period);
      if (local < rise) return dc + (pulse_high - dc) * local / rise;
      if (local < rise + width) return pulse_high;
      if (local < rise + width + fall)
        return pulse_high + (dc - pulse_high) * (local - rise - width) / fall;
      return dc;
    }
  }
  return dc;
}

double Waveform::slope(double t) const {
  switch (shape) {
    case Shape::dc:
      return 0.0;
    case Shape::sine:
      if (t < delay) return 0.0;
      return amplitude * kTwoPi * frequency * std::cos(kTwoPi * frequency * (t - delay) + phase);
    case Shape::pwl: {
      if (points.empty() || t < points.front().first || t >= points.back().first) return 0.0;
      auto upper = std::upper_bound(points.begin(), points.end(), t,
                                    [](double time, const auto& p) { return time < p.first; });
      auto lower = upper - 1;
      return (upper->second - lower->second) / (upper->first - lower->first);
    }
    case Shape::pulse: {
      if (t < delay) return 0.0;
      double local = t - delay;
      if (period > 0.0) local = std::fmod(local, period);
      if (local < rise) return (pulse_high - dc) / rise;
      if (local < rise + width) return 0.0;
      if (local < rise + width + fall) return (dc - pulse_high) / fall;
      return 0.0;
    }
  }
  return 0.0;
}

void Waveform::breakpoints(double t_begin, double t_end, std::vector<double>& out) const {
  auto add = [&](double t) {
    if (t > t_begin && t <= t_end) out.push_back(t);
  };
  switch (shape) {
    case Shape::dc:
      return;
    case Shape::sine:
      add(delay);
      return;
    case Shape::pwl:
      for (const auto& p : points) add(p.first);
      return;
    case Shape::pulse: {
      const double edges[] = {0.0, rise, rise + width, rise + width + fall};
      if (period <= 0.0) {
        for (double e : edges) add(delay + e);
        return;
      }
      const double first = std::max(0.0, std::floor((t_begin - delay) / period));
      for (double k = first; delay + k * period <= t_end; k += 1.0)
        for (double e : edges) add(delay + k * period + e);
      return;
    }
  }
}

Waveform Waveform::scaled(double factor) const {
  Waveform w = *this;
  w.dc *= factor;
  w.pulse_high *= factor;
  w.amplitude *= factor;
  for (auto& point : w.points) point.second *= factor;
  w.ac_magnitude *= factor;
  return w;
}

Waveform Waveform::constant(double value) {
  Waveform w;
  w.dc = value;
  return w;
}

Waveform Waveform::square(double low, double high, double frequency, double duty, double delay,
                          double rise_time) {
  Waveform w;
  w.shape = Shape::pulse;
  w.dc = low;
  w.pulse_high = high;
  w.period = 1.0 / frequency;
  w.delay = delay;
  w.rise = rise_time;
  w.fall = rise_time;
  w.width = std::max(0.0, duty * w.period - rise_time);
  return w;
}

}  // namespace emnet
