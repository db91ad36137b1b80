// libngspice in the caller's own process (NgspiceOptions::library_in_this_process): no worker,
// for timing the library itself. The time limit is kept with `bg_run` / `bg_halt`, one deck
// runs at a time (the library has one circuit state per process), and a crash of ngspice is a
// crash of the caller.
#include <mutex>

#include "emnet/core/terminal_text.hpp"
#include "ngspice_backends.hpp"
#include "ngspice_library.hpp"

namespace emnet {

namespace {

std::mutex in_process_mutex;  // one circuit state per process

}  // namespace

BackendAttempt run_library_in_this_process(const std::vector<std::string>& lines,
                                           const NgspiceOptions& options) {
  BackendAttempt attempt;
  std::lock_guard<std::mutex> guard(in_process_mutex);
  NgspiceLibrary* library = NgspiceLibrary::acquire(
      options.library_names, attempt.unavailable_reason, /*may_replace=*/false);
  if (!library) return attempt;
  attempt.available = true;
  NgspiceResult& result = attempt.result;
  result.backend_used = NgspiceBackend::library;
  result.backend_description = "libngspice in-process (" + terminal_text(library->loaded_name()) +
                               ", in emnet's own process)";
  if (library->busy) {
    result.status = Status::failure(
        "libngspice is still busy with an earlier deck that could not be stopped; run the "
        "deck in a worker (library_in_this_process = false)");
    return attempt;
  }
  CollectingSink sink(options.max_message_bytes);
  set_library_run_sink(&sink);
  LibraryRun run = run_deck_in_library(*library, sink, lines, /*in_background=*/true,
                                       options.timeout_seconds, [&] { return sink.snapshot(); });
  if (!library->busy && !run.library_asked_to_be_detached) {
    CollectingSink discard(0);  // clean-up chatter is not the deck's
    set_library_run_sink(&discard);
    library->command("remcirc");
    library->command("destroy all");
  }
  set_library_run_sink(nullptr);
  if (run.library_asked_to_be_detached && !library->busy) NgspiceLibrary::unload();
  result.status = run.status;
  result.plot_names = std::move(run.plot_names);
  result.vectors = std::move(run.vectors);
  result.ngspice_seconds = run.ngspice_seconds;
  result.messages = sink.snapshot();
  return attempt;
}

}  // namespace emnet
