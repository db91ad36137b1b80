// Input files read to a limit, regular files only (emnet/core/bounded_file.hpp).
#include "emnet/core/bounded_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

#include "emnet/core/errors.hpp"
#include "posix_handles.hpp"

namespace emnet {

namespace {

const char* irregular_kind(mode_t mode) {
  if (S_ISFIFO(mode)) return "a pipe";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

}  // namespace

std::string read_bounded_regular_file(const std::string& path, std::size_t limit,
                                      const std::string& what, const std::string& key) {
  FileDescriptor file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (!file.is_open()) {
    const int error = errno;
    throw InputError(path, key,
                     "cannot open " + what + " (" +
                         (error == ENOENT ? std::string("no such file") : errno_text(error)) + ")");
  }
  struct stat status {};
  if (::fstat(file.get(), &status) != 0)
    throw InputError(path, key, "cannot read " + what + " (" + errno_text(errno) + ")");
  if (S_ISDIR(status.st_mode))
    throw InputError(path, key, "cannot open " + what + " (it is a directory)");
  if (!S_ISREG(status.st_mode))
    throw InputError(path, key,
                     std::string("not a regular file (") + irregular_kind(status.st_mode) + "); " +
                         what + " is read from a regular file");
  const std::string too_large =
      " bytes; " + what + " may have at most " + std::to_string(limit) + " bytes";
  if (static_cast<std::size_t>(status.st_size) > limit)
    throw InputError(path, key, "the file is " + std::to_string(status.st_size) + too_large);
  // Read at most one byte past the limit, whatever the size said (the file may have grown).
  std::string contents;
  char buffer[65536];
  while (contents.size() <= limit) {
    const ssize_t got = ::read(file.get(), buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0)
      throw InputError(path, key, "cannot read " + what + " (" + errno_text(errno) + ")");
    if (got == 0) break;
    contents.append(buffer, static_cast<std::size_t>(got));
  }
  if (contents.size() > limit)
    throw InputError(path, key,
                     "the file grew past the limit while read; " + what + " may have at most " +
                         std::to_string(limit) + " bytes");
  return contents;
}

}  // namespace emnet
