// Long runs show progress on standard error (on a terminal, or with --progress; never with
// --quiet), and Ctrl-C (SIGINT) stops them with exit status 130 and no output file. No timing
// assertion: the runs are long (a sweep of 60001 switching frequencies of the fin cut into 20
// segments, about 8 s on this machine) and are interrupted as soon as their first progress line
// appears; every wait has a generous limit (60 s) that only guards against a hang.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/model/validity.hpp"
#include "shipped_scenes.hpp"
#include "terminal_progress.hpp"
#include "test_directory.hpp"

namespace {

namespace fs = std::filesystem;
using emnet::testing::CliRun;
using emnet::testing::EmnetChild;

using emnet::testing::kFishfin;
const std::vector<std::string> long_sweep = {
    "sweep-switching", kFishfin, "--segments", "20", "--from", "1", "--to", "7",
    "--step",          "0.0001"};  // 60001 frequencies (at most 100 000 are swept)
const std::string progress_text = "emnet sweep-switching: switching frequencies ";

class CliProgress : public emnet::testing::TestDirectory {
 protected:
  CliProgress() : TestDirectory("emnet_progress_") {}
  std::vector<std::string> with(std::vector<std::string> arguments,
                                const std::vector<std::string>& more) const {
    arguments.insert(arguments.end(), more.begin(), more.end());
    return arguments;
  }
};

// --progress prints also into a pipe, a line when a step begins and one a second: the line
// names the step and its counts.
TEST_F(CliProgress, ForcedProgressAppearsInAPipe) {
  const CliRun r = emnet::testing::run_emnet("sweep-switching " + kFishfin +
                                             " --from 1 --to 7 --step 0.01 --progress"
                                             // the fin's resonant swing is 10.8 % of L: inside
                                             " --set model.deflection_limit=0.2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::regex_search(r.err, std::regex(progress_text + "[0-9]+/601 \\([0-9.]+ %\\)")))
      << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << "lines, not a rewritten line";
}

// Ctrl-C after the first progress line: exit 130, no result printed, no CSV (nor a temporary
// file) left behind.
TEST_F(CliProgress, InterruptLeavesNoOutputFile) {
  EmnetChild child(with(long_sweep, {"--progress", "--csv", path("sweep.csv")}), false,
                   path("stdout.txt"));
  ASSERT_TRUE(child.started());
  ASSERT_TRUE(child.wait_for_error_text(progress_text, 60.0)) << child.error_output();
  child.send(SIGINT);
  EXPECT_EQ(child.wait(60.0), 130) << child.error_output();
  EXPECT_NE(child.error_output().find("interrupted"), std::string::npos) << child.error_output();
  EXPECT_FALSE(fs::exists(path("sweep.csv")));
  EXPECT_EQ(contents("stdout.txt"), "");
  EXPECT_EQ(entries(), 1u);  // stdout.txt only
}

// modes shows its phases (it was silent: 25 s at 100 000 segments) and stops at Ctrl-C too: the
// interrupt is sent when the Arnoldi iterations report their first solve, on a fin of 100 000
// segments (the run would take tens of seconds), and no CSV is written.
TEST_F(CliProgress, ModesShowsItsPhasesAndStopsAtInterrupt) {
  EmnetChild child({"modes", kFishfin, "--segments", "100000", "--count", "3",
                    "--no-error-estimate", "--progress", "--csv", path("modes.csv")},
                   false, path("stdout.txt"));
  ASSERT_TRUE(child.started());
  ASSERT_TRUE(child.wait_for_error_text("emnet modes: modal analysis: Arnoldi (solves)", 120.0))
      << child.error_output();
  EXPECT_NE(child.error_output().find("modal analysis: sparse LU"), std::string::npos)
      << child.error_output();
  child.send(SIGINT);
  EXPECT_EQ(child.wait(60.0), 130) << child.error_output();
  EXPECT_FALSE(fs::exists(path("modes.csv")));
  EXPECT_EQ(contents("stdout.txt"), "");
}

// On a terminal the line appears by itself (after a second) and is rewritten in place by
// carriage returns; with --quiet nothing appears. The quiet run is watched for 3 s, longer than
// the second after which the line would appear, then interrupted.
TEST_F(CliProgress, TerminalShowsProgressUnlessQuiet) {
  if (!emnet::testing::pseudo_terminals_available()) GTEST_SKIP() << "no pseudo-terminals here";
  {
    EmnetChild child(long_sweep, true, path("stdout.txt"));
    ASSERT_TRUE(child.started());
    ASSERT_TRUE(child.wait_for_error_text(progress_text, 60.0)) << child.error_output();
    EXPECT_EQ(child.error_output().find('\n'), std::string::npos) << "rewritten, not scrolled";
    EXPECT_NE(child.error_output().find('\r'), std::string::npos);
    child.send(SIGINT);
    EXPECT_EQ(child.wait(60.0), 130) << child.error_output();
  }
  {
    EmnetChild child(with(long_sweep, {"--quiet"}), true, path("stdout.txt"));
    ASSERT_TRUE(child.started());
    EXPECT_FALSE(child.wait_for_error_text(progress_text, 3.0)) << child.error_output();
    child.send(SIGINT);
    const int status = child.wait(60.0);
    // 5: a machine fast enough to finish (the sweep peak lies outside the small-deflection
    // validity, kExitOutsideValidity).
    EXPECT_TRUE(status == 130 || status == emnet::kExitOutsideValidity) << status;
    EXPECT_EQ(child.error_output().find(progress_text), std::string::npos) << child.error_output();
  }
}

// The line's text: counts, percentage, elapsed time and the estimate from the current step's
// rate (25 of 100 in 10 s: 75 more take 30 s).
TEST(ProgressLine, SaysWhatHowFarAndTheTimeLeft) {
  EXPECT_EQ(emnet_cli::progress_line("emnet ac", "AC frequencies", 25, 100, 12.0, 10.0, 25, false),
            "emnet ac: AC frequencies 25/100 (25.0 %), 12 s, about 30 s left");
  EXPECT_EQ(emnet_cli::progress_line("emnet ac", "AC frequencies", 0, 100, 0.5, 0.5, 0, false),
            "emnet ac: AC frequencies 0/100 (0.0 %), 0.5 s");
  EXPECT_EQ(emnet_cli::progress_line("emnet sweep-switching", "eigen-decomposition", 0, 0, 75.0,
                                     75.0, 0, false),
            "emnet sweep-switching: eigen-decomposition, 1 min 15 s");
  EXPECT_EQ(emnet_cli::progress_line("emnet tran", "output times", 1, 3600, 5.0, 5.0, 1, false),
            "emnet tran: output times 1/3600 (0.0 %), 5.0 s, about 4 h 59 min left");
  EXPECT_EQ(emnet_cli::progress_line("emnet ac", "x\x1b[2J", 1, 2, 1.0, 1.0, 1, false),
            "emnet ac: x\\e[2J 1/2 (50.0 %), 1.0 s, about 1.0 s left");
  EXPECT_EQ(emnet_cli::progress_line("emnet ac", "AC frequencies", 1, 2, 1.0, 1.0, 1, true),
            "emnet ac: interrupted, stopping (Ctrl-C again: at once)");
}

}  // namespace
