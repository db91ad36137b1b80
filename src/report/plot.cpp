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

constexpr double kPi = 3.14159265358979323846;
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

Status write_bode_plot(const std::string& path, const std::string& title,
                       const std::vector<double>& frequencies_hz,
                       const std::vector<BodeSeries>& series,
                       const std::vector<PlotMarker>& markers, bool log_frequency,
                       const PlotOutput& output) {
  PlotFiles files;
  if (Status status = plot_files_for(path, files); !status.ok()) return status;
  if (series.empty()) return Status::failure("Bode plot '" + path + "': no series to plot");
  if (frequencies_hz.empty()) return Status::failure("Bode plot '" + path + "': no frequencies");
  for (const auto& one : series) {
    if (one.values.size() != frequencies_hz.size()) {
      return Status::failure("Bode plot '" + path + "': series '" + one.label + "' has " +
                             std::to_string(one.values.size()) + " values for " +
                             std::to_string(frequencies_hz.size()) + " frequencies");
    }
  }

  // Rows kept: finite frequencies (positive ones on a log axis).
  std::vector<size_t> rows;
  for (size_t f = 0; f < frequencies_hz.size(); ++f) {
    const double frequency = frequencies_hz[f];
    if (std::isfinite(frequency) && (!log_frequency || frequency > 0.0)) rows.push_back(f);
  }
  if (rows.empty()) {
    return Status::failure("Bode plot '" + path + "': no " +
                           std::string(log_frequency ? "positive finite" : "finite") +
                           " frequency to plot");
  }

  // The magnitude panels: one per unit.
  std::vector<std::string> series_units;
  for (const auto& one : series) series_units.push_back(one.unit);
  std::vector<size_t> group_of;
  const std::vector<std::string> units = unit_groups(series_units, group_of);
  std::vector<double> group_lo(units.size(), std::numeric_limits<double>::infinity()),
      group_hi(units.size(), 0.0);

  // Magnitude and unwrapped phase; zero or non-finite values are missing (NaN) points.
  const size_t series_count = series.size();
  std::vector<std::vector<double>> magnitude(series_count), phase_deg(series_count);
  double phase_min = std::numeric_limits<double>::infinity(), phase_max = -phase_min;
  bool any_magnitude = false;
  for (size_t k = 0; k < series_count; ++k) {
    bool have_previous = false;
    double previous_phase = 0.0;
    for (size_t f : rows) {
      const std::complex<double> value = series[k].values[f];
      const double size = std::abs(value);
      if (!(size > 0.0) || !std::isfinite(size)) {
        magnitude[k].push_back(std::nan(""));
        phase_deg[k].push_back(std::nan(""));
        continue;
      }
      double phase = std::arg(value) * 180.0 / kPi;
      if (have_previous) phase += 360.0 * std::round((previous_phase - phase) / 360.0);
      previous_phase = phase;
      have_previous = true;
      any_magnitude = true;
      group_lo[group_of[k]] = std::min(group_lo[group_of[k]], size);
      group_hi[group_of[k]] = std::max(group_hi[group_of[k]], size);
      magnitude[k].push_back(size);
      phase_deg[k].push_back(phase);
    }
    normalise_phase(phase_deg[k]);
    for (double phase : phase_deg[k]) {
      if (!std::isfinite(phase)) continue;
      phase_min = std::min(phase_min, phase);
      phase_max = std::max(phase_max, phase);
    }
  }

  std::ostringstream data = classic_stream();
  data << "# " << one_line(title) << "\n# frequency [Hz]";
  for (const auto& one : series) {
    data << " | |" << one_line(one.label) << "| [" << one_line(one.unit) << "] | phase of "
         << one_line(one.label) << " [deg]";
  }
  data << "\n# NaN: zero or non-finite value (no point on the log axis)\n";
  for (size_t row = 0; row < rows.size(); ++row) {
    data << number_text(frequencies_hz[rows[row]]);
    for (size_t k = 0; k < series_count; ++k) {
      data << ' ' << number_text(magnitude[k][row]) << ' ' << number_text(phase_deg[k][row]);
    }
    data << '\n';
  }

  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  for (size_t f : rows) {
    x_lo = std::min(x_lo, frequencies_hz[f]);
    x_hi = std::max(x_hi, frequencies_hz[f]);
  }
  const std::vector<MarkerGroup> groups = marker_groups(markers, x_lo, x_hi, log_frequency);

  std::vector<std::string> legend_entries;
  for (const auto& one : series) {
    legend_entries.push_back(
        legend_label(one.label + (one.unit.empty() ? "" : " [" + one.unit + "]")));
  }
  constexpr int kWidthPx = 1000;
  MarkerLabelLayout marker_labels =
      marker_label_layout(groups, x_lo, x_hi, log_frequency, kWidthPx);
  const int height_px = 750 + 230 * static_cast<int>(units.size() - 1) +
                        static_cast<int>(std::lround(marker_labels.strip_px));
  int title_lines = 1;
  const std::string title_expression = title_text(title, 110, title_lines);
  const LegendLayout legend = legend_layout(legend_entries, "", kWidthPx, height_px, title_lines);
  // Panels from under the marker labels down to the bottom: the magnitudes, then the phase.
  const double top = legend.panel_top - marker_labels.strip_px / height_px;
  place_rows(marker_labels, top, height_px);
  const double bottom = 70.0 / height_px, gap = 45.0 / height_px;
  std::vector<double> weights(units.size(), 1.0);
  weights.push_back(units.size() > 1 ? 0.8 : 1.0);
  const auto panels = stacked_panels(top, bottom, gap, weights);

  const std::string preamble =
      script_header(files, "Bode plot", title) + gnuplot_terminal_line(files, kWidthPx, height_px);
  const ScriptBody body = [&](const std::string& data_name) {
    std::ostringstream script = classic_stream();
    script << multiplot_start(title_expression) << "set xrange " << range_text(x_lo, x_hi) << "\n"
           << (log_frequency ? "set logscale x\n" : "") << "set grid xtics ytics\n"
           << "set border lw 1\n"
           << kMarkerLabelStyle;

    for (size_t g = 0; g < units.size(); ++g) {
      const std::string label =
          units[g].empty() ? "magnitude" : "magnitude [" + one_line(units[g]) + "]";
      script << "\n# Magnitude" << (units[g].empty() ? "" : " [" + one_line(units[g]) + "]") << "\n"
             << (g ? unset_markers() : "") << "set tmargin at screen "
             << number_text(panels[g].first) << "\nset bmargin at screen "
             << number_text(panels[g].second) << "\n"
             << "set format x ''\nunset xlabel\n"
             << "set ytics autofreq\nset ylabel " << gnuplot_string(label) << " noenhanced\n"
             << (any_magnitude ? magnitude_axis(group_lo[g], group_hi[g])
                               : "set logscale y\nset format y '%h'\nset yrange [0.1:10]\nset "
                                 "label 99 'no non-zero values to plot' at graph 0.5, graph 0.5 "
                                 "center\n")
             << (g == 0 ? legend.key_line : "unset key\n")
             << marker_lines(groups, g == 0 ? &marker_labels : nullptr) << "plot ";
      bool first = true;
      for (size_t k = 0; k < series_count; ++k) {
        if (group_of[k] != g) continue;
        script << (first ? "" : ", \\\n     ") << gnuplot_string(data_name)
               << " using 1:" << 2 + 2 * k << " with lines lw 2 " << colour_of(static_cast<int>(k))
               << " title " << gnuplot_string(legend_entries[k]);
        first = false;
      }
      // With one key for the figure, the other panels' series join it from the first panel.
      if (g == 0) {
        for (size_t k = 0; k < series_count; ++k) {
          if (group_of[k] == 0) continue;
          script << ", \\\n     NaN with lines lw 2 " << colour_of(static_cast<int>(k)) << " title "
                 << gnuplot_string(legend_entries[k]);
        }
      }
      script << "\n";
    }

    // Bottom panel: unwrapped phase.
    const auto& phase_panel = panels.back();
    const double step = any_magnitude ? phase_tic_step(phase_max - phase_min) : 45.0;
    script << "\n# Phase (unwrapped along frequency)\n"
           << unset_markers() << "set tmargin at screen " << number_text(phase_panel.first)
           << "\nset bmargin at screen " << number_text(phase_panel.second) << "\n"
           << "set format x '% h'\nset xlabel 'frequency [Hz]'\n"
           << "unset logscale y\nset format y '% h'\nset yrange [*:*]\nset ytics autofreq\n"
           << "set ylabel 'phase [deg]'\n"
           << (any_magnitude ? "" : "set yrange [-180:180]\n")
           << (step > 0.0 ? "set ytics " + number_text(step) + "\n" : "") << "unset key\n"
           << marker_lines(groups, nullptr) << "plot ";
    for (size_t k = 0; k < series_count; ++k) {
      script << (k ? ", \\\n     " : "") << gnuplot_string(data_name) << " using 1:" << 3 + 2 * k
             << " with lines lw 2 " << colour_of(static_cast<int>(k)) << " notitle";
    }
    script << "\n\nunset multiplot\n";
    return script.str();
  };
  return write_script_and_run(files, preamble, body, data.str(), path, output);
}

Status write_line_plot(const std::string& path, const std::string& title,
                       const std::string& x_label, const std::vector<LineSeries>& series,
                       const LinePlotOptions& options) {
  PlotFiles files;
  if (Status status = plot_files_for(path, files); !status.ok()) return status;
  if (series.empty()) return Status::failure("line plot '" + path + "': no series to plot");
  for (const auto& one : series) {
    if (one.x.size() != one.y.size()) {
      return Status::failure("line plot '" + path + "': series '" + one.label + "' has " +
                             std::to_string(one.x.size()) + " x values and " +
                             std::to_string(one.y.size()) + " y values");
    }
  }
  std::vector<std::string> series_units;
  for (const auto& one : series) series_units.push_back(one.unit);
  std::vector<size_t> group_of;
  const std::vector<std::string> units = unit_groups(series_units, group_of);
  auto axis_label = [&](const std::string& unit) {
    const auto named = options.axis_labels.find(unit);
    if (named != options.axis_labels.end()) return named->second;
    return unit.empty() ? std::string("value") : "value [" + unit + "]";
  };

  // One data block per series (gnuplot `index k`), separated by two blank lines.
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  bool any_point = false;
  std::vector<bool> group_has_point(units.size(), false);
  std::ostringstream data = classic_stream();
  data << "# " << one_line(title) << "\n# columns: " << one_line(x_label)
       << " | the series' value in its unit"
       << "; one block per series (gnuplot index 0, 1, ...); NaN: missing point\n";
  for (size_t k = 0; k < series.size(); ++k) {
    const auto& one = series[k];
    data << (k ? "\n\n" : "") << "# index " << k << ": " << one_line(one.label) << " ["
         << one_line(one.unit) << "]\n";
    for (size_t i = 0; i < one.x.size(); ++i) {
      const bool finite = std::isfinite(one.x[i]) && std::isfinite(one.y[i]);
      data << number_text(finite ? one.x[i] : std::nan("")) << ' '
           << number_text(finite ? one.y[i] : std::nan("")) << '\n';
      if (finite) {
        any_point = true;
        group_has_point[group_of[k]] = true;
        x_lo = std::min(x_lo, one.x[i]);
        x_hi = std::max(x_hi, one.x[i]);
      }
    }
    if (one.x.empty()) data << "NaN NaN\n";  // keeps the block, so the indices stay in step
  }

  std::vector<std::string> legend_entries;
  for (const auto& one : series)
    if (one.in_legend) legend_entries.push_back(legend_label(one.label));
  constexpr int kWidthPx = 1000;
  const std::vector<MarkerGroup> groups =
      any_point ? marker_groups(options.markers, x_lo, x_hi, false) : std::vector<MarkerGroup>{};
  MarkerLabelLayout marker_labels = marker_label_layout(groups, x_lo, x_hi, false, kWidthPx);
  const int height_px = 650 + 260 * static_cast<int>(units.size() - 1) +
                        static_cast<int>(std::lround(marker_labels.strip_px));
  int title_lines = 1;
  const std::string title_expression = title_text(title, 110, title_lines);
  const LegendLayout legend =
      legend_layout(legend_entries, options.legend_note, kWidthPx, height_px, title_lines);
  // Panels from under the marker labels down; the first (the response) a little taller than the
  // others (the drive, other units).
  const double top = legend.panel_top - marker_labels.strip_px / height_px;
  place_rows(marker_labels, top, height_px);
  std::vector<double> weights(units.size(), 1.0);
  if (units.size() > 1) weights.front() = 1.4;
  const auto panels = stacked_panels(top, 72.0 / height_px, 40.0 / height_px, weights);
  auto style_of = [&](size_t k) {
    const LineSeries& one = series[k];
    return "with lines lw 2 " + colour_of(one.colour >= 0 ? one.colour : static_cast<int>(k)) +
           (one.dashed ? " dt (8,5)" : "");
  };

  const std::string preamble =
      script_header(files, "Line plot", title) + gnuplot_terminal_line(files, kWidthPx, height_px);
  const ScriptBody body = [&](const std::string& data_name) {
    std::ostringstream script = classic_stream();
    script << multiplot_start(title_expression)
           << "set grid xtics ytics\nset border lw 1\nset format y '%g'\n"
           << "set offsets 0, 0, graph 0.06, graph 0.06\n"
           << kMarkerLabelStyle
           << (any_point ? "set xrange " + range_text(x_lo, x_hi) + "\n" : "set xrange [0:1]\n");
    for (size_t g = 0; g < units.size(); ++g) {
      const bool last = g + 1 == units.size();
      script << "\n# Panel " << g + 1 << ": " << one_line(axis_label(units[g])) << "\n"
             << (g ? unset_markers() : "") << "set tmargin at screen "
             << number_text(panels[g].first) << "\nset bmargin at screen "
             << number_text(panels[g].second) << "\n"
             << (last
                     ? "set format x '% h'\nset xlabel " + gnuplot_string(x_label) + " noenhanced\n"
                     : std::string("set format x ''\nunset xlabel\n"))
             << "set ylabel " << gnuplot_string(axis_label(units[g])) << " noenhanced\n"
             << (group_has_point[g] ? "set yrange [*:*]\n" : "set yrange [0:1]\n")
             << (g == 0 ? legend.key_line + legend.note_line : std::string("unset key\n"))
             << marker_lines(groups, g == 0 ? &marker_labels : nullptr)
             << reference_lines(options.reference_lines, units[g]) << "plot ";
      bool first = true;
      for (size_t k = 0; k < series.size(); ++k) {
        if (group_of[k] != g) continue;
        script << (first ? "" : ", \\\n     ") << gnuplot_string(data_name) << " index " << k
               << " using 1:2 " << style_of(k) << " "
               << (series[k].in_legend && g == 0
                       ? "title " + gnuplot_string(legend_label(series[k].label))
                       : std::string("notitle"));
        first = false;
      }
      // One key for the figure: the other panels' series join it from the first panel.
      if (g == 0) {
        for (size_t k = 0; k < series.size(); ++k) {
          if (group_of[k] == 0 || !series[k].in_legend) continue;
          script << ", \\\n     NaN " << style_of(k) << " title "
                 << gnuplot_string(legend_label(series[k].label));
        }
      }
      script << "\n";
    }
    script << "\nunset multiplot\n";
    return script.str();
  };
  return write_script_and_run(files, preamble, body, data.str(), path, options.output);
}

}  // namespace emnet
