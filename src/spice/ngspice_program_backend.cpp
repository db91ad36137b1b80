// The runner's program backend: `ngspice -b -r RAWFILE DECK` in a private temporary directory,
// through the process helper (emnet/core/process.hpp), which kills the program and everything
// it started (also a grandchild that left its process group and session) at the time limit and
// when it ends, and limits the size of every file it writes to max_result_bytes (past it the
// program gets SIGXFSZ). Its output is read in chunks of at most 64 KiB into a bounded
// MessageLog; the rawfile (binary, or ASCII when SPICE_ASCIIRAWFILE is set) is read only when
// its size on disk is within max_result_bytes, and parsed by ngspice_rawfile.cpp.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/posix_handles.hpp"
#include "emnet/core/process.hpp"
#include "emnet/core/temporary_files.hpp"
#include "emnet/core/terminal_text.hpp"
#include "ngspice_backends.hpp"
#include "ngspice_messages.hpp"
#include "ngspice_rawfile.hpp"

namespace emnet {

namespace {

// Reads the file at `path` into `bytes` when it holds at most `limit` bytes; a missing file
// gives no bytes. The size is the file's own (fstat), never a claim inside it.
bool read_file_bounded(const std::string& path, std::uint64_t limit, std::string& bytes,
                       std::string& why) {
  bytes.clear();
  // O_NONBLOCK: a FIFO left at the path opens at once (and is refused below) instead of
  // blocking open() forever; O_NOFOLLOW: a symbolic link there is not followed.
  FileDescriptor file(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOFOLLOW));
  if (!file.is_open()) {
    if (errno == ENOENT) return true;
    why = "cannot open the rawfile: " + errno_text(errno);
    return false;
  }
  struct stat status {};
  if (::fstat(file.get(), &status) != 0 || !S_ISREG(status.st_mode)) {
    why = "the rawfile is not a regular file";
    return false;
  }
  const auto size = static_cast<std::uint64_t>(status.st_size);
  if (size > limit) {
    why = "the rawfile is " + std::to_string(size) + " bytes, more than max_result_bytes (" +
          std::to_string(limit) + ")";
    return false;
  }
  bytes.resize(static_cast<std::size_t>(size));
  std::size_t filled = 0;
  while (filled < bytes.size()) {
    const std::size_t count = read_chunk(file.get(), bytes.data() + filled, bytes.size() - filled);
    if (count == 0) break;
    filled += count;
  }
  bytes.resize(filled);
  return true;
}

}  // namespace

BackendAttempt run_program_backend(const std::vector<std::string>& lines,
                                   const NgspiceOptions& options) {
  BackendAttempt attempt;
  NgspiceResult& result = attempt.result;
  const auto fail_here = [&](const std::string& why) {
    attempt.available = true;
    result.status = Status::failure(why);
    return attempt;
  };
  TemporaryDirectory directory;
  if (Status made = directory.create("", "emnet-ngspice-"); !made.ok())
    return fail_here(made.message);
  std::string why;
  const std::string deck_path = directory.path() + "/deck.cir";
  const std::string rawfile_path = directory.path() + "/deck.raw";
  {
    std::ofstream deck(deck_path, std::ios::binary);
    for (const std::string& line : lines) deck << line << '\n';
    if (!deck.flush()) return fail_here("cannot write the deck to " + deck_path);
  }
  MessageLog log(options.max_message_bytes);
  LineCollector out_lines(NgspiceStream::out, log);
  LineCollector err_lines(NgspiceStream::err, log);
  bool printed_anything = false;
  const auto collect = [&](LineCollector& collector) {
    return ProcessOutput::to_callback([&](const char* data, std::size_t size) {
      printed_anything = true;
      collector.add(data, size);
      return true;
    });
  };
  ProcessOptions program;
  program.arguments = {options.program, "-b", "-r", rawfile_path, deck_path};
  program.standard_output = collect(out_lines);
  program.standard_error = collect(err_lines);
  program.timeout_seconds = options.timeout_seconds;
  program.file_size_limit = options.max_result_bytes;
  const ProcessResult end = run_process(program);
  out_lines.finish();
  err_lines.finish();
  result.messages = log.messages();
  result.ngspice_seconds = end.seconds;

  using How = ProcessResult::How;
  if (end.how == How::not_started) {
    attempt.unavailable_reason =
        "cannot run '" + terminal_text(options.program) + "': " + errno_text(end.error_number);
    return attempt;
  }
  if (end.how == How::failed) return fail_here("cannot run ngspice: " + end.problem);
  attempt.available = true;
  result.backend_used = NgspiceBackend::program;
  result.backend_description = "ngspice program as a subprocess";

  if (end.how == How::timed_out)
    return fail_here("ngspice timed out: still running after " +
                     ngspice_seconds_text(std::max(0.0, options.timeout_seconds)) +
                     " s (timeout_seconds); the program and everything it started were killed");
  if (end.how == How::signalled && end.signal_number == SIGXFSZ)
    return fail_here("ngspice was stopped: a file it wrote (its rawfile) reached the limit of " +
                     std::to_string(options.max_result_bytes) + " bytes (max_result_bytes)" +
                     ngspice_error_excerpt(result.messages));
  if (end.how == How::signalled)
    return fail_here("ngspice crashed (" + ngspice_signal_text(end.signal_number) +
                     ") on the deck" + ngspice_error_excerpt(result.messages));
  if (end.exit_status != 0) {
    if (end.exit_status == 127 && !printed_anything) {
      attempt.available = false;
      attempt.unavailable_reason = "'" + terminal_text(options.program) + "' could not be executed";
      return attempt;
    }
    return fail_here("ngspice failed on the deck (exit status " + std::to_string(end.exit_status) +
                     ")" + ngspice_error_excerpt(result.messages));
  }
  if (has_ngspice_error_line(result.messages))
    return fail_here("ngspice failed on the deck" + ngspice_error_excerpt(result.messages));

  std::string bytes;
  if (!read_file_bounded(rawfile_path, options.max_result_bytes, bytes, why))
    return fail_here("ngspice wrote no readable results (" + why + ")" +
                     ngspice_error_excerpt(result.messages));
  std::vector<NgspiceRawPlot> plots;
  if (bytes.empty() || !parse_ngspice_rawfile(bytes, plots, why) || plots.empty())
    return fail_here(
        "ngspice wrote no readable results" +
        (bytes.empty() ? std::string(" (has the deck an analysis line?)") : " (" + why + ")") +
        ngspice_error_excerpt(result.messages));
  for (const NgspiceRawPlot& plot : plots)
    result.plot_names.push_back(terminal_text(plot.plot_name));
  result.vectors = std::move(plots.back().vectors);
  for (NgspiceVector& vector : result.vectors)
    vector.name = terminal_text(vector_name_from_rawfile(vector.name));
  result.status = Status::success();
  return attempt;
}

}  // namespace emnet
