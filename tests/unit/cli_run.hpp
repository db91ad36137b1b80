// Runs the emnet program for tests: exit status, standard output and standard error.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

namespace emnet::testing {

struct CliRun {
  int status = -1;
  std::string out, err;
};

// `prefix` goes before the binary (e.g. "timeout 10 "). Standard error goes through a file
// unique per process and call: CTest runs the tests in parallel processes.
inline CliRun run_emnet(const std::string& arguments, const std::string& prefix = "") {
  static int counter = 0;
  const std::string err_path = ::testing::TempDir() + "emnet_cli_err_" + std::to_string(getpid()) +
                               "_" + std::to_string(counter++);
  const std::string command =
      prefix + std::string(EMNET_BINARY) + " " + arguments + " 2>" + err_path;
  CliRun result;
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer{};
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.out.append(buffer.data(), n);
  const int raw = pclose(pipe);
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream err(err_path);
  result.err.assign(std::istreambuf_iterator<char>(err), {});
  std::remove(err_path.c_str());
  return result;
}

}  // namespace emnet::testing
