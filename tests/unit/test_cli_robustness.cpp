// Inputs a robustness pass found mishandled by the command line: counts that CLI11 wrapped or
// clamped silently, a study's -o failure named --csv, an eigen-solver failure reported as an
// internal error.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "cli_run.hpp"
#include "shipped_scenes.hpp"

namespace {

using emnet::testing::run_emnet;

using emnet::testing::kCantilever;
const std::string kFinger = std::string(EMNET_SOURCE_DIR) + "/netlists/gripper-finger.toml";

// --samples -1 read "more than 1000000 variants"; --seed -1, 2^64 and 1e23 ran with a seed
// clamped or wrapped (the same variants for all three). Each is now refused naming its option.
TEST(CliRobustness, StudyCountsAreWholeNumbersInRange) {
  const std::string study =
      "study " + kCantilever + " --vary 'beam.bending_stiffness=uniform(1,2)' --analysis modes ";
  for (const std::string& bad :
       {"--samples -1", "--samples 2.5", "--samples 1000001 --seed 1", "--samples 3 --seed -1",
        "--samples 3 --seed 18446744073709551616", "--samples 3 --seed 1e23"}) {
    const auto run = run_emnet(study + bad);
    EXPECT_EQ(run.status, 2) << bad << ": " << run.err;
    EXPECT_NE(run.err.find("must be a whole number"), std::string::npos) << bad << ": " << run.err;
  }
  const auto good = run_emnet(study + "--samples 3 --seed 18446744073709551615 --quiet");
  EXPECT_EQ(good.status, 0) << good.err;
}

// --variants had no type or size limit: /dev/zero grew to 8.4 GB, a FIFO blocked. Now it is
// read as the scene and pwl files are (emnet/core/bounded_file.hpp): a regular file, opened
// without blocking, at most 256 MiB.
TEST(CliRobustness, VariantsFileIsARegularFileOfBoundedSize) {
  const std::string study = "study " + kCantilever + " --analysis modes --variants ";
  const auto device = run_emnet(study + "/dev/zero", "timeout 20 ");
  EXPECT_EQ(device.status, 2) << device.err;
  EXPECT_NE(device.err.find("not a regular file (a character device)"), std::string::npos)
      << device.err;
  const std::string fifo = ::testing::TempDir() + "emnet_variants_fifo_" + std::to_string(getpid());
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const auto pipe = run_emnet(study + fifo, "timeout 20 ");
  EXPECT_EQ(pipe.status, 2) << pipe.err;
  EXPECT_NE(pipe.err.find("not a regular file (a pipe)"), std::string::npos) << pipe.err;
  unlink(fifo.c_str());
}

// A NUL in a variants CSV value cut the message where it was printed, and a 100 000-character
// value was echoed whole, twice: the quoted input is escaped and cut to 60 bytes.
TEST(CliRobustness, QuotedInputIsEscapedAndShort) {
  const std::string csv = ::testing::TempDir() + "emnet_nul_" + std::to_string(getpid()) + ".csv";
  {
    std::ofstream file(csv, std::ios::binary);
    file << "beam.bending_stiffness\n" << std::string("1", 1) << '\0' << "x N*m^2\n";
  }
  const auto nul = run_emnet("study " + kCantilever + " --analysis modes --variants " + csv);
  EXPECT_EQ(nul.status, 2) << nul.err;
  EXPECT_NE(nul.err.find("1\\x00x N*m^2"), std::string::npos) << nul.err;
  std::remove(csv.c_str());
  const auto long_value =
      run_emnet("study " + kCantilever + " --analysis modes --vary beam.bending_stiffness=" +
                std::string(100000, '7') + "x");
  EXPECT_EQ(long_value.status, 2) << long_value.err.substr(0, 400);
  EXPECT_LT(long_value.err.size(), 1000u) << long_value.err.substr(0, 400);
}

// tran --atol 1e-300 failed inside IDA with "tstop ... behind t"; refused up front, exit 2.
TEST(CliRobustness, AnAbsoluteToleranceThatOverflowsIdasWeightsIsRefused) {
  const std::string fin = std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml";
  const auto run = run_emnet("tran " + fin + " --periods 1 --atol 1e-300");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("1e-150"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("tstop"), std::string::npos) << run.err;
  EXPECT_EQ(run_emnet("tran " + fin + " --periods 1 --atol 1e-12").status, 0);
}

// A study's -o that cannot be written says -o/--output, not --csv.
TEST(CliRobustness, StudyOutputFailureNamesTheOptionGiven) {
  const auto run = run_emnet("study " + kCantilever +
                             " --vary beam.bending_stiffness=1,2 --quiet -o /nonexistent/x.csv");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("-o/--output"), std::string::npos) << run.err;
}

// A 1e300 kg sensor mass: the eigen-solver gives up ("Schur decomposition failed", exit 1 as an
// internal error before); now a numerical failure, exit 3, with its reason.
TEST(CliRobustness, AnEigenSolverFailureIsANumericalFailure) {
  const auto run = run_emnet("modes " + kFinger + " --set mass.sensor.mass=1e300");
  EXPECT_EQ(run.status, 3) << run.err;
  EXPECT_NE(run.err.find("eigen-solver failed"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("internal error"), std::string::npos) << run.err;
}

}  // namespace
