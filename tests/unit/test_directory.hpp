// A fresh directory per test and process for tests that write files (CTest runs the tests in
// parallel processes), removed after the test.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace emnet::testing {

class TestDirectory : public ::testing::Test {
 protected:
  // `prefix`: the directory's name before the test's name and the process id.
  explicit TestDirectory(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    directory_ = std::filesystem::path(::testing::TempDir()) /
                 (prefix_ + std::string(test->name()) + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(directory_);
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override {
    std::error_code ignored;
    std::filesystem::remove_all(directory_, ignored);
  }
  std::string path(const std::string& name) const { return (directory_ / name).string(); }
  std::string contents(const std::string& name) const {
    std::ifstream in(path(name));
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  // The names of the directory's entries, sorted.
  std::vector<std::string> names() const {
    std::vector<std::string> found;
    for (const auto& entry : std::filesystem::directory_iterator(directory_))
      found.push_back(entry.path().filename().string());
    std::sort(found.begin(), found.end());
    return found;
  }
  size_t entries() const { return names().size(); }

  std::filesystem::path directory_;

 private:
  std::string prefix_;
};

}  // namespace emnet::testing
