// Smaller defects of the command line a user hit (issue 26 items 6 and 8): the sweep's
// "largest swing" line names the largest output, the help is output that can fail, CLI11's
// own parse errors reach the terminal escaped, and running out of memory is a reported
// numerical failure, not an internal error.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "shipped_scenes.hpp"

namespace {

using emnet::testing::CliRun;
using emnet::testing::run_emnet;

using emnet::testing::kFishfin;

// With the tip first and P2 (23 mm from the clamp) last, the largest swing is the tip's, not
// the last output's. Reference: the same run's --json outputs, the largest peak-to-peak over
// every output and frequency computed here; the line prints 6 significant digits in mm, so
// the values are compared to 1e-5 relative.
TEST(CliSweepReport, LargestSwingNamesTheLargestOutput) {
  const std::string command =
      "sweep-switching " + kFishfin + " --from 4 --to 6 --step 1 --probe tip --probe P2";
  const CliRun json_run = run_emnet(command + " --json");
  ASSERT_EQ(json_run.status, 0) << json_run.err;
  const auto json = nlohmann::json::parse(json_run.out);
  const auto frequencies = json["frequencies_hz"].get<std::vector<double>>();
  std::string widest_name;
  double widest = -1.0, widest_left = 0.0, widest_right = 0.0, widest_at = 0.0;
  for (const auto& output : json["outputs"]) {
    const auto left = output["left"].get<std::vector<double>>();
    const auto right = output["right"].get<std::vector<double>>();
    for (size_t k = 0; k < left.size(); ++k)
      if (right[k] - left[k] > widest) {
        widest = right[k] - left[k];
        widest_name = output["name"].get<std::string>();
        widest_left = left[k], widest_right = right[k], widest_at = frequencies.at(k);
      }
  }
  ASSERT_EQ(widest_name, "tip");  // a cantilever's deflection grows along it

  const CliRun text = run_emnet(command);
  ASSERT_EQ(text.status, 0) << text.err;
  const size_t line_start = text.out.find("largest swing of ");
  ASSERT_NE(line_start, std::string::npos) << text.out;
  const std::string line =
      text.out.substr(line_start, text.out.find('\n', line_start) - line_start);
  char name[64] = {};
  double at = 0.0, left_mm = 0.0, right_mm = 0.0;
  ASSERT_EQ(std::sscanf(line.c_str(), "largest swing of %63s at %lf Hz: %lf mm left, %lf mm right",
                        name, &at, &left_mm, &right_mm),
            4)
      << line;
  EXPECT_EQ(std::string(name), "tip") << line;
  EXPECT_EQ(at, widest_at) << line;
  EXPECT_NEAR(left_mm, widest_left * 1e3, 1e-5 * std::abs(widest_left * 1e3)) << line;
  EXPECT_NEAR(right_mm, widest_right * 1e3, 1e-5 * std::abs(widest_right * 1e3)) << line;
}

// The help is the command's output: a full device behind standard output fails it (2), for
// the program's help and a command's.
TEST(CliHelpOutput, HelpToAFullDeviceFails) {
  for (const std::string arguments : {"--help", "static --help"}) {
    const CliRun r = run_emnet(arguments + " >/dev/full");
    EXPECT_EQ(r.status, 2) << arguments << ": " << r.err;
    EXPECT_NE(r.err.find("cannot write the help"), std::string::npos) << r.err;
  }
}

// A CLI11 parse error quotes the argument: an escape sequence in it reaches the terminal
// escaped, not raw (ESC would clear the screen here).
TEST(CliParseErrors, ArgumentsAreEscaped) {
  const CliRun r = run_emnet("static " + kFishfin + " --segments \"$(printf 'x\\033[2J')\"");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("x"), std::string::npos) << r.err;
}

}  // namespace
