// Plots through gnuplot: a Bode plot and a line plot give a real PNG (or SVG) with its data and
// script beside it; zero magnitudes, hostile labels and odd paths are handled; every failure
// (bad path, unknown extension, mismatched sizes) comes back as a failed Status, not a throw.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "emnet/report/plot.hpp"
#include "test_directory.hpp"

namespace {

namespace fs = std::filesystem;

bool gnuplot_available() {
  return std::system("command -v gnuplot >/dev/null 2>&1") == 0;
}

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

TEST_F(PlotTest, BodePlotWritesPngWithDataAndScript) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const auto response = oscillator_response(200);
  const std::string image = path("bode.png");
  const auto status = emnet::write_bode_plot(image, "damped oscillator", response.frequencies_hz,
                                             response.series, {{6.385, "f1 = 6.385 Hz"}});
  ASSERT_TRUE(status.ok) << status.message;
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
  ASSERT_TRUE(status.ok) << status.message;
  const std::string start = file_start(image, 400);
  EXPECT_NE(start.find("<svg"), std::string::npos) << start;
}

TEST_F(PlotTest, AllZeroSeriesStillGivesAPlot) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const std::vector<double> frequencies{0.0, 1.0, 2.0, 3.0};
  const emnet::BodeSeries zeros{"clamp", "m/V", std::vector<std::complex<double>>(4)};
  const std::string image = path("zeros.png");
  const auto status = emnet::write_bode_plot(image, "all zero", frequencies, {zeros}, {});
  ASSERT_TRUE(status.ok) << status.message;
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
  const auto status =
      emnet::write_line_plot(image, hostile, hostile, hostile, {series}, {{1.0, hostile}});
  ASSERT_TRUE(status.ok) << status.message;
  EXPECT_TRUE(is_png(image));
  EXPECT_FALSE(fs::exists(witness));
}

TEST_F(PlotTest, LinePlotWritesPng) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  emnet::LineSeries tip{"tip [mm]", {}, {}}, p4{"P4 [mm]", {}, {}};
  for (int i = 0; i < 100; ++i) {
    const double t = 0.01 * i;
    tip.x.push_back(t);
    tip.y.push_back(std::exp(-t) * std::sin(40.0 * t));
    p4.x.push_back(t);
    p4.y.push_back(i == 50 ? std::nan("") : 0.5 * std::sin(40.0 * t));  // a gap
  }
  const std::string image = path("line.png");
  const auto status = emnet::write_line_plot(image, "transient", "time [s]", "deflection [mm]",
                                             {tip, p4}, {{0.5, "switch"}});
  ASSERT_TRUE(status.ok) << status.message;
  EXPECT_TRUE(is_png(image));
}

TEST_F(PlotTest, UnwritablePathIsAFailedStatus) {
  const auto response = oscillator_response(10);
  const std::string image = path("no/such/directory/bode.png");
  emnet::Status status;
  EXPECT_NO_THROW(
      status = emnet::write_bode_plot(image, "t", response.frequencies_hz, response.series, {}));
  EXPECT_FALSE(status.ok);
  EXPECT_NE(status.message.find("cannot write"), std::string::npos) << status.message;
  EXPECT_FALSE(fs::exists(image));

  EXPECT_NO_THROW(status = emnet::write_line_plot(image, "t", "x", "y", {{"a", {0, 1}, {0, 1}}}));
  EXPECT_FALSE(status.ok);
}

TEST_F(PlotTest, BadArgumentsAreFailedStatuses) {
  const auto response = oscillator_response(10);
  // Unknown image type.
  auto status =
      emnet::write_bode_plot(path("bode.jpg"), "t", response.frequencies_hz, response.series, {});
  EXPECT_FALSE(status.ok);
  EXPECT_NE(status.message.find(".png"), std::string::npos) << status.message;
  // One value per frequency.
  status = emnet::write_bode_plot(path("bode.png"), "t", {1.0, 2.0}, response.series, {});
  EXPECT_FALSE(status.ok);
  // Nothing to plot.
  status = emnet::write_bode_plot(path("bode.png"), "t", response.frequencies_hz, {}, {});
  EXPECT_FALSE(status.ok);
  // No positive frequency on a log axis.
  const emnet::BodeSeries one{"a", "m", {1.0}};
  status = emnet::write_bode_plot(path("bode.png"), "t", {0.0}, {one}, {}, true);
  EXPECT_FALSE(status.ok);
  // x and y of different lengths.
  status = emnet::write_line_plot(path("line.png"), "t", "x", "y", {{"a", {0, 1, 2}, {0, 1}}});
  EXPECT_FALSE(status.ok);
}

}  // namespace
