// The ngspice runner (include/emnet/spice/ngspice_runner.hpp) on small hand-written decks, over
// every backend: libngspice in the worker program, libngspice in this process, the ngspice program.
//
// References are closed forms of an RC low-pass (R = 1 kΩ, C = 1 µF, RC = 1 ms) and a resistive
// divider; each tolerance says where it comes from. Failure cases (syntax error, a deck that
// makes libngspice ask to be detached, a run past the time limit, a crash, missing library or
// program) must give a failure status with a clear message, never a hang or a crash of the
// test process. Time bounds in these tests only guard against hangs; they measure nothing.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.hpp"
#include "emnet/core/process.hpp"
#include "emnet/spice/ngspice_runner.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using emnet::testing::kPi;
constexpr double kResistance = 1e3;
constexpr double kCapacitance = 1e-6;
constexpr double kTimeConstant = kResistance * kCapacitance;

// V1 = 1 V over R1 = 1 kΩ and R2 = 3 kΩ: out = 3/4 V, the source's branch current −1/4 mA.
const char* const kDividerDeck = R"(divider for the runner tests
V1 in 0 DC 1
R1 in out 1k
R2 out 0 3k
.op
.end
)";

// RC low-pass driven by a unit AC source: out = 1 / (1 + jωRC).
const char* const kLowPassAcDeck = R"(rc low-pass ac
V1 in 0 DC 0 AC 1
R1 in out 1k
C1 out 0 1u
.ac dec 5 1 100k
.end
)";

// RC low-pass, unit step at t = 0 (UIC: the capacitor starts at its IC = 0 while the source is
// already 1 V): out = 1 − exp(−t/RC). reltol = 1e-6 sets the integration error (see the test).
const char* const kLowPassStepDeck = R"(rc low-pass step
V1 in 0 DC 1
R1 in out 1k
C1 out 0 1u IC=0
.options reltol=1e-6
.tran 10u 5m UIC
.end
)";

struct BackendCase {
  std::string name;
  NgspiceOptions options;
};

void PrintTo(const BackendCase& backend, std::ostream* stream) {
  *stream << backend.name;
}

std::vector<BackendCase> backend_cases() {
  NgspiceOptions worker;
  worker.backend = NgspiceBackend::library;
  NgspiceOptions in_this_process = worker;
  in_this_process.library_in_this_process = true;
  NgspiceOptions program;
  program.backend = NgspiceBackend::program;
  return {{"library_worker", worker},
          {"library_in_this_process", in_this_process},
          {"program", program}};
}

const NgspiceVector& vector_named(const NgspiceResult& result, const std::string& name) {
  const NgspiceVector* vector = result.find(name);
  if (!vector) {
    ADD_FAILURE() << "no vector " << name << "\n" << result.messages_text();
    static const NgspiceVector empty;
    return empty;
  }
  return *vector;
}

class NgspiceRunnerBackends : public ::testing::TestWithParam<BackendCase> {};

TEST_P(NgspiceRunnerBackends, OperatingPointOfDividerIsExact) {
  const NgspiceResult result = run_ngspice(kDividerDeck, GetParam().options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.backend_used, GetParam().options.backend);
  ASSERT_EQ(result.plot_names, std::vector<std::string>{"Operating Point"});
  const NgspiceVector& out = vector_named(result, "v(out)");
  const NgspiceVector& current = vector_named(result, "i(v1)");
  ASSERT_EQ(out.real_values.size(), 1u);
  ASSERT_EQ(current.real_values.size(), 1u);
  // A linear resistive network: ngspice's operating point is one LU solve of a 3×3 system
  // (no gmin on resistors, Newton converges on its second pass), so the result is exact up
  // to a few roundings: 1e-12 relative leaves a margin of ~1e3 over rounding.
  EXPECT_NEAR(out.real_values[0], 0.75, 0.75 * 1e-12);
  EXPECT_NEAR(current.real_values[0], -2.5e-4, 2.5e-4 * 1e-12);
  EXPECT_EQ(result.find("out"), &out);  // ngspice's own name
  EXPECT_EQ(result.find("V1#BRANCH"), &current);
}

TEST_P(NgspiceRunnerBackends, AcOfRcLowPassMatchesClosedForm) {
  const NgspiceResult result = run_ngspice(kLowPassAcDeck, GetParam().options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.plot_names, std::vector<std::string>{"AC Analysis"});
  const NgspiceVector* frequency = result.scale();
  ASSERT_NE(frequency, nullptr);
  EXPECT_EQ(frequency->name, "frequency");
  const NgspiceVector& out = vector_named(result, "out");
  ASSERT_TRUE(out.is_complex);
  ASSERT_EQ(frequency->size(), 26u);  // 5 a decade over 5 decades, both ends
  ASSERT_EQ(out.size(), frequency->size());
  // Each AC point is one complex LU solve of the linear network at ω = 2πf (f as ngspice
  // reports it), so it is exact up to rounding: 1e-12 relative on the complex value, on the
  // magnitude, and 1e-12 rad on the phase, with a margin of ~1e3 over rounding.
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double f = frequency->complex_values[k].real();
    const double omega_rc = 2 * kPi * f * kTimeConstant;
    const std::complex<double> expected = 1.0 / std::complex<double>(1.0, omega_rc);
    const std::complex<double> actual = out.complex_values[k];
    EXPECT_LE(std::abs(actual - expected), 1e-12 * std::abs(expected)) << "f = " << f;
    EXPECT_NEAR(std::abs(actual), 1 / std::sqrt(1 + omega_rc * omega_rc),
                1e-12 * std::abs(expected));
    EXPECT_NEAR(std::arg(actual), -std::atan(omega_rc), 1e-12) << "f = " << f;
  }
  EXPECT_NEAR(frequency->complex_values.front().real(), 1.0, 1e-12);
  EXPECT_NEAR(frequency->complex_values.back().real(), 1e5, 1e-7);
}

TEST_P(NgspiceRunnerBackends, TransientStepOfRcLowPassWithinIntegrationError) {
  const NgspiceResult result = run_ngspice(kLowPassStepDeck, GetParam().options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  const NgspiceVector* time = result.scale();
  ASSERT_NE(time, nullptr);
  EXPECT_EQ(time->name, "time");
  const NgspiceVector& out = vector_named(result, "v(out)");
  ASSERT_EQ(out.size(), time->size());
  ASSERT_GT(out.size(), 100u);
  // With UIC ngspice's first output point is its first time step (0.1 µs here), not t = 0.
  EXPECT_GE(time->real_values.front(), 0.0);
  EXPECT_LT(time->real_values.front(), 1e-5);
  EXPECT_NEAR(time->real_values.back(), 5e-3, 1e-15);
  // ngspice's trapezoidal rule keeps each step's estimated truncation error below
  // trtol·reltol·|v| = 7 × 1e-6 × 1 V; on this one decaying mode the global error stays of
  // that order (measured 3.0e-6 V). Held to 2e-5 V, about 3·trtol·reltol. The start (UIC,
  // capacitor at 0 with the source at 1 V) is an exact step, so no rise time enters.
  double largest_error = 0;
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double t = time->real_values[k];
    largest_error =
        std::max(largest_error, std::abs(out.real_values[k] - (1 - std::exp(-t / kTimeConstant))));
  }
  EXPECT_LT(largest_error, 2e-5);
  RecordProperty("largest_error_volts", std::to_string(largest_error));
}

TEST_P(NgspiceRunnerBackends, SyntaxErrorIsAFailureWithNgspicesMessage) {
  const NgspiceResult result = run_ngspice(
      "bad deck\nV1 in 0 DC 1\nR1 in out 1k zzz\nC1 out 0 1u\n.op\n.end\n", GetParam().options);
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("unknown parameter (zzz)"), std::string::npos)
      << result.status.message;
  EXPECT_TRUE(result.vectors.empty());
}

TEST_P(NgspiceRunnerBackends, DeckThatMakesLibngspiceAskToBeDetachedIsAFailure) {
  // A .subckt without .ends: libngspice calls ControlledExit ("cannot recover and awaits to
  // be detached"); the program stops with an error.
  const NgspiceResult result =
      run_ngspice("unbalanced subcircuit\nV1 in 0 1\n.subckt foo a b\nR1 a b 1\n.op\n.end\n",
                  GetParam().options);
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("Mismatch of .subckt ... .ends"), std::string::npos)
      << result.status.message;
  // The next deck runs normally (in this process: on a freshly loaded library).
  const NgspiceResult next = run_ngspice(kDividerDeck, GetParam().options);
  ASSERT_TRUE(next.status.ok()) << next.status.message;
  EXPECT_NEAR(vector_named(next, "out").real_values.at(0), 0.75, 1e-12);
}

TEST_P(NgspiceRunnerBackends, RunPastTheTimeLimitIsStoppedAndReported) {
  NgspiceOptions options = GetParam().options;
  options.timeout_seconds = 1;
  const auto start = std::chrono::steady_clock::now();
  // 1e11 steps of at most 1 ns: hours of work.
  const NgspiceResult result = run_ngspice(
      "endless\nV1 in 0 SIN(0 1 1meg)\nR1 in out 1k\nC1 out 0 1u\n.tran 1n 100 0 1n\n.end\n",
      options);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("timed out"), std::string::npos) << result.status.message;
  EXPECT_LT(elapsed, 30.0);  // a hang guard only
  // The runner (and, in this process, the library) is usable afterwards.
  const NgspiceResult next = run_ngspice(kDividerDeck, GetParam().options);
  ASSERT_TRUE(next.status.ok()) << next.status.message;
}

INSTANTIATE_TEST_SUITE_P(Ngspice, NgspiceRunnerBackends, ::testing::ValuesIn(backend_cases()),
                         [](const ::testing::TestParamInfo<BackendCase>& info) {
                           return info.param.name;
                         });

// Every backend runs the same engine on the same deck: the same vectors, in the same order,
// to the last bit (1e-12 relative is asked; the rawfile and the worker's pipe both carry raw
// doubles).
TEST(NgspiceRunner, BackendsGiveTheSameVectors) {
  for (const char* deck : {kDividerDeck, kLowPassAcDeck, kLowPassStepDeck}) {
    std::vector<NgspiceResult> results;
    for (const BackendCase& backend : backend_cases()) {
      results.push_back(run_ngspice(deck, backend.options));
      ASSERT_TRUE(results.back().status.ok())
          << backend.name << ": " << results.back().status.message;
    }
    const NgspiceResult& reference = results.front();
    for (std::size_t r = 1; r < results.size(); ++r) {
      const NgspiceResult& other = results[r];
      EXPECT_EQ(other.plot_names, reference.plot_names);
      ASSERT_EQ(other.vectors.size(), reference.vectors.size());
      for (std::size_t v = 0; v < reference.vectors.size(); ++v) {
        const NgspiceVector& a = reference.vectors[v];
        const NgspiceVector& b = other.vectors[v];
        EXPECT_EQ(b.name, a.name);
        EXPECT_EQ(b.is_scale, a.is_scale);
        EXPECT_EQ(b.is_complex, a.is_complex);
        ASSERT_EQ(b.size(), a.size()) << a.name;
        for (std::size_t k = 0; k < a.size(); ++k) {
          const std::complex<double> x = a.is_complex ? a.complex_values[k] : a.real_values[k];
          const std::complex<double> y = b.is_complex ? b.complex_values[k] : b.real_values[k];
          EXPECT_LE(std::abs(x - y), 1e-12 * std::abs(x)) << a.name << "[" << k << "]";
        }
      }
    }
  }
}

TEST(NgspiceRunner, MissingLibraryFallsBackToTheProgramAndSaysSo) {
  NgspiceOptions options;
  options.library_names = {"/nonexistent/libngspice.so.0"};
  const NgspiceResult result = run_ngspice(kDividerDeck, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.backend_used, NgspiceBackend::program);
  EXPECT_NE(result.backend_description.find("libngspice not available"), std::string::npos)
      << result.backend_description;
  EXPECT_NE(result.backend_description.find("/nonexistent/libngspice.so.0"), std::string::npos)
      << result.backend_description;
  EXPECT_NEAR(vector_named(result, "out").real_values.at(0), 0.75, 1e-12);

  options.library_in_this_process = true;
  const NgspiceResult here = run_ngspice(kDividerDeck, options);
  ASSERT_TRUE(here.status.ok()) << here.status.message;
  EXPECT_EQ(here.backend_used, NgspiceBackend::program);
}

TEST(NgspiceRunner, LibraryWithoutTheNgspiceApiFallsBack) {
  NgspiceOptions options;
  options.library_names = {"libm.so.6"};  // loads, but is not ngspice
  const NgspiceResult result = run_ngspice(kDividerDeck, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.backend_used, NgspiceBackend::program);
  EXPECT_NE(result.backend_description.find("has no ngSpice_Init"), std::string::npos)
      << result.backend_description;
}

TEST(NgspiceRunner, MissingLibraryOrProgramSaysWhatToInstall) {
  NgspiceOptions options;
  options.library_names = {"/nonexistent/libngspice.so.0"};
  options.backend = NgspiceBackend::library;
  NgspiceResult result = run_ngspice(kDividerDeck, options);
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("libngspice0"), std::string::npos) << result.status.message;

  options.backend = NgspiceBackend::program;
  options.program = "/nonexistent/ngspice";
  result = run_ngspice(kDividerDeck, options);
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("install the Debian package ngspice"), std::string::npos)
      << result.status.message;

  options.backend = NgspiceBackend::automatic;
  result = run_ngspice(kDividerDeck, options);
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("libngspice0 and ngspice"), std::string::npos)
      << result.status.message;
}

TEST(NgspiceRunner, ControlBlockIsRefused) {
  const NgspiceResult result = run_ngspice(
      "title\nV1 in 0 1\n.op\n.control\nshell touch /tmp/emnet-should-not-exist\n.endc\n.end\n");
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find(".control"), std::string::npos) << result.status.message;
  EXPECT_TRUE(result.messages.empty());  // ngspice never saw it
}

TEST(NgspiceRunner, DeckWithoutAnalysisIsAFailure) {
  for (const BackendCase& backend : backend_cases()) {
    const NgspiceResult result =
        run_ngspice("no analysis\nV1 in 0 1\nR1 in 0 1k\n.end\n", backend.options);
    EXPECT_FALSE(result.status.ok()) << backend.name;
    EXPECT_NE(result.status.message.find("analysis"), std::string::npos)
        << backend.name << ": " << result.status.message;
  }
}

// A stand-in libngspice whose ngSpice_Circ (or, with FAKE_NGSPICE_CRASH_IN_INIT set, whose
// ngSpice_Init) dereferences a null pointer: a crash inside the library, caught by the worker.
std::string build_crashing_library() {
  const std::string directory =
      ::testing::TempDir() + "emnet_fake_ngspice_" + std::to_string(::getpid());
  const std::string source = directory + ".c", library = directory + ".so";
  std::ofstream(source) << R"(#include <stdlib.h>
static volatile int* nowhere = 0;
int ngSpice_Init(void* a, void* b, void* c, void* d, void* e, void* f, void* g) {
  if (getenv("FAKE_NGSPICE_CRASH_IN_INIT")) return *nowhere;
  return 0;
}
int ngSpice_Command(char* command) { return 0; }
int ngSpice_Circ(char** lines) { return *nowhere; }
char** ngSpice_AllVecs(char* plot) { return 0; }
void* ngGet_Vec_Info(char* name) { return 0; }
)";
  const std::string command = "cc -shared -fPIC -o '" + library + "' '" + source + "' 2>/dev/null";
  return std::system(command.c_str()) == 0 ? library : std::string();
}

TEST(NgspiceRunner, CrashInsideTheLibraryIsReportedNotSuffered) {
  const std::string library = build_crashing_library();
  if (library.empty()) GTEST_SKIP() << "no C compiler (cc) to build the crashing stand-in";
  NgspiceOptions options;
  options.library_names = {library};
  options.backend = NgspiceBackend::library;
  const NgspiceResult result = run_ngspice(kDividerDeck, options);
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("ngspice crashed (signal 11"), std::string::npos)
      << result.status.message;

  // A library that crashes while loading counts as not available: the program runs instead.
  ::setenv("FAKE_NGSPICE_CRASH_IN_INIT", "1", 1);
  options.backend = NgspiceBackend::automatic;
  const NgspiceResult fallback = run_ngspice(kDividerDeck, options);
  ::unsetenv("FAKE_NGSPICE_CRASH_IN_INIT");
  ASSERT_TRUE(fallback.status.ok()) << fallback.status.message;
  EXPECT_EQ(fallback.backend_used, NgspiceBackend::program);
  EXPECT_NE(fallback.backend_description.find("while loading libngspice"), std::string::npos)
      << fallback.backend_description;
}

TEST(NgspiceRunner, AsciiRawfileGivesTheSameValues) {
  NgspiceOptions options;
  options.backend = NgspiceBackend::program;
  const NgspiceResult binary = run_ngspice(kLowPassAcDeck, options);
  ::setenv("SPICE_ASCIIRAWFILE", "1", 1);
  const NgspiceResult ascii = run_ngspice(kLowPassAcDeck, options);
  ::unsetenv("SPICE_ASCIIRAWFILE");
  ASSERT_TRUE(binary.status.ok()) << binary.status.message;
  ASSERT_TRUE(ascii.status.ok()) << ascii.status.message;
  const NgspiceVector& a = vector_named(binary, "out");
  const NgspiceVector& b = vector_named(ascii, "out");
  ASSERT_EQ(a.size(), b.size());
  // The ASCII rawfile prints 16 significant digits (%.15e): 1e-15 relative rounding.
  for (std::size_t k = 0; k < a.size(); ++k)
    EXPECT_LE(std::abs(a.complex_values[k] - b.complex_values[k]),
              2e-15 * std::abs(a.complex_values[k]));
}

TEST(NgspiceRunner, RawfileParserRefusesATruncatedFile) {
  const std::string header =
      "Title: t\nDate: d\nPlotname: Operating Point\nFlags: real\nNo. Variables: 2\n"
      "No. Points: 1\nVariables:\n\t0\tv(a)\tvoltage\n\t1\ti(v1)\tcurrent\nBinary:\n";
  const double values[2] = {0.75, -2.5e-4};
  std::string bytes = header + std::string(reinterpret_cast<const char*>(values), sizeof values);
  std::vector<NgspiceRawPlot> plots;
  std::string why;
  ASSERT_TRUE(parse_ngspice_rawfile(bytes, plots, why)) << why;
  ASSERT_EQ(plots.size(), 1u);
  EXPECT_EQ(plots[0].vectors[1].name, "i(v1)");
  EXPECT_EQ(plots[0].vectors[1].real_values.at(0), -2.5e-4);
  bytes.pop_back();
  plots.clear();
  EXPECT_FALSE(parse_ngspice_rawfile(bytes, plots, why));
  EXPECT_NE(why.find("truncated"), std::string::npos) << why;
}

// A header with two variable lists would give a plot two scales, and a count after the list
// could make the list and the count disagree: both are malformed, refused with the reason
// (the first was a finding of the rawfile fuzz target).
TEST(NgspiceRunner, RawfileParserRefusesASecondVariableListOrCount) {
  const double values[2] = {0.75, -2.5e-4};
  const std::string data(reinterpret_cast<const char*>(values), sizeof values);
  const std::string start = "Title: t\nPlotname: Operating Point\nFlags: real\n";
  const std::string two_lists = start +
                                "No. Variables: 1\nVariables:\n\t0\tv(a)\tvoltage\n"
                                "Variables:\n\t0\tv(b)\tvoltage\nNo. Points: 1\nBinary:\n" +
                                data;
  const std::string count_after_list = start +
                                       "No. Variables: 1\nVariables:\n\t0\tv(a)\tvoltage\n"
                                       "No. Variables: 2\nNo. Points: 1\nBinary:\n" +
                                       data;
  for (const auto& [bytes, reason] :
       {std::pair{two_lists, "a second 'Variables:' list"},
        std::pair{count_after_list, "'No. Variables:' after the variable list"}}) {
    std::vector<NgspiceRawPlot> plots;
    std::string why;
    EXPECT_FALSE(parse_ngspice_rawfile(bytes, plots, why)) << reason;
    EXPECT_NE(why.find(reason), std::string::npos) << why;
  }
}

// ---- bounds: output, time, processes, rawfile sizes, control characters ---------------------
//
// These drive stand-ins for ngspice: shell scripts written into the test's temporary directory
// (the program backend runs them as `PROGRAM -b -r RAWFILE DECK`, so a script finds the
// rawfile's path in $3) and a C stand-in for libngspice.

// A stand-in "ngspice" program with the given shell-script body.
std::string write_fake_program(const std::string& name, const std::string& body) {
  const std::string path =
      ::testing::TempDir() + "emnet_fake_" + name + "_" + std::to_string(::getpid());
  std::ofstream(path) << "#!/bin/sh\n" << body;
  ::chmod(path.c_str(), 0755);
  return path;
}

// Shell lines that write an ASCII rawfile of the divider's operating point to $3.
const char* const kWriteDividerRawfile = R"(cat > "$3" <<'RAW'
Title: fake
Date: today
Plotname: Operating Point
Flags: real
No. Variables: 2
No. Points: 1
Variables:
	0	v(out)	voltage
	1	i(v1)	current
Values:
 0	7.5e-01
	-2.5e-04
RAW
)";

NgspiceOptions program_options(const std::string& program, double timeout_seconds) {
  NgspiceOptions options;
  options.backend = NgspiceBackend::program;
  options.program = program;
  options.timeout_seconds = timeout_seconds;
  return options;
}

// The memory the messages take as the log counts it: text plus one NgspiceMessage each.
std::size_t message_bytes(const NgspiceResult& result) {
  std::size_t bytes = 0;
  for (const NgspiceMessage& message : result.messages)
    bytes += message.text.size() + sizeof(NgspiceMessage);
  return bytes;
}

// What the log may hold beyond max_message_bytes: the line that marks the left-out part and
// the first error line among it, at most 4096 bytes of text that can grow 4× when every byte
// is escaped, plus their bookkeeping: 20 KiB covers both.
constexpr std::size_t kMessageLogSlackBytes = 20 * 1024;

bool has_message_containing(const NgspiceResult& result, const std::string& text) {
  for (const NgspiceMessage& message : result.messages)
    if (message.text.find(text) != std::string::npos) return true;
  return false;
}

// A program that prints 9 MB of lines (and a 2 MB line without a newline on standard error)
// and then succeeds: its results are read, and of its output the first and last lines are
// kept within max_message_bytes (1 MiB by default), with a line saying what was left out.
TEST(NgspiceRunnerBounds, FloodOfProgramOutputIsCappedAndTheResultsStillRead) {
  const std::string program = write_fake_program("flood_then_succeed",
                                                 "seq -f 'flood line %.0f' 1 500000\n"
                                                 "head -c 2000000 /dev/zero | tr '\\0' x >&2\n" +
                                                     std::string(kWriteDividerRawfile));
  const NgspiceOptions options = program_options(program, 20);
  const NgspiceResult result = run_ngspice(kDividerDeck, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(vector_named(result, "out").real_values.at(0), 0.75);
  EXPECT_LE(message_bytes(result), options.max_message_bytes + kMessageLogSlackBytes);
  ASSERT_FALSE(result.messages.empty());
  EXPECT_EQ(result.messages.front().text, "flood line 1");
  EXPECT_TRUE(has_message_containing(result, "flood line 500000"));
  EXPECT_TRUE(has_message_containing(result, "of ngspice's output left out here"));
  // The 2 MB line: its first 4096 bytes, then how much of it was cut.
  EXPECT_TRUE(has_message_containing(result, std::string(4096, 'x') + " [... 1995904 more bytes"));
}

// A program that floods its output without end: the time limit holds (the read loop looks at
// the clock between bounded reads), and what is kept stays within max_message_bytes.
TEST(NgspiceRunnerBounds, EndlessFloodOfProgramOutputIsStoppedAtTheTimeLimit) {
  const NgspiceOptions options =
      program_options(write_fake_program("endless_flood", "exec yes"), 1);
  const NgspiceResult result = run_ngspice(kDividerDeck, options);
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("timed out: still running after 1 s"), std::string::npos)
      << result.status.message;
  EXPECT_LE(message_bytes(result), options.max_message_bytes + kMessageLogSlackBytes);
  EXPECT_TRUE(has_message_containing(result, "of ngspice's output left out here"));
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

// Runs a program that starts a grandchild which calls setsid (leaving the program's process
// group and session), writes its pid to a file and sleeps; then the program runs `then`. The
// run's result and the grandchild's pid (-1 when it did not start).
struct GrandchildRun {
  NgspiceResult result;
  pid_t grandchild = -1;
};
GrandchildRun run_program_with_grandchild(const std::string& name, const std::string& then,
                                          double timeout_seconds) {
  const std::string pid_file =
      ::testing::TempDir() + "emnet_grandchild_" + name + "_" + std::to_string(::getpid()) + ".pid";
  std::remove(pid_file.c_str());
  const std::string program = write_fake_program(
      name, "setsid sh -c 'echo $$ > \"" + pid_file + ".new\"; mv \"" + pid_file + ".new\" \"" +
                pid_file + "\"; exec sleep 1234' </dev/null >/dev/null 2>&1 &\n" +
                "while [ ! -s '" + pid_file + "' ]; do sleep 0.01; done\n" + then);
  GrandchildRun run;
  run.result = run_ngspice(kDividerDeck, program_options(program, timeout_seconds));
  std::ifstream(pid_file) >> run.grandchild;
  return run;
}

TEST(NgspiceRunnerBounds, TimeoutKillsAGrandchildThatLeftTheProcessGroup) {
  const GrandchildRun run =
      run_program_with_grandchild("grandchild_timeout", "exec sleep 100\n", 2);
  EXPECT_FALSE(run.result.status.ok());
  EXPECT_NE(run.result.status.message.find("timed out"), std::string::npos)
      << run.result.status.message;
  ASSERT_GT(run.grandchild, 0) << "the grandchild did not start";
  const bool survived = process_runs(run.grandchild, "sleep 1234");
  EXPECT_FALSE(survived) << "grandchild " << run.grandchild << " outlived the timeout";
  if (survived) ::kill(run.grandchild, SIGKILL);
}

// Also when the program ends by itself: nothing it started outlives the run.
TEST(NgspiceRunnerBounds, NothingTheProgramStartedOutlivesIt) {
  const GrandchildRun run = run_program_with_grandchild(
      "grandchild_left_behind", std::string(kWriteDividerRawfile) + "exit 0\n", 10);
  ASSERT_TRUE(run.result.status.ok()) << run.result.status.message;
  ASSERT_GT(run.grandchild, 0) << "the grandchild did not start";
  const bool survived = process_runs(run.grandchild, "sleep 1234");
  EXPECT_FALSE(survived) << "grandchild " << run.grandchild << " outlived the run";
  if (survived) ::kill(run.grandchild, SIGKILL);
}

// A rawfile header's claim is checked against the bytes that follow it before anything is
// allocated: claims of 1e11 points (800 GB per vector), of a count that overflows 64 bits when
// multiplied out, and of points without variables are refused as truncated or malformed,
// never by an exception.
TEST(NgspiceRunnerBounds, RawfileHeaderClaimingMoreThanTheFileHoldsIsRefused) {
  const auto header = [](const std::string& points, const std::string& variables,
                         const std::string& section) {
    std::string text =
        "Title: t\nDate: d\nPlotname: Operating Point\nFlags: real\nNo. Variables: " + variables +
        "\nNo. Points: " + points + "\nVariables:\n";
    if (variables != "0") text += "\t0\tv(a)\tvoltage\n\t1\ti(v1)\tcurrent\n";
    return text + section;
  };
  const double values[2] = {0.75, -2.5e-4};
  const std::string data(reinterpret_cast<const char*>(values), sizeof values);
  for (const std::string& points : {"100000000000", "2305843009213693952"}) {
    for (const std::string& section :
         {"Binary:\n" + data, std::string("Values:\n 0\t0.75\n\t-2.5e-4\n")}) {
      std::vector<NgspiceRawPlot> plots;
      std::string why;
      bool parsed = true;
      EXPECT_NO_THROW(parsed = parse_ngspice_rawfile(header(points, "2", section), plots, why))
          << points;
      EXPECT_FALSE(parsed) << points;
      EXPECT_NE(why.find("truncated: its header claims " + points + " points"), std::string::npos)
          << why;
    }
  }
  std::vector<NgspiceRawPlot> plots;
  std::string why;
  EXPECT_FALSE(parse_ngspice_rawfile(header("1000000000000000000", "0", "Binary:\n"), plots, why));
  EXPECT_NE(why.find("has no variables"), std::string::npos) << why;
}

// A stand-in program writing a binary rawfile whose header claims $CLAIMED_POINTS points of
// three variables, followed by 16 bytes.
std::string write_lying_rawfile_program() {
  return write_fake_program(
      "lying_rawfile",
      "printf 'Title: t\\nDate: d\\nPlotname: Operating Point\\nFlags: real\\nNo. Variables: "
      "3\\nNo. Points: %s\\nVariables:\\n\\t0\\tv(a)\\tvoltage\\n\\t1\\tv(b)\\tvoltage\\n\\t2\\t"
      "i(v1)\\tcurrent\\nBinary:\\n0123456789abcdef' \"$CLAIMED_POINTS\" > \"$3\"\n");
}

// At the command line a lying rawfile is ngspice's failure (exit 3), never an internal error
// (exit 1, "std::bad_alloc"). 1e8 points (2.4 GB when allocated from the claim) runs under a
// 1 GB address-space limit, so that allocating from the claim fails the test too.
TEST(NgspiceRunnerBounds, LyingRawfileIsNgspicesFailureAtTheCommandLine) {
  const std::string program = write_lying_rawfile_program();
  for (const char* points : {"100000000", "100000000000"}) {
    const auto run = emnet::testing::run_emnet(
        "crosscheck " + std::string(EMNET_SOURCE_DIR) +
            "/netlists/fishfin.toml --analysis op --backend program --timeout 10 "
            "--ngspice-program " +
            program,
        "ulimit -v 1000000; CLAIMED_POINTS=" + std::string(points) + " ");
    EXPECT_EQ(run.status, 3) << points << "\n" << run.err;
    EXPECT_NE(run.err.find("is truncated: its header claims " + std::string(points) + " points"),
              std::string::npos)
        << run.err;
  }
}

// Control characters in ngspice's messages are escaped before they are stored: the warning
// lines ngspice prints for this deck quote the line with its escape sequence and bell.
TEST_P(NgspiceRunnerBackends, ControlCharactersInNgspicesMessagesAreEscaped) {
  const NgspiceResult result =
      run_ngspice("escape\nV1 in 0 DC 1\nR1 in out 1k zzz\x1b[2J\a\nC1 out 0 1u\n.op\n.end\n",
                  GetParam().options);
  EXPECT_FALSE(result.status.ok());
  // A control character other than tab; the status message's own line breaks aside.
  const auto has_control = [](const std::string& text, bool newline_allowed) {
    return std::any_of(text.begin(), text.end(), [&](char c) {
      const auto byte = static_cast<unsigned char>(c);
      return (byte < 0x20 && c != '\t' && !(newline_allowed && c == '\n')) || byte == 0x7f;
    });
  };
  for (const NgspiceMessage& message : result.messages)
    EXPECT_FALSE(has_control(message.text, false)) << message.text;
  EXPECT_FALSE(has_control(result.status.message, true)) << result.status.message;
  EXPECT_TRUE(has_message_containing(result, "zzz\\e[2j\\x07")) << result.messages_text();
}

// A library name is the caller's, but the loader's message that quotes it reaches the terminal
// too: escaped, in the worker and in this process.
TEST(NgspiceRunnerBounds, LoaderMessagesAreEscaped) {
  for (const BackendCase& backend : backend_cases()) {
    if (backend.options.backend != NgspiceBackend::library) continue;
    NgspiceOptions options = backend.options;
    options.library_names = {"/nonexistent/\x1b[2Jlibngspice.so.0"};
    const NgspiceResult result = run_ngspice(kDividerDeck, options);
    EXPECT_FALSE(result.status.ok()) << backend.name;
    EXPECT_EQ(result.status.message.find('\x1b'), std::string::npos)
        << backend.name << ": " << result.status.message;
  }
}

// A deck that makes ngspice print 40 000 warning lines (3 MB as messages): every backend
// keeps the first and the last within max_message_bytes.
TEST_P(NgspiceRunnerBackends, FloodOfNgspiceMessagesIsCapped) {
  std::string deck = "many warnings\nV1 in 0 DC 1\n";
  for (int k = 0; k < 20000; ++k)
    deck += "R" + std::to_string(k) + " in 0 1k zzz" + std::to_string(k) + "\n";
  deck += ".op\n.end\n";
  const NgspiceResult result = run_ngspice(deck, GetParam().options);
  EXPECT_LE(message_bytes(result), GetParam().options.max_message_bytes + kMessageLogSlackBytes);
  EXPECT_TRUE(has_message_containing(result, "can't find model 'zzz0'"));
  EXPECT_TRUE(has_message_containing(result, "of ngspice's output left out here"));
  EXPECT_TRUE(has_message_containing(result, "r19999 in 0 1k zzz19999"));
}

// Results larger than max_result_bytes are refused: the worker's vectors by their record
// lengths, the program's rawfile by the file-size limit it runs under. (In this process the
// vectors are copied from ngspice's own memory, no untrusted length is involved.)
TEST(NgspiceRunnerBounds, ResultsLargerThanTheLimitAreRefused) {
  for (const BackendCase& backend : backend_cases()) {
    if (backend.options.library_in_this_process) continue;
    NgspiceOptions options = backend.options;
    options.max_result_bytes =
        500;  // the AC deck's results: 26 points of 2 complex vectors, 832 bytes
    const NgspiceResult result = run_ngspice(kLowPassAcDeck, options);
    EXPECT_FALSE(result.status.ok()) << backend.name;
    EXPECT_NE(result.status.message.find("max_result_bytes"), std::string::npos)
        << backend.name << ": " << result.status.message;
    EXPECT_TRUE(result.vectors.empty()) << backend.name;
  }
}

// A stand-in libngspice whose ngSpice_Circ prints through the output callback a line with
// control characters and 100 000 further lines, and writes 2 MB with control characters to
// its standard output directly, then fails: the worker's messages and its own output are
// bounded and escaped.
std::string build_chatty_library() {
  const std::string stem =
      ::testing::TempDir() + "emnet_chatty_ngspice_" + std::to_string(::getpid());
  const std::string source = stem + ".c", library = stem + ".so";
  std::ofstream(source) << R"(#include <stdio.h>
typedef int send_char(char*, int, void*);
static send_char* print;
int ngSpice_Init(send_char* a, void* b, void* c, void* d, void* e, void* f, void* g) {
  print = a;
  return 0;
}
int ngSpice_Command(char* command) { return 0; }
int ngSpice_Circ(char** lines) {
  char line[64];
  print("stderr Error: chatty \033]0;title\007 \033[2J end", 0, 0);
  for (int k = 0; k < 100000; ++k) {
    snprintf(line, sizeof line, "stdout chatty line %d", k);
    print(line, 0, 0);
  }
  for (int k = 0; k < 200000; ++k) fputs("raw\033[1m", stdout);
  fflush(stdout);
  return 1;
}
char** ngSpice_AllVecs(char* plot) { return 0; }
void* ngGet_Vec_Info(char* name) { return 0; }
)";
  const std::string command = "cc -shared -fPIC -o '" + library + "' '" + source + "' 2>/dev/null";
  return std::system(command.c_str()) == 0 ? library : std::string();
}

TEST(NgspiceRunnerBounds, LibraryMessagesInTheWorkerAreCappedAndEscaped) {
  const std::string library = build_chatty_library();
  if (library.empty()) GTEST_SKIP() << "no C compiler (cc) to build the chatty stand-in";
  NgspiceOptions options;
  options.library_names = {library};
  options.backend = NgspiceBackend::library;
  const NgspiceResult result = run_ngspice(kDividerDeck, options);
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("Error: chatty \\e]0;title\\x07 \\e[2J end"),
            std::string::npos)
      << result.status.message;
  EXPECT_LE(message_bytes(result), options.max_message_bytes + kMessageLogSlackBytes);
  EXPECT_TRUE(has_message_containing(result, "chatty line 0"));
  EXPECT_TRUE(has_message_containing(result, "raw\\e[1mraw"));
  for (const NgspiceMessage& message : result.messages)
    EXPECT_EQ(message.text.find('\x1b'), std::string::npos) << message.text;
}

// ---- the worker program ---------------------------------------------------------------------

// The library backend from a process with other threads: one loads and unloads a shared
// library and allocates the whole time (what a Python host or a threaded study may do). A fork
// of this process that then ran the loader or the allocator could find their locks held by
// that thread and hang until the time limit; the worker is a program started with exec, so
// every run must give the divider's exact operating point (reference and 1e-12 as in
// OperatingPointOfDividerIsExact).
TEST(NgspiceRunner, WorkerRunsFromAProcessWithAnotherThreadBusy) {
  std::atomic<bool> stop{false};
  std::thread busy([&] {
    while (!stop) {
      if (void* library = ::dlopen("libm.so.6", RTLD_NOW | RTLD_LOCAL)) ::dlclose(library);
      std::vector<double> values(1000, 1.0);
      values.push_back(values.size());
    }
  });
  NgspiceOptions options;
  options.backend = NgspiceBackend::library;
  options.timeout_seconds = 20;
  for (int run = 0; run < 10; ++run) {
    const NgspiceResult result = run_ngspice(kDividerDeck, options);
    EXPECT_TRUE(result.status.ok()) << "run " << run << ": " << result.status.message;
    EXPECT_EQ(result.backend_used, NgspiceBackend::library);
    if (const NgspiceVector* out = result.find("out"))
      EXPECT_NEAR(out->real_values.at(0), 0.75, 0.75 * 1e-12);
    else
      ADD_FAILURE() << "run " << run << ": no vector out";
  }
  stop = true;
  busy.join();
}

// The library backend forks nothing of the calling process that runs its fork handlers
// (pthread_atfork, as fork() would): the worker is a program started with exec through the
// process helper's supervisor. The forked worker this replaced ran the handler below once per
// run, and then dlopen and C++ code in the copy.
std::atomic<int> fork_handler_calls{0};

TEST(NgspiceRunner, WorkerIsNoForkOfTheCaller) {
  static const int registered = ::pthread_atfork([] { ++fork_handler_calls; }, nullptr, nullptr);
  ASSERT_EQ(registered, 0);
  const int before = fork_handler_calls.load();
  NgspiceOptions options;
  options.backend = NgspiceBackend::library;
  const NgspiceResult result = run_ngspice(kDividerDeck, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.backend_used, NgspiceBackend::library);
  EXPECT_EQ(fork_handler_calls.load(), before);
}

// A worker program that is not there: the library backend fails and says where it looked
// (given in the options, or in EMNET_NGSPICE_WORKER), and the automatic backend runs the
// ngspice program instead, saying why.
TEST(NgspiceRunner, MissingWorkerProgramIsAClearFailure) {
  const std::string missing = "/nonexistent/emnet-ngspice-worker";
  NgspiceOptions options;
  options.backend = NgspiceBackend::library;
  options.worker_program = missing;
  NgspiceResult result = run_ngspice(kDividerDeck, options);
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("NgspiceOptions::worker_program, '" + missing +
                                       "', is not an executable file"),
            std::string::npos)
      << result.status.message;
  EXPECT_TRUE(result.vectors.empty());

  options.worker_program.clear();
  ::setenv("EMNET_NGSPICE_WORKER", missing.c_str(), 1);
  result = run_ngspice(kDividerDeck, options);
  ::unsetenv("EMNET_NGSPICE_WORKER");
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("the environment variable EMNET_NGSPICE_WORKER, '" +
                                       missing + "'"),
            std::string::npos)
      << result.status.message;

  options.worker_program = missing;
  options.backend = NgspiceBackend::automatic;
  result = run_ngspice(kDividerDeck, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.backend_used, NgspiceBackend::program);
  EXPECT_NE(result.backend_description.find(missing), std::string::npos)
      << result.backend_description;
  EXPECT_NEAR(vector_named(result, "out").real_values.at(0), 0.75, 0.75 * 1e-12);
}

// A worker of another build (another protocol) refuses the request, and the run says so
// instead of misreading its records: the real worker asked for protocol 99, and a stand-in
// that answers like it does.
TEST(NgspiceRunner, WorkerOfAnotherProtocolIsRefused) {
  const std::string built = std::string(EMNET_BINARY);
  ProcessOptions refusal;
  refusal.arguments = {built.substr(0, built.rfind('/') + 1) + "emnet-ngspice-worker",
                       "protocol=99", "max_message_bytes=1000"};
  refusal.standard_error = ProcessOutput::captured(4096);
  refusal.timeout_seconds = 20;
  const ProcessResult end = run_process(refusal);
  EXPECT_TRUE(end.exited_with(2)) << end.description();
  EXPECT_NE(end.standard_error.find("asked for protocol 99; this worker speaks protocol 1"),
            std::string::npos)
      << end.standard_error;

  const std::string worker = write_fake_program(
      "other_protocol_worker",
      "echo \"emnet-ngspice-worker: asked for ${1#protocol=}; this worker speaks protocol 0\" >&2\n"
      "exit 2\n");
  NgspiceOptions options;
  options.backend = NgspiceBackend::library;
  options.worker_program = worker;
  const NgspiceResult result = run_ngspice(kDividerDeck, options);
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("exit status 2"), std::string::npos)
      << result.status.message;
  EXPECT_NE(result.status.message.find("this worker speaks protocol 0"), std::string::npos)
      << result.status.message;
}

}  // namespace
}  // namespace emnet
