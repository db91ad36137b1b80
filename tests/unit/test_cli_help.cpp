// Every command's --help: an example, which runs, and the scene keys the command reads.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

using emnet::testing::run_emnet;

const std::vector<std::string> commands = {
    "static",      "modes",    "ac",      "tran",       "sweep-switching", "identify",
    "sensitivity", "mismatch", "netlist", "crosscheck", "study",           "schema"};

// How often `text` holds `part`.
size_t count(const std::string& text, const std::string& part) {
  size_t found = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++found;
  return found;
}

// Reference: the help text itself. Each command's help names the keys it reads ("Reads:") and
// gives an example (an "Example:" block, or "e.g. emnet …" in the description);
// an "Example:" is run as written, from a scratch directory with the shipped scenes' path
// made absolute, and must succeed (exit status 0), so that a renamed option or key breaks
// this test and not a reader.
TEST(CliHelp, EveryCommandGivesAnExampleThatRunsAndTheKeysItReads) {
  const std::string scratch = ::testing::TempDir() + "emnet_help_examples";
  std::filesystem::create_directories(scratch);
  for (const std::string& command : commands) {
    const auto help = run_emnet(command + " --help");
    ASSERT_EQ(help.status, 0) << command << ": " << help.err;
    EXPECT_NE(help.out.find("Reads: "), std::string::npos) << command;
    // The usage line says "emnet <command> [OPTIONS]"; every other mention is an example.
    const size_t examples = count(help.out, "emnet " + command + " ") - 1;
    EXPECT_GE(examples, 1u) << command << "'s help:\n" << help.out;
    const size_t block = help.out.find("Example:\n  emnet " + command + " ");
    if (block == std::string::npos) continue;  // the description's "e.g." is the example
    const size_t start = block + std::string("Example:\n  emnet ").size();
    std::string arguments = help.out.substr(start, help.out.find('\n', start) - start);
    for (size_t at = arguments.find("netlists/"); at != std::string::npos;
         at = arguments.find("netlists/", at + 1)) {
      arguments.insert(at, std::string(EMNET_SOURCE_DIR) + "/");
      at += std::string(EMNET_SOURCE_DIR).size() + 1;
    }
    const auto run = run_emnet(arguments, "cd " + scratch + " && ");
    EXPECT_EQ(run.status, 0) << "emnet " << arguments << ":\n" << run.err;
  }
  std::filesystem::remove_all(scratch);
}

}  // namespace
