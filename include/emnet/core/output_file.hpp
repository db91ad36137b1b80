// Output files written completely or not at all: CSV tables, SPICE decks, plot data, scripts and
// images.
//
// The text goes to a temporary file in the same directory (".NAME.PID-K.tmp", so that it is on
// the same file system and hidden from a plain `ls`), and is renamed onto NAME only when every
// write, the flush to disk (fsync) and the close have succeeded. A full disk, a quota, a file
// size limit or an interruption therefore leaves the previous NAME (or none), never a truncated
// one, and is reported. A NAME that is a symbolic link is followed: the file it points to is
// replaced and the link kept. A NAME that exists and is not a regular file (a terminal, a pipe,
// /dev/null, /dev/full) is written in place, every write and the close checked, as there is
// nothing to rename onto. A new file gets the permissions 0666 less the umask, as an ordinary
// open would; a replaced one keeps its permissions.
//
// Failures are Statuses naming the file and the system's reason (strerror), never exceptions.
#pragma once

#include <string>
#include <string_view>

#include "emnet/core/errors.hpp"

namespace emnet {

/// A file written completely or not at all (see above).
class OutputFile {
 public:
  /// Opens the temporary file (or, see above, `path` itself); a failure is kept in status().
  explicit OutputFile(std::string path);
  /// Removes the temporary file unless commit() succeeded.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Appends text (buffered). After a failure further writes are ignored; status() says why.
  void write(std::string_view text);
  /// Writes what is buffered, flushes to disk, closes and renames into place. Once only.
  Status commit();
  /// The first failure so far, or success.
  const Status& status() const { return status_; }
  /// The path as given.
  const std::string& path() const { return path_; }

 private:
  bool flush_buffer();
  void fail(const std::string& what, int error_number);

  std::string path_;       // as given, for messages
  std::string target_;     // the file replaced (symbolic links followed)
  std::string temporary_;  // empty when writing in place
  std::string buffer_;
  int descriptor_ = -1;
  bool committed_ = false;
  Status status_;
};

/// The whole `text` as the file `path`, through OutputFile.
Status write_output_file(const std::string& path, std::string_view text);

}  // namespace emnet
