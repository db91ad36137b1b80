// The supervisor of a program run by run_process (emnet/core/process.hpp): the code that runs
// in the forked copy of the calling process, and the reports it sends back.
//
// Everything here runs after a fork of a process that may have other threads: system calls
// only, no lock, no allocation, no C++ library call that might take either. The supervisor
// receives everything prepared (C strings, descriptors) in a SupervisorPlan.
//
// Reports, supervisor to caller over the control socket (a stream socket pair), each a
// SupervisorReport, at most three: started (the program's pid), not executed (errno of the
// exec, or of the pipe or vfork before it), ended (the program's wait status). Each carries the
// supervisor's CLOCK_MONOTONIC time: "started" just before the program is created, "ended"
// when it was reaped. The caller sends nothing: closing its end is the request to stop.
#pragma once

#include <sys/resource.h>

#include <cstdint>

namespace emnet {

enum class SupervisorReportKind : std::int32_t { started = 1, not_executed = 2, ended = 3 };

struct SupervisorReport {
  SupervisorReportKind kind;
  std::int32_t value;
  std::int64_t monotonic_nanoseconds;
};

struct SupervisorPlan {
  const char* path = nullptr;  // the program, found already (execve, no PATH search)
  char* const* arguments = nullptr;
  char* const* environment = nullptr;
  const char* working_directory = nullptr;  // nullptr: the caller's
  // The program's standard streams: a pipe end, or -1 for /dev/null.
  int input = -1, output = -1, error = -1;
  int control = -1;  // the supervisor's end of the control socket
  rlim_t file_size_limit = RLIM_INFINITY;
};

// CLOCK_MONOTONIC in nanoseconds (async-signal-safe).
std::int64_t monotonic_nanoseconds();

// The supervisor's whole life, in the forked child: starts the program, waits for it or for
// the caller's request to stop, kills everything left, reports, exits. Never returns.
[[noreturn]] void run_supervisor(const SupervisorPlan& plan);

}  // namespace emnet
