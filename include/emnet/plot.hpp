// Plots through gnuplot: Bode plots for the AC analysis, line plots for the rest.
//
// Each plot writes its data (path + ".dat") and its gnuplot script (path + ".gp") beside the
// image, so a user can re-run or edit it; the image is PNG (pngcairo) or SVG, by extension.
// Failures (gnuplot missing, unwritable path) come back as a Status, never as an exception.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "emnet/errors.hpp"

namespace emnet {

struct BodeSeries {
  std::string label;
  std::string unit;
  std::vector<std::complex<double>> values;  // one per frequency
};

struct PlotMarker {
  double frequency_hz;  // x position of a vertical line
  std::string label;    // "f1 = 6.385 Hz"
};

// Magnitude (log axis) on top, unwrapped phase [deg] below, shared frequency axis.
Status write_bode_plot(const std::string& path, const std::string& title,
                       const std::vector<double>& frequencies_hz,
                       const std::vector<BodeSeries>& series,
                       const std::vector<PlotMarker>& markers, bool log_frequency = false);

struct LineSeries {
  std::string label;
  std::vector<double> x, y;
};

// Single-panel x–y plot of several series.
Status write_line_plot(const std::string& path, const std::string& title,
                       const std::string& x_label, const std::string& y_label,
                       const std::vector<LineSeries>& series,
                       const std::vector<PlotMarker>& markers = {});

}  // namespace emnet
