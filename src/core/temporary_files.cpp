// Temporary files and directories; see include/emnet/core/temporary_files.hpp.
#include "emnet/core/temporary_files.hpp"

#include <stdlib.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>
#include <system_error>

namespace emnet {

namespace {

struct Registry {
  std::mutex mutex;
  std::set<std::string> paths;
};

// Never destroyed: a signal may end the program while static destructors run.
Registry& registry() {
  static Registry* const instance = new Registry;
  return *instance;
}

}  // namespace

void register_temporary_path(const std::string& path) {
  if (path.empty()) return;
  Registry& shared = registry();
  const std::lock_guard<std::mutex> lock(shared.mutex);
  shared.paths.insert(path);
}

void unregister_temporary_path(const std::string& path) {
  if (path.empty()) return;
  Registry& shared = registry();
  const std::lock_guard<std::mutex> lock(shared.mutex);
  shared.paths.erase(path);
}

void remove_registered_temporaries() noexcept {
  Registry& shared = registry();
  const std::lock_guard<std::mutex> lock(shared.mutex);
  for (const std::string& path : shared.paths) {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  shared.paths.clear();
}

Status TemporaryDirectory::create(const std::string& parent, const std::string& prefix) {
  if (!path_.empty()) return Status::failure("the temporary directory '" + path_ + "' exists");
  std::string base = parent;
  if (base.empty()) {
    const char* variable = std::getenv("TMPDIR");
    base = variable && *variable ? variable : "/tmp";
  }
  std::string pattern = (std::filesystem::path(base) / (prefix + "XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    const int error_number = errno;
    return Status::failure("cannot create a temporary directory (" + pattern +
                           "): " + std::strerror(error_number));
  }
  path_ = pattern;
  register_temporary_path(path_);
  return Status::success();
}

TemporaryDirectory::~TemporaryDirectory() {
  if (path_.empty()) return;
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
  unregister_temporary_path(path_);
}

}  // namespace emnet
