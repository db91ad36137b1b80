// The process helper (include/emnet/core/process.hpp) on small shell programs: how a program
// ended (exit status, signal, time limit, stop, not found), what it was given (standard input,
// environment, working directory) and what came back (captured output within its cap), and
// that nothing it started outlives the run. Each expectation is exact: the programs are
// deterministic, and what a test asks of the helper has one right answer. Time limits here
// only guard against hangs; they measure nothing.
#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "emnet/core/process.hpp"

namespace emnet {
namespace {

ProcessResult run_shell(const std::string& script, ProcessOptions options = {}) {
  options.arguments = {"/bin/sh", "-c", script};
  if (options.timeout_seconds == ProcessOptions{}.timeout_seconds) options.timeout_seconds = 20;
  return run_process(options);
}

ProcessOptions capturing(std::size_t limit = 1 << 20) {
  ProcessOptions options;
  options.standard_output = ProcessOutput::captured(limit);
  options.standard_error = ProcessOutput::captured(limit);
  return options;
}

TEST(Process, ExitStatusIsReported) {
  const ProcessResult result = run_shell("exit 3");
  EXPECT_EQ(result.how, ProcessResult::How::exited) << result.description();
  EXPECT_EQ(result.exit_status, 3);
  EXPECT_TRUE(result.exited_with(3));
  EXPECT_EQ(result.description(), "exited with status 3");
  EXPECT_GE(result.seconds, 0.0);
  EXPECT_GE(result.total_seconds, result.seconds);
}

TEST(Process, SignalIsReported) {
  const ProcessResult result = run_shell("kill -TERM $$; sleep 5");
  EXPECT_EQ(result.how, ProcessResult::How::signalled) << result.description();
  EXPECT_EQ(result.signal_number, SIGTERM);
  EXPECT_NE(result.description().find("killed by signal 15"), std::string::npos)
      << result.description();
}

TEST(Process, OutputIsCapturedPerStream) {
  const ProcessResult result = run_shell("printf out; printf err >&2", capturing());
  ASSERT_TRUE(result.exited_with(0)) << result.description();
  EXPECT_EQ(result.standard_output, "out");
  EXPECT_EQ(result.standard_error, "err");
  EXPECT_EQ(result.standard_output_bytes_left_out, 0u);
}

// 300 000 bytes against a cap of 1000: the first 1000 are kept, the rest counted, and the
// program still runs to its end (it is not blocked on a full pipe).
TEST(Process, CaptureKeepsTheFirstBytesUpToItsCap) {
  const ProcessResult result =
      run_shell("head -c 300000 /dev/zero | tr '\\0' x; echo done >&2", capturing(1000));
  ASSERT_TRUE(result.exited_with(0)) << result.description();
  EXPECT_EQ(result.standard_output, std::string(1000, 'x'));
  EXPECT_EQ(result.standard_output_bytes_left_out, 299000u);
  EXPECT_EQ(result.standard_error, "done\n");
}

TEST(Process, DiscardedOutputIsNotKept) {
  ProcessOptions options;  // both streams discarded by default
  const ProcessResult result = run_shell("head -c 1000000 /dev/zero; echo x >&2", options);
  ASSERT_TRUE(result.exited_with(0)) << result.description();
  EXPECT_TRUE(result.standard_output.empty());
  EXPECT_TRUE(result.standard_error.empty());
  EXPECT_EQ(result.standard_output_bytes_left_out, 0u);
}

// 3 MB through `cat`: more than a pipe holds, so writing the input and reading the output must
// go on together.
TEST(Process, StandardInputBytesReachTheProgram) {
  std::string input;
  for (int k = 0; input.size() < 3000000; ++k) input += "line " + std::to_string(k) + "\n";
  ProcessOptions options = capturing(8 << 20);
  options.standard_input = input;
  const ProcessResult result = run_shell("cat", options);
  ASSERT_TRUE(result.exited_with(0)) << result.description();
  EXPECT_EQ(result.standard_output.size(), input.size());
  EXPECT_TRUE(result.standard_output == input);
}

TEST(Process, WithoutInputStandardInputIsEmpty) {
  const ProcessResult result = run_shell("wc -c", capturing());
  ASSERT_TRUE(result.exited_with(0)) << result.description();
  EXPECT_EQ(std::stoi(result.standard_output), 0);
}

// A program that ends without reading its input: the helper (and this process) is not hurt
// by the broken pipe.
TEST(Process, InputTheProgramDoesNotReadIsDropped) {
  ProcessOptions options;
  options.standard_input = std::string(4 << 20, 'x');
  const ProcessResult result = run_shell("exit 0", options);
  EXPECT_TRUE(result.exited_with(0)) << result.description();
}

TEST(Process, EnvironmentAdditionsReplaceAndAdd) {
  ::setenv("EMNET_PROCESS_TEST_REPLACED", "old", 1);
  ProcessOptions options = capturing();
  options.environment_additions = {{"EMNET_PROCESS_TEST_REPLACED", "new"},
                                   {"EMNET_PROCESS_TEST_ADDED", "a b"}};
  const ProcessResult result = run_shell(
      "printf '%s|%s|%s' \"$EMNET_PROCESS_TEST_REPLACED\" \"$EMNET_PROCESS_TEST_ADDED\" "
      "\"$HOME\"",
      options);
  ::unsetenv("EMNET_PROCESS_TEST_REPLACED");
  ASSERT_TRUE(result.exited_with(0)) << result.description();
  const char* home = std::getenv("HOME");
  EXPECT_EQ(result.standard_output, "new|a b|" + std::string(home ? home : ""));
}

TEST(Process, WorkingDirectoryIsTheProgramsOwn) {
  ProcessOptions options = capturing();
  options.working_directory = "/";
  const ProcessResult result = run_shell("pwd", options);
  ASSERT_TRUE(result.exited_with(0)) << result.description();
  EXPECT_EQ(result.standard_output, "/\n");
}

TEST(Process, MissingProgramIsNotStarted) {
  ProcessOptions options;
  options.arguments = {"/nonexistent/program"};
  ProcessResult result = run_process(options);
  EXPECT_EQ(result.how, ProcessResult::How::not_started) << result.description();
  EXPECT_EQ(result.error_number, ENOENT);

  options.arguments = {"emnet-no-such-program-in-path"};
  result = run_process(options);
  EXPECT_EQ(result.how, ProcessResult::How::not_started) << result.description();
  EXPECT_EQ(result.error_number, ENOENT);

  // Found and executable, but neither a binary nor a script (no "#!"): the exec in the
  // supervisor fails with ENOEXEC (the helper runs no shell in its place).
  const std::string not_a_program =
      ::testing::TempDir() + "emnet_process_not_a_program_" + std::to_string(::getpid());
  std::ofstream(not_a_program) << "echo this is no program\n";
  ::chmod(not_a_program.c_str(), 0755);
  options.arguments = {not_a_program};
  result = run_process(options);
  std::remove(not_a_program.c_str());
  EXPECT_EQ(result.how, ProcessResult::How::not_started) << result.description();
  EXPECT_EQ(result.error_number, ENOEXEC);

  options.arguments.clear();
  result = run_process(options);
  EXPECT_EQ(result.how, ProcessResult::How::failed) << result.description();
}

TEST(Process, FileSizeLimitStopsTheProgram) {
  const std::string path =
      ::testing::TempDir() + "emnet_process_big_file_" + std::to_string(::getpid());
  ProcessOptions options;
  options.file_size_limit = 1000;
  const ProcessResult result = run_shell("head -c 10000 /dev/zero > '" + path + "'", options);
  struct stat status {};
  const bool exists = ::stat(path.c_str(), &status) == 0;
  std::remove(path.c_str());
  // The shell's `head` gets SIGXFSZ; the shell reports it as its exit status 128 + signal.
  EXPECT_TRUE(result.exited_with(128 + SIGXFSZ) ||
              (result.how == ProcessResult::How::signalled && result.signal_number == SIGXFSZ))
      << result.description();
  ASSERT_TRUE(exists);
  EXPECT_EQ(status.st_size, 1000);
}

TEST(Process, CallbackGetsTheOutputAndCanStopTheProgram) {
  ProcessOptions options;
  std::string seen;
  options.standard_output = ProcessOutput::to_callback([&](const char* data, std::size_t size) {
    seen.append(data, size);
    return seen.size() < 100000;  // enough: stop
  });
  options.timeout_seconds = 20;
  options.arguments = {"yes"};
  const ProcessResult result = run_process(options);
  EXPECT_EQ(result.how, ProcessResult::How::stopped) << result.description();
  EXPECT_GE(seen.size(), 100000u);
  EXPECT_EQ(seen.substr(0, 4), "y\ny\n");
}

// Whether the process `pid` is alive and runs `marker` in its command line (so that a pid
// reused by another process does not count).
bool process_runs(pid_t pid, const std::string& marker) {
  std::ifstream command_line("/proc/" + std::to_string(pid) + "/cmdline");
  std::string text((std::istreambuf_iterator<char>(command_line)),
                   std::istreambuf_iterator<char>());
  for (char& c : text)
    if (c == '\0') c = ' ';
  return text.find(marker) != std::string::npos;
}

// A shell that starts a grandchild which calls setsid (leaving the program's process group and
// session), writes its pid to a file and sleeps; then the shell runs `then`. The grandchild's
// pid, -1 when it did not start.
pid_t run_with_grandchild(const std::string& name, const std::string& then, double timeout,
                          ProcessResult& result) {
  const std::string pid_file = ::testing::TempDir() + "emnet_process_grandchild_" + name + "_" +
                               std::to_string(::getpid()) + ".pid";
  std::remove(pid_file.c_str());
  ProcessOptions options;
  options.timeout_seconds = timeout;
  result =
      run_shell("setsid sh -c 'echo $$ > \"" + pid_file + ".new\"; mv \"" + pid_file + ".new\" \"" +
                    pid_file + "\"; exec sleep 4321' </dev/null >/dev/null 2>&1 &\n" +
                    "while [ ! -s '" + pid_file + "' ]; do sleep 0.01; done\n" + then,
                options);
  pid_t grandchild = -1;
  std::ifstream(pid_file) >> grandchild;
  std::remove(pid_file.c_str());
  return grandchild;
}

TEST(Process, TimeoutKillsAGrandchildThatLeftTheProcessGroup) {
  ProcessResult result;
  const pid_t grandchild = run_with_grandchild("timeout", "exec sleep 100", 2, result);
  EXPECT_EQ(result.how, ProcessResult::How::timed_out) << result.description();
  ASSERT_GT(grandchild, 0) << "the grandchild did not start";
  const bool survived = process_runs(grandchild, "sleep 4321");
  EXPECT_FALSE(survived) << "grandchild " << grandchild << " outlived the timeout";
  if (survived) ::kill(grandchild, SIGKILL);
}

TEST(Process, NothingTheProgramStartedOutlivesIt) {
  ProcessResult result;
  const pid_t grandchild = run_with_grandchild("left_behind", "exit 7", 20, result);
  EXPECT_TRUE(result.exited_with(7)) << result.description();
  ASSERT_GT(grandchild, 0) << "the grandchild did not start";
  const bool survived = process_runs(grandchild, "sleep 4321");
  EXPECT_FALSE(survived) << "grandchild " << grandchild << " outlived the run";
  if (survived) ::kill(grandchild, SIGKILL);
}

// The helper forks only its supervisor, which makes system calls only: a thread of this
// process that holds the allocator busy the whole time does not get in its way.
TEST(Process, WorksWhileAnotherThreadAllocates) {
  std::atomic<bool> stop{false};
  std::thread busy([&] {
    while (!stop) {
      std::string text(1000, 'x');
      text += std::to_string(text.size());
    }
  });
  for (int run = 0; run < 20; ++run) {
    const ProcessResult result = run_shell("printf " + std::to_string(run), capturing());
    EXPECT_TRUE(result.exited_with(0)) << result.description();
    EXPECT_EQ(result.standard_output, std::to_string(run));
  }
  stop = true;
  busy.join();
}

// The supervisor's fork runs none of this process's fork handlers (pthread_atfork): a host's
// handlers (Python registers some) take locks and allocate, which a fork of a process with
// other threads must not do. A plain fork() would run the handler below once per run.
std::atomic<int> fork_handler_calls{0};

TEST(Process, RunsNoForkHandlerOfTheCaller) {
  static const int registered = ::pthread_atfork([] { ++fork_handler_calls; }, nullptr, nullptr);
  ASSERT_EQ(registered, 0);
  const int before = fork_handler_calls.load();
  for (int run = 0; run < 3; ++run) EXPECT_TRUE(run_shell("exit 0").exited_with(0));
  EXPECT_EQ(fork_handler_calls.load(), before);
}

// stop_requested (a Ctrl-C flag) stops a program that prints nothing: the poll wakes at least
// every 100 ms to ask. A quiet `sleep 30` asked to stop once it runs ends as `stopped`, far
// inside its 20 s time limit (the 20 s is a hang guard, not a timing assertion).
TEST(Process, StopRequestedStopsAQuietProgram) {
  ProcessOptions options;
  int asked = 0;
  options.stop_requested = [&] { return ++asked > 3; };
  const ProcessResult result = run_shell("exec sleep 30", options);
  EXPECT_EQ(result.how, ProcessResult::How::stopped) << result.description();
  EXPECT_EQ(asked, 4);
}

}  // namespace
}  // namespace emnet
