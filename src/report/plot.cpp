// Plots: the page's layout (a legend over stacked panels, one per unit, marker labels in rows
// above the top panel, a palette readable on white) and the two kinds, Bode and x-y line plots;
// see include/emnet/report/plot.hpp. The gnuplot script each becomes is written and run by
// gnuplot_script.hpp: every text from the caller goes into it as a single-quoted gnuplot string
// drawn `noenhanced`, so '_', '^', '@', '{' are shown literally.
#include "emnet/report/plot.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/core/constants.hpp"
#include "gnuplot_script.hpp"

namespace emnet {

namespace {

using gnuplot::classic_stream;
using gnuplot::gnuplot_string;
using gnuplot::gnuplot_terminal_line;
using gnuplot::number_text;
using gnuplot::one_line;
using gnuplot::plot_files_for;
using gnuplot::PlotFiles;
using gnuplot::script_header;
using gnuplot::ScriptBody;
using gnuplot::write_script_and_run;
// The panels' horizontal extent on the page, in screen fractions (the multiplot's margins).
constexpr double kPanelLeft = 0.11, kPanelRight = 0.97;

// The start of every script body: missing values, the multiplot with its title, the margins
// that keep the stacked panels' axes aligned.
std::string multiplot_start(const std::string& title_expression) {
  return "set datafile missing 'NaN'\nset multiplot title " + title_expression +
         " font ',13' noenhanced\nset lmargin at screen " + number_text(kPanelLeft) +
         "\nset rmargin at screen " + number_text(kPanelRight) + "\n";
}

// The palette: dark and saturated enough to read on white (no yellow, no pale tints), the
// colour-blind-safe set of Okabe and Ito with its yellow and sky blue replaced by a dark blue
// and a brown, in an order whose neighbours differ in hue and lightness.
constexpr const char* kPalette[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                    "#1a1a1a", "#e69f00", "#3b4cc0", "#8c564b"};
constexpr int kPaletteSize = static_cast<int>(sizeof kPalette / sizeof kPalette[0]);

std::string colour_of(int index) {
  const int k = ((index % kPaletteSize) + kPaletteSize) % kPaletteSize;
  return std::string("lc rgb '") + kPalette[k] + "'";
}

// Markers closer than this fraction of the x span (in the axis's own scale: log10 on a log
// axis) share one label: 3 % of a panel 860 px wide is 26 px, about three characters, so two
// labels this close would sit almost on top of each other and read better as one. Labels farther
// apart that would still touch are set on separate rows (marker_label_layout).
constexpr double kMarkerMergeFraction = 0.03;

// Markers inside [x_lo, x_hi], sorted, in groups that share a label.
struct MarkerGroup {
  std::vector<double> xs;  // the lines, increasing
  std::string label;       // the group's texts joined by "; "
};

std::vector<MarkerGroup> marker_groups(const std::vector<PlotMarker>& markers, double x_lo,
                                       double x_hi, bool log_axis) {
  std::vector<PlotMarker> inside;
  for (const auto& marker : markers) {
    const double x = marker.frequency_hz;
    if (std::isfinite(x) && x >= x_lo && x <= x_hi && (!log_axis || x > 0.0))
      inside.push_back(marker);
  }
  std::stable_sort(inside.begin(), inside.end(), [](const PlotMarker& a, const PlotMarker& b) {
    return a.frequency_hz < b.frequency_hz;
  });
  auto position = [&](double x) { return log_axis ? std::log10(x) : x; };
  const double span = log_axis && x_lo > 0.0 ? std::log10(x_hi) - std::log10(x_lo) : x_hi - x_lo;
  std::vector<MarkerGroup> groups;
  for (const auto& marker : inside) {
    const bool joins = !groups.empty() && span > 0.0 &&
                       position(marker.frequency_hz) - position(groups.back().xs.front()) <
                           kMarkerMergeFraction * span;
    if (joins) {
      groups.back().xs.push_back(marker.frequency_hz);
      groups.back().label += "; " + marker.label;
    } else {
      groups.push_back({{marker.frequency_hz}, marker.label});
    }
  }
  return groups;
}

// Where the marker labels go: horizontal, in a strip between the legend and the top panel, each
// centred over its lines (shifted to stay on the page) on the lowest row where it overlaps no
// label already placed. A label's width is estimated from its length at 7.6 px per character
// (the widest average of the 11-point Sans font; a byte of a multi-byte character counts as one,
// so the estimate errs wide) plus its box; labels are kept 8 px apart.
struct MarkerLabelLayout {
  std::vector<int> row;   // per group; row 0 is next to the panel
  std::vector<double> x;  // per group: the label's centre [screen fraction]
  int rows = 0;
  double strip_px = 0.0;  // the strip's height
  std::vector<double> y;  // per row: its centre [screen fraction], set by place_rows
};

constexpr double kLabelCharacterPx = 7.6, kLabelBoxPx = 12.0, kLabelGapPx = 8.0, kLabelRowPx = 22.0,
                 kLabelStripMarginPx = 6.0;

MarkerLabelLayout marker_label_layout(const std::vector<MarkerGroup>& groups, double x_lo,
                                      double x_hi, bool log_axis, int width_px) {
  MarkerLabelLayout layout;
  if (groups.empty()) return layout;
  auto position = [&](double x) { return log_axis ? std::log10(x) : x; };
  const double from = position(x_lo), span = position(x_hi) - from;
  std::vector<double> row_right;  // the right edge of each row's rightmost label [px]
  for (const auto& group : groups) {
    double fraction = 0.0;
    for (double x : group.xs) fraction += span > 0.0 ? (position(x) - from) / span : 0.5;
    fraction /= static_cast<double>(group.xs.size());
    const double width =
        static_cast<double>(one_line(group.label).size()) * kLabelCharacterPx + kLabelBoxPx;
    double centre = (kPanelLeft + fraction * (kPanelRight - kPanelLeft)) * width_px;
    centre = std::min(std::max(centre, 0.5 * width + 4.0), width_px - 0.5 * width - 4.0);
    const double left = centre - 0.5 * width;
    size_t row = 0;
    while (row < row_right.size() && row_right[row] + kLabelGapPx > left) ++row;
    if (row == row_right.size()) row_right.push_back(-std::numeric_limits<double>::infinity());
    row_right[row] = std::max(row_right[row], centre + 0.5 * width);
    layout.row.push_back(static_cast<int>(row));
    layout.x.push_back(centre / width_px);
  }
  layout.rows = static_cast<int>(row_right.size());
  layout.strip_px = layout.rows * kLabelRowPx + kLabelStripMarginPx;
  return layout;
}

// Each row's centre, for a top panel whose top edge is at `panel_top` [screen fraction].
void place_rows(MarkerLabelLayout& layout, double panel_top, int height_px) {
  layout.y.clear();
  for (int r = 0; r < layout.rows; ++r)
    layout.y.push_back(panel_top + (kLabelStripMarginPx + kLabelRowPx * (r + 0.5)) / height_px);
}

// Vertical dashed lines at the markers, behind the curves. With a label layout (the top panel),
// each line runs on up to its label's row, and the labels are drawn there on opaque boxes: a
// line that crosses a lower row passes behind that row's labels, and no label covers a curve.
std::string marker_lines(const std::vector<MarkerGroup>& groups, const MarkerLabelLayout* labels) {
  std::ostringstream out = classic_stream();
  int arrow = 1;
  for (size_t g = 0; g < groups.size(); ++g) {
    for (double x : groups[g].xs) {
      out << "set arrow " << arrow++ << " from first " << number_text(x) << ", graph 0 to first "
          << number_text(x) << ", "
          << (labels ? "screen " + number_text(labels->y[labels->row[g]]) : std::string("graph 1"))
          << " nohead back dt 2 lw 1.5 lc rgb '#b00000'\n";
    }
    if (labels) {
      out << "set label " << 100 + g << " " << gnuplot_string(groups[g].label) << " at screen "
          << number_text(labels->x[g]) << ", screen " << number_text(labels->y[labels->row[g]])
          << " center front boxed noenhanced tc rgb '#b00000'\n";
    }
  }
  return out.str();
}

// Text box of the marker labels: opaque, so the lines behind a label do not cross its text.
constexpr const char* kMarkerLabelStyle =
    "set style textbox opaque fillcolor 'white' border lc rgb '#b00000' lw 0.5 margins 1,1\n";

std::string unset_markers() {
  return "unset arrow\nunset label\n";
}

// The reference lines of the panel of `unit` (arrows and labels 500 on; the next panel's
// unset_markers clears them).
std::string reference_lines(const std::vector<ReferenceLine>& lines, const std::string& unit) {
  std::string out;
  for (size_t k = 0; k < lines.size(); ++k) {
    if (lines[k].unit != unit || !std::isfinite(lines[k].value)) continue;
    const std::string at = number_text(lines[k].value);
    out += "set arrow " + std::to_string(500 + k) + " from graph 0, first " + at +
           " to graph 1, first " + at + " nohead front lc rgb '#c00000' dt 3 lw 1.5\n";
    if (!lines[k].label.empty())
      out += "set label " + std::to_string(500 + k) + " " + gnuplot_string(lines[k].label) +
             " at graph 0.005, first " + at +
             " offset 0, 0.6 left front tc rgb '#c00000' font ',9' noenhanced\n";
  }
  return out;
}

// "[lo:hi]" for a range of finite values, or "[*:*]" when there is nothing finite or one value.
std::string range_text(double lo, double hi) {
  if (!(lo < hi)) return "[*:*]";
  return "[" + number_text(lo) + ":" + number_text(hi) + "]";
}

// Phase step for the tics of an unwrapped phase axis spanning `span` degrees (0: automatic).
double phase_tic_step(double span) {
  if (span <= 360.0) return 45.0;
  if (span <= 1080.0) return 90.0;
  if (span <= 2160.0) return 180.0;
  return 0.0;
}

// A series' legend entry: its label on one line, cut to kLegendCharacters (with "...") at a
// word boundary where it can be. A longer entry made gnuplot leave the key out altogether
// (descriptions of reaction, strain and DEA-force probes run to 120 characters); the full
// description stays in the table and the data file.
constexpr size_t kLegendCharacters = 72;
std::string legend_label(const std::string& label) {
  std::string text = one_line(label);
  if (text.size() <= kLegendCharacters) return text;
  size_t cut = text.rfind(' ', kLegendCharacters - 3);
  if (cut == std::string::npos || cut < kLegendCharacters / 2) cut = kLegendCharacters - 3;
  return text.substr(0, cut) + "...";
}

// The legend: one row of entries between the page title and the top panel, wrapped into as
// many rows as the label lengths need, and an optional note line under it. Pixel sizes are for
// the 11-point Sans font.
struct LegendLayout {
  std::string key_line;   // "set key ..." line
  std::string note_line;  // "set label ..." line of the note, or empty
  double panel_top = 0;   // screen fraction where the (top) panel starts, below the legend
};

LegendLayout legend_layout(const std::vector<std::string>& entries, const std::string& note,
                           int width_px, int height_px, int title_lines) {
  constexpr double kCharacterWidthPx = 7.5, kRowHeightPx = 19.0;
  const double kTitleHeightPx = 42.0 + 20.0 * (title_lines - 1);
  size_t longest = 1;
  for (const auto& entry : entries) longest = std::max(longest, one_line(entry).size());
  const double column_width_px = (static_cast<double>(longest) + 9.0) * kCharacterWidthPx;
  const size_t fitting = static_cast<size_t>(0.9 * width_px / column_width_px);
  const size_t columns = std::max<size_t>(1, std::min(entries.size(), fitting));
  const size_t rows = std::max<size_t>(1, (entries.size() + columns - 1) / columns);
  const double key_top = 1.0 - kTitleHeightPx / height_px;
  LegendLayout layout;
  layout.key_line = "set key at screen 0.5, screen " + number_text(key_top) +
                    " center top horizontal maxcols " + std::to_string(columns) + " maxrows " +
                    std::to_string(rows) + " samplen 3 noenhanced\n";
  double used_px = static_cast<double>(rows) * kRowHeightPx + 12.0;
  if (!note.empty()) {
    layout.note_line = "set label 90 " + gnuplot_string(note) + " at screen 0.5, screen " +
                       number_text(key_top - (used_px + 2.0) / height_px) +
                       " center noenhanced tc rgb '#404040'\n";
    used_px += kRowHeightPx + 6.0;
  }
  layout.panel_top = key_top - used_px / height_px;
  return layout;
}

// Panels stacked from `top` down to `bottom`, `gap` apart, heights in proportion to `weights`:
// each panel's (top, bottom) in screen fractions.
std::vector<std::pair<double, double>> stacked_panels(double top, double bottom, double gap,
                                                      const std::vector<double>& weights) {
  double total = 0.0;
  for (double w : weights) total += w;
  const double available = top - bottom - gap * static_cast<double>(weights.size() - 1);
  std::vector<std::pair<double, double>> panels;
  double at = top;
  for (double w : weights) {
    const double height = available * w / total;
    panels.emplace_back(at, at - height);
    at -= height + gap;
  }
  return panels;
}

// The units of `units_of_series` in the order they first appear, and each series' group.
std::vector<std::string> unit_groups(const std::vector<std::string>& units_of_series,
                                     std::vector<size_t>& group_of_series) {
  std::vector<std::string> units;
  group_of_series.clear();
  for (const auto& unit : units_of_series) {
    auto found = std::find(units.begin(), units.end(), unit);
    if (found == units.end()) found = units.insert(units.end(), unit);
    group_of_series.push_back(static_cast<size_t>(found - units.begin()));
  }
  return units;
}

// The y axis of a magnitude panel whose finite positive values lie in [lo, hi]: logarithmic, at
// most kBodeMagnitudeDecades below hi, widened by 4 % of its span (at least 0.05 decade) each
// side, so no curve runs along the border and no empty decade is left; tics at 1, 2, 5 times the
// powers of ten when it spans fewer than 2.5 decades (a decade's tics alone would leave at most
// two labels). Under one decade a log axis shows nothing a linear one does not, and gets too
// few tics to read: the axis is then linear, 5 % of the span wider each side.
std::string magnitude_axis(double lo, double hi) {
  if (!(lo > 0.0) || !(hi >= lo) || !std::isfinite(hi))
    return "set logscale y\nset format y '%h'\nset yrange [*:*]\n";
  const double top = std::log10(hi);
  const double bottom = std::max(std::log10(lo), top - kBodeMagnitudeDecades);
  if (top - bottom < 1.0) {
    const double low = std::pow(10.0, bottom);
    const double pad = hi > low ? 0.05 * (hi - low) : 0.05 * hi;
    return "unset logscale y\nset format y '%.4g'\nset yrange [" + number_text(low - pad) + ":" +
           number_text(hi + pad) + "]\n";
  }
  const double pad = std::max(0.05, 0.04 * (top - bottom));
  const double from = std::pow(10.0, bottom - pad), to = std::pow(10.0, top + pad);
  std::string axis = "set logscale y\nset format y '%h'\nset yrange [" + number_text(from) + ":" +
                     number_text(to) + "]\n";
  if (top - bottom < 2.5) {
    std::string tics;
    for (int e = static_cast<int>(std::floor(bottom - pad)); e <= static_cast<int>(top + pad); ++e)
      for (double m : {1.0, 2.0, 5.0}) {
        const double tic = m * std::pow(10.0, e);
        if (tic >= from && tic <= to) tics += (tics.empty() ? "" : ", ") + number_text(tic);
      }
    axis += "set ytics (" + tics + ")\n";
  }
  return axis;
}

// Shifts an unwrapped phase curve [deg] by whole turns so that its first finite point lies in
// (-270, 90]: a phase of ±180 (a sign inversion, where rounding decides the side arg() returns)
// then starts every curve on the same side, and the lags of a mechanical response stay below it.
void normalise_phase(std::vector<double>& phase) {
  for (double first : phase) {
    if (!std::isfinite(first)) continue;
    const double turns = std::ceil((first - 90.0) / 360.0);
    for (double& value : phase) value -= 360.0 * turns;
    return;
  }
}

// The title in at most two lines: split at the last ", " or " " before `width` characters when
// longer, as a gnuplot string expression; `lines` is set to the count.
std::string title_text(const std::string& title, size_t width, int& lines) {
  const std::string text = one_line(title);
  lines = 1;
  if (text.size() <= width) return gnuplot_string(text);
  size_t cut = text.rfind(" (", width);
  if (cut == std::string::npos || cut < width / 2) cut = text.rfind(' ', width);
  if (cut == std::string::npos || cut == 0) return gnuplot_string(text);
  lines = 2;
  return gnuplot_string(text.substr(0, cut)) + ".\"\\n\"." +
         gnuplot_string(text.substr(text[cut] == ' ' ? cut + 1 : cut));
}

}  // namespace

bool resonance_shows_peak(double damping_ratio) {
  return damping_ratio < kResonanceDampingLimit;  // the mode rule's limit (kModeRule)
}

namespace {

Status check_bode_input(const std::string& path, const std::vector<double>& frequencies_hz,
                        const std::vector<BodeSeries>& series) {
  if (series.empty()) return Status::failure("Bode plot '" + path + "': no series to plot");
  if (frequencies_hz.empty()) return Status::failure("Bode plot '" + path + "': no frequencies");
  for (const auto& one : series) {
    if (one.values.size() != frequencies_hz.size()) {
      return Status::failure("Bode plot '" + path + "': series '" + one.label + "' has " +
                             std::to_string(one.values.size()) + " values for " +
                             std::to_string(frequencies_hz.size()) + " frequencies");
    }
  }
  return Status::success();
}

// The Bode plot's curves over the rows kept, magnitudes grouped into one panel per unit.
struct BodeCurves {
  std::vector<size_t> rows;  ///< finite frequencies (positive ones on a log axis)
  std::vector<std::string> units;
  std::vector<size_t> group_of;  ///< the panel of each series
  std::vector<double> group_lo, group_hi;
  std::vector<std::vector<double>> magnitude, phase_deg;  ///< NaN: a missing point
  double phase_min = std::numeric_limits<double>::infinity();
  double phase_max = -std::numeric_limits<double>::infinity();
  bool any_magnitude = false;
  double x_lo = std::numeric_limits<double>::infinity();
  double x_hi = -std::numeric_limits<double>::infinity();
};

std::vector<size_t> plotted_rows(const std::vector<double>& frequencies_hz, bool log_frequency) {
  std::vector<size_t> rows;
  for (size_t f = 0; f < frequencies_hz.size(); ++f) {
    const double frequency = frequencies_hz[f];
    if (std::isfinite(frequency) && (!log_frequency || frequency > 0.0)) rows.push_back(f);
  }
  return rows;
}

// Magnitude and unwrapped phase of series k; zero or non-finite values are missing (NaN) points.
void add_bode_curve(const BodeSeries& series, size_t k, BodeCurves& curves) {
  bool have_previous = false;
  double previous_phase = 0.0;
  const size_t group = curves.group_of[k];
  for (size_t f : curves.rows) {
    const std::complex<double> value = series.values[f];
    const double size = std::abs(value);
    if (!(size > 0.0) || !std::isfinite(size)) {
      curves.magnitude[k].push_back(std::nan(""));
      curves.phase_deg[k].push_back(std::nan(""));
      continue;
    }
    double phase = std::arg(value) * 180.0 / kPi;
    if (have_previous) phase += 360.0 * std::round((previous_phase - phase) / 360.0);
    previous_phase = phase;
    have_previous = true;
    curves.any_magnitude = true;
    curves.group_lo[group] = std::min(curves.group_lo[group], size);
    curves.group_hi[group] = std::max(curves.group_hi[group], size);
    curves.magnitude[k].push_back(size);
    curves.phase_deg[k].push_back(phase);
  }
  normalise_phase(curves.phase_deg[k]);
  for (double phase : curves.phase_deg[k]) {
    if (!std::isfinite(phase)) continue;
    curves.phase_min = std::min(curves.phase_min, phase);
    curves.phase_max = std::max(curves.phase_max, phase);
  }
}

BodeCurves bode_curves(const std::vector<double>& frequencies_hz,
                       const std::vector<BodeSeries>& series, std::vector<size_t> rows) {
  BodeCurves curves;
  curves.rows = std::move(rows);
  std::vector<std::string> series_units;
  for (const auto& one : series) series_units.push_back(one.unit);
  curves.units = unit_groups(series_units, curves.group_of);
  curves.group_lo.assign(curves.units.size(), std::numeric_limits<double>::infinity());
  curves.group_hi.assign(curves.units.size(), 0.0);
  curves.magnitude.resize(series.size());
  curves.phase_deg.resize(series.size());
  for (size_t k = 0; k < series.size(); ++k) add_bode_curve(series[k], k, curves);
  for (size_t f : curves.rows) {
    curves.x_lo = std::min(curves.x_lo, frequencies_hz[f]);
    curves.x_hi = std::max(curves.x_hi, frequencies_hz[f]);
  }
  return curves;
}

std::string bode_data_text(const std::string& title, const std::vector<double>& frequencies_hz,
                           const std::vector<BodeSeries>& series, const BodeCurves& curves) {
  std::ostringstream data = classic_stream();
  data << "# " << one_line(title) << "\n# frequency [Hz]";
  for (const auto& one : series) {
    data << " | |" << one_line(one.label) << "| [" << one_line(one.unit) << "] | phase of "
         << one_line(one.label) << " [deg]";
  }
  data << "\n# NaN: zero or non-finite value (no point on the log axis)\n";
  for (size_t row = 0; row < curves.rows.size(); ++row) {
    data << number_text(frequencies_hz[curves.rows[row]]);
    for (size_t k = 0; k < series.size(); ++k) {
      data << ' ' << number_text(curves.magnitude[k][row]) << ' '
           << number_text(curves.phase_deg[k][row]);
    }
    data << '\n';
  }
  return data.str();
}

// Where the Bode plot's parts go: marker labels, legend, panels (magnitudes, then the phase).
struct BodeLayout {
  std::vector<MarkerGroup> groups;
  MarkerLabelLayout marker_labels;
  std::vector<std::string> legend_entries;
  LegendLayout legend;
  std::string title_expression;
  std::vector<std::pair<double, double>> panels;
  int height_px = 0;
};
constexpr int kBodeWidthPx = 1000;

BodeLayout bode_layout(const std::string& title, const std::vector<BodeSeries>& series,
                       const std::vector<PlotMarker>& markers, bool log_frequency,
                       const BodeCurves& curves) {
  BodeLayout layout;
  layout.groups = marker_groups(markers, curves.x_lo, curves.x_hi, log_frequency);
  for (const auto& one : series) {
    layout.legend_entries.push_back(
        legend_label(one.label + (one.unit.empty() ? "" : " [" + one.unit + "]")));
  }
  layout.marker_labels =
      marker_label_layout(layout.groups, curves.x_lo, curves.x_hi, log_frequency, kBodeWidthPx);
  layout.height_px = 750 + 230 * static_cast<int>(curves.units.size() - 1) +
                     static_cast<int>(std::lround(layout.marker_labels.strip_px));
  int title_lines = 1;
  layout.title_expression = title_text(title, 110, title_lines);
  layout.legend =
      legend_layout(layout.legend_entries, "", kBodeWidthPx, layout.height_px, title_lines);
  // Panels from under the marker labels down to the bottom: the magnitudes, then the phase.
  const double top = layout.legend.panel_top - layout.marker_labels.strip_px / layout.height_px;
  place_rows(layout.marker_labels, top, layout.height_px);
  const double bottom = 70.0 / layout.height_px, gap = 45.0 / layout.height_px;
  std::vector<double> weights(curves.units.size(), 1.0);
  weights.push_back(curves.units.size() > 1 ? 0.8 : 1.0);
  layout.panels = stacked_panels(top, bottom, gap, weights);
  return layout;
}

// The magnitude panel of unit group g; the first also carries the figure's one key.
std::string bode_magnitude_panel(size_t g, const std::string& data_name, const BodeCurves& curves,
                                 BodeLayout& layout) {
  std::ostringstream script = classic_stream();
  const std::string& unit = curves.units[g];
  const std::string label = unit.empty() ? "magnitude" : "magnitude [" + one_line(unit) + "]";
  script << "\n# Magnitude" << (unit.empty() ? "" : " [" + one_line(unit) + "]") << "\n"
         << (g ? unset_markers() : "") << "set tmargin at screen "
         << number_text(layout.panels[g].first) << "\nset bmargin at screen "
         << number_text(layout.panels[g].second) << "\n"
         << "set format x ''\nunset xlabel\n"
         << "set ytics autofreq\nset ylabel " << gnuplot_string(label) << " noenhanced\n"
         << (curves.any_magnitude ? magnitude_axis(curves.group_lo[g], curves.group_hi[g])
                                  : "set logscale y\nset format y '%h'\nset yrange [0.1:10]\nset "
                                    "label 99 'no non-zero values to plot' at graph 0.5, graph "
                                    "0.5 center\n")
         << (g == 0 ? layout.legend.key_line : "unset key\n")
         << marker_lines(layout.groups, g == 0 ? &layout.marker_labels : nullptr) << "plot ";
  const size_t series_count = curves.group_of.size();
  bool first = true;
  for (size_t k = 0; k < series_count; ++k) {
    if (curves.group_of[k] != g) continue;
    script << (first ? "" : ", \\\n     ") << gnuplot_string(data_name) << " using 1:" << 2 + 2 * k
           << " with lines lw 2 " << colour_of(static_cast<int>(k)) << " title "
           << gnuplot_string(layout.legend_entries[k]);
    first = false;
  }
  // With one key for the figure, the other panels' series join it from the first panel.
  if (g == 0) {
    for (size_t k = 0; k < series_count; ++k) {
      if (curves.group_of[k] == 0) continue;
      script << ", \\\n     NaN with lines lw 2 " << colour_of(static_cast<int>(k)) << " title "
             << gnuplot_string(layout.legend_entries[k]);
    }
  }
  script << "\n";
  return script.str();
}

// The bottom panel: the unwrapped phase of every series.
std::string bode_phase_panel(const std::string& data_name, const BodeCurves& curves,
                             const BodeLayout& layout) {
  std::ostringstream script = classic_stream();
  const auto& phase_panel = layout.panels.back();
  const double step =
      curves.any_magnitude ? phase_tic_step(curves.phase_max - curves.phase_min) : 45.0;
  script << "\n# Phase (unwrapped along frequency)\n"
         << unset_markers() << "set tmargin at screen " << number_text(phase_panel.first)
         << "\nset bmargin at screen " << number_text(phase_panel.second) << "\n"
         << "set format x '% h'\nset xlabel 'frequency [Hz]'\n"
         << "unset logscale y\nset format y '% h'\nset yrange [*:*]\nset ytics autofreq\n"
         << "set ylabel 'phase [deg]'\n"
         << (curves.any_magnitude ? "" : "set yrange [-180:180]\n")
         << (step > 0.0 ? "set ytics " + number_text(step) + "\n" : "") << "unset key\n"
         << marker_lines(layout.groups, nullptr) << "plot ";
  for (size_t k = 0; k < curves.group_of.size(); ++k) {
    script << (k ? ", \\\n     " : "") << gnuplot_string(data_name) << " using 1:" << 3 + 2 * k
           << " with lines lw 2 " << colour_of(static_cast<int>(k)) << " notitle";
  }
  script << "\n\nunset multiplot\n";
  return script.str();
}

}  // namespace

Status write_bode_plot(const std::string& path, const std::string& title,
                       const std::vector<double>& frequencies_hz,
                       const std::vector<BodeSeries>& series,
                       const std::vector<PlotMarker>& markers, bool log_frequency,
                       const PlotOutput& output) {
  PlotFiles files;
  if (Status status = plot_files_for(path, files); !status.ok()) return status;
  if (Status status = check_bode_input(path, frequencies_hz, series); !status.ok()) return status;
  std::vector<size_t> rows = plotted_rows(frequencies_hz, log_frequency);
  if (rows.empty()) {
    return Status::failure("Bode plot '" + path + "': no " +
                           std::string(log_frequency ? "positive finite" : "finite") +
                           " frequency to plot");
  }
  const BodeCurves curves = bode_curves(frequencies_hz, series, std::move(rows));
  BodeLayout layout = bode_layout(title, series, markers, log_frequency, curves);
  const std::string preamble = script_header(files, "Bode plot", title) +
                               gnuplot_terminal_line(files, kBodeWidthPx, layout.height_px);
  const ScriptBody body = [&](const std::string& data_name) {
    std::ostringstream script = classic_stream();
    script << multiplot_start(layout.title_expression) << "set xrange "
           << range_text(curves.x_lo, curves.x_hi) << "\n"
           << (log_frequency ? "set logscale x\n" : "") << "set grid xtics ytics\n"
           << "set border lw 1\n"
           << kMarkerLabelStyle;
    for (size_t g = 0; g < curves.units.size(); ++g)
      script << bode_magnitude_panel(g, data_name, curves, layout);
    script << bode_phase_panel(data_name, curves, layout);
    return script.str();
  };
  return write_script_and_run(files, preamble, body,
                              bode_data_text(title, frequencies_hz, series, curves), path, output);
}

namespace {

Status check_line_input(const std::string& path, const std::vector<LineSeries>& series) {
  if (series.empty()) return Status::failure("line plot '" + path + "': no series to plot");
  for (const auto& one : series) {
    if (one.x.size() != one.y.size()) {
      return Status::failure("line plot '" + path + "': series '" + one.label + "' has " +
                             std::to_string(one.x.size()) + " x values and " +
                             std::to_string(one.y.size()) + " y values");
    }
  }
  return Status::success();
}

// The line plot's data: one block per series (gnuplot `index k`), separated by two blank lines,
// and the ranges and panels they fill.
struct LineData {
  std::string text;
  std::vector<std::string> units;
  std::vector<size_t> group_of;  ///< the panel of each series
  std::vector<bool> group_has_point;
  bool any_point = false;
  double x_lo = std::numeric_limits<double>::infinity();
  double x_hi = -std::numeric_limits<double>::infinity();
};

LineData line_data(const std::string& title, const std::string& x_label,
                   const std::vector<LineSeries>& series) {
  LineData data;
  std::vector<std::string> series_units;
  for (const auto& one : series) series_units.push_back(one.unit);
  data.units = unit_groups(series_units, data.group_of);
  data.group_has_point.assign(data.units.size(), false);
  std::ostringstream text = classic_stream();
  text << "# " << one_line(title) << "\n# columns: " << one_line(x_label)
       << " | the series' value in its unit"
       << "; one block per series (gnuplot index 0, 1, ...); NaN: missing point\n";
  for (size_t k = 0; k < series.size(); ++k) {
    const auto& one = series[k];
    text << (k ? "\n\n" : "") << "# index " << k << ": " << one_line(one.label) << " ["
         << one_line(one.unit) << "]\n";
    for (size_t i = 0; i < one.x.size(); ++i) {
      const bool finite = std::isfinite(one.x[i]) && std::isfinite(one.y[i]);
      text << number_text(finite ? one.x[i] : std::nan("")) << ' '
           << number_text(finite ? one.y[i] : std::nan("")) << '\n';
      if (finite) {
        data.any_point = true;
        data.group_has_point[data.group_of[k]] = true;
        data.x_lo = std::min(data.x_lo, one.x[i]);
        data.x_hi = std::max(data.x_hi, one.x[i]);
      }
    }
    if (one.x.empty()) text << "NaN NaN\n";  // keeps the block, so the indices stay in step
  }
  data.text = text.str();
  return data;
}

// Where the line plot's parts go: marker labels, legend and the panels, one per unit.
struct LineLayout {
  std::vector<MarkerGroup> groups;
  MarkerLabelLayout marker_labels;
  LegendLayout legend;
  std::string title_expression;
  std::vector<std::pair<double, double>> panels;
  int height_px = 0;
};
constexpr int kLineWidthPx = 1000;

LineLayout line_layout(const std::string& title, const std::vector<LineSeries>& series,
                       const LinePlotOptions& options, const LineData& data) {
  LineLayout layout;
  std::vector<std::string> legend_entries;
  for (const auto& one : series)
    if (one.in_legend) legend_entries.push_back(legend_label(one.label));
  layout.groups = data.any_point ? marker_groups(options.markers, data.x_lo, data.x_hi, false)
                                 : std::vector<MarkerGroup>{};
  layout.marker_labels =
      marker_label_layout(layout.groups, data.x_lo, data.x_hi, false, kLineWidthPx);
  layout.height_px = 650 + 260 * static_cast<int>(data.units.size() - 1) +
                     static_cast<int>(std::lround(layout.marker_labels.strip_px));
  int title_lines = 1;
  layout.title_expression = title_text(title, 110, title_lines);
  layout.legend = legend_layout(legend_entries, options.legend_note, kLineWidthPx, layout.height_px,
                                title_lines);
  // Panels from under the marker labels down; the first (the response) a little taller than the
  // others (the drive, other units).
  const double top = layout.legend.panel_top - layout.marker_labels.strip_px / layout.height_px;
  place_rows(layout.marker_labels, top, layout.height_px);
  std::vector<double> weights(data.units.size(), 1.0);
  if (data.units.size() > 1) weights.front() = 1.4;
  layout.panels = stacked_panels(top, 72.0 / layout.height_px, 40.0 / layout.height_px, weights);
  return layout;
}

std::string line_axis_label(const LinePlotOptions& options, const std::string& unit) {
  const auto named = options.axis_labels.find(unit);
  if (named != options.axis_labels.end()) return named->second;
  return unit.empty() ? std::string("value") : "value [" + unit + "]";
}

std::string line_style(const LineSeries& one, size_t k) {
  return "with lines lw 2 " + colour_of(one.colour >= 0 ? one.colour : static_cast<int>(k)) +
         (one.dashed ? " dt (8,5)" : "");
}

// Panel g of the line plot; the first also carries the figure's one key.
std::string line_panel(size_t g, const std::string& data_name, const std::string& x_label,
                       const std::vector<LineSeries>& series, const LinePlotOptions& options,
                       const LineData& data, LineLayout& layout) {
  std::ostringstream script = classic_stream();
  const bool last = g + 1 == data.units.size();
  const std::string axis_label = line_axis_label(options, data.units[g]);
  script << "\n# Panel " << g + 1 << ": " << one_line(axis_label) << "\n"
         << (g ? unset_markers() : "") << "set tmargin at screen "
         << number_text(layout.panels[g].first) << "\nset bmargin at screen "
         << number_text(layout.panels[g].second) << "\n"
         << (last ? "set format x '% h'\nset xlabel " + gnuplot_string(x_label) + " noenhanced\n"
                  : std::string("set format x ''\nunset xlabel\n"))
         << "set ylabel " << gnuplot_string(axis_label) << " noenhanced\n"
         << (data.group_has_point[g] ? "set yrange [*:*]\n" : "set yrange [0:1]\n")
         << (g == 0 ? layout.legend.key_line + layout.legend.note_line : std::string("unset key\n"))
         << marker_lines(layout.groups, g == 0 ? &layout.marker_labels : nullptr)
         << reference_lines(options.reference_lines, data.units[g]) << "plot ";
  bool first = true;
  for (size_t k = 0; k < series.size(); ++k) {
    if (data.group_of[k] != g) continue;
    script << (first ? "" : ", \\\n     ") << gnuplot_string(data_name) << " index " << k
           << " using 1:2 " << line_style(series[k], k) << " "
           << (series[k].in_legend && g == 0
                   ? "title " + gnuplot_string(legend_label(series[k].label))
                   : std::string("notitle"));
    first = false;
  }
  // One key for the figure: the other panels' series join it from the first panel.
  if (g == 0) {
    for (size_t k = 0; k < series.size(); ++k) {
      if (data.group_of[k] == 0 || !series[k].in_legend) continue;
      script << ", \\\n     NaN " << line_style(series[k], k) << " title "
             << gnuplot_string(legend_label(series[k].label));
    }
  }
  script << "\n";
  return script.str();
}

}  // namespace

Status write_line_plot(const std::string& path, const std::string& title,
                       const std::string& x_label, const std::vector<LineSeries>& series,
                       const LinePlotOptions& options) {
  PlotFiles files;
  if (Status status = plot_files_for(path, files); !status.ok()) return status;
  if (Status status = check_line_input(path, series); !status.ok()) return status;
  const LineData data = line_data(title, x_label, series);
  LineLayout layout = line_layout(title, series, options, data);
  const std::string preamble = script_header(files, "Line plot", title) +
                               gnuplot_terminal_line(files, kLineWidthPx, layout.height_px);
  const ScriptBody body = [&](const std::string& data_name) {
    std::ostringstream script = classic_stream();
    script << multiplot_start(layout.title_expression)
           << "set grid xtics ytics\nset border lw 1\nset format y '%g'\n"
           << "set offsets 0, 0, graph 0.06, graph 0.06\n"
           << kMarkerLabelStyle
           << (data.any_point ? "set xrange " + range_text(data.x_lo, data.x_hi) + "\n"
                              : "set xrange [0:1]\n");
    for (size_t g = 0; g < data.units.size(); ++g)
      script << line_panel(g, data_name, x_label, series, options, data, layout);
    script << "\nunset multiplot\n";
    return script.str();
  };
  return write_script_and_run(files, preamble, body, data.text, path, options.output);
}

}  // namespace emnet
