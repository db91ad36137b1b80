// The ngspice runner's facade: the deck's preparation, the choice of backend and the fallback,
// and the result's look-ups; see include/emnet/spice/ngspice_runner.hpp for what the runner
// does and why.
//
// The runner's pieces, one concern a file:
//   ngspice_messages.*         ngspice's messages in bounded memory, and which are errors
//   ngspice_library.*          the binding to libngspice (dlopen, callbacks, one deck)
//   ngspice_worker_protocol.*  the runner–worker protocol (command line, deck, records)
//   ngspice_worker_main.cpp    the worker program, emnet-ngspice-worker
//   ngspice_worker_backend.cpp the library backend: the worker, started and read
//   ngspice_in_this_process.cpp the library backend inside the caller (library_in_this_process)
//   ngspice_program_backend.cpp the program backend: `ngspice -b -r RAWFILE DECK`
//   ngspice_rawfile.*          the rawfile parser
#include "emnet/spice/ngspice_runner.hpp"

#include <chrono>
#include <sstream>

#include "emnet/core/terminal_text.hpp"
#include "ngspice_backends.hpp"
#include "ngspice_messages.hpp"
#include "ngspice_rawfile.hpp"

namespace emnet {

namespace {

using Clock = std::chrono::steady_clock;

// The deck's lines, `.end` last. Refuses a NUL byte (lines go to C strings) and any
// `.control` / `.endc` line (no control commands through this runner).
bool prepare_deck(const std::string& deck_text, std::vector<std::string>& lines, std::string& why) {
  if (deck_text.find('\0') != std::string::npos) {
    why = "the deck contains a NUL character";
    return false;
  }
  std::istringstream stream(deck_text);
  for (std::string line; std::getline(stream, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
  }
  if (lines.empty()) {
    why = "the deck is empty";
    return false;
  }
  const auto first_word = [](const std::string& line) {
    const std::string_view text = ngspice_trimmed(line);
    return ngspice_lower_case(std::string(text.substr(0, text.find_first_of(" \t"))));
  };
  for (std::size_t index = 1; index < lines.size(); ++index) {
    const std::string word = first_word(lines[index]);
    if (word == ".control" || word == ".endc") {
      why = "the deck has a " + word + " line (line " + std::to_string(index + 1) +
            "); the runner runs the deck's own analyses and takes no control commands: "
            "write the deck without its .control block";
      return false;
    }
  }
  std::size_t last = lines.size();
  while (last > 1 && ngspice_trimmed(lines[last - 1]).empty()) --last;
  if (last <= 1 || first_word(lines[last - 1]) != ".end") lines.push_back(".end");
  return true;
}

}  // namespace

// ---- the result -----------------------------------------------------------------------------

const NgspiceVector* NgspiceResult::find(std::string_view name) const {
  const std::string wanted = vector_name_from_rawfile(std::string(ngspice_trimmed(name)));
  for (const NgspiceVector& vector : vectors)
    if (ngspice_lower_case(vector.name) == wanted) return &vector;
  return nullptr;
}

const NgspiceVector* NgspiceResult::scale() const {
  for (const NgspiceVector& vector : vectors)
    if (vector.is_scale) return &vector;
  return nullptr;
}

std::string NgspiceResult::messages_text() const {
  std::string text;
  for (const NgspiceMessage& message : messages)
    text += (message.stream == NgspiceStream::err ? "stderr: " : "") + message.text + "\n";
  return text;
}

// ---- run_ngspice ------------------------------------------------------------------------

NgspiceResult run_ngspice(const std::string& deck_text, const NgspiceOptions& options) {
  const Clock::time_point start = Clock::now();
  const auto finish = [&](NgspiceResult result) {
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
  };
  NgspiceResult result;
  std::vector<std::string> lines;
  std::string why;
  if (!prepare_deck(deck_text, lines, why)) {
    result.status = Status::failure("the deck was not run: " + why);
    result.backend_description = "none (the deck was refused)";
    return finish(std::move(result));
  }

  // Why the library backend could not run, as "libngspice could not be loaded (...)" or, when
  // its worker program is missing, "libngspice could not be run (...)".
  std::string library_reason, library_failure;
  if (options.backend != NgspiceBackend::program) {
    BackendAttempt attempt = options.library_in_this_process
                                 ? run_library_in_this_process(lines, options)
                                 : run_library_in_worker(lines, options);
    if (attempt.available) return finish(std::move(attempt.result));
    library_reason = terminal_text(attempt.unavailable_reason);  // dlerror's text, paths
    library_failure = std::string(attempt.missing_worker ? "libngspice could not be run ("
                                                         : "libngspice could not be loaded (") +
                      library_reason + ")";
    if (options.backend == NgspiceBackend::library) {
      result.status = Status::failure(
          library_failure + (attempt.missing_worker
                                 ? std::string("; build or install emnet-ngspice-worker")
                                 : std::string("; install the Debian package libngspice0")));
      result.backend_description = attempt.missing_worker
                                       ? "none (the ngspice worker program not found)"
                                       : "none (libngspice not available)";
      return finish(std::move(result));
    }
  }

  BackendAttempt attempt = run_program_backend(lines, options);
  if (attempt.available) {
    if (options.backend == NgspiceBackend::automatic)
      attempt.result.backend_description += " (libngspice not available: " + library_reason + ")";
    return finish(std::move(attempt.result));
  }
  if (options.backend == NgspiceBackend::automatic) {
    result.status =
        Status::failure("ngspice is not available: " + library_failure +
                        " and the ngspice program could not be run (" + attempt.unavailable_reason +
                        "); install the Debian packages libngspice0 and ngspice");
  } else {
    result.status =
        Status::failure("the ngspice program could not be run (" + attempt.unavailable_reason +
                        "); install the Debian package ngspice");
  }
  result.backend_description = "none (ngspice not available)";
  return finish(std::move(result));
}

}  // namespace emnet
