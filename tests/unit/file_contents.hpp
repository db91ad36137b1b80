// A file's bytes as a string, for tests that check what a command or writer wrote.
#pragma once

#include <fstream>
#include <iterator>
#include <string>

namespace emnet::testing {

// The whole file at `path` ("" when it cannot be opened).
inline std::string file_contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace emnet::testing
