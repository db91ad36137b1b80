// The SPICE deck's independent sources: DC, SIN, PULSE or PWL time functions of emnet's
// waveforms, instant switching as stated narrow linear edges
// (include/emnet/spice/spice_netlist.hpp).
#include "deck_writer.hpp"

namespace emnet::spice_deck {

std::string DeckWriter::pwl(const std::vector<std::pair<double, double>>& points,
                            const std::string& what) {
  std::string text = "PWL(";
  for (size_t k = 0; k < points.size(); ++k) {
    if (k > 0) text += (k % 4 == 0) ? "\n+ " : " ";
    text += value(points[k].first, what) + " " + value(points[k].second, what);
  }
  return text + ")";
}

std::string DeckWriter::time_function(const Waveform& w, const std::string& what) {
  switch (w.shape) {
    case Waveform::Shape::dc:
      return "DC " + value(w.dc, what);
    case Waveform::Shape::sine:
      if (w.frequency == 0.0 || w.amplitude == 0.0)
        return "DC " + value(w.dc + w.amplitude * std::sin(w.phase), what);
      return "SIN(" + value(w.dc, what) + " " + value(w.amplitude, what) + " " +
             value(w.frequency, what) + " " + value(w.delay, what) + " 0 " +
             value(w.phase * 180.0 / pi, what) + ")";
    case Waveform::Shape::pwl:
      if (w.points.empty()) return "DC " + value(w.dc, what);
      return pwl(w.points, what);
    case Waveform::Shape::pulse:
      break;
  }
  const double low = w.dc, high = w.pulse_high, delay = w.delay, width = w.width, period = w.period;
  if (low == high) return "DC " + value(low, what);
  if (w.rise > 0.0 && w.fall > 0.0) {
    if (period > 0.0)
      return "PULSE(" + value(low, what) + " " + value(high, what) + " " + value(delay, what) +
             " " + value(w.rise, what) + " " + value(w.fall, what) + " " + value(width, what) +
             " " + value(period, what) + ")";
    return pwl({{0.0, w.value(0.0)},
                {delay, low},
                {delay + w.rise, high},
                {delay + w.rise + width, high},
                {delay + w.rise + width + w.fall, low}},
               what);
  }
  if (w.rise != 0.0 || w.fall != 0.0)
    throw InputError(where(), what,
                     "a pulse with one zero and one non-zero edge time is not written to SPICE "
                     "decks (SPICE reads a zero edge as the output step); give both edges a "
                     "time");
  // Instant switching: centred linear edges of width ε.
  const double on_time = std::min(width, period > 0.0 ? period : width);
  const double off_time = period > 0.0 ? period - width : on_time;
  if (width <= 0.0) return "DC " + value(low, what);
  if (period > 0.0 && width >= period) {
    if (delay <= 0.0) return "DC " + value(high, what);
    const double edge = options_.edge_fraction * delay;
    edge_notes_.push_back(what + ": step at " + number(delay) + " s as an edge of " + number(edge) +
                          " s centred on it");
    return pwl({{0.0, low}, {delay - edge / 2, low}, {delay + edge / 2, high}}, what);
  }
  double edge = options_.edge_fraction * std::min(on_time, off_time);
  if (delay > 0.0) edge = std::min(edge, delay);
  edge_notes_.push_back(what + ": instant switching as linear edges of " + number(edge) +
                        " s centred on emnet's switching instants");
  if (period <= 0.0) {
    if (delay <= 0.0)
      return pwl({{0.0, high}, {width - edge / 2, high}, {width + edge / 2, low}}, what);
    return pwl({{0.0, low},
                {delay - edge / 2, low},
                {delay + edge / 2, high},
                {delay + width - edge / 2, high},
                {delay + width + edge / 2, low}},
               what);
  }
  if (delay > 0.0)
    return "PULSE(" + value(low, what) + " " + value(high, what) + " " +
           value(delay - edge / 2, what) + " " + value(edge, what) + " " + value(edge, what) + " " +
           value(width - edge, what) + " " + value(period, what) + ")";
  // On at t = 0: the PULSE runs from the high level and its first edge falls at `width`.
  return "PULSE(" + value(high, what) + " " + value(low, what) + " " +
         value(width - edge / 2, what) + " " + value(edge, what) + " " + value(edge, what) + " " +
         value(period - width - edge, what) + " " + value(period, what) + ")";
}

std::string DeckWriter::source(const Waveform& w, const std::string& what) {
  if (tran_) return time_function(w, what);
  std::string text = "DC " + value(w.value(0.0), what);
  if (ac_ && w.ac_magnitude != 0.0) {
    double phase = w.ac_phase + (w.ac_magnitude < 0.0 ? pi : 0.0);
    phase = std::remainder(phase, 2.0 * pi) * 180.0 / pi;
    text += " AC " + value(std::abs(w.ac_magnitude), what) + " " + value(phase, what);
  }
  return text;
}

}  // namespace emnet::spice_deck
