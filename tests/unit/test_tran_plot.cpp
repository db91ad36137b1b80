// `emnet tran --plot` draws the DEA voltages under the response by their probe text, whatever
// the scene's own probes are named: with a dea_voltage probe named other than u_<DEA>, the plot
// asked for the output "u_A", which no such scene has, and failed ("--probe: key 'u_A'").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_run.hpp"
#include "gnuplot_on_path.hpp"
#include "test_directory.hpp"

namespace {

class CliTranPlot : public emnet::testing::TestDirectory {
 protected:
  CliTranPlot() : TestDirectory("emnet_tran_plot_") {}
};

TEST_F(CliTranPlot, DeaVoltageUnderAProbeNameOfItsOwnStillPlots) {
  if (!emnet::testing::gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  std::ifstream shipped(std::string(EMNET_SOURCE_DIR) + "/netlists/gripper-finger.toml");
  std::string text((std::istreambuf_iterator<char>(shipped)), {});
  const std::string named = "name = \"u_A\"";
  ASSERT_NE(text.find(named), std::string::npos);
  text.replace(text.find(named), named.size(), "name = \"volts_A\"");
  std::ofstream(path("finger.toml")) << text;
  const auto run = emnet::testing::run_emnet("tran " + path("finger.toml") +
                                             " --periods 1 --probe tip --plot " + path("f.png"));
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(std::filesystem::exists(path("f.png")));
}

}  // namespace
