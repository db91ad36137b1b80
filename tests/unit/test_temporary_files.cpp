// Private temporary directories and the registry a terminating signal empties
// (include/emnet/core/temporary_files.hpp).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "emnet/core/output_file.hpp"
#include "emnet/core/temporary_files.hpp"
#include "test_directory.hpp"

namespace {

namespace fs = std::filesystem;

class TemporaryFiles : public emnet::testing::TestDirectory {
 protected:
  TemporaryFiles() : TestDirectory("emnet_temporaries_") {}
};

// mkdtemp's directory: new, only its owner may enter it (0700), removed with its contents.
TEST_F(TemporaryFiles, DirectoryIsPrivateAndRemovedWithItsContents) {
  std::string made;
  {
    emnet::TemporaryDirectory directory;
    ASSERT_TRUE(directory.create(directory_.string(), ".emnet-test-").ok());
    made = directory.path();
    EXPECT_EQ(fs::path(made).parent_path(), directory_);
    EXPECT_EQ(fs::path(made).filename().string().rfind(".emnet-test-", 0), 0u);
    struct stat status {};
    ASSERT_EQ(::stat(made.c_str(), &status), 0);
    EXPECT_TRUE(S_ISDIR(status.st_mode));
    EXPECT_EQ(status.st_mode & 0777, 0700u);
    std::ofstream(made + "/inside") << "x";
    fs::create_directories(made + "/nested/deeper");
  }
  EXPECT_FALSE(fs::exists(made));
  EXPECT_EQ(entries(), 0u);
}

TEST_F(TemporaryFiles, TwoDirectoriesNeverShareAName) {
  emnet::TemporaryDirectory first, second;
  ASSERT_TRUE(first.create(directory_.string(), "d-").ok());
  ASSERT_TRUE(second.create(directory_.string(), "d-").ok());
  EXPECT_NE(first.path(), second.path());
  EXPECT_FALSE(first.create(directory_.string(), "d-").ok());  // once only
}

TEST_F(TemporaryFiles, AMissingParentIsAFailureNamingIt) {
  emnet::TemporaryDirectory directory;
  const emnet::Status status = directory.create(path("absent"), "d-");
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message.find("absent"), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("No such file"), std::string::npos) << status.message;
}

// What the command line's SIGTERM handling calls: every registered temporary goes, the
// directory of a TemporaryDirectory and an OutputFile's hidden file alike; a path taken off
// the registry stays.
TEST_F(TemporaryFiles, RemovingTheRegisteredOnesRemovesEachOfThem) {
  emnet::TemporaryDirectory directory;
  ASSERT_TRUE(directory.create(directory_.string(), "d-").ok());
  std::ofstream(directory.path() + "/data") << "1 2\n";
  emnet::OutputFile file(path("result.csv"));
  file.write("a,b\n");
  ASSERT_TRUE(file.status().ok());
  const std::string kept = path("kept");
  std::ofstream(kept) << "k";
  emnet::register_temporary_path(kept);
  emnet::unregister_temporary_path(kept);
  ASSERT_EQ(entries(), 3u);  // the directory, the output file's hidden temporary, kept
  emnet::remove_registered_temporaries();
  EXPECT_EQ(names(), std::vector<std::string>{"kept"});
}

}  // namespace
