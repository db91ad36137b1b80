// Plots through gnuplot: Bode plots (magnitude panels over a phase panel) and x-y line plots
// (one panel per unit, stacked on a shared x axis).
//
// By default only the image is written: PNG through the pngcairo terminal when the path ends in
// ".png", SVG when it ends in ".svg". With `data_and_script` the plotted numbers (path + ".dat")
// and the gnuplot script that draws them (path + ".gp") are written beside it too; the script
// names the data and image files relative to its own directory, so a user can edit it and
// re-run it there with `gnuplot NAME.gp`. Each file is written completely or not at all (through
// a temporary file renamed into place, include/emnet/core/output_file.hpp): a failure leaves the
// previous file, if any, never a truncated one. gnuplot runs under a time limit; every failure
// (gnuplot missing, an unwritable directory, a full disk, a gnuplot error, a timeout) is
// returned as a failed Status, never thrown. gnuplot reads and writes only inside a private
// directory (mode 0700, made by mkdtemp beside the image and removed afterwards), so no other
// user can swap its files; the image is renamed from there onto the path.
//
// No axis carries two units: series are grouped by their unit, one panel (one y axis) per
// group, in the order the units first appear. Colours come from a palette readable on white
// (no yellow or pale colours); a colour can be shared by several series (the left and right
// extremes of one output), told apart by a dashed line. Marker lines run behind the curves;
// their labels stand above the top panel, never over a curve, and never overlap: markers closer
// than 3 % of the x axis's span share one label, and a label that would touch another goes up a
// row.
//
// Titles and labels are written as single-quoted gnuplot strings with control characters
// replaced by spaces and quotes doubled, and drawn without enhanced-text markup, so any text
// (quotes, backticks, '@', '_', '^', newlines) is shown literally and cannot run a command.
#pragma once

#include <complex>
#include <map>
#include <string>
#include <vector>

#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"

namespace emnet {

// One curve of a Bode plot: a complex response, one value per frequency of the plot.
// `unit` is the unit of the magnitude, e.g. "m/V" or "V/V"; series of one unit share a
// magnitude panel, whose axis names it.
struct BodeSeries {
  std::string label;
  std::string unit;
  std::vector<std::complex<double>> values;
};

// A vertical dashed line at `frequency_hz` (an x value for line plots) through every panel, with
// a text label above the top panel, e.g. {6.385, "f1 = 6.385 Hz"}. Markers outside the plotted x
// range are left out; markers closer together than 3 % of the x span get one label, their texts
// joined by "; ".
struct PlotMarker {
  double frequency_hz;
  std::string label;
};

// Whether a resonance of damping ratio ζ shows as a peak, and so gets a marker: a second-order
// response |H| = 1/|1 − r² + 2jζr| (r = f/f_n) rises above its static value only for
// ζ < 1/√2 (d|H|/dr = 0 at r² = 1 − 2ζ²); a more damped mode has no peak to point at.
bool resonance_shows_peak(double damping_ratio);

/// What a plot writes besides its image, and when it stops.
struct PlotOutput {
  /// Also write the data (path + ".dat") and the gnuplot script (path + ".gp") beside the
  /// image, once the image is drawn.
  bool data_and_script = false;
  /// Asked while gnuplot draws (at least every 100 ms): when cancelled, gnuplot is killed, no
  /// file is written and the plot returns cancelled_status(). Null: not cancellable.
  const Progress* progress = nullptr;
};

// Bode plot: one magnitude panel per unit of the series (logarithmic axis; its range fits the
// data, at most kBodeMagnitudeDecades decades below the panel's largest value: deeper
// anti-resonance notches are cut at the panel's bottom so that the peaks and the roll-off keep
// the axis), then the phase in degrees (unwrapped along frequency), on a shared frequency axis
// in Hz, linear or, with `log_frequency`, logarithmic (non-positive frequencies are then left
// out). Zero and non-finite values are left out of every panel (the curve shows a gap there).
// Every series must have one value per frequency.
inline constexpr double kBodeMagnitudeDecades = 6.0;
Status write_bode_plot(const std::string& path, const std::string& title,
                       const std::vector<double>& frequencies_hz,
                       const std::vector<BodeSeries>& series,
                       const std::vector<PlotMarker>& markers, bool log_frequency = false,
                       const PlotOutput& output = {});

// One curve of a line plot: points (x[i], y[i]); x and y must have the same length.
struct LineSeries {
  std::string label;
  std::vector<double> x, y;
  std::string unit;       // of y; one panel per unit ("" is a unit of its own)
  int colour = -1;        // palette index (any integer, taken modulo its size); -1: own index
  bool dashed = false;    // a dashed line (e.g. the second side of one output)
  bool in_legend = true;  // false: drawn without a legend entry (its pair's entry names it)
};

// A horizontal line across the panel of `unit` at `value` (a model's limit, e.g. the
// deflection limit ±model.deflection_limit·L), dotted in red with `label` above it.
struct ReferenceLine {
  std::string unit;
  double value = 0.0;
  std::string label;
};

struct LinePlotOptions {
  std::vector<PlotMarker> markers;
  std::vector<ReferenceLine> reference_lines;
  // Each panel's y-axis label by unit; a unit not named here is labelled "value [unit]".
  std::map<std::string, std::string> axis_labels;
  // One line of text under the legend, e.g. which line style is which side.
  std::string legend_note;
  PlotOutput output;
};

// x-y line plot on linear axes, for time-domain and sweep plots: one panel per unit of the
// series, stacked top to bottom in the order the units first appear, sharing the x axis (its
// label under the bottom panel). Non-finite points are left out (the curve shows a gap there).
Status write_line_plot(const std::string& path, const std::string& title,
                       const std::string& x_label, const std::vector<LineSeries>& series,
                       const LinePlotOptions& options = {});

}  // namespace emnet
