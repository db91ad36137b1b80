// Plots through gnuplot: two-panel Bode plots and single-panel x-y line plots.
//
// Each plot is written as three files: the image itself (PNG through the pngcairo terminal when
// the path ends in ".png", SVG when it ends in ".svg"), the plotted numbers (path + ".dat") and
// the gnuplot script that draws them (path + ".gp"). The script names the data and image files
// relative to its own directory, so a user can edit it and re-run it there with
// `gnuplot NAME.gp`. Each of the three is written completely or not at all (through a temporary
// file renamed into place, include/emnet/core/output_file.hpp): a failure leaves the previous file,
// if any, never a truncated one. gnuplot runs under a time limit; every failure (gnuplot missing,
// an unwritable directory, a full disk, a gnuplot error, a timeout) is returned as a failed Status,
// never thrown.
//
// Titles and labels are written as single-quoted gnuplot strings with control characters
// replaced by spaces and quotes doubled, and drawn without enhanced-text markup, so any text
// (quotes, backticks, '@', '_', '^', newlines) is shown literally and cannot run a command.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "emnet/core/errors.hpp"

namespace emnet {

// One curve of a Bode plot: a complex response, one value per frequency of the plot.
// `unit` is the unit of the magnitude, e.g. "m/V" or "m/s/V"; it is shown in the legend.
struct BodeSeries {
  std::string label;
  std::string unit;
  std::vector<std::complex<double>> values;
};

// A vertical dashed line at `frequency_hz` (an x value for line plots) with a text label beside
// it, e.g. {6.385, "f1 = 6.385 Hz"}. Markers outside the plotted x range are left out.
struct PlotMarker {
  double frequency_hz;
  std::string label;
};

// Two-panel Bode plot: magnitude on a logarithmic axis (in the series' units) on top, phase in
// degrees (unwrapped along frequency) below, on a shared frequency axis in Hz, linear or, with
// `log_frequency`, logarithmic (non-positive frequencies are then left out). Zero and non-finite
// values are left out of both panels (the curve shows a gap there). Every series must have one
// value per frequency.
Status write_bode_plot(const std::string& path, const std::string& title,
                       const std::vector<double>& frequencies_hz,
                       const std::vector<BodeSeries>& series,
                       const std::vector<PlotMarker>& markers, bool log_frequency = false);

// One curve of a line plot: points (x[i], y[i]); x and y must have the same length.
struct LineSeries {
  std::string label;
  std::vector<double> x, y;
};

// Single-panel x-y line plot of several series on linear axes, for time-domain and sweep plots.
// Non-finite points are left out (the curve shows a gap there).
Status write_line_plot(const std::string& path, const std::string& title,
                       const std::string& x_label, const std::string& y_label,
                       const std::vector<LineSeries>& series,
                       const std::vector<PlotMarker>& markers = {});

}  // namespace emnet
