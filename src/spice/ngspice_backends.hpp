// The ngspice runner's backends, as the facade (ngspice_runner.cpp) calls them: each runs a
// prepared deck (its lines, `.end` last) and says whether it could run at all.
//
//   run_library_in_worker         libngspice in the worker program (ngspice_worker_backend.cpp)
//   run_library_in_this_process   libngspice in the caller's process (ngspice_in_this_process.cpp)
//   run_program_backend           `ngspice -b -r RAWFILE DECK` (ngspice_program_backend.cpp)
#pragma once

#include <string>
#include <vector>

#include "emnet/spice/ngspice_runner.hpp"

namespace emnet {

// What an attempt at a backend gave: `available` false means it could not be started at all
// (with `unavailable_reason`); then the caller may fall back. `missing_worker`: the library
// backend's worker program was not found (the reason says where it was looked for), rather
// than libngspice failing to load.
struct BackendAttempt {
  bool available = false;
  bool missing_worker = false;
  std::string unavailable_reason;
  NgspiceResult result;
};

BackendAttempt run_library_in_worker(const std::vector<std::string>& lines,
                                     const NgspiceOptions& options);
BackendAttempt run_library_in_this_process(const std::vector<std::string>& lines,
                                           const NgspiceOptions& options);
BackendAttempt run_program_backend(const std::vector<std::string>& lines,
                                   const NgspiceOptions& options);

}  // namespace emnet
