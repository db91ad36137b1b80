// POSIX handles in RAII wrappers, shared by the process helper (emnet/core/process.hpp) and
// the ngspice runner: a file descriptor, a pipe, a child process that is killed and reaped
// when its handle goes away, and the few system-call helpers around them (write everything,
// read one chunk).
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <string>
#include <system_error>
#include <utility>

namespace emnet {

inline std::string errno_text(int error_number) {
  return std::generic_category().message(error_number);
}

class FileDescriptor {
 public:
  FileDescriptor() = default;
  explicit FileDescriptor(int descriptor) : descriptor_(descriptor) {}
  FileDescriptor(FileDescriptor&& other) noexcept : descriptor_(other.release()) {}
  FileDescriptor& operator=(FileDescriptor&& other) noexcept {
    if (this != &other) reset(other.release());
    return *this;
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() { reset(); }

  int get() const { return descriptor_; }
  bool is_open() const { return descriptor_ >= 0; }
  int release() { return std::exchange(descriptor_, -1); }
  void reset(int descriptor = -1) {
    if (descriptor_ >= 0) ::close(descriptor_);
    descriptor_ = descriptor;
  }

 private:
  int descriptor_ = -1;
};

struct Pipe {
  FileDescriptor read_end, write_end;
};

// A pipe whose ends are closed in programs this process starts (O_CLOEXEC).
inline bool open_pipe(Pipe& pipe, std::string& why) {
  int ends[2];
  if (::pipe2(ends, O_CLOEXEC) != 0) {
    why = "cannot create a pipe: " + errno_text(errno);
    return false;
  }
  pipe.read_end.reset(ends[0]);
  pipe.write_end.reset(ends[1]);
  return true;
}

// Writes all of `size` bytes, retrying after interruptions; false when the reader is gone.
inline bool write_fully(int descriptor, const void* data, std::size_t size) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = ::write(descriptor, bytes, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    bytes += written;
    size -= static_cast<std::size_t>(written);
  }
  return true;
}

// One read of at most `capacity` bytes into `buffer`, retried after interruptions: the count
// read, 0 at end of file or on an error. One call never reads more than `capacity`, so a
// reader that calls it once per wake-up does bounded work between two looks at its clock.
inline std::size_t read_chunk(int descriptor, char* buffer, std::size_t capacity) {
  for (;;) {
    const ssize_t count = ::read(descriptor, buffer, capacity);
    if (count > 0) return static_cast<std::size_t>(count);
    if (count < 0 && errno == EINTR) continue;
    return 0;
  }
}

// A child process that is killed (SIGKILL, its whole process group when it leads one) and
// reaped when this handle goes away without having reaped it.
class ChildProcess {
 public:
  ChildProcess() = default;
  ChildProcess(pid_t process_id, bool leads_process_group)
      : process_id_(process_id), leads_process_group_(leads_process_group) {}
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess() {
    if (running()) {
      kill();
      wait_blocking();
    }
  }

  pid_t process_id() const { return process_id_; }
  bool running() const { return process_id_ > 0 && !reaped_; }
  void kill() {
    if (!running()) return;
    if (leads_process_group_) ::kill(-process_id_, SIGKILL);
    ::kill(process_id_, SIGKILL);
  }
  // True once the child has ended (its wait status in `status()`).
  bool try_wait() { return reap(WNOHANG); }
  void wait_blocking() { reap(0); }
  int status() const { return wait_status_; }
  bool reap_failed() const { return reap_failed_; }

 private:
  bool reap(int flags) {
    if (!running()) return reaped_;
    for (;;) {
      const pid_t result = ::waitpid(process_id_, &wait_status_, flags);
      if (result == process_id_) {
        reaped_ = true;
        return true;
      }
      if (result == 0) return false;
      if (errno == EINTR) continue;
      // ECHILD: someone else reaped it (SIGCHLD ignored); its status is unknown.
      reaped_ = true;
      reap_failed_ = true;
      return true;
    }
  }
  pid_t process_id_ = -1;
  bool leads_process_group_ = false;
  bool reaped_ = false;
  bool reap_failed_ = false;
  int wait_status_ = 0;
};

}  // namespace emnet
