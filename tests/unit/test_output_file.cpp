// Output files are written completely or not at all: a failure (a missing directory, a full
// device, a file size limit) is a failed Status naming the file and the reason, leaves the
// previous file as it was and no temporary file behind; a device is written in place, not
// replaced. References: the contents written and the file system's own state.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "emnet/core/output_file.hpp"
#include "file_contents.hpp"
#include "test_directory.hpp"

namespace {

namespace fs = std::filesystem;

class OutputFileTest : public emnet::testing::TestDirectory {
 protected:
  OutputFileTest() : TestDirectory("emnet_output_") {}
};

TEST_F(OutputFileTest, WritesTheWholeTextAndReplacesAnOldFileKeepingItsMode) {
  const std::string file = path("table.csv");
  std::ofstream(file) << "old";
  ASSERT_EQ(chmod(file.c_str(), 0640), 0);
  std::string text;
  for (int k = 0; k < 100000; ++k) text += std::to_string(k) + ",";  // several buffers
  ASSERT_TRUE(emnet::write_output_file(file, text).ok());
  EXPECT_EQ(emnet::testing::file_contents(file), text);
  struct stat info {};
  ASSERT_EQ(stat(file.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0640u);
  EXPECT_EQ(entries(), 1u);  // no temporary file left
}

TEST_F(OutputFileTest, FollowsASymbolicLink) {
  const std::string target = path("real.cir"), link = path("link.cir");
  std::ofstream(target) << "old";
  fs::create_symlink(target, link);
  ASSERT_TRUE(emnet::write_output_file(link, "new deck").ok());
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(emnet::testing::file_contents(target), "new deck");
}

TEST_F(OutputFileTest, MissingDirectoryIsAFailedStatusNamingTheFile) {
  const std::string file = path("no/such/dir/table.csv");
  const emnet::Status status = emnet::write_output_file(file, "x");
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message.find(file), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("No such file or directory"), std::string::npos) << status.message;
}

TEST_F(OutputFileTest, AFullDeviceIsAFailureAndStaysADevice) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const emnet::Status status = emnet::write_output_file("/dev/full", std::string(100000, 'x'));
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message.find("No space left on device"), std::string::npos) << status.message;
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  EXPECT_TRUE(emnet::write_output_file("/dev/null", "x").ok());
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

// A file size limit (RLIMIT_FSIZE, with SIGXFSZ ignored) makes the write fail part-way, as a
// full disk does: in a child process, so that the limit does not reach the test runner.
TEST_F(OutputFileTest, AWriteFailingPartWayKeepsThePreviousFile) {
  const std::string file = path("deck.cir");
  std::ofstream(file) << "previous deck\n";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{4096, 4096};
    setrlimit(RLIMIT_FSIZE, &limit);
    const emnet::Status status = emnet::write_output_file(file, std::string(1 << 20, 'x'));
    _exit(status.ok() ? 0 : status.message.find("File too large") != std::string::npos ? 1 : 2);
  }
  int raw = 0;
  ASSERT_EQ(waitpid(child, &raw, 0), child);
  ASSERT_TRUE(WIFEXITED(raw));
  EXPECT_EQ(WEXITSTATUS(raw), 1) << "expected a failed Status saying 'File too large'";
  EXPECT_EQ(emnet::testing::file_contents(file), "previous deck\n");
  EXPECT_EQ(entries(), 1u);  // the temporary file is gone
}

TEST_F(OutputFileTest, CommitOnceOnly) {
  emnet::OutputFile file(path("once.txt"));
  file.write("a");
  EXPECT_TRUE(file.commit().ok());
  EXPECT_FALSE(file.commit().ok());
  EXPECT_EQ(emnet::testing::file_contents(path("once.txt")), "a");
}

TEST_F(OutputFileTest, NotCommittedLeavesNothing) {
  {
    emnet::OutputFile file(path("abandoned.txt"));
    file.write("half");
  }
  EXPECT_EQ(entries(), 0u);
}

}  // namespace
