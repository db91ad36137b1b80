// Runs the emnet program for tests: exit status, standard output and standard error.
//
// EMNET_TEST_BINARY (environment) names another emnet program to run instead of the one built
// with the tests, e.g. an older build, to see a regression test fail there.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

namespace emnet::testing {

struct CliRun {
  int status = -1;
  std::string out, err;
};

inline std::string emnet_binary() {
  const char* other = std::getenv("EMNET_TEST_BINARY");
  return other != nullptr && *other != '\0' ? other : EMNET_BINARY;
}

// `prefix` goes before the binary (e.g. "timeout 10 "). Standard error goes through a file
// unique per process and call: CTest runs the tests in parallel processes.
inline CliRun run_emnet(const std::string& arguments, const std::string& prefix = "") {
  static int counter = 0;
  const std::string err_path = ::testing::TempDir() + "emnet_cli_err_" + std::to_string(getpid()) +
                               "_" + std::to_string(counter++);
  const std::string command = prefix + emnet_binary() + " " + arguments + " 2>" + err_path;
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

// Whether this system gives pseudo-terminals (a container without /dev/ptmx does not).
inline bool pseudo_terminals_available() {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0) return false;
  close(master);
  return true;
}

// The emnet program as a child process whose standard error is read while it runs, through a
// pipe or a pseudo-terminal (so that the program sees a terminal there), for the progress line
// and Ctrl-C. Standard output goes to `stdout_path`. Every wait has a time limit; the destructor
// kills (SIGKILL) and reaps a child still running.
class EmnetChild {
 public:
  EmnetChild(const std::vector<std::string>& arguments, bool stderr_is_terminal,
             const std::string& stdout_path) {
    int child_end = -1;
    if (stderr_is_terminal) {
      read_end_ = posix_openpt(O_RDWR | O_NOCTTY);
      if (read_end_ < 0 || grantpt(read_end_) != 0 || unlockpt(read_end_) != 0) return;
      child_end = open(ptsname(read_end_), O_RDWR | O_NOCTTY);
    } else {
      int ends[2];
      if (pipe(ends) != 0) return;
      read_end_ = ends[0];
      child_end = ends[1];
    }
    if (child_end < 0) return;
    std::vector<std::string> argv_text{emnet_binary()};
    argv_text.insert(argv_text.end(), arguments.begin(), arguments.end());
    pid_ = fork();
    if (pid_ == 0) {
      const int out = open(stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (out < 0 || dup2(out, STDOUT_FILENO) < 0 || dup2(child_end, STDERR_FILENO) < 0) _exit(127);
      std::vector<char*> argv;
      for (auto& text : argv_text) argv.push_back(text.data());
      argv.push_back(nullptr);
      signal(SIGINT, SIG_DFL);
      execv(argv[0], argv.data());
      _exit(127);
    }
    close(child_end);
  }
  ~EmnetChild() {
    if (pid_ > 0 && !reaped_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    if (read_end_ >= 0) close(read_end_);
  }
  EmnetChild(const EmnetChild&) = delete;
  EmnetChild& operator=(const EmnetChild&) = delete;

  bool started() const { return pid_ > 0; }

  // Reads standard error until it contains `text` or `seconds` have passed; true if it does.
  bool wait_for_error_text(const std::string& text, double seconds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (err_.find(text) == std::string::npos) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                            until - std::chrono::steady_clock::now())
                            .count();
      if (left <= 0 || !read_some(static_cast<int>(left))) break;
    }
    return err_.find(text) != std::string::npos;
  }

  void send(int signal_number) {
    if (pid_ > 0 && !reaped_) kill(pid_, signal_number);
  }

  // The exit status once the child has ended (at most `seconds`, then it is killed): its exit
  // code, 128 + the signal that ended it, or -1 when it had to be killed.
  int wait(double seconds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    int raw = 0;
    while (!reaped_) {
      read_some(20);
      const pid_t done = waitpid(pid_, &raw, WNOHANG);
      if (done == pid_) {
        reaped_ = true;
        break;
      }
      if (std::chrono::steady_clock::now() > until) {
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
        reaped_ = true;
        return -1;
      }
    }
    while (read_some(50)) {
    }
    if (WIFEXITED(raw)) return WEXITSTATUS(raw);
    if (WIFSIGNALED(raw)) return 128 + WTERMSIG(raw);
    return -1;
  }

  const std::string& error_output() const { return err_; }

 private:
  // Appends what standard error has within `milliseconds`; false when nothing more came.
  bool read_some(int milliseconds) {
    if (read_end_ < 0) return false;
    pollfd entry{read_end_, POLLIN, 0};
    if (poll(&entry, 1, milliseconds) <= 0 || !(entry.revents & (POLLIN | POLLHUP))) return false;
    char buffer[4096];
    const ssize_t n = read(read_end_, buffer, sizeof buffer);
    if (n <= 0) return false;  // end of the pipe; EIO on a terminal whose child has gone
    err_.append(buffer, static_cast<size_t>(n));
    return true;
  }

  pid_t pid_ = -1;
  int read_end_ = -1;
  bool reaped_ = false;
  std::string err_;
};

}  // namespace emnet::testing
