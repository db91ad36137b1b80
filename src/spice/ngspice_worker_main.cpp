// emnet-ngspice-worker: runs one SPICE deck in libngspice in a process of its own, for the
// ngspice runner's library backend (ngspice_worker_backend.cpp starts it through the process
// helper; the protocol is in ngspice_worker_protocol.hpp).
//
// Why a process of its own: libngspice keeps one circuit state per process in global
// variables, asks to be "detached" (ControlledExit) after some parse errors, and a crash or an
// endless run inside it must not take the caller down or hang it. The worker is a program
// started with exec, not a fork of the caller, so it is safe whatever else the caller runs
// (other threads, a Python host): nothing of the caller's state comes along.
//
// The worker reads the deck from standard input, loads the first library that loads, runs the
// deck with a plain `run` (the runner keeps the time limit and kills the worker past it) and
// streams ngspice's messages, then the plot names, the vectors (raw IEEE doubles, so
// bit-exact), ngspice's time and the status as records on its standard output. Its standard
// output is the record stream only: the worker moves it to another descriptor and points
// descriptor 1 at standard error, so that what libngspice prints directly lands there.
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "core/posix_handles.hpp"
#include "ngspice_library.hpp"
#include "ngspice_worker_protocol.hpp"

namespace {

// Collects like CollectingSink and also streams every message to the runner.
class StreamingSink : public emnet::CollectingSink {
 public:
  StreamingSink(emnet::RecordWriter& writer, std::size_t max_message_bytes)
      : CollectingSink(max_message_bytes), writer_(writer) {}
  void message(emnet::NgspiceStream stream, std::string text) noexcept override {
    try {
      writer_.write(stream == emnet::NgspiceStream::err ? emnet::RecordTag::message_err
                                                        : emnet::RecordTag::message_out,
                    emnet::encode_message(text));
    } catch (...) {
    }
    CollectingSink::message(stream, std::move(text));
  }

 private:
  emnet::RecordWriter& writer_;
};

// Standard input to its end.
bool read_standard_input(std::string& text) {
  char buffer[65536];
  for (;;) {
    const ssize_t count = ::read(STDIN_FILENO, buffer, sizeof buffer);
    if (count > 0) {
      text.append(buffer, static_cast<std::size_t>(count));
    } else if (count == 0) {
      return true;
    } else if (errno != EINTR) {
      return false;
    }
  }
}

int run_worker(const emnet::NgspiceWorkerRequest& request, int record_descriptor) {
  using namespace emnet;
  std::string input;
  if (!read_standard_input(input)) {
    std::fprintf(stderr, "%s: cannot read the deck from standard input\n", kNgspiceWorkerName);
    return kNgspiceWorkerFailureExitStatus;
  }
  const std::vector<std::string> lines = ngspice_worker_deck_lines(input);
  RecordWriter writer(record_descriptor);
  std::string why;
  NgspiceLibrary* library =
      NgspiceLibrary::acquire(request.library_names, why, /*may_replace=*/true);
  if (!library) {
    writer.write(RecordTag::library_unavailable, cut_to(why, kMaxTextRecordBytes));
    return 0;
  }
  writer.write(RecordTag::library_loaded, cut_to(library->loaded_name(), kMaxTextRecordBytes));
  StreamingSink sink(writer, request.max_message_bytes);
  set_library_run_sink(&sink);
  const LibraryRun run =
      run_deck_in_library(*library, sink, lines, /*in_background=*/false,
                          /*timeout_seconds=*/0.0, [&] { return sink.snapshot(); });
  for (const std::string& name : run.plot_names)
    writer.write(RecordTag::plot_name, cut_to(name, kNgspiceMaxLineBytes));
  for (const NgspiceVector& vector : run.vectors)
    writer.write(RecordTag::vector, encode_vector(vector));
  writer.write(RecordTag::ngspice_seconds, encode_seconds(run.ngspice_seconds));
  writer.write(RecordTag::status, encode_status(run.status));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  emnet::NgspiceWorkerRequest request;
  std::string why;
  if (!emnet::parse_ngspice_worker_arguments(argc, argv, request, why)) {
    std::fprintf(stderr, "%s: %s\n", emnet::kNgspiceWorkerName, why.c_str());
    return emnet::kNgspiceWorkerUsageExitStatus;
  }
  // The records keep the original standard output; descriptor 1 becomes standard error.
  const int record_descriptor = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, STDERR_FILENO + 1);
  if (record_descriptor < 0 || ::dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
    std::fprintf(stderr, "%s: cannot set up its output: %s\n", emnet::kNgspiceWorkerName,
                 emnet::errno_text(errno).c_str());
    return emnet::kNgspiceWorkerFailureExitStatus;
  }
  try {
    const int status = run_worker(request, record_descriptor);
    // ngspice's own exit handlers may print or crash; the result is complete already.
    std::fflush(nullptr);
    ::_exit(status);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s: %s\n", emnet::kNgspiceWorkerName, error.what());
  } catch (...) {
  }
  std::fflush(nullptr);
  ::_exit(emnet::kNgspiceWorkerFailureExitStatus);
}
