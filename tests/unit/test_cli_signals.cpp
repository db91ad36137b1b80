// Signals while a helper program runs: Ctrl-C during gnuplot stops it (exit 130, no image and no
// side files: it used to be swallowed, the image written and exit 0), and SIGTERM, SIGHUP or a
// Ctrl-C of `crosscheck` end emnet by the signal with nothing of its own left behind (they used
// to leave the hidden plot temporaries, one of 61 MB, and the `emnet-ngspice-*` directory).
// Stand-in programs (a `gnuplot` first on PATH, an ngspice given by --ngspice-program) mark that
// they started and then sleep, so each signal arrives while the helper runs, without any
// timing assumption; every wait has a 60 s limit that only guards against a hang.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.hpp"
#include "shipped_scenes.hpp"
#include "test_directory.hpp"

namespace {

namespace fs = std::filesystem;
using emnet::testing::EmnetChild;

using emnet::testing::kFishfin;

class CliSignals : public emnet::testing::TestDirectory {
 protected:
  CliSignals() : TestDirectory("emnet_signals_") {}
  void SetUp() override {
    TestDirectory::SetUp();
    fs::create_directories(path("bin"));
    fs::create_directories(path("tmp"));
    const char* path_variable = std::getenv("PATH");
    saved_path_ = path_variable ? path_variable : "";
    const char* tmpdir = std::getenv("TMPDIR");
    saved_tmpdir_ = tmpdir ? tmpdir : "";
    had_tmpdir_ = tmpdir != nullptr;
    ::setenv("PATH", (path("bin") + ":" + saved_path_).c_str(), 1);
    ::setenv("TMPDIR", path("tmp").c_str(), 1);
  }
  void TearDown() override {
    ::setenv("PATH", saved_path_.c_str(), 1);
    if (had_tmpdir_)
      ::setenv("TMPDIR", saved_tmpdir_.c_str(), 1);
    else
      ::unsetenv("TMPDIR");
    TestDirectory::TearDown();
  }
  // A program at bin/NAME that creates the file `marker` and sleeps a minute.
  std::string stand_in(const std::string& name) {
    const std::string program = path("bin/" + name);
    std::ofstream(program) << "#!/bin/sh\n: > '" << path("marker") << "'\nexec sleep 60\n";
    fs::permissions(program, fs::perms::owner_all);
    return program;
  }
  bool wait_for_marker() const {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!fs::exists(path("marker"))) {
      if (std::chrono::steady_clock::now() > until) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
  }
  // What is left in the test directory and in TMPDIR besides the test's own files.
  std::vector<std::string> left_behind() const {
    std::vector<std::string> left;
    for (const std::string& name : names())
      if (name != "bin" && name != "tmp" && name != "marker" && name != "stdout.txt")
        left.push_back(name);
    for (const auto& entry : fs::directory_iterator(path("tmp")))
      left.push_back("tmp/" + entry.path().filename().string());
    return left;
  }
  // A short sweep whose plot (with its data and script) is drawn by the stand-in gnuplot.
  std::vector<std::string> plotted_sweep() const {
    return {"sweep-switching",
            kFishfin,
            "--from",
            "4",
            "--to",
            "6",
            "--step",
            "1",
            "--plot",
            path("x.png"),
            "--plot-script",
            "--set",
            "model.deflection_limit=0.2"};
  }

 private:
  std::string saved_path_, saved_tmpdir_;
  bool had_tmpdir_ = false;
};

using Files = std::vector<std::string>;

TEST_F(CliSignals, CtrlCWhileGnuplotDrawsWritesNoFile) {
  stand_in("gnuplot");
  EmnetChild child(plotted_sweep(), false, path("stdout.txt"));
  ASSERT_TRUE(child.started());
  ASSERT_TRUE(wait_for_marker()) << child.error_output();
  child.send(SIGINT);
  EXPECT_EQ(child.wait(60.0), 130) << child.error_output();
  EXPECT_NE(child.error_output().find("interrupted"), std::string::npos) << child.error_output();
  EXPECT_EQ(left_behind(), Files{});  // no x.png, x.png.dat, x.png.gp nor .emnet-plot-*
}

TEST_F(CliSignals, TerminateAndHangupWhileGnuplotDrawsLeaveNothing) {
  stand_in("gnuplot");
  for (const int signal_number : {SIGTERM, SIGHUP}) {
    fs::remove(path("marker"));
    EmnetChild child(plotted_sweep(), false, path("stdout.txt"));
    ASSERT_TRUE(child.started());
    ASSERT_TRUE(wait_for_marker()) << child.error_output();
    child.send(signal_number);
    EXPECT_EQ(child.wait(60.0), 128 + signal_number) << child.error_output();
    EXPECT_EQ(left_behind(), Files{}) << signal_number;
  }
}

TEST_F(CliSignals, SignalsDuringCrosscheckRemoveTheNgspiceDirectory) {
  const std::string ngspice = stand_in("fake-ngspice");
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    fs::remove(path("marker"));
    EmnetChild child({"crosscheck", kFishfin, "--backend", "program", "--ngspice-program", ngspice,
                      "--analysis", "op"},
                     false, path("stdout.txt"));
    ASSERT_TRUE(child.started());
    ASSERT_TRUE(wait_for_marker()) << child.error_output();
    // The stand-in runs inside the private directory emnet made for it.
    size_t directories = 0;
    for (const auto& entry : fs::directory_iterator(path("tmp")))
      directories += entry.path().filename().string().rfind("emnet-ngspice-", 0) == 0;
    EXPECT_EQ(directories, 1u);
    child.send(signal_number);
    EXPECT_EQ(child.wait(60.0), 128 + signal_number) << child.error_output();
    EXPECT_EQ(left_behind(), Files{}) << signal_number;
  }
}

}  // namespace
