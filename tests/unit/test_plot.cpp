// Plots through gnuplot: a Bode plot and a line plot give a real PNG (or SVG), with its data and
// script beside it only when asked; series of different units get panels of their own; zero
// magnitudes, hostile labels and odd paths are handled; every failure (bad path, unknown
// extension, mismatched sizes) comes back as a failed Status, not a throw.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "emnet/report/plot.hpp"
#include "file_contents.hpp"
#include "gnuplot_on_path.hpp"
#include "test_directory.hpp"

namespace {

namespace fs = std::filesystem;

using emnet::testing::gnuplot_available;

class PlotTest : public emnet::testing::TestDirectory {
 protected:
  PlotTest() : TestDirectory("emnet_plot_") {}
};

std::string file_start(const std::string& path, size_t count) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(count, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(count));
  bytes.resize(static_cast<size_t>(in.gcount()));
  return bytes;
}

bool is_png(const std::string& path) {
  return file_start(path, 8) == std::string("\x89PNG\r\n\x1a\n", 8);
}

// Response of a damped oscillator (resonance 6.385 Hz) from 0 to 10 Hz; the velocity-like
// series is zero at 0 Hz, which a log magnitude axis cannot show.
struct OscillatorResponse {
  std::vector<double> frequencies_hz;
  std::vector<emnet::BodeSeries> series;
};

OscillatorResponse oscillator_response(int points) {
  const double pi = std::acos(-1.0), natural_hz = 6.385, damping_ratio = 0.05;
  OscillatorResponse response;
  emnet::BodeSeries deflection{"tip", "m/V", {}}, velocity{"P4 velocity", "m/s/V", {}};
  for (int i = 0; i < points; ++i) {
    const double frequency = 10.0 * i / (points - 1);
    const std::complex<double> s(0.0, 2.0 * pi * frequency);
    const double omega = 2.0 * pi * natural_hz;
    const auto h = 1e-3 * omega * omega / (s * s + 2.0 * damping_ratio * omega * s + omega * omega);
    response.frequencies_hz.push_back(frequency);
    deflection.values.push_back(h);
    velocity.values.push_back(s * h);
  }
  response.series = {deflection, velocity};
  return response;
}

// The lines of a gnuplot script that contain `text`.
std::vector<std::string> lines_with(const std::string& script, const std::string& text) {
  std::vector<std::string> found;
  std::istringstream in(script);
  for (std::string line; std::getline(in, line);)
    if (line.find(text) != std::string::npos) found.push_back(line);
  return found;
}

TEST_F(PlotTest, OnlyTheImageUnlessTheSideFilesAreAsked) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const auto response = oscillator_response(50);
  const std::string bode = path("bode.png"), line = path("line.png");
  ASSERT_TRUE(emnet::write_bode_plot(bode, "t", response.frequencies_hz, response.series, {}).ok());
  ASSERT_TRUE(emnet::write_line_plot(line, "t", "x", {{"a", {0, 1}, {0, 1}, "m"}}).ok());
  for (const std::string& image : {bode, line}) {
    EXPECT_TRUE(is_png(image)) << image;
    EXPECT_FALSE(fs::exists(image + ".dat")) << image;
    EXPECT_FALSE(fs::exists(image + ".gp")) << image;
  }
  // Nothing else is left in the directory (the hidden copies gnuplot ran are removed).
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(directory_)) ++files;
  EXPECT_EQ(files, 2u);
}

TEST_F(PlotTest, BodePlotWritesPngWithDataAndScript) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const auto response = oscillator_response(200);
  const std::string image = path("bode.png");
  const auto status =
      emnet::write_bode_plot(image, "damped oscillator", response.frequencies_hz, response.series,
                             {{6.385, "f1 = 6.385 Hz"}}, false, {/*data_and_script=*/true});
  ASSERT_TRUE(status.ok()) << status.message;
  EXPECT_TRUE(is_png(image));
  EXPECT_GT(fs::file_size(image), 1000u);
  EXPECT_TRUE(fs::exists(image + ".dat"));
  EXPECT_TRUE(fs::exists(image + ".gp"));
  // The zero at 0 Hz is a missing point, not a zero on the log axis.
  std::ifstream data(image + ".dat");
  std::string line;
  while (std::getline(data, line) && line.rfind('#', 0) == 0) {
  }
  EXPECT_NE(line.find("NaN"), std::string::npos) << line;
}

TEST_F(PlotTest, BodePlotWritesSvgOnLogFrequencyAxis) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const auto response = oscillator_response(100);  // includes 0 Hz, left out on a log axis
  const std::string image = path("bode.svg");
  const auto status = emnet::write_bode_plot(image, "log axis", response.frequencies_hz,
                                             response.series, {}, /*log_frequency=*/true);
  ASSERT_TRUE(status.ok()) << status.message;
  const std::string start = file_start(image, 400);
  EXPECT_NE(start.find("<svg"), std::string::npos) << start;
}

TEST_F(PlotTest, AllZeroSeriesStillGivesAPlot) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const std::vector<double> frequencies{0.0, 1.0, 2.0, 3.0};
  const emnet::BodeSeries zeros{"clamp", "m/V", std::vector<std::complex<double>>(4)};
  const std::string image = path("zeros.png");
  const auto status = emnet::write_bode_plot(image, "all zero", frequencies, {zeros}, {});
  ASSERT_TRUE(status.ok()) << status.message;
  EXPECT_TRUE(is_png(image));
}

TEST_F(PlotTest, LabelsCannotInjectGnuplotOrShellCommands) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const std::string witness = path("injected");
  const std::string hostile =
      "it's \"quoted\"\nsystem 'touch " + witness + "'\n`touch " + witness + "` @macro a_b^c {x}";
  const emnet::LineSeries series{hostile, {0.0, 1.0, 2.0}, {0.0, 1.0, 0.5}};
  // A directory name with a quote, a dollar and a backquote, to test the shell quoting.
  fs::create_directories(directory_ / "it's $(x) `y`");
  const std::string image = path("it's $(x) `y`/line.png");
  emnet::LinePlotOptions options;
  options.markers = {{1.0, hostile}};
  options.axis_labels = {{"", hostile}};
  options.legend_note = hostile;
  const auto status = emnet::write_line_plot(image, hostile, hostile, {series}, options);
  ASSERT_TRUE(status.ok()) << status.message;
  EXPECT_TRUE(is_png(image));
  EXPECT_FALSE(fs::exists(witness));
}

TEST_F(PlotTest, LinePlotWritesPng) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  emnet::LineSeries tip{"tip", {}, {}, "mm"}, p4{"P4", {}, {}, "mm"};
  for (int i = 0; i < 100; ++i) {
    const double t = 0.01 * i;
    tip.x.push_back(t);
    tip.y.push_back(std::exp(-t) * std::sin(40.0 * t));
    p4.x.push_back(t);
    p4.y.push_back(i == 50 ? std::nan("") : 0.5 * std::sin(40.0 * t));  // a gap
  }
  const std::string image = path("line.png");
  emnet::LinePlotOptions options;
  options.markers = {{0.5, "switch"}};
  const auto status = emnet::write_line_plot(image, "transient", "time [s]", {tip, p4}, options);
  ASSERT_TRUE(status.ok()) << status.message;
  EXPECT_TRUE(is_png(image));
}

TEST_F(PlotTest, UnwritablePathIsAFailedStatus) {
  const auto response = oscillator_response(10);
  const std::string image = path("no/such/directory/bode.png");
  emnet::Status status;
  EXPECT_NO_THROW(
      status = emnet::write_bode_plot(image, "t", response.frequencies_hz, response.series, {}));
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message.find("cannot write"), std::string::npos) << status.message;
  EXPECT_FALSE(fs::exists(image));

  EXPECT_NO_THROW(status = emnet::write_line_plot(image, "t", "x", {{"a", {0, 1}, {0, 1}}}));
  EXPECT_FALSE(status.ok());
}

// A cancelled plot writes nothing: not before gnuplot starts, nor when the cancellation comes
// while gnuplot runs (the process helper asks before its first wait, so the second question,
// the first one asked while gnuplot runs, stops it).
class CancelledAfter : public emnet::Progress {
 public:
  explicit CancelledAfter(int answers) : answers_(answers) {}
  void report(long, long, std::string_view) override {}
  bool cancelled() const override { return ++asked_ > answers_; }

 private:
  int answers_;
  mutable int asked_ = 0;
};

TEST_F(PlotTest, ACancelledPlotWritesNoFile) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  for (const int answers : {0, 1}) {
    const CancelledAfter progress(answers);
    emnet::LinePlotOptions options;
    options.output.data_and_script = true;
    options.output.progress = &progress;
    const auto status =
        emnet::write_line_plot(path("line.png"), "t", "x", {{"a", {0, 1}, {0, 1}, "m"}}, options);
    EXPECT_FALSE(status.ok()) << answers;
    EXPECT_TRUE(status.cancelled()) << answers;
    EXPECT_EQ(entries(), 0u) << answers;  // no image, no side files, no private directory
  }
}

TEST_F(PlotTest, BadArgumentsAreFailedStatuses) {
  const auto response = oscillator_response(10);
  // Unknown image type.
  auto status =
      emnet::write_bode_plot(path("bode.jpg"), "t", response.frequencies_hz, response.series, {});
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message.find(".png"), std::string::npos) << status.message;
  // One value per frequency.
  status = emnet::write_bode_plot(path("bode.png"), "t", {1.0, 2.0}, response.series, {});
  EXPECT_FALSE(status.ok());
  // Nothing to plot.
  status = emnet::write_bode_plot(path("bode.png"), "t", response.frequencies_hz, {}, {});
  EXPECT_FALSE(status.ok());
  // No positive frequency on a log axis.
  const emnet::BodeSeries one{"a", "m", {1.0}};
  status = emnet::write_bode_plot(path("bode.png"), "t", {0.0}, {one}, {}, true);
  EXPECT_FALSE(status.ok());
  // x and y of different lengths.
  status = emnet::write_line_plot(path("line.png"), "t", "x", {{"a", {0, 1, 2}, {0, 1}}});
  EXPECT_FALSE(status.ok());
}

// Series of different units never share an axis: a Bode plot of a deflection [m/V] and a
// voltage [V/V] gets one magnitude panel per unit, each labelled with its one unit; a line plot
// of metres and volts one panel per unit, in the order the units first appear.
TEST_F(PlotTest, SeriesAreGroupedByUnitOnePanelEach) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  auto response = oscillator_response(60);
  response.series[1].unit = "V/V";
  response.series.push_back({"tip again", "m/V", response.series[0].values});
  const std::string bode = path("bode.png");
  ASSERT_TRUE(emnet::write_bode_plot(bode, "two units", response.frequencies_hz, response.series,
                                     {}, false, {true})
                  .ok());
  const std::string bode_script = emnet::testing::file_contents(bode + ".gp");
  const auto bode_labels = lines_with(bode_script, "set ylabel 'magnitude");
  ASSERT_EQ(bode_labels.size(), 2u) << bode_script;
  EXPECT_NE(bode_labels[0].find("[m/V]"), std::string::npos) << bode_labels[0];
  EXPECT_NE(bode_labels[1].find("[V/V]"), std::string::npos) << bode_labels[1];
  // Both m/V series (magnitude columns 2 and 6) in the first panel, the V/V one (column 4) in
  // the second.
  const size_t second_at = bode_script.find(bode_labels[1]);
  const std::string first_panel = bode_script.substr(0, second_at);
  const std::string second_panel =
      bode_script.substr(second_at, bode_script.find("# Phase") - second_at);
  EXPECT_NE(first_panel.find("using 1:2 "), std::string::npos) << first_panel;
  EXPECT_NE(first_panel.find("using 1:6 "), std::string::npos) << first_panel;
  EXPECT_EQ(first_panel.find("using 1:4 "), std::string::npos) << first_panel;
  EXPECT_NE(second_panel.find("using 1:4 "), std::string::npos) << second_panel;

  const std::string line = path("line.png");
  emnet::LinePlotOptions options;
  options.axis_labels = {{"m", "deflection [m]"}, {"V", "voltage [V]"}};
  options.output.data_and_script = true;
  ASSERT_TRUE(emnet::write_line_plot(line, "t", "time [s]",
                                     {{"tip", {0, 1}, {0, 1e-3}, "m"},
                                      {"u_A", {0, 1}, {0, 3e3}, "V"},
                                      {"P4", {0, 1}, {0, 5e-4}, "m"}},
                                     options)
                  .ok());
  const std::string line_script = emnet::testing::file_contents(line + ".gp");
  const auto labels = lines_with(line_script, "set ylabel");
  ASSERT_EQ(labels.size(), 2u) << line_script;
  EXPECT_NE(labels[0].find("'deflection [m]'"), std::string::npos) << labels[0];
  EXPECT_NE(labels[1].find("'voltage [V]'"), std::string::npos) << labels[1];
  // The second panel (after its label) plots index 1 (u_A) only.
  const std::string second = line_script.substr(line_script.find("set ylabel 'voltage [V]'"));
  EXPECT_NE(second.find("index 1 "), std::string::npos) << second;
  EXPECT_EQ(second.find("index 0 "), std::string::npos) << second;
  EXPECT_EQ(second.find("index 2 "), std::string::npos) << second;
}

// A legend entry longer than 72 characters made gnuplot leave the whole key out (a transient of
// reaction, strain and DEA-force probes, whose descriptions run to 120 characters): each entry
// is cut at a word boundary with "...", the short ones kept whole.
TEST_F(PlotTest, LongLegendEntriesAreCutSoThatTheKeyIsDrawn) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const std::string long_label =
      "strain@20mm,top,1.5mm (strain of the top face at x = 20 mm, z = 1.5 mm from the neutral "
      "plane (positive stretched))";
  const std::string line = path("legend.png");
  emnet::LinePlotOptions options;
  options.output.data_and_script = true;
  ASSERT_TRUE(emnet::write_line_plot(
                  line, "t", "time [s]",
                  {{"tip", {0, 1}, {0, 1e-3}, "m"}, {long_label, {0, 1}, {0, 2e-4}, ""}}, options)
                  .ok());
  const std::string script = emnet::testing::file_contents(line + ".gp");
  EXPECT_NE(script.find("title 'tip'"), std::string::npos) << script;
  EXPECT_EQ(script.find("positive stretched"), std::string::npos) << script;
  const size_t cut = script.find("title 'strain@20mm,top,1.5mm (strain of the top face");
  ASSERT_NE(cut, std::string::npos) << script;
  const std::string title = script.substr(cut + 7, script.find('\'', cut + 7) - cut - 7);
  EXPECT_LE(title.size(), 72u) << title;
  EXPECT_EQ(title.substr(title.size() - 3), "...") << title;
}

// A shared colour and a dashed line: the two series given one colour index are drawn in the same
// colour, the dashed one with a dash type, and a series left out of the legend has no title.
TEST_F(PlotTest, PairedSeriesShareAColour) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  emnet::LineSeries left{"tip", {1, 2, 3}, {-1, -2, -1}, "mm"};
  emnet::LineSeries right{"tip right", {1, 2, 3}, {1, 2, 1}, "mm"};
  left.colour = right.colour = 3;
  right.dashed = true;
  right.in_legend = false;
  emnet::LinePlotOptions options;
  options.output.data_and_script = true;
  options.legend_note = "solid: left; dashed: right";
  const std::string image = path("pair.png");
  ASSERT_TRUE(emnet::write_line_plot(image, "pair", "f [Hz]", {left, right}, options).ok());
  const std::string script = emnet::testing::file_contents(image + ".gp");
  const auto first = lines_with(script, "index 0 using");
  const auto second = lines_with(script, "index 1 using");
  ASSERT_EQ(first.size(), 1u);
  ASSERT_EQ(second.size(), 1u);
  const auto colour = [](const std::string& line) {
    const auto at = line.find("lc rgb '");
    return at == std::string::npos ? std::string() : line.substr(at, 16);
  };
  EXPECT_FALSE(colour(first[0]).empty()) << first[0];
  EXPECT_EQ(colour(first[0]), colour(second[0]));
  EXPECT_EQ(first[0].find(" dt "), std::string::npos) << first[0];
  EXPECT_NE(second[0].find(" dt "), std::string::npos) << second[0];
  EXPECT_NE(second[0].find("notitle"), std::string::npos) << second[0];
  EXPECT_EQ(lines_with(script, "solid: left; dashed: right").size(), 1u);
}

// Markers closer than 3 % of the x span share one label (their lines stay); markers farther
// apart keep their own. Reference: the span 1..7 Hz, so 0.18 Hz is the limit.
TEST_F(PlotTest, CloseMarkersShareOneLabel) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  emnet::LinePlotOptions options;
  options.output.data_and_script = true;
  options.markers = {{6.385, "f1 = 6.385 Hz"}, {6.4, "sweep peak 6.4 Hz"}, {2.0, "other"}};
  const std::string image = path("markers.png");
  ASSERT_TRUE(
      emnet::write_line_plot(image, "m", "f [Hz]", {{"a", {1, 7}, {0, 1}, "mm"}}, options).ok());
  const std::string script = emnet::testing::file_contents(image + ".gp");
  EXPECT_EQ(lines_with(script, "set arrow").size(), 3u) << script;
  const auto labels = lines_with(script, "boxed");
  ASSERT_EQ(labels.size(), 2u) << script;
  EXPECT_NE(labels[1].find("'f1 = 6.385 Hz; sweep peak 6.4 Hz'"), std::string::npos) << labels[1];
}

// The (x, y) screen position of a marker label line "set label N 'TEXT' at screen X, screen Y".
std::pair<double, double> label_position(const std::string& line) {
  const auto at = line.rfind(" at screen ");
  std::istringstream in(line.substr(at + 11));
  double x = 0.0, y = 0.0;
  char comma = 0;
  std::string screen;
  in >> x >> comma >> screen >> y;
  return {x, y};
}

// Marker labels never cover a curve and never overlap. Two markers 5 % of the span apart (too far
// to share a label, 43 px on the 860 px panel) have labels about 200 px wide: the second goes a
// row up. A third far away stays on the first row. Every label lies above the top panel (its y
// above the panel's top margin), and labels on one row are at least their half-widths apart; the
// width of a label is taken at 6 px per character, below any character of the 11-point Sans
// font but the narrowest ("i", "l", "."), so the check cannot pass on an overlap of real text.
TEST_F(PlotTest, MarkerLabelsStandAboveThePanelOnRowsThatDoNotOverlap) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  emnet::LinePlotOptions options;
  options.output.data_and_script = true;
  options.markers = {{3.0, "first resonance = 3.000 Hz"},
                     {3.3, "second resonance = 3.300 Hz"},
                     {6.5, "sweep peak 6.5 Hz"}};
  const std::string image = path("rows.png");
  ASSERT_TRUE(
      emnet::write_line_plot(image, "m", "f [Hz]", {{"a", {1, 7}, {0, 1}, "mm"}}, options).ok());
  const std::string script = emnet::testing::file_contents(image + ".gp");
  const auto labels = lines_with(script, "boxed");
  ASSERT_EQ(labels.size(), 3u) << script;
  const auto top_margin = lines_with(script, "set tmargin at screen");
  ASSERT_FALSE(top_margin.empty());
  const double panel_top = std::stod(top_margin.front().substr(22));
  const double width_px = 1000.0;
  std::vector<std::pair<double, double>> at;
  for (const auto& line : labels) {
    at.push_back(label_position(line));
    EXPECT_GT(at.back().second, panel_top) << line;
  }
  EXPECT_GT(at[1].second, at[0].second) << "the second label goes a row up";
  EXPECT_DOUBLE_EQ(at[2].second, at[0].second) << "the far label stays on the first row";
  const std::vector<size_t> lengths = {26, 27, 17};
  for (size_t i = 0; i < at.size(); ++i)
    for (size_t j = i + 1; j < at.size(); ++j) {
      if (at[i].second != at[j].second) continue;
      const double half_widths = 3.0 * static_cast<double>(lengths[i] + lengths[j]);
      EXPECT_GT(std::abs(at[i].first - at[j].first) * width_px, half_widths) << i << ", " << j;
    }
}

// The marker rule against its reference, the peak of the second-order response
// |H(r)| = 1/|1 − r² + 2jζr|: a resonance is marked exactly when |H| rises above its static value
// |H(0)| = 1 somewhere. The peak is found on a grid of r in (0, 3] of step 1e-5 (the peak, when
// there is one, lies at r = sqrt(1 − 2ζ²) < 1); the ζ values keep at least 0.01 from 1/√2, where
// the rise over the grid is far above the 1e-12 margin that rounding of |H| could reach.
TEST(ResonanceMarker, MarkedExactlyWhenTheSecondOrderResponseHasAPeak) {
  for (double zeta : {0.01, 0.05, 0.3, 0.6, 0.69, 0.72, 0.87, 1.0, 2.0}) {
    double largest = 0.0;
    for (int i = 1; i <= 300000; ++i) {
      const double r = 1e-5 * i;
      largest =
          std::max(largest, 1.0 / std::abs(std::complex<double>(1.0 - r * r, 2.0 * zeta * r)));
    }
    EXPECT_EQ(emnet::resonance_shows_peak(zeta), largest > 1.0 + 1e-12) << "zeta " << zeta;
  }
}

}  // namespace
