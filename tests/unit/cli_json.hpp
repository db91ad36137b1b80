// Runs the emnet program with --json for tests that read its JSON (one home for the test files
// that share it: they can be compiled together as one unit).
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"

namespace emnet::testing {

/// The JSON `emnet ARGUMENTS --json` prints; null (and a test failure) when it exits non-zero.
inline nlohmann::json run_json(const std::string& arguments) {
  const auto run = run_emnet(arguments + " --json");
  EXPECT_EQ(run.status, 0) << arguments << "\n" << run.err;
  return run.status == 0 ? nlohmann::json::parse(run.out) : nlohmann::json();
}

}  // namespace emnet::testing
