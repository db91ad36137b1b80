// Plot file names that reach a gnuplot script: a newline or another control character in the
// name is refused before anything is written (it used to become a script line of its own and
// run gnuplot commands, or make gnuplot fail and leave a hidden temporary behind).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "emnet/report/plot.hpp"
#include "gnuplot_on_path.hpp"
#include "test_directory.hpp"

namespace {

namespace fs = std::filesystem;

using emnet::testing::gnuplot_available;

class PlotNames : public emnet::testing::TestDirectory {
 protected:
  PlotNames() : TestDirectory("emnet_plot_names_") {}
  size_t entries() const {
    size_t count = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(directory_)) ++count;
    return count;
  }
};

const std::vector<emnet::LineSeries> kLine{{"a", {0.0, 1.0}, {0.0, 1.0}, "m"}};

TEST_F(PlotNames, ANewlineInTheNameRunsNoCommand) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  // The name: before the refusal the script header wrote it raw into comment lines,
  // so `system("touch X")` became a line of the saved script and of the copy gnuplot ran
  // (gnuplot runs in the image's directory, the test directory, where X would appear).
  const std::string image = path("a\nsystem(\"touch X\")\n#.png");
  emnet::LinePlotOptions options;
  options.output.data_and_script = true;
  const auto status = emnet::write_line_plot(image, "t", "x", kLine, options);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message.find("control character"), std::string::npos) << status.message;
  EXPECT_FALSE(fs::exists(path("X")));
  EXPECT_EQ(entries(), 0u);  // no image, no side files, no hidden temporary
}

TEST_F(PlotNames, EveryControlCharacterIsRefusedBeforeAnythingIsWritten) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  for (const char control : {'\t', '\r', '\x01', '\x1b', '\x7f'}) {
    const std::string image = path(std::string("a") + control + "b.png");
    const auto status = emnet::write_line_plot(image, "t", "x", kLine);
    EXPECT_FALSE(status.ok()) << static_cast<int>(control);
    EXPECT_EQ(entries(), 0u) << static_cast<int>(control);
  }
  // Also in the directory part of the path.
  const std::string nested = path("d\ne/line.png");
  EXPECT_FALSE(emnet::write_line_plot(nested, "t", "x", kLine).ok());
}

TEST_F(PlotNames, OrdinaryNamesWithSpacesAndQuotesStillDraw) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const std::string image = path("it's a \"plot\" #1.png");
  const auto status = emnet::write_line_plot(image, "t", "x", kLine);
  ASSERT_TRUE(status.ok()) << status.message;
  EXPECT_TRUE(fs::exists(image));
}

}  // namespace
