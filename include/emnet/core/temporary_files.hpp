// Temporary files and directories that nothing leaves behind: removed when their owner goes out
// of scope, and, through a process-wide registry, by a program that ends on a signal (the
// command line's SIGTERM, SIGHUP and second SIGINT call remove_registered_temporaries() before
// the signal's default action ends it).
//
// A TemporaryDirectory is made by mkdtemp (a new name no other process can have chosen, created
// with mode 0700: only this user may enter it), so files written inside it cannot be replaced,
// read or pre-placed by another local user even in a shared, sticky directory such as /tmp.
#pragma once

#include <string>

#include "emnet/core/errors.hpp"

namespace emnet {

/// Adds `path` (a file or a directory) to the paths removed by remove_registered_temporaries().
/// @param path  an absolute or working-directory-relative path; empty paths are ignored
void register_temporary_path(const std::string& path);

/// Takes `path` off the registry (it was renamed into place or removed by its owner).
void unregister_temporary_path(const std::string& path);

/// Removes every registered path (a directory with everything in it) and empties the registry.
/// For a program about to end on a signal; errors are ignored. Thread-safe.
void remove_registered_temporaries() noexcept;

/// A private directory, removed with its contents when this object is destroyed.
class TemporaryDirectory {
 public:
  TemporaryDirectory() = default;
  ~TemporaryDirectory();
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

  /// Creates the directory `parent`/`prefix`XXXXXX (mode 0700) and registers it.
  /// @param parent  the directory to create it in; empty: $TMPDIR, or /tmp when that is unset
  /// @param prefix  the start of its name, e.g. "emnet-ngspice-"
  /// @return a failure naming the pattern and the system's reason; nothing is thrown
  Status create(const std::string& parent, const std::string& prefix);

  /// The directory's path; empty before a successful create().
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace emnet
