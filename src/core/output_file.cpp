// Output files written completely or not at all; see include/emnet/core/output_file.hpp.
#include "emnet/core/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "emnet/core/temporary_files.hpp"

namespace emnet {

namespace {

constexpr size_t kBufferBytes = 1 << 16;

// `path` with symbolic links followed as far as they lead (a dangling link: its target).
std::string followed(const std::string& path) {
  std::error_code error;
  std::filesystem::path current(path);
  for (int hop = 0; hop < 40 && std::filesystem::is_symlink(current, error); ++hop) {
    const std::filesystem::path link = std::filesystem::read_symlink(current, error);
    if (error) break;
    current = link.is_absolute() ? link : current.parent_path() / link;
  }
  return current.string();
}

}  // namespace

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
  if (path_.empty()) {
    status_ = Status::failure("cannot write a file without a name");
    return;
  }
  target_ = followed(path_);
  struct stat existing {};
  const bool exists = ::stat(target_.c_str(), &existing) == 0;
  if (exists && !S_ISREG(existing.st_mode)) {
    // A device, a pipe, a terminal: written in place.
    descriptor_ = ::open(target_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (descriptor_ < 0) fail("cannot write", errno);
    return;
  }
  const std::filesystem::path target(target_);
  const std::filesystem::path directory = target.parent_path();
  const std::string name = target.filename().string();
  for (int attempt = 0; attempt < 100 && descriptor_ < 0; ++attempt) {
    static std::atomic<int> counter{0};
    const std::string candidate = (directory / ("." + name + "." + std::to_string(::getpid()) +
                                                "-" + std::to_string(counter++) + ".tmp"))
                                      .string();
    descriptor_ = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (descriptor_ >= 0) {
      temporary_ = candidate;
      register_temporary_path(temporary_);
    } else if (errno != EEXIST) {
      fail("cannot write", errno);
      return;
    }
  }
  if (descriptor_ < 0) {
    fail("cannot create a temporary file for", EEXIST);
    return;
  }
  if (exists) ::fchmod(descriptor_, existing.st_mode & 07777);
}

OutputFile::~OutputFile() {
  if (descriptor_ >= 0) ::close(descriptor_);
  if (!committed_ && !temporary_.empty()) ::unlink(temporary_.c_str());
  unregister_temporary_path(temporary_);
}

void OutputFile::fail(const std::string& what, int error_number) {
  if (!status_.ok()) return;
  status_ = Status::failure(what + " '" + path_ + "': " + std::strerror(error_number));
}

void OutputFile::write(std::string_view text) {
  if (!status_.ok() || committed_) return;
  buffer_.append(text.data(), text.size());
  if (buffer_.size() >= kBufferBytes) flush_buffer();
}

bool OutputFile::flush_buffer() {
  size_t written = 0;
  while (status_.ok() && written < buffer_.size()) {
    const ssize_t n = ::write(descriptor_, buffer_.data() + written, buffer_.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot write", errno);
    } else if (n == 0) {
      fail("cannot write", EIO);
    } else {
      written += static_cast<size_t>(n);
    }
  }
  buffer_.clear();
  return status_.ok();
}

Status OutputFile::commit() {
  if (committed_) return Status::failure("'" + path_ + "' was already written");
  if (status_.ok()) flush_buffer();
  // fsync reports the write errors some file systems only find when the data reach the disk;
  // a device or a pipe cannot be synced (EINVAL), which is not an error.
  if (status_.ok() && ::fsync(descriptor_) != 0 && errno != EINVAL && errno != EROFS)
    fail("cannot write", errno);
  if (descriptor_ >= 0) {
    if (::close(descriptor_) != 0 && errno != EINTR) fail("cannot write", errno);
    descriptor_ = -1;
  }
  if (status_.ok() && !temporary_.empty()) {
    if (::rename(temporary_.c_str(), target_.c_str()) != 0)
      fail("cannot write", errno);
    else
      unregister_temporary_path(temporary_);
  }
  if (status_.ok()) committed_ = true;
  return status_;
}

Status write_output_file(const std::string& path, std::string_view text) {
  OutputFile file(path);
  file.write(text);
  return file.commit();
}

}  // namespace emnet
