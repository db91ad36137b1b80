// Runs a SPICE deck in ngspice and returns the vectors of its last analysis.
//
// Two backends:
//
//  * libngspice, in process: libngspice.so.0 is loaded at run time with dlopen (never linked
//    at build time, so emnet starts and falls back when it is missing) and driven through its
//    shared-library API (ngSpice_Init with output callbacks, ngSpice_Circ with the deck's
//    lines, ngSpice_Command("run"), ngSpice_AllVecs / ngGet_Vec_Info for the results).
//    By default this runs in a worker process, the program emnet-ngspice-worker (built next
//    to emnet; found as NgspiceOptions::worker_program says): libngspice keeps one circuit
//    state per process in global variables, asks to be "detached" (ControlledExit) after some
//    parse errors, and a crash or an endless run inside it must not take emnet down or hang
//    it. The worker is started with exec through the process helper
//    (emnet/core/process.hpp), never as a fork of the calling process, so the runner is safe
//    in a process with other threads. It reads the deck on its standard input and streams
//    ngspice's messages and then the vectors (raw IEEE doubles, so bit-exact) back; the
//    runner keeps the time limit, kills the worker and everything it started when it is
//    exceeded, and reports a signal death as a crash. `library_in_this_process` skips the
//    worker (for timing the library itself); the time limit is then kept with `bg_run` /
//    `bg_halt`, and a crash of ngspice is a crash of the caller.
//  * the ngspice program, as a subprocess, when libngspice cannot be loaded (or on request):
//    `ngspice -b -r RAWFILE DECK` in a private temporary directory, through the process
//    helper, which kills the program and everything it started (also a grandchild that left
//    its process group and session) at the time limit; the rawfile (binary, or ASCII when
//    SPICE_ASCIIRAWFILE is set) is parsed here.
//
// When the worker program cannot be found the library backend is not available: with
// NgspiceBackend::library the run fails saying where the worker was looked for; with
// `automatic` the program runs instead, and backend_description says why.
//
// Bounds, whatever ngspice does: the time limit holds however much it writes (its output is
// read in chunks of at most 64 KiB between looks at the clock); of its messages at most
// `max_message_bytes` are kept: the first lines and the last ones, with one line saying how
// much was left out between them (and the first error line among that); every line is cut at
// 4096 bytes and its control characters are escaped ("\x1b") before it is stored, so no
// message can drive the terminal it is printed on. Results are accepted up to
// `max_result_bytes`: the rawfile's size (the program cannot write a larger file: it gets
// SIGXFSZ) and the vectors the worker sends back. A rawfile's header is checked against the
// file's actual size before anything is allocated for it; a malformed or truncated rawfile
// is a failed status, like any other failure of ngspice.
//
// Both backends give the same vectors under the same names: ngspice's own vector names
// ("out", "v1#branch", "time"); the rawfile's "v(out)" and "i(v1)" are renamed to those.
// NgspiceResult::find also accepts the v(...)/i(...) spellings, in any letter case.
//
// The deck is plain SPICE: title line first, `.end` last (added when missing). A deck with a
// `.control` block is refused: the runner runs the deck's own analysis lines, and no deck
// text can issue control commands (such as `shell`) through it. Note that ngspice itself
// reads `.spiceinit` from the working directory and the home directory at start-up.
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "emnet/core/errors.hpp"

namespace emnet {

/// Which of the two backends runs the deck (see the header comment).
enum class NgspiceBackend {
  automatic,  ///< libngspice; the ngspice program when the library cannot be loaded
  library,    ///< libngspice only
  program,    ///< the ngspice program only
};

/// How run_ngspice runs a deck.
struct NgspiceOptions {
  /// Wall-clock limit on ngspice's part; the run is stopped and reported as timed out after it.
  double timeout_seconds = 60.0;
  NgspiceBackend backend = NgspiceBackend::automatic;  ///< which backend runs the deck
  /// Shared library names tried in turn with dlopen (a path, or a name the loader searches).
  std::vector<std::string> library_names = {"libngspice.so.0", "libngspice.so"};
  /// Program run by the subprocess backend (searched in PATH when it has no '/').
  std::string program = "ngspice";
  /// Run libngspice in this process instead of the worker program (see the header comment).
  bool library_in_this_process = false;
  /// The worker program (emnet-ngspice-worker) of the library backend. Empty: the environment
  /// variable EMNET_NGSPICE_WORKER, else the first that exists of the running program's
  /// directory, the path the build writes it to, and the installed path (libexec). A path
  /// given here or in the variable is used as it is (one that names no executable file makes
  /// the library backend unavailable, with that reason).
  std::string worker_program;
  /// ngspice's messages kept, in bytes (each message's text and bookkeeping): the first three
  /// quarters for the first lines, the last quarter for the last ones (see the header comment).
  std::size_t max_message_bytes = std::size_t{1} << 20;
  /// Largest result accepted, in bytes: the program's rawfile (and any file it writes), the
  /// vectors the worker sends back; a larger one makes the run fail.
  std::uint64_t max_result_bytes = std::uint64_t{1} << 29;
};

/// The stream a message of ngspice came on: its standard output or its standard error.
enum class NgspiceStream { out, err };

/// One line ngspice wrote.
struct NgspiceMessage {
  NgspiceStream stream = NgspiceStream::out;
  std::string text;  ///< one line, without its newline
};

/// One vector of an analysis plot: its name and values.
struct NgspiceVector {
  std::string name;         ///< ngspice's vector name, lower case: "out", "v1#branch", "time"
  bool is_scale = false;    ///< the plot's scale (time, frequency; for .op the first vector)
  bool is_complex = false;  ///< then `complex_values` holds the data, else `real_values`
  std::vector<double> real_values;
  std::vector<std::complex<double>> complex_values;
  /// The number of values.
  std::size_t size() const { return is_complex ? complex_values.size() : real_values.size(); }
};

/// What run_ngspice gives back: its status, the last plot's vectors and ngspice's messages.
struct NgspiceResult {
  Status status;  ///< a failure of the run (see run_ngspice)
  NgspiceBackend backend_used = NgspiceBackend::automatic;  ///< library or program once run
  std::string backend_description;  ///< "libngspice in-process (... worker process ...)", ...
  /// Every analysis plot of the run in order ("Operating Point", "AC Analysis", "Transient
  /// Analysis"); the vectors are those of the last.
  std::vector<std::string> plot_names;
  std::vector<NgspiceVector> vectors;    ///< the scale first, then in ngspice's output order
  std::vector<NgspiceMessage> messages;  ///< as kept within NgspiceOptions::max_message_bytes
  double ngspice_seconds = 0.0;          ///< loading and running the deck, reading the vectors back
  double seconds = 0.0;                  ///< everything, including starting the worker or program

  /// A vector by name: ngspice's ("out", "v1#branch") or the rawfile's ("v(out)", "i(v1)"),
  /// any letter case; nullptr when absent.
  const NgspiceVector* find(std::string_view name) const;
  /// The plot's scale vector; nullptr when there is none.
  const NgspiceVector* scale() const;
  /// The messages as text, one per line, stderr lines prefixed "stderr: ".
  std::string messages_text() const;
};

/// Runs `deck_text` with the backend `options` choose. A failure (the deck refused, no backend
/// available, ngspice's error, the time limit, a crash, a result too large or malformed) is the
/// result's status.
NgspiceResult run_ngspice(const std::string& deck_text, const NgspiceOptions& options = {});

// ---- rawfile ----------------------------------------------------------------------------
/// One plot of an ngspice rawfile (binary or ASCII; several plots may follow each other).
struct NgspiceRawPlot {
  std::string title, plot_name, flags;
  std::vector<NgspiceVector> vectors;  ///< rawfile names ("v(out)"); the first is the scale
};
/// Parses every plot of `bytes`; false with `why` on a malformed or truncated file. Each plot's
/// claimed size (points times variables) is checked against the bytes that follow its header
/// before anything is allocated for it, so memory stays of the order of `bytes.size()`.
bool parse_ngspice_rawfile(const std::string& bytes, std::vector<NgspiceRawPlot>& plots,
                           std::string& why);

}  // namespace emnet
