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

// Plots of a result outside validity showed nothing of it. The fin's sweep through its
// resonance swings 10.7 % of L (limit 10 %, exit 5): its plot draws the limit at ±12.25 mm
// (its deflections are in mm); a transient inside the limit draws none.
TEST_F(CliTranPlot, DeflectionLimitIsDrawnWhereTheResultLeavesIt) {
  if (!emnet::testing::gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const std::string fin = std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml";
  const auto sweep = emnet::testing::run_emnet("sweep-switching " + fin + " --plot " +
                                               path("sweep.png") + " --plot-script");
  ASSERT_EQ(sweep.status, 5) << sweep.err;
  const std::string text = contents("sweep.png.gp");
  EXPECT_NE(text.find("set arrow 500 from graph 0, first 12.25 "), std::string::npos) << text;
  EXPECT_NE(text.find("first -12.25 "), std::string::npos) << text;
  EXPECT_NE(text.find("deflection limit +/-12.25 mm (model.deflection_limit)"), std::string::npos)
      << text;
  const auto tran = emnet::testing::run_emnet("tran " + fin + " --periods 1 --plot " +
                                              path("tran.png") + " --plot-script");
  ASSERT_EQ(tran.status, 0) << tran.err;
  const std::string inside = contents("tran.png.gp");
  EXPECT_EQ(inside.find("set arrow 500"), std::string::npos) << inside;
}

// Lengths in one unit across plots (the transient's were in m, the sweep's in mm, and the
// sweep's only when every output was a deflection): mm in every plot, whatever else is drawn,
// the deflection limit included (1 % of L = 1.225 mm, exceeded by the fin's transient).
TEST_F(CliTranPlot, LengthsAreInMillimetresInEveryPlot) {
  if (!emnet::testing::gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const std::string fin = std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml";
  const auto tran = emnet::testing::run_emnet(
      "tran " + fin + " --periods 1 --probe tip --probe u_A --set model.deflection_limit=0.01" +
      " --plot " + path("tran.png") + " --plot-script");
  ASSERT_EQ(tran.status, 5) << tran.err;
  const std::string tran_script = contents("tran.png.gp");
  EXPECT_NE(tran_script.find("set ylabel 'deflection [mm]'"), std::string::npos) << tran_script;
  EXPECT_NE(tran_script.find("deflection limit +/-1.225 mm"), std::string::npos) << tran_script;
  const auto sweep = emnet::testing::run_emnet("sweep-switching " + fin +
                                               " --from 4 --to 6 --step 1 --probe tip --probe "
                                               "rotation@0.1 --plot " +
                                               path("sweep.png") + " --plot-script");
  ASSERT_EQ(sweep.status, 0) << sweep.err;
  const std::string sweep_script = contents("sweep.png.gp");
  EXPECT_NE(sweep_script.find("set ylabel 'peak deflection [mm]'"), std::string::npos)
      << sweep_script;
  EXPECT_NE(sweep_script.find("set ylabel 'peak rotation [rad]'"), std::string::npos)
      << sweep_script;
}

}  // namespace
