// What the ngspice program leaves at the rawfile's path is read only when it is a regular
// file: a FIFO there used to block open() forever (past --timeout), a symbolic link was followed.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <future>
#include <iterator>
#include <string>

#include "emnet/spice/ngspice_runner.hpp"
#include "file_contents.hpp"

namespace emnet {
namespace {

const char* const kDeck = "divider\nV1 in 0 DC 1\nR1 in out 1k\nR2 out 0 3k\n.op\n.end\n";

// A stand-in ngspice program (called as `ngspice -b -r RAW DECK`) that runs `body` with the
// rawfile path in $3 and records that path in `witness`.
std::string fake_program(const std::string& name, const std::string& body,
                         const std::string& witness) {
  const std::string path =
      ::testing::TempDir() + "emnet_rawkind_" + name + "_" + std::to_string(::getpid());
  std::ofstream(path) << "#!/bin/sh\nprintf '%s' \"$3\" > '" << witness << "'\n" << body;
  ::chmod(path.c_str(), 0755);
  return path;
}

TEST(NgspiceRawfileKinds, AFifoAtTheRawfilePathIsRefusedWithoutBlocking) {
  const std::string witness =
      ::testing::TempDir() + "emnet_rawkind_path_" + std::to_string(::getpid());
  NgspiceOptions options;
  options.backend = NgspiceBackend::program;
  options.program = fake_program("fifo", "mkfifo \"$3\"\nexit 0\n", witness);
  options.timeout_seconds = 5.0;
  auto run = std::async(std::launch::async, [&] { return run_ngspice(kDeck, options); });
  // 30 s is six times the run's own limit: a reader that blocks in open() never returns.
  if (run.wait_for(std::chrono::seconds(30)) != std::future_status::ready) {
    // Unblock the reader (a writer opening the FIFO), so the test ends, and fail.
    const int writer =
        ::open(emnet::testing::file_contents(witness).c_str(), O_WRONLY | O_NONBLOCK);
    if (writer >= 0) ::close(writer);
    run.wait();
    FAIL() << "reading a FIFO left as the rawfile blocked past the time limit";
  }
  const NgspiceResult result = run.get();
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("not a regular file"), std::string::npos)
      << result.status.message;
  ::unlink(witness.c_str());
}

TEST(NgspiceRawfileKinds, ASymbolicLinkAtTheRawfilePathIsNotFollowed) {
  const std::string witness =
      ::testing::TempDir() + "emnet_rawkind_link_" + std::to_string(::getpid());
  // The link's target is a valid rawfile of the divider: following it would read the values.
  const std::string target = witness + ".raw";
  std::ofstream(target) << "Title: fake\nDate: today\nPlotname: Operating Point\nFlags: real\n"
                           "No. Variables: 2\nNo. Points: 1\nVariables:\n\t0\tv(in)\tvoltage\n"
                           "\t1\tv(out)\tvoltage\nValues:\n 0\t1\n\t0.75\n";
  NgspiceOptions options;
  options.backend = NgspiceBackend::program;
  options.program = fake_program("link", "ln -s '" + target + "' \"$3\"\nexit 0\n", witness);
  options.timeout_seconds = 5.0;
  const NgspiceResult result = run_ngspice(kDeck, options);
  EXPECT_FALSE(result.status.ok()) << "the link was followed";
  ::unlink(witness.c_str());
  ::unlink(target.c_str());
}

}  // namespace
}  // namespace emnet
