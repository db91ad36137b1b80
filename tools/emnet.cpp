// emnet command-line program: static, ac, modes, sensitivity and identify over one scene.
//
// Exit status: 0 success; 2 bad input (scene file, override, option), with one message naming
// the file, line and key, or an output file (--csv, --plot, -o) or standard output that could
// not be written (the result is printed first); 3 numerical failure, with the reason (for
// crosscheck also: ngspice missing, failing or timed out); 4 crosscheck: a difference exceeds its
// tolerance; 5 computed but outside the model's validity (a deflection above
// model.deflection_limit of the beam length, or a DEA's field V/d above its breakdown field;
// emnet/model/validity.hpp): the result is printed with a WARNING line on standard output and error
// and "validity" in --json; 130 interrupted (Ctrl-C), no output file written; 1 anything else.
//
// Output files are written only after the result is computed and printed, each one completely or
// not at all (emnet::OutputFile). Text from outside (names, titles, file names, tool messages)
// reaches the terminal through emnet::terminal_text, control characters escaped.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "emnet/analysis/analysis.hpp"
#include "emnet/verification/crosscheck.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/model/model.hpp"
#include "emnet/core/output_file.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/scene/parameter_listing.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/studies/sensitivity.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/core/terminal_text.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/validity.hpp"
#include "terminal_progress.hpp"

namespace {

using emnet::InputError;
using Json = nlohmann::ordered_json;
constexpr double pi = 3.14159265358979323846;

// Raised for numerical failure: exit status 3.
struct NumericalFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An output file (--csv, --plot, -o) that could not be written: exit status 2, reported after
// the result.
struct FileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Ctrl-C: exit status 130, no output file written.
struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CommonOptions {
  std::string scene_path;
  std::optional<int> segments;
  std::vector<std::string> overrides;
  std::vector<std::string> probes;
  bool json = false;
  std::string csv;
  bool progress = false, quiet = false;             // --progress, --quiet
  emnet_cli::TerminalProgress* reporter = nullptr;  // set by main: the progress line, Ctrl-C
};

// --probe or --csv given to a command that has no use for it: refused, never ignored.
void refuse_option(bool given, const std::string& option, const std::string& why) {
  if (given) throw InputError(option, option, why);
}

emnet::Progress* progress_of(const CommonOptions& options) {
  return options.reporter;
}

// A step of a command without counts, shown on the progress line.
void show_phase(const CommonOptions& options, const std::string& what) {
  if (options.reporter) options.reporter->phase(what);
}

// The progress line ends before the result (or a warning) is printed.
void end_progress(const CommonOptions& options) {
  if (options.reporter) options.reporter->finish();
}

void stop_if_interrupted() {
  if (emnet_cli::InterruptHandler::interrupted()) throw Interrupted("interrupted");
}

// Text from outside (scene, override, tool output) as shown on the terminal.
std::string shown(const std::string& text) {
  return emnet::terminal_text(text);
}

// --json output: strings with invalid UTF-8 (a name given by --set) are shown with U+FFFD
// instead of ending the program.
std::string json_text(const nlohmann::ordered_json& json) {
  return json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

std::string si(double value, const std::string& unit) {
  return format("%.6g", value) + (unit.empty() ? "" : " " + unit);
}

std::string milliseconds(double seconds) {
  return seconds < 1.0 ? format("%.3g ms", seconds * 1e3) : format("%.3g s", seconds);
}

// Upper bound of the values a command stores and prints or writes (time steps × outputs, AC
// points × probes, ...): 20 million doubles, 160 MB, which --json prints as several hundred MB
// of text. Checked before computing, with the estimate and what to change.
constexpr double kMaximumStoredValues = 2e7;

// A size in bytes as it is read: "168 MB", "4 GB".
std::string bytes_text(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, bytes < 1e9 ? "%.3g MB" : "%.3g GB",
                bytes < 1e9 ? bytes / 1e6 : bytes / 1e9);
  return text;
}

void check_stored_values(double values, const std::string& what, const std::string& option,
                         const std::string& remedy) {
  if (values <= kMaximumStoredValues) return;
  char counts[96];
  std::snprintf(counts, sizeof counts, " would store %.3g values (", values);
  throw InputError(option, option,
                   what + counts + bytes_text(8.0 * values) + " of doubles); at most " +
                       format("%.0f", kMaximumStoredValues) + " values (" +
                       bytes_text(8.0 * kMaximumStoredValues) +
                       ") are stored (inclusive): " + remedy);
}

// Every printed result must be finite: a NaN is a numerical failure, never an output.
double finite(double value, const std::string& what) {
  if (!std::isfinite(value)) throw NumericalFailure("non-finite result for " + what);
  return value;
}

// --set overrides with --segments appended.
std::vector<std::string> overrides_with_segments(const CommonOptions& options) {
  std::vector<std::string> overrides = options.overrides;
  if (options.segments) {
    if (*options.segments < 1)
      throw InputError(
          "--segments", "--segments",
          "must be >= 1 (a number of beam segments), got " + std::to_string(*options.segments));
    overrides.push_back("beam.segments=" + std::to_string(*options.segments));
  }
  return overrides;
}

emnet::Scene load_scene(const CommonOptions& options) {
  const std::vector<std::string> overrides = overrides_with_segments(options);
  emnet::Scene scene = emnet::read_scene(options.scene_path, overrides);
  // beam.segments = "auto": chosen once here, so that every model a command builds from the
  // scene (sweeps, fits, finite differences) has the same N; the choice travels with the scene.
  if (scene.beam.auto_segments) {
    // N only: the fluid loading's resonance and drive.electrical_dynamics = "auto" stay to be
    // chosen for each scene the command builds.
    emnet::ResolveOptions segments_only;
    segments_only.fluid_resonance = false;
    segments_only.electrical_dynamics = false;
    scene = emnet::resolve_scene(scene, segments_only).scene;
  }
  return scene;
}

// A --probe asking for an electrical quantity (drive.electrical_dynamics = "auto" keeps the
// RC dynamics for it).
bool electrical_probe_requested(const CommonOptions& options) {
  for (const auto& text : options.probes)
    if (text.rfind("dea_voltage", 0) == 0 || text.rfind("dea_current", 0) == 0) return true;
  return false;
}

// The model of `scene` with its remaining "auto" keys resolved for the command's probes.
emnet::Model resolved_model(const emnet::Scene& scene, const CommonOptions& options) {
  emnet::PrepareOptions prepare;
  prepare.electrical_probe_requested = electrical_probe_requested(options);
  return emnet::prepare_model(scene, prepare);
}

// "automatic_choices" of --json: what each "auto" key became, why, its error estimate, cost.
Json automatic_choices_json(const std::vector<emnet::AutomaticChoice>& automatic_choices) {
  Json choices = Json::array();
  for (const auto& choice : automatic_choices)
    choices.push_back({{"key", choice.key},
                       {"value", choice.value},
                       {"reason", choice.reason},
                       {"estimated_error", choice.estimated_error},
                       {"tolerance", choice.tolerance},
                       {"band_hz", {choice.band_from_hz, choice.band_to_hz}},
                       {"seconds", choice.seconds}});
  return choices;
}

std::vector<emnet::Probe> selected_probes(const emnet::Model& model, const CommonOptions& options) {
  if (options.probes.empty()) return model.probes;
  std::vector<emnet::Probe> probes;
  for (const auto& text : options.probes) probes.push_back(model.parse_probe(text));
  return probes;
}

std::string drive_summary(const emnet::Scene& scene) {
  const auto& drive = scene.drive;
  std::ostringstream out;
  out << "drive " << emnet::drive_kind_name(drive.kind);
  switch (drive.kind) {
    case emnet::DriveKind::antagonistic:
      out << " 0/" << si(drive.voltage, "V") << " square wave at " << si(drive.frequency, "Hz");
      break;
    case emnet::DriveKind::switched:
      out << " 0/" << si(drive.voltage, "V") << " square wave at " << si(drive.frequency, "Hz")
          << " on DEA " << drive.deas[0];
      break;
    case emnet::DriveKind::bias_differential:
      out << " V0 = " << si(drive.bias, "V") << ", v = " << si(drive.amplitude, "V");
      break;
    case emnet::DriveKind::single:
      out << " V0 + v*sin(2*pi*f*t), V0 = " << si(drive.bias, "V")
          << ", v = " << si(drive.amplitude, "V") << ", f = " << si(drive.frequency, "Hz")
          << " on DEA " << drive.deas[0];
      break;
    case emnet::DriveKind::none:
      break;
  }
  return out.str();
}

// What the AC input is, in words: printed with every AC result. `top_hz`: the sweep's highest
// frequency, where the square-wave drives' omitted RC factor is largest.
std::string ac_input_description(const emnet::Scene& scene, double top_hz) {
  std::ostringstream out;
  const auto& drive = scene.drive;
  // The square-wave drives' force goes in directly; through the RC loops its fundamental would
  // be 1/(1 + j*omega*tau) times it (src/model/model.cpp).
  auto rc_loops = [&] {
    const double tau = emnet::drive_time_constant(scene);
    const std::complex<double> lag = 1.0 / std::complex<double>(1.0, 2 * pi * top_hz * tau);
    out << " The DEAs' RC loops are not in this input, whatever drive.electrical_dynamics: "
           "through them the force's fundamental would be 1/(1 + j*2*pi*f*tau) times it (exact "
           "at duty 0.5; tau = "
        << milliseconds(tau) << ": at " << si(top_hz, "Hz") << " " << format("%.6g", std::abs(lag))
        << ", " << format("%.3g", std::arg(lag) * 180.0 / pi) << " deg).";
  };
  switch (drive.kind) {
    case emnet::DriveKind::antagonistic:
      out << "AC input: the alternating part of the antagonistic square-wave drive: each DEA's "
             "force k_F*V^2/2 (V = "
          << si(drive.voltage, "V") << ") as a sinusoid, DEA " << shown(drive.deas[0])
          << " and DEA " << shown(drive.deas[1])
          << " in antiphase (the square wave's +/- level; its fundamental is 4/pi times this); "
             "exact, no linearisation: a 0/V voltage squares to a 0/k_F*V^2 force.";
      rc_loops();
      break;
    case emnet::DriveKind::switched:
      out << "AC input: the alternating part of the switched square-wave drive on DEA "
          << shown(drive.deas[0])
          << ": its force, a 0/k_F*V^2 square wave (V = " << si(drive.voltage, "V")
          << "), is +/- k_F*V^2/2 about its mean k_F*V^2/2; the +/- level as a sinusoid (its "
             "fundamental is 4/pi times this); exact, no linearisation: a 0/V voltage squares to "
             "a 0/k_F*V^2 force. The mean is a static offset, not in this input. The network is "
             "linearised at the static state (DEA on), which only the back-coupling sees.";
      rc_loops();
      break;
    case emnet::DriveKind::bias_differential:
      out << "AC input: v = " << si(drive.amplitude, "V") << " on DEA " << shown(drive.deas[0])
          << " and -v on DEA " << shown(drive.deas[1])
          << " about the bias V0 = " << si(drive.bias, "V")
          << "; the network linearised at V0 (the moment is exactly linear in v).";
      break;
    case emnet::DriveKind::single:
      out << "AC input: v = " << si(drive.amplitude, "V") << " on DEA " << shown(drive.deas[0])
          << ", linearised about the bias V0 = " << si(drive.bias, "V")
          << " (the force's part 2*k_F*V0*v; its DC and 2f parts, k_F*v^2/2 each, are left out).";
      break;
    case emnet::DriveKind::none:
      out << "AC input: the scene's loads, each with its value as amplitude.";
      break;
  }
  if (drive.kind != emnet::DriveKind::none && !scene.loads.empty())
    out << " Plus the scene's loads, each with its value as amplitude.";
  return out.str();
}

// The validity checks of a result (emnet/model/validity.hpp): "validity" of --json; in text a line
// with the largest values against their limits and a WARNING line per violation.
Json validity_json(const emnet::Validity& validity) {
  Json violations = Json::array();
  for (const auto& v : validity.violations)
    violations.push_back({{"check", emnet::validity_check_name(v.check)},
                          {"subject", v.subject},
                          {"key", v.key},
                          {"value", v.value},
                          {"limit", v.limit},
                          {"message", v.message}});
  return {{"status", validity.within() ? "within" : "OUTSIDE"},
          {"summary", validity.summary},
          {"deflection_fraction_of_limit", validity.deflection_fraction},
          {"field_fraction_of_breakdown", validity.field_fraction},
          {"violations", violations}};
}

std::string validity_warning(const emnet::ValidityViolation& violation) {
  return "WARNING: outside the model's validity: " + violation.message;
}

void print_validity(const emnet::Validity& validity) {
  std::cout << "validity: " << validity.summary << "\n";
  for (const auto& v : validity.violations) std::cout << validity_warning(v) << "\n";
}

// The exit status of a computed result: 0, or 5 with the warnings on standard error.
int validity_exit(const emnet::Validity& validity) {
  for (const auto& v : validity.violations) std::cerr << "emnet: " << validity_warning(v) << "\n";
  return validity.within() ? 0 : emnet::kExitOutsideValidity;
}

void print_header(const emnet::Model& model, const emnet::System& system) {
  const auto& scene = model.scene;
  std::cout << "scene " << shown(scene.name) << " (" << shown(scene.file)
            << "): " << scene.beam.segments << " segments, L = " << si(scene.beam.length, "m")
            << ", EI = " << si(scene.beam.bending_stiffness, "N*m^2")
            << ", rhoA = " << si(scene.beam.mass_per_length, "kg/m") << ", " << scene.deas.size()
            << " DEA(s), " << drive_summary(scene) << "\n"
            << "network: " << model.network.nodes().size() << " nodes, "
            << model.network.elements().size() << " elements, " << system.size() << " unknowns\n";
  for (const auto& note : model.notes) std::cout << "note: " << shown(note) << "\n";
}

// A CSV file of `count` rows, row i filled by fill_row(i, row), written completely or not at
// all; FileError when it cannot be. The rows are formatted as they are written, not stored.
template <class FillRow>
void write_csv_rows(const std::string& path, const std::vector<std::string>& header, size_t count,
                    const FillRow& fill_row) {
  stop_if_interrupted();
  emnet::OutputFile out(path);
  // A header field with a comma, quote or line break is quoted (RFC 4180).
  auto field = [](const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
  };
  std::string line;
  for (size_t k = 0; k < header.size(); ++k) line += (k ? "," : "") + field(header[k]);
  out.write(line + "\n");
  char number[32];
  std::vector<double> row;
  for (size_t i = 0; i < count; ++i) {
    row.clear();
    fill_row(i, row);
    line.clear();
    for (size_t k = 0; k < row.size(); ++k) {
      std::snprintf(number, sizeof number, "%s%.12g", k ? "," : "", row[k]);
      line += number;
    }
    out.write(line + "\n");
  }
  if (const emnet::Status status = out.commit(); !status.ok)
    throw FileError("--csv: " + status.message);
}

void write_csv(const std::string& path, const std::vector<std::string>& header,
               const std::vector<std::vector<double>>& rows) {
  write_csv_rows(path, header, rows.size(),
                 [&](size_t i, std::vector<double>& row) { row = rows[i]; });
}

// A plot's Status as a FileError (gnuplot missing or failing is no numerical failure).
void check_plot(const emnet::Status& status) {
  if (!status.ok) throw FileError("--plot: " + status.message);
}

struct Prepared {
  emnet::Model model;
  emnet::System system;
  emnet::StaticResult rest;
};

// Builds the model and its operating point. A linear network without a static state (a free
// body) can still be analysed dynamically: its operating point is then zero, as said in a note;
// `static` itself requires the static state.
Prepared prepare(const CommonOptions& options, bool require_static = false,
                 std::optional<emnet::Scene> scene = std::nullopt) {
  if (!scene) scene = load_scene(options);
  show_phase(options, "building the network");
  Prepared p{resolved_model(*scene, options), {}, {}};
  p.system = p.model.network.assemble();
  emnet::StaticOptions static_options;
  static_options.progress = progress_of(options);
  p.rest = emnet::solve_static(p.system, static_options);
  stop_if_interrupted();
  if (!p.rest.status.ok) {
    if (require_static || p.system.is_nonlinear())
      throw NumericalFailure("static operating point: " + p.rest.status.message);
    p.model.notes.push_back("no static state (" + p.rest.status.message +
                            "); the linear network is analysed about zero");
    p.rest.operating_point = Eigen::VectorXd::Zero(p.system.size());
  }
  return p;
}

// ---- static ---------------------------------------------------------------------------

int run_static(const CommonOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  Prepared p = prepare(options, true);
  const auto probes = selected_probes(p.model, options);
  const auto& beam = p.model.beam;
  std::vector<std::vector<double>> rows;
  for (size_t k = 0; k < beam.x.size(); ++k) {
    emnet::ProbeSpec w{"w", emnet::ProbeQuantity::deflection, beam.x[k], ""};
    emnet::ProbeSpec phi{"phi", emnet::ProbeQuantity::rotation, beam.x[k], ""};
    rows.push_back(
        {beam.x[k],
         finite(emnet::static_probe_value(p.system, p.rest, p.model.make_probe(w)), "deflection"),
         finite(emnet::static_probe_value(p.system, p.rest, p.model.make_probe(phi)), "rotation")});
  }
  std::vector<double> probe_values;
  for (const auto& probe : probes)
    probe_values.push_back(
        finite(emnet::static_probe_value(p.system, p.rest, probe), "probe " + probe.name));
  // Validity: the nodal deflections and the deflection probes, the sources at t = 0.
  std::vector<emnet::DeflectionPeak> peaks{{"the beam's nodes", 0.0}};
  for (const auto& row : rows) peaks[0].peak = std::max(peaks[0].peak, std::abs(row[1]));
  for (size_t k = 0; k < probes.size(); ++k)
    if (probes[k].quantity == emnet::ProbeQuantity::deflection)
      peaks.push_back({probes[k].name, std::abs(probe_values[k])});
  const emnet::Validity validity =
      emnet::check_validity(p.model.scene, peaks, emnet::drive_voltages_at_start(p.model.scene));
  const double total = seconds_since(start);
  end_progress(options);
  auto write_files = [&] {
    if (!options.csv.empty()) write_csv(options.csv, {"x_m", "deflection_m", "rotation_rad"}, rows);
  };
  if (options.json) {
    Json out;
    out["scene"] = p.model.scene.name;
    out["automatic_choices"] = automatic_choices_json(p.model.automatic_choices);
    out["segments"] = p.model.scene.beam.segments;
    out["nodes"] = Json::array();
    for (const auto& row : rows)
      out["nodes"].push_back({{"x_m", row[0]}, {"deflection_m", row[1]}, {"rotation_rad", row[2]}});
    out["probes"] = Json::array();
    for (size_t k = 0; k < probes.size(); ++k)
      out["probes"].push_back({{"name", probes[k].name},
                               {"description", probes[k].description},
                               {"unit", probes[k].unit},
                               {"value", probe_values[k]}});
    out["accuracy"] = {{"relative_residual", p.rest.relative_residual},
                       {"newton_iterations", p.rest.newton_iterations},
                       {"discretisation", "exact at the nodes for any N (Hermite statics)"}};
    out["cost"] = {{"solve_seconds", p.rest.seconds}, {"total_seconds", total}};
    out["validity"] = validity_json(validity);
    std::cout << json_text(out) << "\n";
    write_files();
    return validity_exit(validity);
  }
  print_header(p.model, p.system);
  std::cout << "static state at rest (" << drive_summary(p.model.scene) << ", first half-period)\n"
            << "accuracy: Newton " << p.rest.newton_iterations
            << " iteration(s), relative residual " << format("%.2g", p.rest.relative_residual)
            << "; nodal values exact for any N (Hermite statics), cubic Hermite between nodes\n"
            << "cost: solve " << milliseconds(p.rest.seconds) << ", total " << milliseconds(total)
            << "\n\n";
  std::printf("%8s %12s %16s %16s\n", "node", "x [mm]", "deflection [m]", "rotation [rad]");
  for (size_t k = 0; k < rows.size(); ++k)
    std::printf("%8zu %12.6g %16.6e %16.6e\n", k, rows[k][0] * 1e3, rows[k][1], rows[k][2]);
  if (!probes.empty()) std::cout << "\nprobes:\n";
  for (size_t k = 0; k < probes.size(); ++k)
    std::printf("  %-10s %-40s %14.6e %s\n", shown(probes[k].name).c_str(),
                shown(probes[k].description).c_str(), probe_values[k],
                shown(probes[k].unit).c_str());
  print_validity(validity);
  write_files();
  return validity_exit(validity);
}

// ---- modes ----------------------------------------------------------------------------

struct ModesOptions {
  int count = 0;
  bool shapes = false;
  bool error_estimate = true;
  bool dense = false;  // every pole by the dense method, whatever the size (up to a limit)
};

// Unknowns up to which `modes --dense` runs: a dense eigen-decomposition is O(n³) (measured on
// the fish fin: 606 unknowns 0.75 s, 1206 unknowns 6.5 s; 2000 about half a minute).
constexpr int kDenseModesLimit = 2000;

// Richardson estimate of the discretisation error of each mode from N and 2N segments
// (lumped-mass convergence is O(N⁻²): f∞ ≈ f2N + (f2N − fN)/3).
std::vector<double> discretisation_errors(const CommonOptions& options, const emnet::Scene& scene,
                                          const std::vector<emnet::Mode>& modes, int count,
                                          double& seconds) {
  const auto start = std::chrono::steady_clock::now();
  CommonOptions doubled = options;
  doubled.segments = 2 * scene.beam.segments;
  Prepared fine = prepare(doubled);
  emnet::ModalOptions modal_options;
  modal_options.count = count;
  modal_options.keep_vectors = false;
  const auto fine_modes = emnet::run_modes(fine.system, fine.rest.operating_point, modal_options);
  std::vector<double> errors;
  if (fine_modes.status.ok) {
    std::vector<double> coarse, refined;
    for (const auto& mode : modes) coarse.push_back(mode.frequency_hz);
    for (const auto& mode : fine_modes.modes) refined.push_back(mode.frequency_hz);
    errors = emnet::richardson_errors(coarse, refined);
  }
  seconds = seconds_since(start);
  return errors;
}

// Deflection mode shape at the beam nodes, scaled to a largest value of 1; `scale` receives
// the divisor (the largest nodal deflection of the vector), for values elsewhere.
std::vector<std::complex<double>> mode_shape(const emnet::Model& model, const emnet::Mode& mode,
                                             std::complex<double>* scale = nullptr) {
  std::vector<std::complex<double>> shape;
  for (double x : model.beam.x) {
    std::complex<double> value = 0.0;
    for (const auto& [index, c] : model.beam.deflection_terms(x)) value += c * mode.vector[index];
    shape.push_back(value / mode.pole);  // w = v/s
  }
  std::complex<double> largest = 0.0;
  for (auto v : shape)
    if (std::abs(v) > std::abs(largest)) largest = v;
  if (std::abs(largest) > 0.0)
    for (auto& v : shape) v /= largest;
  if (scale) *scale = std::abs(largest) > 0.0 ? largest : 1.0;
  return shape;
}

// A probe's value in a mode, relative to the mode's largest nodal deflection: the quantity's
// phasor Σ c·y / s^integrations (a deflection is the velocity over s).
std::complex<double> mode_probe_value(const emnet::Model& model, const emnet::Mode& mode,
                                      const emnet::Probe& probe) {
  std::complex<double> scale = 1.0;
  mode_shape(model, mode, &scale);
  std::complex<double> value = 0.0;
  for (const auto& [index, c] : probe.terms) value += c * mode.vector[index];
  for (int k = 0; k < probe.integrations; ++k) value /= mode.pole;
  return value / scale;
}

// A rigid-body motion in words: its deflection w(x) = a + b·x along the beam is a translation
// (b·L negligible against a), or a rotation about the point where w = 0.
std::string rigid_body_motion_name(const emnet::Model& model, const Eigen::VectorXd& motion) {
  auto deflection = [&](double x) {
    double w = 0.0;
    for (const auto& [index, c] : model.beam.deflection_terms(x)) w += c * motion[index];
    return w;
  };
  const double length = model.beam.length;
  const double w0 = deflection(0.0), w1 = deflection(length);
  const double slope = (w1 - w0) / length;
  if (std::abs(slope) * length <= 1e-9 * std::max(std::abs(w0), std::abs(w1))) return "translation";
  double pivot = -w0 / slope;
  if (std::abs(pivot) <= 1e-9 * length) pivot = 0.0;  // no "-0"
  return "rotation about x = " + si(pivot * 1e3, "mm");
}

int run_modes_command(const CommonOptions& options, const ModesOptions& modes_options) {
  const auto start = std::chrono::steady_clock::now();
  Prepared p = prepare(options);
  const std::vector<emnet::Probe> probes =
      options.probes.empty() ? std::vector<emnet::Probe>{} : selected_probes(p.model, options);
  emnet::ModalOptions modal_options;
  modal_options.count = modes_options.count;
  modal_options.keep_vectors = true;
  modal_options.progress = progress_of(options);
  if (modes_options.dense) {
    if (p.system.size() > kDenseModesLimit)
      throw InputError("--dense", "--dense",
                       "the network has " + std::to_string(p.system.size()) +
                           " unknowns; a dense eigen-decomposition is limited to " +
                           std::to_string(kDenseModesLimit) + " (inclusive; it grows as n^3)");
    modal_options.dense_limit = 2 * kDenseModesLimit;  // the pencil has the mass velocities too
  }
  const emnet::ModalResult result =
      emnet::run_modes(p.system, p.rest.operating_point, modal_options);
  stop_if_interrupted();
  if (!result.status.ok) throw NumericalFailure("modes: " + result.status.message);
  std::vector<emnet::Mode> modes = result.modes;
  if (modes_options.count > 0 && static_cast<int>(modes.size()) > modes_options.count)
    modes.resize(static_cast<size_t>(modes_options.count));
  std::vector<std::string> unbounded;
  for (size_t k = 0; k < modes.size(); ++k) {
    finite(modes[k].frequency_hz, "a modal frequency");
    finite(modes[k].damping_ratio, "a damping ratio");
    if (!modes[k].error_bounded)
      unbounded.push_back("mode " + std::to_string(k + 1) + " (" +
                          format("%.6g", modes[k].frequency_hz) +
                          " Hz): " + modes[k].unbounded_reason);
  }
  // Each mode's rounding error bound, relative to its damped frequency (and to |s| for ζ).
  auto frequency_error = [](const emnet::Mode& mode) {
    return mode.pole_error / std::max(std::abs(mode.pole.imag()), 1e-300);
  };
  double estimate_seconds = 0.0;
  std::vector<double> errors;
  const bool estimate = modes_options.error_estimate && p.model.scene.beam.segments <= 1000;
  if (estimate)
    errors = discretisation_errors(options, p.model.scene, modes,
                                   std::max<int>(static_cast<int>(modes.size()) + 2, 6),
                                   estimate_seconds);
  const double total = seconds_since(start);
  std::vector<std::string> rigid_names;
  for (const auto& motion : result.rigid_body_modes)
    rigid_names.push_back(rigid_body_motion_name(p.model, motion));
  if (rigid_names.size() > 1) rigid_names = {"translation and rotation (a free body)"};

  end_progress(options);
  auto write_files = [&] {
    if (options.csv.empty()) return;
    std::vector<std::vector<double>> rows;
    for (size_t k = 0; k < modes.size(); ++k)
      rows.push_back({static_cast<double>(k + 1), modes[k].frequency_hz, modes[k].damping_ratio,
                      modes[k].natural_frequency_hz, modes[k].pole.real(), modes[k].pole.imag(),
                      modes[k].pole_error / (2 * pi), modes[k].error_bounded ? 1.0 : 0.0});
    write_csv(options.csv,
              {"mode", "frequency_hz", "damping_ratio", "natural_frequency_hz", "pole_real",
               "pole_imag", "frequency_error_bound_hz", "error_bounded"},
              rows);
  };
  if (options.json) {
    Json out;
    out["scene"] = p.model.scene.name;
    out["automatic_choices"] = automatic_choices_json(p.model.automatic_choices);
    out["segments"] = p.model.scene.beam.segments;
    out["modes"] = Json::array();
    for (size_t k = 0; k < modes.size(); ++k) {
      Json mode = {{"frequency_hz", modes[k].frequency_hz},
                   {"damping_ratio", modes[k].damping_ratio},
                   {"natural_frequency_hz", modes[k].natural_frequency_hz},
                   {"pole", {modes[k].pole.real(), modes[k].pole.imag()}},
                   {"relative_residual", modes[k].relative_residual},
                   {"error_bounded", modes[k].error_bounded}};
      if (modes[k].error_bounded) {
        mode["pole_error_bound"] = modes[k].pole_error;
        mode["frequency_error_bound_hz"] = modes[k].pole_error / (2 * pi);
        mode["damping_ratio_error_bound"] = modes[k].pole_error / std::abs(modes[k].pole);
      } else {
        mode["unbounded_reason"] = modes[k].unbounded_reason;
      }
      if (k < errors.size()) mode["discretisation_error_estimate"] = errors[k];
      if (modes_options.shapes) {
        const auto shape = mode_shape(p.model, modes[k]);
        Json nodes = Json::array();
        for (size_t i = 0; i < shape.size(); ++i)
          nodes.push_back({{"x_m", p.model.beam.x[i]},
                           {"deflection", shape[i].real()},
                           {"deflection_imag", shape[i].imag()}});
        mode["shape"] = nodes;
      }
      if (!probes.empty()) {
        Json at = Json::array();
        for (const auto& probe : probes) {
          const auto value = mode_probe_value(p.model, modes[k], probe);
          at.push_back({{"name", probe.name},
                        {"description", probe.description},
                        {"value", value.real()},
                        {"value_imag", value.imag()},
                        {"unit", probe.unit + " per unit largest deflection"}});
        }
        mode["probes"] = at;
      }
      out["modes"].push_back(mode);
    }
    out["real_poles"] = Json::array();
    for (const auto& pole : result.real_poles) {
      Json entry = {{"pole", pole.pole.real()},
                    {"time_constant_s", -1.0 / pole.pole.real()},
                    {"error_bounded", pole.error_bounded}};
      if (pole.error_bounded)
        entry["pole_error_bound"] = pole.pole_error;
      else
        entry["unbounded_reason"] = pole.unbounded_reason;
      out["real_poles"].push_back(entry);
    }
    out["rigid_body_modes"] = Json::array();
    for (const auto& name : rigid_names) out["rigid_body_modes"].push_back(name);
    out["method"] = result.method;
    out["complete"] = result.complete;
    out["pencil_size"] = result.pencil_size;
    out["cost"] = {{"modal_seconds", result.seconds},
                   {"error_bound_seconds", result.bound_seconds},
                   {"error_estimate_seconds", estimate_seconds},
                   {"total_seconds", total}};
    if (!unbounded.empty()) out["status"] = "NOT BOUNDED";
    std::cout << json_text(out) << "\n";
  } else {
    print_header(p.model, p.system);
    std::cout << "modes: " << result.method
              << (result.complete ? " (every finite pole of the pencil)"
                                  : " shift-invert Arnoldi (the poles nearest 0)")
              << ", " << modes.size() << " oscillatory shown, " << result.real_poles.size()
              << " real pole(s)"
              << (rigid_names.empty() ? "" : ", rigid-body motion: " + rigid_names.front()) << "\n"
              << (result.note.empty()
                      ? ""
                      : "note: " + result.note +
                            (result.method == "arnoldi"
                                 ? " (poles beyond a cluster of nearly equal real poles, such "
                                   "as Kelvin-Voigt relaxations near -1/tau, are not reached; "
                                   "--dense computes every pole)"
                                 : "") +
                            "\n")
              << "accuracy: 'rounding' bounds each frequency's error from the computation "
                 "(first order: residual in extended precision times the pole's condition); "
                 "discretisation error vs the continuum beam "
              << (estimate ? "estimated from N and 2N segments (Richardson, O(N^-2))"
                  : modes_options.error_estimate ? "not estimated (N > 1000)"
                                                 : "not estimated (--no-error-estimate)")
              << "\ncost: modes " << milliseconds(result.seconds) << " (of which error bounds "
              << milliseconds(result.bound_seconds) << "), error estimate "
              << milliseconds(estimate_seconds) << ", total " << milliseconds(total) << "\n\n";
    std::printf("%5s %16s %14s %16s %12s %14s\n", "mode", "freq [Hz]", "damping ratio",
                "natural f [Hz]", "rounding", "discr. error");
    for (size_t k = 0; k < modes.size(); ++k) {
      const std::string err = k < errors.size() ? format("%.2g", errors[k]) : "-";
      const std::string bound =
          modes[k].error_bounded ? format("%.2g", frequency_error(modes[k])) : "unbounded";
      std::printf("%5zu %16.9g %14.6g %16.9g %12s %14s\n", k + 1, modes[k].frequency_hz,
                  modes[k].damping_ratio, modes[k].natural_frequency_hz, bound.c_str(),
                  err.c_str());
    }
    if (!result.real_poles.empty()) {
      // Real poles: the DEAs' RC loops and overdamped (Kelvin–Voigt) relaxations; listed in
      // full by --json, summarised here.
      const auto& first = result.real_poles.front();
      const auto& last = result.real_poles.back();
      int unbounded_real = 0;
      for (const auto& pole : result.real_poles) unbounded_real += pole.error_bounded ? 0 : 1;
      std::printf(
          "\n%zu real (non-oscillatory) pole(s): time constants %.4g s to %.4g s%s (all in "
          "--json)\n",
          result.real_poles.size(), -1.0 / first.pole.real(), -1.0 / last.pole.real(),
          unbounded_real == 0
              ? ""
              : (", " + std::to_string(unbounded_real) +
                 " of them not bounded individually (clusters of nearly equal poles)")
                    .c_str());
    }
    if (!rigid_names.empty())
      std::cout << "\nrigid-body motion (pole s = 0): " << rigid_names.front() << "\n";
    if (modes_options.shapes)
      for (size_t k = 0; k < modes.size(); ++k) {
        std::cout << "\nmode " << k + 1 << " shape (deflection, largest = 1):\n";
        const auto shape = mode_shape(p.model, modes[k]);
        for (size_t i = 0; i < shape.size(); ++i)
          std::printf("  x = %10.6g mm  %+.6f\n", p.model.beam.x[i] * 1e3, shape[i].real());
      }
    if (!probes.empty()) {
      std::cout << "\nmode shape at the probes (per unit largest nodal deflection; real and "
                   "imaginary part):\n";
      for (size_t k = 0; k < modes.size(); ++k)
        for (const auto& probe : probes) {
          const auto value = mode_probe_value(p.model, modes[k], probe);
          std::printf("  mode %zu  %-10s %-36s %+.6g %+.6g %s\n", k + 1, shown(probe.name).c_str(),
                      shown(probe.description).c_str(), value.real(), value.imag(),
                      shown(probe.unit).c_str());
        }
    }
  }
  if (!unbounded.empty()) {  // refused: no output file
    std::string message = "modes: the error of these modes cannot be bounded:";
    for (const auto& line : unbounded) message += "\n  " + line;
    throw NumericalFailure(message);
  }
  write_files();
  return 0;
}

// ---- ac -------------------------------------------------------------------------------

struct AcOptions {
  std::string from, to;  // as given; parsed by checked_ac_spec
  std::optional<int> points;
  std::string scale;
  std::string plot;
  bool reduce = false;
  std::string tolerance, band;  // --reduce: as given, parsed and checked by reduction_options
};

double parse_frequency(const std::string& text, const std::string& option) {
  try {
    size_t used = 0;
    const double value = std::stod(text, &used);
    std::string rest = text.substr(used);
    rest.erase(0, rest.find_first_not_of(' '));
    double factor = 1.0;
    if (rest == "kHz")
      factor = 1e3;
    else if (rest == "mHz")
      factor = 1e-3;
    else if (!rest.empty() && rest != "Hz")
      throw std::invalid_argument("unit");
    if (!std::isfinite(value)) throw std::invalid_argument("finite");
    return value * factor;
  } catch (const std::exception&) {
    throw InputError(option, option, "expected a frequency in Hz, got '" + text + "'");
  }
}

// Frequencies an AC sweep (or deck) may have: 1 to 1000000, inclusive.
constexpr int kMaximumAcPoints = 1000000;

// The AC sweep of the scene's [ac] table with --from, --to, --points and --scale applied
// (ac and netlist --analysis ac): one frequency (--points 1, --to equal to --from or not
// given) or an increasing range.
emnet::AcSpec checked_ac_spec(emnet::AcSpec spec, const std::string& from_text,
                              const std::string& to_text, std::optional<int> points,
                              const std::string& scale) {
  if (!from_text.empty()) spec.from = parse_frequency(from_text, "--from");
  if (!to_text.empty()) spec.to = parse_frequency(to_text, "--to");
  if (points) spec.points = *points;
  if (!scale.empty()) spec.log = scale == "log";
  if (spec.points < 1 || spec.points > kMaximumAcPoints)
    throw InputError("--points", "--points",
                     "must be from 1 to " + std::to_string(kMaximumAcPoints) +
                         " (inclusive), got " + std::to_string(spec.points));
  if (spec.from < 0.0) throw InputError("--from", "--from", "must be >= 0 Hz");
  if (spec.points == 1) {
    if (to_text.empty()) spec.to = spec.from;
    if (spec.to != spec.from)
      throw InputError("--to", "--to",
                       "one frequency (--points 1) needs --to equal to --from, or no --to");
  } else if (!(spec.to > spec.from)) {
    throw InputError("--to", "--to",
                     "must be > --from for a sweep of --points >= 2 (equal to it with --points 1)");
  }
  if (spec.log && !(spec.from > 0.0))
    throw InputError("--from", "--from", "a log sweep needs --from > 0 Hz");
  return spec;
}

// Why the scene gives the AC analysis no input (B_ac = 0), in its own terms.
std::string no_ac_input_reason(const emnet::Scene& scene) {
  const auto& drive = scene.drive;
  std::string why;
  switch (drive.kind) {
    case emnet::DriveKind::none:
      why = "drive.kind = \"none\"";
      break;
    case emnet::DriveKind::antagonistic:
      why = "the antagonistic drive at drive.voltage = " + si(drive.voltage, "V");
      break;
    case emnet::DriveKind::bias_differential:
    case emnet::DriveKind::single:
      why = "drive.kind = \"" + std::string(emnet::drive_kind_name(drive.kind)) +
            "\" with drive.bias = " + si(drive.bias, "V") +
            " and drive.amplitude = " + si(drive.amplitude, "V") +
            " (at a bias of 0 V a V^2 force has no part linear in v: it acts at 0 and 2f)";
      break;
  }
  return "nothing excites the AC analysis: " + why +
         (scene.loads.empty() ? " and no [[load]]" : " and loads of zero value") +
         ", so every response would be zero; set a drive with a small-signal part or a load";
}

// The fields a reduced model reports in --json, for ac and sweep-switching alike.
Json reduction_json(const emnet::ModalReduction& m, bool tolerance_met) {
  return {{"status", tolerance_met ? "met" : "NOT MET"},
          {"tolerance", m.tolerance},
          {"band_hz", m.band_hz},
          {"cutoff_hz", m.cutoff_hz},
          {"kept_modes", m.kept_modes},
          {"kept_real_poles", m.kept_real_poles},
          {"truncated_poles", m.truncated_poles},
          {"full_unknowns", m.full_unknowns},
          {"modal_method", m.modal_method}};
}

// --tolerance and --band of a modal reduction (ac, sweep-switching); band defaults to
// `default_band` [Hz], tolerance to the scene's model.tolerance. Bad values are input errors
// naming the option.
emnet::ReductionOptions reduction_options(const std::string& tolerance, const std::string& band,
                                          double default_band, double default_tolerance) {
  emnet::ReductionOptions reduction;
  reduction.tolerance = default_tolerance;
  if (!tolerance.empty()) {
    try {
      size_t used = 0;
      reduction.tolerance = std::stod(tolerance, &used);
      if (used != tolerance.size()) throw std::invalid_argument("trailing text");
    } catch (const std::exception&) {
      throw InputError("--tolerance", "tolerance",
                       "expected a relative error in (0, 1), got '" + tolerance + "'");
    }
  }
  reduction.band = band.empty() ? default_band : parse_frequency(band, "--band");
  emnet::validate(reduction);
  return reduction;
}

// The reduction's modes, cut-off and measured error, said loudly when the tolerance is not met.
std::string tolerance_warning(double measured, double tolerance) {
  return "WARNING: modal reduction: the requested tolerance is NOT MET: measured error " +
         format("%.3g", measured) + " > " + format("%.3g", tolerance) +
         " against the full model. Raise --band (a higher cut-off keeps more modes) unless the "
         "note says poles below the cut-off were not found, or run without --reduce.";
}

int run_ac_command(const CommonOptions& options, const AcOptions& ac_options) {
  const auto start = std::chrono::steady_clock::now();
  if (!ac_options.reduce && (!ac_options.tolerance.empty() || !ac_options.band.empty()))
    throw InputError("--tolerance/--band", "--reduce", "--tolerance and --band need --reduce");
  emnet::Scene scene = load_scene(options);
  const emnet::AcSpec spec = checked_ac_spec(scene.ac, ac_options.from, ac_options.to,
                                             ac_options.points, ac_options.scale);
  // The scene's probes, or a tip probe when it has none, unless --probe names them.
  const size_t probe_count =
      options.probes.empty() ? std::max<size_t>(1, scene.probes.size()) : options.probes.size();
  check_stored_values(static_cast<double>(spec.points) * (2.0 * probe_count + 1.0),
                      "the AC sweep of " + std::to_string(spec.points) + " frequencies x " +
                          std::to_string(probe_count) + " complex probes",
                      "--points", "lower --points or give fewer --probe");
  Prepared p = prepare(options, false, std::move(scene));
  const auto probes = selected_probes(p.model, options);
  if (p.system.b_ac().norm() == 0.0)
    throw InputError(p.model.scene.file, "drive.kind", no_ac_input_reason(p.model.scene));
  const auto grid = emnet::frequency_grid(spec.from, spec.to, spec.points, spec.log);
  std::optional<emnet::AcReductionResult> reduction;
  if (ac_options.reduce) {
    const emnet::ReductionOptions reduction_settings = reduction_options(
        ac_options.tolerance, ac_options.band, spec.to, p.model.scene.model.tolerance);
    show_phase(options, "modal reduction and its check");
    reduction =
        emnet::run_ac_reduced(p.system, p.rest.operating_point, grid, probes, reduction_settings);
    if (!reduction->status.ok) throw NumericalFailure("ac --reduce: " + reduction->status.message);
  }
  emnet::AcOptions sweep_options;
  sweep_options.progress = progress_of(options);
  const emnet::AcResult result =
      reduction ? reduction->ac
                : emnet::run_ac(p.system, p.rest.operating_point, grid, probes, sweep_options);
  if (!result.status.ok) throw NumericalFailure("ac: " + result.status.message);
  for (const auto& series : result.values)
    for (const auto& v : series) finite(std::abs(v), "an AC response");

  // Resonances in the band, to mark them and to report them (reduced: the kept modes).
  std::vector<emnet::PlotMarker> markers;
  std::vector<double> resonances;
  if (reduction) {
    for (const auto& kept : reduction->model.kept)
      if (kept.oscillatory) resonances.push_back(std::abs(kept.pole.imag()) / (2 * pi));
    std::sort(resonances.begin(), resonances.end());
  } else {
    emnet::ModalOptions modal_options;
    modal_options.keep_vectors = false;
    if (p.system.size() > modal_options.dense_limit) modal_options.count = 10;
    show_phase(options, "modes for the resonance markers");
    const auto modes = emnet::run_modes(p.system, p.rest.operating_point, modal_options);
    if (modes.status.ok)
      for (const auto& mode : modes.modes) resonances.push_back(mode.frequency_hz);
  }
  for (double f : resonances)
    if (f >= spec.from && f <= spec.to) markers.push_back({f, "f = " + format("%.6g", f) + " Hz"});
  end_progress(options);
  if (reduction && !reduction->tolerance_met)
    std::cerr << tolerance_warning(reduction->measured_error, reduction->model.tolerance) << "\n";
  // Validity: each deflection probe's largest AC amplitude. Every drive's AC input has the
  // scene's own amplitude (the square waves' force level, v, the loads' values), so these are
  // deflection amplitudes; a switched drive's mean offset and a sine's 2f part are not added.
  std::vector<emnet::DeflectionPeak> peaks;
  for (size_t k = 0; k < probes.size(); ++k)
    if (probes[k].quantity == emnet::ProbeQuantity::deflection) {
      peaks.push_back({probes[k].name, 0.0});
      for (const auto& v : result.values[k])
        peaks.back().peak = std::max(peaks.back().peak, std::abs(v));
    }
  const emnet::Validity validity =
      emnet::check_validity(p.model.scene, peaks, emnet::drive_peak_voltages(p.model.scene));
  const double total = seconds_since(start);
  const std::string input = ac_input_description(p.model.scene, spec.to);

  auto write_files = [&] {
    if (!options.csv.empty()) {
      std::vector<std::string> header{"frequency_hz"};
      for (const auto& probe : probes) {
        header.push_back(probe.name + "_magnitude_" + probe.unit);
        header.push_back(probe.name + "_phase_deg");
      }
      write_csv_rows(options.csv, header, grid.size(), [&](size_t f, auto& row) {
        row.push_back(grid[f]);
        for (size_t k = 0; k < probes.size(); ++k) {
          row.push_back(std::abs(result.values[k][f]));
          row.push_back(std::arg(result.values[k][f]) * 180.0 / pi);
        }
      });
    }
    if (!ac_options.plot.empty()) {
      std::vector<emnet::BodeSeries> series;
      for (size_t k = 0; k < probes.size(); ++k)
        series.push_back(
            {probes[k].name + ": " + probes[k].description, probes[k].unit, result.values[k]});
      stop_if_interrupted();
      check_plot(emnet::write_bode_plot(ac_options.plot,
                                        p.model.scene.name + ": small-signal response", grid,
                                        series, markers, spec.log));
    }
  };
  if (options.json) {
    Json out;
    out["scene"] = p.model.scene.name;
    out["automatic_choices"] = automatic_choices_json(p.model.automatic_choices);
    out["segments"] = p.model.scene.beam.segments;
    out["input"] = input;
    out["frequencies_hz"] = grid;
    out["probes"] = Json::array();
    for (size_t k = 0; k < probes.size(); ++k) {
      std::vector<double> magnitude, phase;
      for (const auto& v : result.values[k]) {
        magnitude.push_back(std::abs(v));
        phase.push_back(std::arg(v) * 180.0 / pi);
      }
      out["probes"].push_back({{"name", probes[k].name},
                               {"description", probes[k].description},
                               {"unit", probes[k].unit},
                               {"magnitude", magnitude},
                               {"phase_deg", phase}});
    }
    out["resonances_hz"] = Json::array();
    for (const auto& m : markers) out["resonances_hz"].push_back(m.frequency_hz);
    out["accuracy"] = {{"max_relative_residual", result.max_relative_residual}};
    out["cost"] = {{"ac_seconds", result.seconds}, {"total_seconds", total}};
    if (reduction) {
      const auto& r = *reduction;
      const auto& m = r.model;
      Json errors = Json::object();
      for (size_t k = 0; k < probes.size(); ++k) errors[probes[k].name] = r.probe_errors[k];
      Json reduced = reduction_json(m, r.tolerance_met);
      reduced.update({{"clustered_poles", m.clustered_poles},
                      {"all_poles_below_cutoff_found", m.all_found},
                      {"correction_order", m.correction_order},
                      {"error_estimate", r.error_estimate},
                      {"measured_error", r.measured_error},
                      {"probe_errors", errors},
                      {"check_frequencies_hz", r.check_frequencies},
                      {"note", m.note},
                      {"cost",
                       {{"reduce_seconds", r.reduce_seconds},
                        {"evaluate_seconds", r.evaluate_seconds},
                        {"check_seconds", r.check_seconds}}}});
      out["reduction"] = reduced;
    }
    out["validity"] = validity_json(validity);
    std::cout << json_text(out) << "\n";
    write_files();
    return validity_exit(validity);
  }
  print_header(p.model, p.system);
  std::cout << input << "\n"
            << "sweep: " << grid.size() << " points, " << si(spec.from, "Hz") << " to "
            << si(spec.to, "Hz") << (spec.log ? " (log)" : " (lin)") << "\n";
  if (reduction) {
    const auto& r = *reduction;
    const auto& m = r.model;
    std::cout << "method: modal reduction with static correction: band " << si(m.band_hz, "Hz")
              << ", tolerance " << format("%.3g", m.tolerance)
              << " -> cut-off f_c = band/sqrt(tol) = " << si(m.cutoff_hz, "Hz") << "\n"
              << "  kept " << m.kept_modes << " mode(s) and " << m.kept_real_poles
              << " real pole(s) of a " << m.full_unknowns << "-unknown network (" << m.modal_method
              << "); " << m.truncated_poles
              << " computed pole(s) truncated into the static correction"
              << (m.clustered_poles ? " (" + std::to_string(m.clustered_poles) +
                                          " of them in groups repeated to rounding)"
                                    : std::string())
              << "\n";
    if (!m.note.empty()) std::cout << "  note: " << m.note << "\n";
    if (m.correction_order > 0)
      std::cout << "  the static correction is a series to s^" << m.correction_order
                << " (the truncated part's Taylor terms at s = 0, for the poles not found)\n";
    std::cout << "  error against the full model at " << r.check_frequencies.size()
              << " frequencies (5 spread over the sweep and each probe's largest response), "
                 "relative to each probe's largest |response|: "
              << format("%.3g", r.measured_error) << " (";
    for (size_t k = 0; k < probes.size(); ++k)
      std::cout << (k ? ", " : "") << probes[k].name << " " << format("%.2g", r.probe_errors[k]);
    std::cout << "); a-priori estimate " << format("%.2g", r.error_estimate) << "\n"
              << "  tolerance " << format("%.3g", m.tolerance)
              << (r.tolerance_met ? ": met" : ": NOT MET") << "\n";
    if (!r.tolerance_met) std::cout << tolerance_warning(r.measured_error, m.tolerance) << "\n";
    std::cout << "cost: reduction " << milliseconds(r.reduce_seconds) << " (poles, left vectors, "
              << (m.correction_order > 0 ? std::to_string(1 + m.correction_order) + " static solves"
                                         : std::string("one static solve"))
              << "), evaluation " << milliseconds(r.evaluate_seconds) << " (" << grid.size()
              << " points), check " << milliseconds(r.check_seconds) << " (full model, "
              << r.check_frequencies.size() << " points), total " << milliseconds(total) << "\n";
  } else {
    std::cout << "accuracy: worst relative residual of the complex solves "
              << format("%.2g", result.max_relative_residual) << "\n"
              << "cost: sweep " << milliseconds(result.seconds) << ", total " << milliseconds(total)
              << "\n";
  }
  for (const auto& m : markers) std::cout << "resonance in band: " << m.label << "\n";
  std::cout << "\n";
  std::printf("%14s", "f [Hz]");
  for (const auto& probe : probes)
    std::printf(" %16s %11s", shown("|" + probe.name + "| [" + probe.unit + "]").c_str(),
                shown(probe.name + " [deg]").c_str());
  std::printf("\n");
  for (size_t f = 0; f < grid.size(); ++f) {
    std::printf("%14.6g", grid[f]);
    for (size_t k = 0; k < probes.size(); ++k)
      std::printf(" %16.6e %11.3f", std::abs(result.values[k][f]),
                  std::arg(result.values[k][f]) * 180.0 / pi);
    std::printf("\n");
  }
  for (size_t k = 0; k < probes.size(); ++k) {
    size_t best = 0;
    for (size_t f = 0; f < grid.size(); ++f)
      if (std::abs(result.values[k][f]) > std::abs(result.values[k][best])) best = f;
    std::printf("peak of %s: %.6e %s at %.7g Hz (grid spacing limits this to +/- half a step)\n",
                shown(probes[k].name).c_str(), std::abs(result.values[k][best]),
                shown(probes[k].unit).c_str(), grid[best]);
  }
  write_files();
  if (!ac_options.plot.empty())
    std::cout << "Bode plot written to " << shown(ac_options.plot) << "\n";
  print_validity(validity);
  return validity_exit(validity);
}

// ---- tran -----------------------------------------------------------------------------

struct TranOptions {
  std::optional<double> switching;  // Hz; default: the scene's drive.frequency
  double periods = 10.0;
  double rtol = 1e-6;
  double max_step = 0.0;
  double atol = 0.0;
  std::string method = "ida";
  std::string start = "rest";
  int points_per_period = 100;
  std::string plot;
};

// Outputs of a transient: the scene's probes with P_k replaced by dx_k = P_k − P1 when a probe
// P1 exists (paper Eqs. 20–22), and each DEA's capacitor voltage and current when it has an
// electrical model (emnet/model/outputs.hpp, transient_output_list).
std::vector<emnet::Probe> transient_probes(const emnet::Model& model) {
  return emnet::probes_of(emnet::transient_output_list(model));
}

// The outputs of tran and sweep-switching: with --probe those, each an output name of
// transient_probes (dx4, u_A, ...) or any probe of parse_probe; else transient_probes.
std::vector<emnet::Probe> transient_outputs(const emnet::Model& model,
                                            const CommonOptions& options) {
  std::vector<emnet::Probe> outputs = transient_probes(model);
  if (options.probes.empty()) return outputs;
  std::vector<emnet::Probe> probes;
  for (const auto& text : options.probes) {
    const auto named = std::find_if(outputs.begin(), outputs.end(),
                                    [&](const emnet::Probe& probe) { return probe.name == text; });
    probes.push_back(named != outputs.end() ? *named : model.parse_probe(text));
  }
  return probes;
}

// The outputs a --plot draws, on one axis: the deflections by default; with --probe every probe,
// which must then share a unit (refused before computing otherwise). Deflections in mm.
struct PlottedOutputs {
  std::vector<size_t> indices;
  double scale = 1.0;
  std::string unit, axis_label;
};

PlottedOutputs plotted_outputs(const std::vector<emnet::Probe>& probes,
                               const CommonOptions& options, const std::string& quantity) {
  PlottedOutputs plotted;
  for (size_t k = 0; k < probes.size(); ++k)
    if (!options.probes.empty() || probes[k].unit == "m") plotted.indices.push_back(k);
  if (plotted.indices.empty()) return plotted;
  const emnet::Probe& first = probes[plotted.indices.front()];
  for (size_t k : plotted.indices)
    if (probes[k].unit != first.unit)
      throw InputError("--plot", "--probe",
                       "a plot has one axis, but probe '" + probes[k].name + "' is in " +
                           probes[k].unit + " and '" + first.name + "' in " + first.unit +
                           ": plot probes of one unit per run (--csv and --json take any mix)");
  plotted.unit = first.unit;
  if (first.unit == "m") {
    plotted.scale = 1e3;
    plotted.axis_label = quantity + "deflection [mm]";
  } else {
    plotted.axis_label = quantity + "value [" + first.unit + "]";
  }
  return plotted;
}

int run_tran_command(CommonOptions options, const TranOptions& tran) {
  const auto start = std::chrono::steady_clock::now();
  if (tran.switching) {
    if (!(*tran.switching > 0.0) || !std::isfinite(*tran.switching))
      throw InputError("--switching", "--switching", "must be a positive frequency in Hz (> 0)");
    options.overrides.push_back("drive.frequency=" + format("%.17g", *tran.switching));
  }
  if (!(tran.periods > 0.0) || tran.periods > 1e6)
    throw InputError("--periods", "--periods", "must be > 0 and at most 1e6 (inclusive)");
  if (!(tran.rtol >= 1e-13 && tran.rtol < 1.0))
    throw InputError("--rtol", "--rtol",
                     "must be >= 1e-13 (below that, double-precision rounding of the "
                     "residual exceeds the tolerance) and < 1");
  if (!(tran.atol >= 0.0) || !std::isfinite(tran.atol))
    throw InputError("--atol", "--atol", "must be >= 0");
  if (!(tran.max_step >= 0.0) || !std::isfinite(tran.max_step))
    throw InputError("--max-step", "--max-step", "must be >= 0 (0: no limit)");
  if (tran.points_per_period < 2 || tran.points_per_period > 100000)
    throw InputError("--points-per-period", "--points-per-period",
                     "must be from 2 to 100000 (inclusive)");
  show_phase(options, "building the network");
  const emnet::Model model = resolved_model(load_scene(options), options);
  const emnet::System system = model.network.assemble();
  const double frequency = model.scene.drive.frequency;
  if (!(frequency > 0.0))
    throw InputError(model.scene.file, "drive.frequency",
                     "a transient needs a drive with a frequency > 0 (or --switching)");
  if (tran.method == "exact" && system.is_nonlinear())
    throw InputError("--method", "--method",
                     "the exact method needs a linear network, and this scene's DEAs have their "
                     "electrical model (nonlinear); add --set drive.electrical_dynamics=false for "
                     "ideal voltage-driven DEAs, or use --method ida");
  const auto probes = transient_outputs(model, options);
  const PlottedOutputs plotted =
      tran.plot.empty() ? PlottedOutputs{} : plotted_outputs(probes, options, "");
  const double count = std::round(tran.periods * tran.points_per_period);
  if (count < 1.0)
    throw InputError("--periods", "--periods",
                     "--periods x --points-per-period must be >= 0.5, for at least one output "
                     "step after t = 0");
  check_stored_values((count + 1.0) * (probes.size() + 1.0),
                      format("%.0f", count + 1.0) + " output times x (" +
                          std::to_string(probes.size()) + " outputs + the time)",
                      "--periods", "lower --periods or --points-per-period, or give fewer --probe");
  const double period = 1.0 / frequency;
  emnet::TransientOptions transient;
  transient.end_time = tran.periods * period;
  transient.relative_tolerance = tran.rtol;
  transient.absolute_tolerance = tran.atol;
  transient.max_step = tran.max_step;
  transient.start = tran.start == "static" ? emnet::StartState::static_ : emnet::StartState::rest;
  transient.progress = progress_of(options);
  const long outputs = static_cast<long>(count);
  transient.output_times.reserve(static_cast<size_t>(outputs) + 1);
  for (long k = 0; k <= outputs; ++k)
    transient.output_times.push_back(transient.end_time * static_cast<double>(k) / outputs);
  const emnet::TransientResult result = tran.method == "exact"
                                            ? emnet::run_transient_exact(system, probes, transient)
                                            : emnet::run_transient_ida(system, probes, transient);
  if (!result.status.ok) throw NumericalFailure("tran: " + result.status.message);
  std::vector<emnet::DeflectionPeak> peaks;
  for (size_t k = 0; k < probes.size(); ++k)
    if (probes[k].quantity == emnet::ProbeQuantity::deflection) {
      peaks.push_back({probes[k].name, 0.0});
      for (double v : result.values[k])
        peaks.back().peak = std::max(peaks.back().peak, std::abs(v));
    }
  const emnet::Validity validity =
      emnet::check_validity(model.scene, peaks, emnet::drive_peak_voltages(model.scene));
  const double total = seconds_since(start);
  end_progress(options);
  const std::string start_text =
      tran.start == "static"
          ? "the static state under the drive's first half-period"
          : "at rest (every unknown zero before t = 0; the drive switches on at t = 0)";

  auto write_files = [&] {
    if (!options.csv.empty()) {
      std::vector<std::string> header{"time_s"};
      for (const auto& probe : probes) header.push_back(probe.name + "_" + probe.unit);
      write_csv_rows(options.csv, header, result.times.size(), [&](size_t i, auto& row) {
        row.push_back(result.times[i]);
        for (const auto& series : result.values) row.push_back(series[i]);
      });
    }
    if (!tran.plot.empty()) {
      std::vector<emnet::LineSeries> series;
      for (size_t k : plotted.indices) {
        emnet::LineSeries line{probes[k].name + " (" + probes[k].description + ") [" +
                                   (plotted.unit == "m" ? "mm" : plotted.unit) + "]",
                               result.times,
                               {}};
        for (double v : result.values[k]) line.y.push_back(v * plotted.scale);
        series.push_back(line);
      }
      stop_if_interrupted();
      check_plot(emnet::write_line_plot(
          tran.plot, model.scene.name + ": " + drive_summary(model.scene) + ", " + result.method,
          "time [s]", plotted.axis_label, series));
    }
  };
  const auto& st = result.statistics;
  if (options.json) {
    Json out;
    out["scene"] = model.scene.name;
    out["automatic_choices"] = automatic_choices_json(model.automatic_choices);
    out["method"] = result.method;
    out["start_state"] = start_text;
    out["switching_frequency_hz"] = frequency;
    out["periods"] = tran.periods;
    out["rtol"] = tran.rtol;
    out["times_s"] = result.times;
    out["outputs"] = Json::array();
    for (size_t k = 0; k < probes.size(); ++k)
      out["outputs"].push_back({{"name", probes[k].name},
                                {"description", probes[k].description},
                                {"unit", probes[k].unit},
                                {"values", result.values[k]}});
    out["statistics"] = {{"steps", st.steps},
                         {"residual_evaluations", st.residual_evaluations},
                         {"jacobian_evaluations", st.jacobian_evaluations},
                         {"newton_iterations", st.newton_iterations},
                         {"error_test_failures", st.error_test_failures},
                         {"convergence_failures", st.convergence_failures},
                         {"restarts", st.restarts}};
    out["cost"] = {{"integration_seconds", result.seconds}, {"total_seconds", total}};
    out["validity"] = validity_json(validity);
    std::cout << json_text(out) << "\n";
    write_files();
    return validity_exit(validity);
  }
  print_header(model, system);
  std::cout << "transient: " << shown(result.method) << ", " << format("%.6g", tran.periods)
            << " periods of " << si(frequency, "Hz") << " (" << si(transient.end_time, "s")
            << "), start " << start_text << "\n";
  if (result.method.rfind("ida", 0) == 0)
    std::cout << "accuracy: IDA (BDF) rtol " << format("%.1e", tran.rtol)
              << (tran.atol > 0 ? ", atol " + format("%.1e", tran.atol)
                                : ", atol scaled per unknown")
              << "; exact stop and restart at " << st.restarts << " switching edges\n"
              << "statistics: " << st.steps << " steps, " << st.residual_evaluations
              << " residual and " << st.jacobian_evaluations << " Jacobian evaluations, "
              << st.newton_iterations << " Newton iterations, " << st.error_test_failures
              << " error-test and " << st.convergence_failures << " convergence failures\n";
  else
    std::cout << "accuracy: exact (matrix exponential per constant interval; rounding only), "
              << st.steps << " distinct exponentials\n";
  std::cout << "cost: integration " << milliseconds(result.seconds) << ", total "
            << milliseconds(total) << "\n\n";
  std::printf("%12s", "t [s]");
  for (const auto& probe : probes)
    std::printf(" %14s", shown(probe.name + " [" + probe.unit + "]").c_str());
  std::printf("\n");
  const size_t stride = std::max<size_t>(1, result.times.size() / 200);
  for (size_t i = 0; i < result.times.size(); i += stride) {
    std::printf("%12.7g", result.times[i]);
    for (const auto& series : result.values) std::printf(" %14.6e", series[i]);
    std::printf("\n");
  }
  if (stride > 1) std::printf("(every %zu-th output shown; --csv writes all)\n", stride);
  for (size_t k = 0; k < probes.size(); ++k) {
    const auto [low, high] = std::minmax_element(result.values[k].begin(), result.values[k].end());
    std::printf("range of %-6s %14.6e .. %14.6e %s\n", shown(probes[k].name).c_str(), *low, *high,
                shown(probes[k].unit).c_str());
  }
  write_files();
  if (!tran.plot.empty()) std::cout << "plot written to " << shown(tran.plot) << "\n";
  print_validity(validity);
  return validity_exit(validity);
}

// ---- sweep-switching ------------------------------------------------------------------

struct SweepOptions {
  double from = 1.0, to = 7.0, step = 0.1;
  std::string method = "exact";
  // 0: the method's default. The exact method's extremes, reduced or not, are global whatever
  // the count (a curvature-bounded search between samples), so a few samples per period only
  // seed it; shooting refines the largest samples by a parabola.
  int samples = 0;
  double rtol = 1e-9;
  std::string plot;
  bool reduce = false;
  std::string tolerance, band;  // --reduce
};

// The reduced periodic sweep checked against the exact one at a few switching frequencies.
struct PeriodicReductionCheck {
  emnet::ModalReduction model;
  double build_seconds = 0.0;               // poles, left vectors, static solves
  std::vector<double> frequencies, errors;  // check frequencies, periodic_difference there
  double measured_error = 0.0;
  double full_build_seconds = 0.0;     // PeriodicSolver's decomposition
  double full_solve_seconds = 0.0;     // per frequency: the fastest at the check frequencies
  double reduced_solve_seconds = 0.0;  // the same for the reduced solves there
  bool tolerance_met = false;
};

// drive.overlap is in seconds: DEA A's on-time duty·T + overlap must stay inside the period
// (less the rise time at both edges) at the switching frequency `frequency_hz` too.
void check_overlap_fits(const emnet::Scene& scene, double frequency_hz, const std::string& where) {
  const auto& drive = scene.drive;
  if (drive.overlap == 0.0) return;
  const double period = 1.0 / frequency_hz, on_time = drive.duty * period + drive.overlap;
  if (!(on_time > 2.0 * drive.rise_time && on_time < period - 2.0 * drive.rise_time))
    throw InputError(scene.file, "drive.overlap",
                     si(drive.overlap, "s") + " makes DEA A's on-time leave the period " +
                         si(period, "s") + " at " + si(frequency_hz, "Hz") + " (" + where + ")");
}

// Memory of the exact periodic method's dense eigen-decomposition of the state matrix, measured
// on the fish fin: 31 MB at 306 unknowns, 104 MB at 606, 393 MB at 1206, 1.47 GB at 2406, about
// 254 bytes per unknown squared (complex eigenvectors, their LU and inverse, work space); its
// time grows as the cube (44 s at 1206 unknowns, 237 s at 2406 on this project's machine).
constexpr double kPeriodicDenseBytesPerUnknown2 = 256.0;
constexpr double kPeriodicDenseMemoryLimit = 4e9;  // bytes

void check_periodic_decomposition_size(int unknowns, const std::string& option) {
  const double bytes = kPeriodicDenseBytesPerUnknown2 * unknowns * static_cast<double>(unknowns);
  if (bytes <= kPeriodicDenseMemoryLimit) return;
  throw InputError(option, option,
                   "the exact periodic method decomposes a dense matrix of the network's " +
                       std::to_string(unknowns) + " unknowns: about " +
                       format("%.3g", bytes / 1e9) +
                       " GB (256 bytes per unknown squared), where at most " +
                       format("%.0f", kPeriodicDenseMemoryLimit / 1e9) +
                       " GB is allowed (inclusive); use fewer --segments or --method shooting");
}

int run_sweep_command(CommonOptions options, SweepOptions sweep) {
  const auto start = std::chrono::steady_clock::now();
  if (!(sweep.from > 0.0) || !(sweep.to >= sweep.from) || !(sweep.step > 0.0) ||
      !std::isfinite(sweep.to))
    throw InputError("--from/--to/--step", "--step",
                     "need 0 < from <= to and step > 0 (frequencies in Hz)");
  const double frequency_count = std::floor((sweep.to - sweep.from) / sweep.step + 1e-9) + 1.0;
  if (!(frequency_count <= 100000))
    throw InputError("--step", "--step",
                     "gives " + format("%.6g", frequency_count) +
                         " frequencies; at most 100000 (inclusive) are swept");
  const long count = static_cast<long>(frequency_count);
  if (sweep.samples == 0) sweep.samples = sweep.method == "shooting" ? 256 : 64;
  if (sweep.samples < 8 || sweep.samples > 1000000)
    throw InputError("--samples", "--samples", "must be from 8 to 1000000 (inclusive)");
  if (sweep.reduce && sweep.method != "exact")
    throw InputError("--reduce", "--method", "--reduce replaces the exact method, not shooting");
  if (!sweep.reduce && (!sweep.tolerance.empty() || !sweep.band.empty()))
    throw InputError("--tolerance/--band", "--reduce", "--tolerance and --band need --reduce");
  show_phase(options, "building the network");
  // The exact method needs a linear network: DEAs as ideal voltage-driven forces.
  emnet::Model model = resolved_model(load_scene(options), options);
  std::vector<std::string> notes;
  if (sweep.method == "exact") {
    for (const auto& text : options.probes)
      if (text.rfind("dea_voltage", 0) == 0 || text.rfind("dea_current", 0) == 0)
        throw InputError("--probe", text,
                         "the exact periodic method models the DEAs as ideal voltage-driven "
                         "forces, without the RC loop whose voltage and current this probe asks "
                         "for; use --method shooting");
    if (model.network.assemble().is_nonlinear()) {
      double tau = 0.0;
      for (const auto& dea : model.deas)
        tau = std::max(tau, dea.electrode_resistance * dea.capacitance);
      notes.push_back("exact method: DEAs as ideal voltage-driven forces (their RC time constant " +
                      si(tau, "s") + " is " + format("%.2g", tau * sweep.to) +
                      " of the shortest period); --method shooting integrates the full model");
      options.overrides.push_back("drive.electrical_dynamics=false");
      model = resolved_model(load_scene(options), options);
    }
  }
  // The default outputs: the deflections; with --probe, every probe given.
  std::vector<emnet::Probe> probes;
  for (const auto& probe : transient_outputs(model, options))
    if (!options.probes.empty() || probe.unit == "m") probes.push_back(probe);
  if (sweep.reduce)
    for (const auto& probe : probes)
      if (probe.quantity != emnet::ProbeQuantity::deflection &&
          probe.quantity != emnet::ProbeQuantity::rotation)
        throw InputError("--probe", probe.name,
                         "--reduce takes deflections and rotations only: a velocity of the "
                         "reduced model would need the derivative of the square wave's "
                         "feed-through; run without --reduce");
  if (probes.empty())
    throw InputError(model.scene.file, "probe", "the scene has no deflection output");
  const PlottedOutputs plotted =
      sweep.plot.empty() ? PlottedOutputs{} : plotted_outputs(probes, options, "peak ");
  check_stored_values(static_cast<double>(count) * (2.0 * probes.size() + 1.0),
                      std::to_string(count) + " frequencies x " + std::to_string(probes.size()) +
                          " outputs x 2 extremes",
                      "--step", "raise --step or give fewer --probe");
  if (sweep.method == "exact" && !sweep.reduce)
    check_periodic_decomposition_size(model.network.assemble().size(), "--segments");
  std::unique_ptr<emnet::PeriodicSolver> solver;
  std::unique_ptr<emnet::ReducedPeriodicSolver> reduced;
  std::optional<PeriodicReductionCheck> check;
  emnet::ReductionOptions reduction_settings;
  if (sweep.reduce) {
    reduction_settings =
        reduction_options(sweep.tolerance, sweep.band, sweep.to, model.scene.model.tolerance);
    check.emplace();
  }
  std::vector<double> frequencies;
  // Per frequency only the extremes are kept (the samples of one period are dropped).
  std::vector<emnet::PeriodicResult> results;
  const emnet::Scene base_scene = load_scene(options);  // read once; only the frequency varies
  if (!(base_scene.drive.rise_time < 0.5 / sweep.to))
    throw InputError(base_scene.file, "drive.rise_time",
                     "must be < half the shortest period of the sweep (" + si(0.5 / sweep.to, "s") +
                         " at --to " + si(sweep.to, "Hz") + ")");
  check_overlap_fits(base_scene, sweep.to, "--to");
  // Only the drive's excitation changes with the frequency: one model, its G and C assembled
  // once, the drive sources' waveforms made again per frequency (emnet::drive_excitation, the
  // same b(t) as a model built at that frequency). With drive.electrical_dynamics = "auto" left
  // in the scene the choice may change with the frequency (its default band is 10 x f): then a
  // model per frequency.
  const bool excitation_only = !base_scene.drive.electrical_dynamics_auto;
  std::optional<emnet::Model> swept_model;
  emnet::System swept;
  if (excitation_only) {
    swept_model = emnet::prepare_model(base_scene);
    swept = swept_model->network.assemble();
  }
  auto system_at = [&](double f) -> const emnet::System& {
    if (excitation_only) {
      swept.set_excitation(emnet::drive_excitation(*swept_model, swept.excitation, f));
    } else {
      emnet::Scene at = base_scene;
      at.drive.frequency = f;
      swept = emnet::prepare_model(at).network.assemble();
    }
    return swept;
  };
  // The reduced periodic state at frequency f (the sweep and its check).
  auto reduced_at = [&](const emnet::System& system, double f) {
    if (!reduced) {
      show_phase(options, "modal reduction (" + std::to_string(system.size()) + " unknowns)");
      const auto build_start = std::chrono::steady_clock::now();
      reduced = std::make_unique<emnet::ReducedPeriodicSolver>(system, reduction_settings);
      check->build_seconds = seconds_since(build_start);
      if (!reduced->reduction().status.ok)
        throw NumericalFailure("sweep-switching --reduce: " + reduced->reduction().status.message);
    }
    return reduced->solve(system, probes, 1.0 / f, sweep.samples);
  };
  for (long k = 0; k < count; ++k) {
    const double f = sweep.from + sweep.step * static_cast<double>(k);
    const emnet::System& system = system_at(f);
    if (sweep.method == "exact" && !sweep.reduce && !solver) {
      show_phase(options, "eigen-decomposition of the state matrix (" +
                              std::to_string(system.size()) +
                              " unknowns, dense; one step, no estimate inside it)");
      solver = std::make_unique<emnet::PeriodicSolver>(system);
    }
    if (!keep_going(progress_of(options), k, count, "switching frequencies"))
      throw Interrupted("interrupted");
    emnet::PeriodicResult r;
    if (sweep.reduce) {
      r = reduced_at(system, f);
    } else if (sweep.method == "exact") {
      r = solver->solve(system, probes, 1.0 / f, sweep.samples);
    } else {
      r = emnet::run_periodic_shooting(system, probes, 1.0 / f, sweep.rtol, sweep.samples,
                                       progress_of(options));
    }
    if (!r.status.ok)
      throw NumericalFailure("sweep-switching at " + si(f, "Hz") + ": " + r.status.message);
    for (size_t p = 0; p < probes.size(); ++p) {
      finite(r.minimum[p], "a peak of " + probes[p].name);
      finite(r.maximum[p], "a peak of " + probes[p].name);
    }
    r.times = {};
    r.values = {};
    frequencies.push_back(f);
    results.push_back(std::move(r));
  }
  std::vector<emnet::DeflectionPeak> peaks;
  for (size_t p = 0; p < probes.size(); ++p) {
    if (probes[p].quantity != emnet::ProbeQuantity::deflection) continue;
    peaks.push_back({probes[p].name, 0.0});
    for (const auto& r : results)
      peaks.back().peak =
          std::max({peaks.back().peak, std::abs(r.minimum[p]), std::abs(r.maximum[p])});
  }
  const emnet::Validity validity =
      emnet::check_validity(model.scene, peaks, emnet::drive_peak_voltages(model.scene));
  double solve_seconds = 0.0, worst_periodicity = 0.0;
  for (const auto& r : results) {
    solve_seconds += r.seconds;
    worst_periodicity = std::max(worst_periodicity, r.periodicity_residual);
  }
  // The resonance of the sweep: the frequency of the largest peak-to-peak at the last probe
  // (dx4 or the tip), and the network's first mode.
  const size_t main_probe = probes.size() - 1;
  size_t best = 0;
  for (size_t k = 0; k < results.size(); ++k)
    if (results[k].maximum[main_probe] - results[k].minimum[main_probe] >
        results[best].maximum[main_probe] - results[best].minimum[main_probe])
      best = k;
  if (check && !results.empty()) {
    // The full exact method at the first, the largest-swing and the last frequency, against the
    // reduced solution there (solved again: the sweep keeps no samples).
    show_phase(options, "checking the reduction against the full exact method");
    check->model = reduced->reduction();
    std::vector<size_t> picked{0, best, results.size() - 1};
    std::sort(picked.begin(), picked.end());
    picked.erase(std::unique(picked.begin(), picked.end()), picked.end());
    std::unique_ptr<emnet::PeriodicSolver> full;
    for (size_t k : picked) {
      stop_if_interrupted();
      const emnet::System& system = system_at(frequencies[k]);
      if (!full) {
        const auto build_start = std::chrono::steady_clock::now();
        full = std::make_unique<emnet::PeriodicSolver>(system);
        check->full_build_seconds = seconds_since(build_start);
      }
      const emnet::PeriodicResult exact =
          full->solve(system, probes, 1.0 / frequencies[k], sweep.samples);
      if (!exact.status.ok)
        throw NumericalFailure("sweep-switching --reduce check at " + si(frequencies[k], "Hz") +
                               ": " + exact.status.message);
      const emnet::PeriodicResult again = reduced_at(system, frequencies[k]);
      if (!again.status.ok)
        throw NumericalFailure("sweep-switching --reduce at " + si(frequencies[k], "Hz") + ": " +
                               again.status.message);
      // Per frequency: the fastest check solve (the first also fills per-probe caches).
      check->full_solve_seconds = check->full_solve_seconds > 0.0
                                      ? std::min(check->full_solve_seconds, exact.seconds)
                                      : exact.seconds;
      check->reduced_solve_seconds =
          check->reduced_solve_seconds > 0.0
              ? std::min({check->reduced_solve_seconds, results[k].seconds, again.seconds})
              : std::min(results[k].seconds, again.seconds);
      const double error = emnet::periodic_difference(again, exact);
      check->frequencies.push_back(frequencies[k]);
      check->errors.push_back(error);
      check->measured_error = std::max(check->measured_error, error);
    }
    check->tolerance_met = check->measured_error <= reduction_settings.tolerance;
  }
  std::vector<emnet::PlotMarker> markers;
  {
    show_phase(options, "modes for the resonance marker");
    const emnet::System system = model.network.assemble();
    const emnet::StaticResult rest = emnet::solve_static(system);
    emnet::ModalOptions modal;
    modal.keep_vectors = false;
    if (system.size() > modal.dense_limit) modal.count = 3;
    const auto modes = emnet::run_modes(system, rest.operating_point, modal);
    if (modes.status.ok && !modes.modes.empty())
      markers.push_back({modes.modes[0].frequency_hz,
                         "f1 = " + format("%.6g", modes.modes[0].frequency_hz) + " Hz"});
  }
  if (!results.empty())
    markers.push_back(
        {frequencies[best], "sweep peak " + format("%.6g", frequencies[best]) + " Hz"});
  const double total = seconds_since(start);
  end_progress(options);
  if (check && !check->tolerance_met)
    std::cerr << tolerance_warning(check->measured_error, reduction_settings.tolerance) << "\n";

  auto write_files = [&] {
    if (!options.csv.empty()) {
      std::vector<std::string> header{"switching_frequency_hz"};
      for (const auto& probe : probes) {
        header.push_back(probe.name + "_left_" + probe.unit);
        header.push_back(probe.name + "_right_" + probe.unit);
      }
      write_csv_rows(options.csv, header, results.size(), [&](size_t k, auto& row) {
        row.push_back(frequencies[k]);
        for (size_t p = 0; p < probes.size(); ++p) {
          row.push_back(results[k].minimum[p]);
          row.push_back(results[k].maximum[p]);
        }
      });
    }
    if (!sweep.plot.empty()) {
      const std::string unit = plotted.unit == "m" ? "mm" : plotted.unit;
      std::vector<emnet::LineSeries> series;
      for (size_t p : plotted.indices) {
        emnet::LineSeries left{probes[p].name + " left (negative) [" + unit + "]", frequencies, {}};
        emnet::LineSeries right{
            probes[p].name + " right (positive) [" + unit + "]", frequencies, {}};
        for (const auto& r : results) {
          left.y.push_back(r.minimum[p] * plotted.scale);
          right.y.push_back(r.maximum[p] * plotted.scale);
        }
        series.push_back(left);
        series.push_back(right);
      }
      stop_if_interrupted();
      check_plot(emnet::write_line_plot(
          sweep.plot,
          model.scene.name + ": periodic steady-state peak " +
              (plotted.unit == "m" ? "deflection" : "values") + " vs switching frequency",
          "switching frequency [Hz]", plotted.axis_label, series, markers));
    }
  };
  if (options.json) {
    Json out;
    out["scene"] = model.scene.name;
    out["automatic_choices"] = automatic_choices_json(model.automatic_choices);
    out["method"] = sweep.reduce ? "reduced" : sweep.method;
    out["notes"] = notes;
    out["frequencies_hz"] = frequencies;
    out["outputs"] = Json::array();
    for (size_t p = 0; p < probes.size(); ++p) {
      std::vector<double> left, right;
      for (const auto& r : results) left.push_back(r.minimum[p]), right.push_back(r.maximum[p]);
      out["outputs"].push_back({{"name", probes[p].name},
                                {"description", probes[p].description},
                                {"unit", probes[p].unit},
                                {"left", left},
                                {"right", right}});
    }
    out["sweep_peak_hz"] = results.empty() ? 0.0 : frequencies[best];
    out["accuracy"] = {{"worst_periodicity_residual", worst_periodicity}};
    out["cost"] = {{"solve_seconds", solve_seconds}, {"total_seconds", total}};
    if (check) {
      const auto& m = check->model;
      const double n = static_cast<double>(results.size());
      Json reduced = reduction_json(m, check->tolerance_met);
      reduced.update({{"check_frequencies_hz", check->frequencies},
                      {"errors", check->errors},
                      {"measured_error", check->measured_error},
                      {"cost",
                       {{"reduce_seconds", check->build_seconds},
                        {"reduced_seconds_per_frequency", check->reduced_solve_seconds},
                        {"full_decomposition_seconds", check->full_build_seconds},
                        {"full_seconds_per_frequency", check->full_solve_seconds},
                        {"reduced_sweep_seconds", check->build_seconds + solve_seconds},
                        {"full_sweep_seconds_estimated",
                         check->full_build_seconds + n * check->full_solve_seconds}}}});
      out["reduction"] = reduced;
    }
    out["validity"] = validity_json(validity);
    std::cout << json_text(out) << "\n";
    write_files();
    return validity_exit(validity);
  }
  print_header(model, model.network.assemble());
  for (const auto& note : notes) std::cout << "note: " << shown(note) << "\n";
  std::cout << "periodic steady state, " << (sweep.reduce ? "reduced" : sweep.method)
            << (sweep.reduce ? " (modal coordinates of the kept modes, closed-form periodic state, "
                               "global extremes: bounded search, then Newton)"
                : sweep.method == "exact"
                    ? " (one eigen-decomposition, closed-form periodic state, "
                      "global extremes: bounded search, then Newton)"
                    : " (Newton shooting on one period of IDA)")
            << ", " << results.size() << " switching frequencies\n"
            << "accuracy: worst periodicity residual " << format("%.2g", worst_periodicity)
            << "\ncost: periodic solves " << milliseconds(solve_seconds) << ", total "
            << milliseconds(total) << "\n";
  if (check) {
    const auto& m = check->model;
    const double n = static_cast<double>(results.size());
    const double reduced_sweep = check->build_seconds + solve_seconds;
    const double full_sweep = check->full_build_seconds + n * check->full_solve_seconds;
    std::cout << "reduced: modal coordinates of " << m.kept_modes << " mode(s) and "
              << m.kept_real_poles
              << " real pole(s) below f_c = band/tol = " << si(m.cutoff_hz, "Hz") << " (band "
              << si(m.band_hz, "Hz") << ", tolerance " << format("%.3g", m.tolerance)
              << "), static correction as a direct feed-through; " << m.full_unknowns
              << " unknowns in the full network\n"
              << "  error against the full exact periodic solution (every sample, relative to "
                 "each probe's largest |deflection|):";
    for (size_t k = 0; k < check->frequencies.size(); ++k)
      std::cout << " " << format("%.2e", check->errors[k]) << " at "
                << si(check->frequencies[k], "Hz")
                << (k + 1 < check->frequencies.size() ? "," : "");
    std::cout << "\n  tolerance " << format("%.3g", m.tolerance)
              << (check->tolerance_met ? ": met" : ": NOT MET") << "\n";
    if (!check->tolerance_met)
      std::cout << tolerance_warning(check->measured_error, m.tolerance) << "\n";
    std::cout << "  cost: reduced sweep " << milliseconds(reduced_sweep) << " (reduction "
              << milliseconds(check->build_seconds) << " + " << results.size()
              << " solves); full exact sweep, estimated from the check ("
              << milliseconds(check->full_build_seconds) << " decomposition + "
              << milliseconds(check->full_solve_seconds)
              << " per frequency): " << milliseconds(full_sweep) << " -> the reduced path is "
              << (reduced_sweep <= full_sweep
                      ? format("%.2g", full_sweep / reduced_sweep) + "x faster"
                      : format("%.2g", reduced_sweep / full_sweep) +
                            "x SLOWER (the full eigen-decomposition is small here)")
              << "\n";
  }
  std::cout << "\n";
  // Deflections in mm when every output is one (as the default outputs are); else each output in
  // its own unit, named in its column.
  bool all_deflections = true;
  for (const auto& probe : probes) all_deflections &= probe.unit == "m";
  auto column_unit = [&](const emnet::Probe& probe) {
    return all_deflections ? std::string() : " [" + probe.unit + "]";
  };
  auto in_table = [&](double value) { return all_deflections ? value * 1e3 : value; };
  std::printf("%10s", "f [Hz]");
  for (const auto& probe : probes)
    std::printf(" %12s %12s", shown(probe.name + " left" + column_unit(probe)).c_str(),
                shown(probe.name + " right" + column_unit(probe)).c_str());
  std::printf(all_deflections ? "   [mm]\n" : "\n");
  for (size_t k = 0; k < results.size(); ++k) {
    std::printf("%10.7g", frequencies[k]);
    for (size_t p = 0; p < probes.size(); ++p)
      std::printf(" %12.6g %12.6g", in_table(results[k].minimum[p]),
                  in_table(results[k].maximum[p]));
    std::printf("\n");
  }
  if (!results.empty()) {
    const std::string unit = all_deflections ? "mm" : probes[main_probe].unit;
    std::printf("largest swing of %s at %.7g Hz: %.6g %s left, %.6g %s right\n",
                shown(probes[main_probe].name).c_str(), frequencies[best],
                in_table(results[best].minimum[main_probe]), shown(unit).c_str(),
                in_table(results[best].maximum[main_probe]), shown(unit).c_str());
  }
  for (const auto& m : markers) std::cout << "marker: " << m.label << "\n";
  write_files();
  if (!sweep.plot.empty()) std::cout << "plot written to " << shown(sweep.plot) << "\n";
  print_validity(validity);
  return validity_exit(validity);
}

// ---- identify -------------------------------------------------------------------------

// The identified bending stiffness: the fixed point of EI ← EI·(target/f)², from the
// scene's value. Every trial sets its values on the scene loaded once (set_parameter,
// emnet/scene/parameters.hpp), so beam.segments = "auto" is chosen once, at the start values: the
// fit is of one network, whose N the notes print.
struct StiffnessFit {
  double stiffness = 0.0, frequency = 0.0;
  int iterations = 0;
};
StiffnessFit fit_stiffness(const CommonOptions& options, emnet::Scene scene, double target_hz,
                           int mode_number);

// --peak NAME=VALUE[@VOLTAGE]: the periodic-state peak |deflection| of probe NAME under the
// scene's drive (at VOLTAGE when given) at the switching frequency `frequency_hz`.
struct PeakTarget {
  std::string probe;
  double value = 0.0;    // [m]
  double voltage = 0.0;  // [V]; 0: the scene's drive.voltage
};

StiffnessFit fit_stiffness(const CommonOptions& options, emnet::Scene scene, double target_hz,
                           int mode_number) {
  CommonOptions trial = options;
  trial.reporter = nullptr;  // the iterations are the step shown, not each model they build
  double stiffness = emnet::get_parameter(scene, "beam.bending_stiffness");
  double frequency = 0.0;
  int iterations = 0;
  // Undamped frequencies scale as √EI exactly; damping and the electrical poles make the
  // update a fixed-point iteration, which converges in a few steps.
  for (iterations = 1; iterations <= 30; ++iterations) {
    if (!keep_going(progress_of(options), iterations - 1, 30,
                    "bending stiffness: fixed-point iterations (30 at most)"))
      throw Interrupted("interrupted");
    emnet::set_parameter(scene, "beam.bending_stiffness", stiffness);
    Prepared p = prepare(trial, false, scene);
    emnet::ModalOptions modal_options;
    modal_options.keep_vectors = false;
    if (p.system.size() > modal_options.dense_limit) modal_options.count = mode_number + 5;
    const auto modes = emnet::run_modes(p.system, p.rest.operating_point, modal_options);
    if (!modes.status.ok || static_cast<int>(modes.modes.size()) < mode_number)
      throw NumericalFailure("identify: mode " + std::to_string(mode_number) + " not found");
    frequency = modes.modes[static_cast<size_t>(mode_number - 1)].frequency_hz;
    if (std::abs(frequency - target_hz) <= 1e-10 * target_hz) break;
    stiffness *= (target_hz / frequency) * (target_hz / frequency);
  }
  return {stiffness, frequency, iterations};
}

PeakTarget parse_peak_target(const std::string& text) {
  PeakTarget target;
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw InputError("--peak", "--peak", "expected NAME=VALUE[@VOLTAGE], e.g. P4=9.3mm@4kV");
  target.probe = text.substr(0, equals);
  std::string rest = text.substr(equals + 1);
  const size_t at = rest.find('@');
  try {
    target.value = emnet::parse_quantity(rest.substr(0, at), emnet::dim::length);
    if (at != std::string::npos)
      target.voltage = emnet::parse_quantity(rest.substr(at + 1), emnet::dim::voltage);
  } catch (const std::invalid_argument& e) {
    throw InputError("--peak", "--peak", e.what());
  }
  if (!(target.value > 0.0)) throw InputError("--peak", "--peak", "the peak must be > 0");
  if (at != std::string::npos && !(target.voltage > 0.0))
    throw InputError("--peak", "--peak", "the voltage must be > 0");
  return target;
}

// The periodic extremes (minimum, maximum) of output `probe_name` of `scene` switched at
// `frequency_hz`, DEAs as ideal voltage-driven forces (the exact periodic method needs a linear
// network; the full DEA model moves the fish fin's peak at 5 Hz by 5e-4).
std::pair<double, double> periodic_extremes(emnet::Scene scene, const std::string& probe_name,
                                            double frequency_hz, const std::string& option) {
  check_overlap_fits(scene, frequency_hz, option);
  scene.drive.electrical_dynamics = false;
  scene.drive.electrical_dynamics_auto = false;
  scene.drive.frequency = frequency_hz;
  const emnet::Model model = emnet::prepare_model(scene);
  const emnet::System system = model.network.assemble();
  check_periodic_decomposition_size(system.size(), "--segments");
  std::vector<emnet::Probe> probes;
  for (const auto& probe : transient_probes(model))
    if (probe.name == probe_name) probes.push_back(probe);
  for (const auto& probe : model.probes)
    if (probes.empty() && probe.name == probe_name) probes.push_back(probe);
  if (probes.empty())
    throw InputError(option, option, "no deflection output named '" + probe_name + "'");
  const emnet::PeriodicSolver solver(system);
  const emnet::PeriodicResult r = solver.solve(system, probes, 1.0 / frequency_hz, 256);
  if (!r.status.ok) throw NumericalFailure("periodic state: " + r.status.message);
  finite(r.minimum[0], "a periodic minimum");
  finite(r.maximum[0], "a periodic maximum");
  return {r.minimum[0], r.maximum[0]};
}

// The periodic peak max(|min|, |max|) of `scene`.
double periodic_peak(const emnet::Scene& scene, const std::string& probe_name,
                     double frequency_hz) {
  const auto [minimum, maximum] = periodic_extremes(scene, probe_name, frequency_hz, "--peak");
  return std::max(std::abs(minimum), std::abs(maximum));
}

int run_identify(const CommonOptions& options, double target_hz, int mode_number,
                 const std::string& peak_text) {
  const auto start = std::chrono::steady_clock::now();
  refuse_option(!options.probes.empty(), "--probe",
                "identify has no probe outputs: it fits to --resonance, and with --peak "
                "NAME=VALUE to the peak of output NAME");
  refuse_option(!options.csv.empty(), "--csv",
                "identify prints the fitted values (or --json), not a CSV table");
  if (!(target_hz > 0.0) || !std::isfinite(target_hz))
    throw InputError("--resonance", "--resonance", "must be a positive frequency in Hz (> 0)");
  if (mode_number < 1) throw InputError("--mode", "--mode", "must be >= 1");
  // Only parameters the scene marks as identified or assumed are fitted: a value taken from the
  // paper or a data sheet is a given, not an unknown.
  std::vector<emnet::AutomaticChoice> automatic_choices;
  const emnet::Scene start_scene = load_scene(options);  // every trial sets its values on a copy
  {
    const emnet::Scene& scene = start_scene;
    automatic_choices = scene.automatic_choices;
    std::vector<std::string> fitted_keys{"beam.bending_stiffness"};
    if (!peak_text.empty()) fitted_keys.push_back("damping.loss_factor");
    for (const std::string& key : fitted_keys) {
      const auto entry = scene.provenance.find(key);
      if (entry == scene.provenance.end()) continue;
      const std::string& origin = entry->second;
      if (origin.rfind("paper", 0) == 0 || origin.rfind("data sheet", 0) == 0)
        throw InputError(scene.file, "provenance." + key,
                         "identify would fit " + key + ", which the scene takes as given (\"" +
                             origin.substr(0, origin.find(':')) +
                             "\"); only 'identified:' or 'assumed:' values are fitted");
    }
  }
  // 1. Bending stiffness to the resonance; 2. with --peak, the loss factor to the peak at the
  // resonance, then the stiffness again (the damping moves the damped frequency a little),
  // until both hold.
  emnet::Scene fitted = start_scene;  // with --peak's voltage
  StiffnessFit fit = fit_stiffness(options, start_scene, target_hz, mode_number);
  std::optional<PeakTarget> peak;
  double loss_factor = 0.0, achieved_peak = 0.0;
  int peak_rounds = 0;
  if (!peak_text.empty()) {
    peak = parse_peak_target(peak_text);
    if (!start_scene.damping.loss_factor)
      throw InputError(start_scene.file, "damping.loss_factor",
                       "--peak fits damping.loss_factor, which the scene does not set");
    loss_factor = *start_scene.damping.loss_factor;
    if (peak->voltage > 0.0) emnet::set_parameter(fitted, "drive.voltage", peak->voltage);
    auto with = [&](double eta, double stiffness) {
      emnet::Scene trial = fitted;
      emnet::set_parameter(trial, "damping.loss_factor", eta);
      emnet::set_parameter(trial, "beam.bending_stiffness", stiffness);
      return trial;
    };
    for (peak_rounds = 1; peak_rounds <= 10; ++peak_rounds) {
      // The peak falls monotonically with the loss factor: bisection in log η over [1e-5, 2].
      double low = 1e-5, high = 2.0;
      int bisection_step = 0;
      auto peak_at = [&](double eta) {
        if (!keep_going(progress_of(options), bisection_step++, 82,
                        "loss factor: round " + std::to_string(peak_rounds) +
                            " (10 at most), bisection steps (82 at most)"))
          throw Interrupted("interrupted");
        return periodic_peak(with(eta, fit.stiffness), peak->probe, target_hz);
      };
      if (peak_at(low) < peak->value || peak_at(high) > peak->value)
        throw NumericalFailure("identify --peak: no loss factor in [1e-5, 2] gives the peak " +
                               si(peak->value, "m") + " at " + si(target_hz, "Hz"));
      for (int k = 0; k < 80 && high / low > 1 + 1e-12; ++k) {
        const double middle = std::sqrt(low * high);
        (peak_at(middle) > peak->value ? low : high) = middle;
      }
      const double previous = loss_factor;
      loss_factor = std::sqrt(low * high);
      emnet::Scene trial = fitted;
      emnet::set_parameter(trial, "damping.loss_factor", loss_factor);
      const double previous_stiffness = fit.stiffness;
      fit = fit_stiffness(options, trial, target_hz, mode_number);
      achieved_peak = periodic_peak(with(loss_factor, fit.stiffness), peak->probe, target_hz);
      if (std::abs(loss_factor - previous) <= 1e-9 * loss_factor &&
          std::abs(fit.stiffness - previous_stiffness) <= 1e-9 * fit.stiffness)
        break;
    }
  }
  const double stiffness = fit.stiffness, frequency = fit.frequency;
  const int iterations = fit.iterations;
  // Validity of the periodic peak --peak prints, at the drive's levels (--peak's voltage).
  std::optional<emnet::Validity> validity;
  if (peak) {
    validity = emnet::check_validity(fitted, {{peak->probe, achieved_peak}},
                                     emnet::drive_peak_voltages(fitted));
  }
  const double total = seconds_since(start);
  end_progress(options);
  // The command that re-identifies the values, for the scene's [provenance].
  std::string command =
      "emnet identify " + options.scene_path + " --resonance " + format("%.6g", target_hz);
  if (mode_number != 1) command += " --mode " + std::to_string(mode_number);
  if (peak) command += " --peak " + peak_text;
  if (options.json) {
    Json out = {{"automatic_choices", automatic_choices_json(automatic_choices)},
                {"parameter", "beam.bending_stiffness"},
                {"value", stiffness},
                {"unit", "N*m^2"},
                {"mode", mode_number},
                {"target_hz", target_hz},
                {"achieved_hz", frequency},
                {"iterations", iterations},
                {"command", command},
                {"total_seconds", total}};
    if (peak) {
      out["loss_factor"] = loss_factor;
      out["peak_probe"] = peak->probe;
      out["target_peak_m"] = peak->value;
      out["achieved_peak_m"] = achieved_peak;
      out["peak_rounds"] = peak_rounds;
      out["validity"] = validity_json(*validity);
    }
    std::cout << json_text(out) << "\n";
    return validity ? validity_exit(*validity) : 0;
  }
  std::printf(
      "identified beam.bending_stiffness = %.6e N*m^2: mode %d at %.10g Hz (target %.6g Hz), "
      "%d iteration(s), %s\n",
      stiffness, mode_number, frequency, target_hz, iterations, milliseconds(total).c_str());
  if (peak)
    std::printf(
        "identified damping.loss_factor = %.6e: periodic peak of %s at %.6g Hz = %.6e m "
        "(target %.6g m; DEAs as ideal voltage-driven forces), %d round(s)\n",
        loss_factor, shown(peak->probe).c_str(), target_hz, achieved_peak, peak->value,
        peak_rounds);
  std::printf("scene lines:\n  bending_stiffness = \"%.6e N*m^2\"\n", stiffness);
  if (peak) std::printf("  loss_factor = %.6e\n", loss_factor);
  std::printf("provenance:\n  \"beam.bending_stiffness\" = \"identified: %s\"\n",
              shown(command).c_str());
  if (peak) std::printf("  \"damping.loss_factor\" = \"identified: %s\"\n", shown(command).c_str());
  for (const auto& choice : automatic_choices)
    std::cout << "note: " << shown(choice.reason) << "\n";
  if (validity) print_validity(*validity);
  return validity ? validity_exit(*validity) : 0;
}

// ---- mismatch ---------------------------------------------------------------------------
//
// `emnet mismatch SCENE [--frequency F] [--output NAME] [--change X]`: the left/right asymmetry
// of the periodic swing when the antagonistic pair is not identical — DEA A's electrode area
// (electrode width) or film thickness changed by ±X, or the switching overlapping (A on X·T/2
// longer, both on together) or leaving a dead time (−X·T/2). The paper (Sect. 3) explains its
// larger left-side deflection by such tolerances.
//
// Asymmetry = (|left| − right) / ((|left| + right)/2), left = the negative side: > 0 when the
// swing is larger to the left. In the linear network a mismatch adds a constant force to the
// symmetric square wave: a static offset that the resonance does not amplify.

struct MismatchOptions {
  std::optional<double> frequency;  // default: the scene's drive.frequency
  std::string output;               // "": the last deflection output (dx4 on the fish fin)
  double change = 0.05;
};

int run_mismatch_command(const CommonOptions& options, const MismatchOptions& cmd) {
  const auto start = std::chrono::steady_clock::now();
  refuse_option(!options.probes.empty(), "--probe",
                "mismatch compares one deflection output: name it with --output");
  refuse_option(!options.csv.empty(), "--csv",
                "mismatch prints its table (or --json), not a CSV file");
  const emnet::Scene scene = load_scene(options);
  if (scene.drive.kind != emnet::DriveKind::antagonistic || scene.drive.deas.size() != 2)
    throw InputError(scene.file, "drive.kind",
                     "mismatch needs the antagonistic drive of two DEAs (drive.kind = "
                     "\"antagonistic\", drive.deas = [A, B])");
  if (!(cmd.change > 0.0 && cmd.change < 0.5))
    throw InputError("--change", "--change", "must be > 0 and < 0.5 (a fraction)");
  const double frequency = cmd.frequency.value_or(scene.drive.frequency);
  if (!(frequency > 0.0) || !std::isfinite(frequency))
    throw InputError(cmd.frequency ? "--frequency" : scene.file,
                     cmd.frequency ? "--frequency" : "drive.frequency",
                     "must be a positive frequency in Hz (> 0)");
  std::string output = cmd.output;
  if (output.empty()) {
    const emnet::Model model = emnet::prepare_model(scene);
    // The last speckle-point difference dx_k (the paper measures dx4), else the last deflection.
    const std::vector<emnet::ModelOutput> outputs = emnet::transient_output_list(model);
    const emnet::ModelOutput* chosen = emnet::default_deflection_output(outputs);
    if (!chosen) throw InputError(scene.file, "probe", "the scene has no deflection output");
    output = chosen->probe.name;
  }
  const std::string& dea_name = scene.drive.deas[0];
  size_t dea = scene.deas.size();
  for (size_t k = 0; k < scene.deas.size(); ++k)
    if (scene.deas[k].name == dea_name) dea = k;
  if (dea == scene.deas.size())
    throw InputError(scene.file, "drive.deas", "no DEA named '" + dea_name + "'");

  struct Case {
    std::string label, key;
    std::function<void(emnet::Scene&, double)> apply;  // change by the fraction x
  };
  const double half_period = 0.5 / frequency;
  const std::vector<Case> cases = {
      {"electrode area of " + dea_name, "dea." + dea_name + ".electrode_width",
       [dea](emnet::Scene& s, double x) { s.deas[dea].electrode_width *= 1.0 + x; }},
      {"film thickness of " + dea_name, "dea." + dea_name + ".dielectric_thickness",
       [dea](emnet::Scene& s, double x) { s.deas[dea].dielectric_thickness *= 1.0 + x; }},
      {"switching overlap (of T/2)", "drive.overlap",
       [half_period](emnet::Scene& s, double x) { s.drive.overlap = x * half_period; }},
  };
  auto asymmetry = [](std::pair<double, double> extremes) {
    const double left = std::abs(extremes.first), right = extremes.second;
    return (left - right) / (0.5 * (left + right));
  };
  const long solves = 1 + 2 * static_cast<long>(cases.size());
  if (!keep_going(progress_of(options), 0, solves, "periodic solves"))
    throw Interrupted("interrupted");
  const auto nominal = periodic_extremes(scene, output, frequency, "--output");
  struct Row {
    std::string label, key;
    double change;
    std::pair<double, double> extremes;
    double asymmetry;
  };
  std::vector<Row> rows;
  for (const Case& c : cases)
    for (const double x : {-cmd.change, cmd.change}) {
      emnet::Scene changed = scene;
      c.apply(changed, x);
      if (!keep_going(progress_of(options), static_cast<long>(rows.size()) + 1, solves,
                      "periodic solves"))
        throw Interrupted("interrupted");
      const auto extremes = periodic_extremes(changed, output, frequency, "--output");
      rows.push_back({c.label, c.key, x, extremes, asymmetry(extremes)});
    }
  std::vector<emnet::DeflectionPeak> peaks{
      {output, std::max(std::abs(nominal.first), std::abs(nominal.second))}};
  for (const Row& row : rows)
    peaks.push_back({output + " (" + row.label + " " + format("%+.3g", 100.0 * row.change) + " %)",
                     std::max(std::abs(row.extremes.first), std::abs(row.extremes.second))});
  const emnet::Validity validity =
      emnet::check_validity(scene, peaks, emnet::drive_peak_voltages(scene));
  const double total = seconds_since(start);
  end_progress(options);
  if (options.json) {
    Json out = {{"automatic_choices", automatic_choices_json(scene.automatic_choices)},
                {"output", output},
                {"frequency_hz", frequency},
                {"nominal", {{"left_m", nominal.first}, {"right_m", nominal.second}}},
                {"cases", Json::array()},
                {"total_seconds", total}};
    for (size_t k = 0; k < rows.size(); ++k)
      out["cases"].push_back({{"key", rows[k].key},
                              {"change", rows[k].change},
                              {"left_m", rows[k].extremes.first},
                              {"right_m", rows[k].extremes.second},
                              {"asymmetry", rows[k].asymmetry},
                              {"asymmetry_per_unit_change", rows[k].asymmetry / cmd.change}});
    out["validity"] = validity_json(validity);
    std::cout << json_text(out) << "\n";
    return validity_exit(validity);
  }
  std::printf(
      "scene %s: left/right asymmetry of %s switched at %s, DEAs as ideal voltage-driven "
      "forces\n",
      shown(scene.name).c_str(), shown(output).c_str(), si(frequency, "Hz").c_str());
  std::printf("asymmetry = (|left| - right) / mean, > 0: larger to the left (negative) side\n");
  std::printf("accuracy: exact periodic states, extremes to 1e-11 of the peak\n");
  std::printf("cost: %d periodic solves, total %s\n", static_cast<int>(rows.size()) + 1,
              milliseconds(total).c_str());
  for (const auto& choice : scene.automatic_choices)
    std::cout << "note: " << shown(choice.reason) << "\n";
  std::printf("\n");
  std::printf("%-28s %8s %12s %12s %12s %16s\n", "mismatch", "change", "left [mm]", "right [mm]",
              "asymmetry", "per 1 % change");
  std::printf("%-28s %8s %12.6g %12.6g %11.4f%% %16s\n", "none", "", nominal.first * 1e3,
              nominal.second * 1e3, 100.0 * asymmetry(nominal), "");
  for (const Row& row : rows)  // asymmetry [%] per 1 % of change = asymmetry / |change|
    std::printf("%-28s %+7.1f%% %12.6g %12.6g %11.4f%% %15.6g%%\n", shown(row.label).c_str(),
                100.0 * row.change, row.extremes.first * 1e3, row.extremes.second * 1e3,
                100.0 * row.asymmetry, row.asymmetry / cmd.change);
  print_validity(validity);
  return validity_exit(validity);
}

// ---- sensitivity ------------------------------------------------------------------------
//
// `emnet sensitivity SCENE [--modes K] [--parameter KEY ...] [--check]`: df/dp of the first K
// resonances for every scene parameter, from the eigenvectors
// (include/emnet/studies/sensitivity.hpp), and with --check the finite-difference reference.

struct SensitivityCommandOptions {
  int modes = 3;
  std::vector<std::string> parameters;
  bool check = false;
};

int run_sensitivity_command(const CommonOptions& options, const SensitivityCommandOptions& cmd) {
  const auto start = std::chrono::steady_clock::now();
  refuse_option(!options.probes.empty(), "--probe",
                "sensitivity differentiates resonance frequencies, not probe outputs");
  refuse_option(!options.csv.empty(), "--csv",
                "sensitivity prints its table (or --json), not a CSV file");
  if (cmd.modes < 1) throw InputError("--modes", "--modes", "must be >= 1");
  const emnet::Scene scene = load_scene(options);
  emnet::SensitivityOptions sensitivity_options;
  sensitivity_options.modes = cmd.modes;
  sensitivity_options.check = cmd.check;
  sensitivity_options.progress = progress_of(options);
  const emnet::SensitivityResult result =
      emnet::run_sensitivity(scene, cmd.parameters, sensitivity_options);
  if (!result.status.ok) throw NumericalFailure("sensitivity: " + result.status.message);
  for (const auto& parameter : result.parameters)
    for (const auto& mode : parameter.modes) {
      finite(mode.frequency_derivative, "df/d" + parameter.parameter.key);
      finite(mode.normalised, "the normalised sensitivity to " + parameter.parameter.key);
    }
  const double total = seconds_since(start);
  end_progress(options);
  const auto& modes = result.modes;
  if (options.json) {
    Json out;
    out["scene"] = scene.name;
    out["automatic_choices"] = automatic_choices_json(scene.automatic_choices);
    out["segments"] = scene.beam.segments;
    out["modes"] = Json::array();
    for (const auto& mode : modes)
      out["modes"].push_back({{"frequency_hz", mode.frequency_hz},
                              {"natural_frequency_hz", mode.natural_frequency_hz},
                              {"pole", {mode.pole.real(), mode.pole.imag()}}});
    out["parameters"] = Json::array();
    for (const auto& parameter : result.parameters) {
      Json entry = {{"key", parameter.parameter.key},
                    {"value", parameter.parameter.value},
                    {"unit", parameter.parameter.unit},
                    {"modes", Json::array()}};
      for (const auto& s : parameter.modes) {
        Json mode = {{"pole_derivative", {s.pole_derivative.real(), s.pole_derivative.imag()}},
                     {"frequency_derivative", s.frequency_derivative},
                     {"natural_frequency_derivative", s.natural_frequency_derivative},
                     {"normalised", s.normalised},
                     {"normalised_natural", s.normalised_natural}};
        if (cmd.check) {
          mode["finite_difference_pole_derivative"] = {s.finite_difference_pole_derivative.real(),
                                                       s.finite_difference_pole_derivative.imag()};
          mode["check_difference"] = s.check_difference;
          mode["check_error_estimate"] = s.check_error_estimate;
        }
        entry["modes"].push_back(mode);
      }
      out["parameters"].push_back(entry);
    }
    out["left_vector_residual"] = result.left_vector_residual;
    out["cost"] = {{"sensitivity_seconds", result.seconds - result.check_seconds},
                   {"check_seconds", result.check_seconds},
                   {"total_seconds", total}};
    std::cout << json_text(out) << "\n";
    return 0;
  }
  std::cout << "scene " << shown(scene.name) << " (" << shown(scene.file)
            << "): " << scene.beam.segments << " segments\n";
  for (const auto& choice : scene.automatic_choices)
    std::cout << "note: " << shown(choice.reason) << "\n";
  std::cout << "modes:";
  for (size_t k = 0; k < modes.size(); ++k)
    std::printf(" f%zu = %.7g Hz (natural %.7g Hz)%s", k + 1, modes[k].frequency_hz,
                modes[k].natural_frequency_hz, k + 1 < modes.size() ? "," : "\n");
  std::cout << "method: first-order eigenvalue perturbation, ds/dp = -y^H (dG/dp + s dC/dp) x / "
               "(y^H C x), matrices differenced at p(1 +/- 1e-6); left-vector residual "
            << format("%.2g", result.left_vector_residual) << "\n"
            << "columns per mode: df/dp of the damped frequency [Hz per unit], S = (p/f) df/dp [-]"
            << (cmd.check ? ", and the check: |dS analytic - FD| (FD error estimate), FD of the "
                            "poles at p(1 +/- 1e-4)"
                          : "")
            << "\ncost: " << milliseconds(result.seconds - result.check_seconds)
            << (cmd.check ? ", check " + milliseconds(result.check_seconds) : "") << ", total "
            << milliseconds(total) << "\n\n";
  std::printf("%-32s %13s %-6s", "parameter", "value", "unit");
  for (size_t k = 0; k < modes.size(); ++k) {
    std::printf(" %13s %9s", ("df" + std::to_string(k + 1) + "/dp").c_str(),
                ("S" + std::to_string(k + 1)).c_str());
    if (cmd.check) std::printf(" %19s", "check");
  }
  std::printf("\n");
  for (const auto& parameter : result.parameters) {
    std::printf("%-32s %13.6g %-6s", shown(parameter.parameter.key).c_str(),
                parameter.parameter.value, shown(parameter.parameter.unit).c_str());
    for (const auto& s : parameter.modes) {
      // |S| below 1e-12 is rounding of an exact zero (a parameter the modes do not see).
      const bool zero = std::abs(s.normalised) < 1e-12;
      std::printf(" %13.5g %+9.6g", zero ? 0.0 : s.frequency_derivative, zero ? 0.0 : s.normalised);
      if (cmd.check) std::printf(" %8.1e (%8.1e)", s.check_difference, s.check_error_estimate);
    }
    std::printf("\n");
  }
  return 0;
}

void add_common(CLI::App* command, CommonOptions& options);

// ---- netlist: SPICE export ------------------------------------------------------------
//
// `emnet netlist SCENE --analysis op|ac|tran [-o FILE.cir]`: the scene's network as a SPICE3
// deck (src/spice/spice_netlist.cpp; include/emnet/spice/spice_netlist.hpp explains the mapping).
// The ac options are those of `emnet ac`, the tran options those of `emnet tran`, plus the deck's
// own max step and reltol.

struct NetlistOptions {
  std::string analysis;
  std::string output;  // empty: standard output
  bool control = false;
  // ac, as `emnet ac`
  std::string from_text, to_text;
  std::optional<int> points;
  std::string scale;
  // tran, as `emnet tran`
  std::optional<double> switching;  // default: the scene's drive.frequency
  double periods = 10.0;
  std::string start = "rest";
  int points_per_period = 100;
  double max_step = 0.0;  // s; 0: the output step
  double reltol = 1e-6;
};

int run_netlist_command(CommonOptions options, const NetlistOptions& netlist) {
  if (!options.csv.empty())
    throw InputError("--csv", "--csv", "netlist writes a deck (-o), not a CSV table");
  if (options.json && netlist.output.empty())
    throw InputError("--json", "--json",
                     "--json prints the deck's vector map; give the deck a file with -o");
  emnet::SpiceDeckOptions deck_options;
  deck_options.analysis = netlist.analysis == "ac"     ? emnet::SpiceAnalysis::ac
                          : netlist.analysis == "tran" ? emnet::SpiceAnalysis::tran
                                                       : emnet::SpiceAnalysis::op;
  deck_options.control = netlist.control;
  if (deck_options.analysis == emnet::SpiceAnalysis::tran) {
    if (netlist.switching) {
      if (!(*netlist.switching > 0.0) || !std::isfinite(*netlist.switching))
        throw InputError("--switching", "--switching", "must be a positive frequency in Hz (> 0)");
      options.overrides.push_back("drive.frequency=" + format("%.17g", *netlist.switching));
    }
    if (!(netlist.periods > 0.0) || netlist.periods > 1e6)
      throw InputError("--periods", "--periods", "must be > 0 and at most 1e6 (inclusive)");
    if (netlist.points_per_period < 2 || netlist.points_per_period > 100000)
      throw InputError("--points-per-period", "--points-per-period",
                       "must be from 2 to 100000 (inclusive)");
    if (!(netlist.reltol > 0.0 && netlist.reltol < 1.0))
      throw InputError("--reltol", "--reltol", "must be > 0 and < 1");
    if (!(netlist.max_step >= 0.0) || !std::isfinite(netlist.max_step))
      throw InputError("--max-step", "--max-step", "must be >= 0 s");
  }
  const std::vector<std::string> shown_overrides = overrides_with_segments(options);
  emnet::Scene scene = load_scene(options);
  if (deck_options.analysis == emnet::SpiceAnalysis::ac)
    deck_options.ac = checked_ac_spec(scene.ac, netlist.from_text, netlist.to_text, netlist.points,
                                      netlist.scale);
  const emnet::Model model = resolved_model(scene, options);
  deck_options.overrides = shown_overrides;
  if (!options.probes.empty()) deck_options.outputs = selected_probes(model, options);
  if (deck_options.analysis == emnet::SpiceAnalysis::tran) {
    const double frequency = model.scene.drive.frequency;
    if (!(frequency > 0.0))
      throw InputError(model.scene.file, "drive.frequency",
                       "a transient needs a drive with a frequency (or --switching)");
    const double period = 1.0 / frequency;
    deck_options.end_time = netlist.periods * period;
    deck_options.output_step = period / netlist.points_per_period;
    deck_options.max_step = netlist.max_step;
    deck_options.relative_tolerance = netlist.reltol;
    deck_options.start =
        netlist.start == "static" ? emnet::StartState::static_ : emnet::StartState::rest;
    if (deck_options.start == emnet::StartState::static_)
      deck_options.static_state = emnet::solve_static(model.network.assemble());
  }
  const emnet::SpiceDeck deck = emnet::write_spice_deck(model, deck_options);
  // What the deck asks ngspice to store: every output at every output step (or frequency).
  const double deck_outputs = static_cast<double>(deck.outputs.size()) + 1.0;
  if (deck_options.analysis == emnet::SpiceAnalysis::tran)
    check_stored_values(
        (std::round(netlist.periods * netlist.points_per_period) + 1.0) * deck_outputs,
        "the deck's transient (" + format("%.6g", netlist.periods) + " periods x " +
            std::to_string(netlist.points_per_period) + " output steps, " +
            std::to_string(deck.outputs.size()) + " outputs) in ngspice",
        "--periods", "lower --periods or --points-per-period, or give fewer --probe");
  if (deck_options.analysis == emnet::SpiceAnalysis::ac)
    check_stored_values(deck_options.ac->points * 2.0 * deck_outputs,
                        "the deck's AC sweep (" + std::to_string(deck_options.ac->points) +
                            " frequencies, " + std::to_string(deck.outputs.size()) +
                            " complex outputs) in ngspice",
                        "--points", "lower --points or give fewer --probe");
  if (netlist.output.empty()) {
    std::cout << deck.text;
    return 0;
  }
  stop_if_interrupted();
  if (const emnet::Status status = emnet::write_output_file(netlist.output, deck.text); !status.ok)
    throw FileError("-o: " + status.message);
  if (options.json) {
    const emnet::System system = model.network.assemble();
    Json out;
    out["deck"] = netlist.output;
    out["automatic_choices"] = automatic_choices_json(model.automatic_choices);
    out["analysis"] = emnet::spice_analysis_name(deck.analysis);
    out["unknowns"] = Json::array();
    for (size_t k = 0; k < deck.unknowns.size(); ++k)
      out["unknowns"].push_back({{"name", system.unknowns[k].name},
                                 {"vector", deck.unknowns[k].vector},
                                 {"sign", deck.unknowns[k].sign}});
    out["outputs"] = Json::array();
    for (const auto& o : deck.outputs)
      out["outputs"].push_back({{"probe", o.probe},
                                {"vector", o.vector},
                                {"unit", o.unit},
                                {"description", o.description}});
    out["notes"] = deck.notes;
    std::cout << json_text(out) << "\n";
    return 0;
  }
  std::cout << "SPICE deck (" << emnet::spice_analysis_name(deck.analysis) << ") written to "
            << shown(netlist.output) << ": " << deck.outputs.size() << " outputs\n";
  for (const auto& note : deck.notes) std::cout << "note: " << shown(note) << "\n";
  return 0;
}

void add_netlist_command(CLI::App& app, CommonOptions& options, NetlistOptions& netlist,
                         CLI::App*& command) {
  command = app.add_subcommand(
      "netlist",
      "write the scene's network as a SPICE3 deck (ngspice runs it unchanged; LTspice reads\n"
      "it): op = the static network in displacements, ac = the small-signal input of\n"
      "`emnet ac`, tran = the drive's time functions from the start state of `emnet tran`");
  add_common(command, options);
  command->add_option("--analysis", netlist.analysis, "op, ac or tran")
      ->required()
      ->check(CLI::IsMember({"op", "ac", "tran"}));
  command->add_option("-o,--output", netlist.output, "deck file (default: standard output)");
  command->add_flag("--control", netlist.control,
                    "append an ngspice-only .control block (run, wrdata of the outputs)");
  command->add_option("--from", netlist.from_text, "ac: start frequency [Hz] (scene ac.from)");
  command->add_option("--to", netlist.to_text, "ac: stop frequency [Hz] (scene ac.to)");
  command->add_option("--points", netlist.points, "ac: number of frequencies (scene ac.points)");
  command->add_option("--scale", netlist.scale, "ac: lin or log")
      ->check(CLI::IsMember({"lin", "log"}));
  command->add_option("--switching", netlist.switching,
                      "tran: switching frequency [Hz] (default: the scene's drive.frequency)");
  command->add_option("--periods", netlist.periods, "tran: number of periods (default 10)");
  command
      ->add_option("--start", netlist.start,
                   "tran: rest (default) or static (the static state under the first "
                   "half-period's drive)")
      ->check(CLI::IsMember({"rest", "static"}));
  command->add_option("--points-per-period", netlist.points_per_period,
                      "tran: output step = period / this (default 100)");
  command->add_option("--max-step", netlist.max_step,
                      "tran: largest time step of the deck [s] (default: the output step)");
  command->add_option("--reltol", netlist.reltol, "tran: the deck's .options reltol (1e-6)");
}

// ---- end of netlist --------------------------------------------------------------------

// ---- crosscheck: emnet against ngspice -------------------------------------------------
//
// `emnet crosscheck SCENE [--analysis op,ac,modal,tran]`: exports the decks, runs ngspice
// (include/emnet/spice/ngspice_runner.hpp) and compares with emnet's own analyses
// (include/emnet/verification/crosscheck.hpp says what is compared and why each tolerance). Exit
// status 0 when every difference is within its tolerance, 4 when one is not, 3 when ngspice is
// missing, fails or times out, or an emnet analysis fails.

struct CrosscheckCommandOptions {
  std::string analyses = "all";
  double timeout = 60.0;
  std::string backend = "auto";
  std::string keep_decks;
  std::string program;  // empty: "ngspice"
  double periods = 2.0;
  int points_per_period = 2000;
  double reltol = 1e-6;
};

int run_crosscheck_command(CommonOptions options, const CrosscheckCommandOptions& cross) {
  const auto start = std::chrono::steady_clock::now();
  if (!options.csv.empty())
    throw InputError("--csv", "--csv", "crosscheck prints a table (or --json), not a CSV file");
  if (!options.probes.empty())
    throw InputError("--probe", "--probe", "crosscheck compares every output of the decks");
  if (!(cross.timeout > 0.0) || cross.timeout > 86400.0)
    throw InputError("--timeout", "--timeout", "must be > 0 s and at most 86400 s (inclusive)");
  emnet::CrosscheckOptions check;
  check.analyses = emnet::parse_crosscheck_analyses(cross.analyses, "--analysis");
  check.ngspice.timeout_seconds = cross.timeout;
  check.ngspice.backend = cross.backend == "library"   ? emnet::NgspiceBackend::library
                          : cross.backend == "program" ? emnet::NgspiceBackend::program
                                                       : emnet::NgspiceBackend::automatic;
  if (!cross.program.empty()) check.ngspice.program = cross.program;
  check.keep_decks_directory = cross.keep_decks;
  check.tran_periods = cross.periods;
  check.tran_reltol = cross.reltol;
  check.tran_points_per_period = cross.points_per_period;
  check.overrides = overrides_with_segments(options);
  const emnet::Model model = resolved_model(load_scene(options), options);
  show_phase(options, "ngspice and emnet analyses");
  const emnet::CrosscheckReport report = emnet::run_crosscheck(model, check);
  stop_if_interrupted();
  const double total = seconds_since(start);
  end_progress(options);
  const bool pass = report.all_pass();
  if (options.json) {
    Json out;
    out["scene"] = model.scene.name;
    out["automatic_choices"] = automatic_choices_json(model.automatic_choices);
    out["backend"] = report.backend;
    out["status"] = report.status.ok ? "ok" : "failure";
    if (!report.status.ok) out["failure"] = report.status.message;
    out["pass"] = pass;
    out["rows"] = Json::array();
    for (const auto& row : report.rows)
      out["rows"].push_back(
          {{"analysis", emnet::crosscheck_analysis_name(row.analysis)},
           {"quantity", row.quantity},
           {"largest_difference",
            std::isfinite(row.largest_difference) ? Json(row.largest_difference) : Json(nullptr)},
           {"where", row.where},
           {"tolerance", row.tolerance},
           {"pass", row.pass},
           {"basis", row.basis}});
    out["timings"] = Json::array();
    for (const auto& t : report.timings)
      out["timings"].push_back({{"analysis", emnet::crosscheck_analysis_name(t.analysis)},
                                {"ngspice_seconds", t.ngspice_seconds},
                                {"ngspice_total_seconds", t.ngspice_total_seconds},
                                {"emnet_seconds", t.emnet_seconds},
                                {"emnet_what", t.emnet_what}});
    out["notes"] = report.notes;
    out["total_seconds"] = total;
    std::cout << json_text(out) << "\n";
  } else {
    const emnet::System system = model.network.assemble();
    print_header(model, system);
    std::cout << "ngspice backend: "
              << (report.backend.empty() ? "(none ran)" : shown(report.backend)) << "\n\n";
    std::printf("%-6s %-38s %11s %10s %-4s  %s\n", "", "quantity", "largest", "tolerance", "",
                "where");
    for (const auto& row : report.rows)
      std::printf("%-6s %-38s %11.3e %10.1e %-4s  %s\n",
                  emnet::crosscheck_analysis_name(row.analysis), shown(row.quantity).c_str(),
                  row.largest_difference, row.tolerance, row.pass ? "pass" : "FAIL",
                  shown(row.where).c_str());
    std::cout << "\ndifferences relative to:\n";
    for (const auto& row : report.rows)
      std::cout << "  " << emnet::crosscheck_analysis_name(row.analysis) << " "
                << shown(row.quantity) << ": " << shown(row.basis) << "\n";
    if (!report.timings.empty()) {
      std::cout << "\nwall time, same run:\n";
      std::printf("%-6s %12s %12s %12s  %s\n", "", "ngspice", "(+ start)", "emnet", "emnet did");
      for (const auto& t : report.timings)
        std::printf("%-6s %12s %12s %12s  %s\n", emnet::crosscheck_analysis_name(t.analysis),
                    milliseconds(t.ngspice_seconds).c_str(),
                    milliseconds(t.ngspice_total_seconds).c_str(),
                    milliseconds(t.emnet_seconds).c_str(), shown(t.emnet_what).c_str());
    }
    for (const auto& note : report.notes) std::cout << "note: " << shown(note) << "\n";
    std::cout << "total " << milliseconds(total) << "\n";
  }
  if (!report.status.ok) {
    std::cerr << "emnet: crosscheck failed: " << emnet::terminal_lines(report.status.message)
              << "\n";
    return 3;
  }
  if (!pass) {
    std::cerr << "emnet: crosscheck: a difference exceeds its tolerance (exit 4)\n";
    return 4;
  }
  if (!options.json) std::cout << "crosscheck passed\n";
  return 0;
}

void add_crosscheck_command(CLI::App& app, CommonOptions& options, CrosscheckCommandOptions& cross,
                            CLI::App*& command) {
  command = app.add_subcommand(
      "crosscheck",
      "export the scene's decks, run them in ngspice and compare with emnet: op (every node),\n"
      "ac (magnitude and phase at every frequency), modal (modes against ngspice's AC peaks),\n"
      "tran (emnet's exact solution against ngspice at reltol 1e-6).\n"
      "Exit status: 0 every difference within its tolerance; 4 one exceeds it; 3 ngspice\n"
      "missing, failing or timed out, or an emnet analysis failed; 2 bad input.");
  add_common(command, options);
  command->add_option("--analysis", cross.analyses,
                      "comma-separated subset of op,ac,modal,tran (default: all)");
  command->add_option("--timeout", cross.timeout,
                      "wall-clock limit per ngspice run [s] (default 60)");
  command
      ->add_option("--backend", cross.backend,
                   "auto (libngspice, else the ngspice program), library or program")
      ->check(CLI::IsMember({"auto", "library", "program"}));
  command->add_option("--ngspice-program", cross.program,
                      "the ngspice program of the program backend (default: ngspice in PATH)");
  command->add_option("--keep-decks", cross.keep_decks,
                      "also write the decks that were run into this directory");
  command->add_option("--periods", cross.periods,
                      "tran: periods of the drive (or of the first mode) to compare (default 2)");
  command->add_option("--points-per-period", cross.points_per_period,
                      "tran: ngspice's max step = period / this (default 2000)");
  command->add_option("--reltol", cross.reltol, "tran: ngspice's reltol (default 1e-6)");
}

// ---- end of crosscheck -----------------------------------------------------------------

void add_common(CLI::App* command, CommonOptions& options) {
  command->add_option("scene", options.scene_path, "scene file (TOML), e.g. netlists/fishfin.toml")
      ->required();
  command->add_option("--segments", options.segments,
                      "number of beam segments, >= 1 (same as --set beam.segments=N)");
  command
      ->add_option("--set", options.overrides,
                   "override a scene key: --set beam.length=0.2 or --set \"drive.voltage=3 kV\"")
      ->allow_extra_args(false);
  command
      ->add_option("--probe", options.probes,
                   "output: a probe name of the scene, QUANTITY@POSITION "
                   "(deflection, velocity, rotation, angular_velocity; e.g. deflection@70mm) or "
                   "dea_voltage:NAME / dea_current:NAME")
      ->allow_extra_args(false);
  command->add_flag("--json", options.json, "print machine-readable JSON instead of tables");
  command->add_option("--csv", options.csv, "also write the result table to this CSV file");
  auto* progress = command->add_flag(
      "--progress", options.progress,
      "show progress on standard error also when it is not a terminal (a line per step "
      "and per second)");
  command
      ->add_flag("--quiet", options.quiet,
                 "no progress line (by default shown on a terminal for runs over a second)")
      ->excludes(progress);
}

}  // namespace

// ---- schema ------------------------------------------------------------------------------
//
// `emnet schema [--markdown | --json]`: the scene's parameter table (emnet/scene/parameters.hpp),
// every key with its unit, default, range, users and meaning; no scene is read.

struct SchemaOptions {
  bool markdown = false;
  bool json = false;
};

CLI::App* add_schema_command(CLI::App& app, SchemaOptions& schema) {
  CLI::App* command = app.add_subcommand(
      "schema",
      "every scene key: its unit, default, range, which drive kinds or components use it and\n"
      "what it means (a text table; --markdown or --json)");
  auto* markdown = command->add_flag("--markdown", schema.markdown, "a Markdown table");
  command->add_flag("--json", schema.json, "a JSON array, one object per key")->excludes(markdown);
  return command;
}

int run_schema_command(const SchemaOptions& schema) {
  if (schema.markdown) {
    std::cout << emnet::parameter_listing_markdown();
  } else if (schema.json) {
    Json keys = Json::array();
    for (const auto& row : emnet::parameter_listing())
      keys.push_back({{"key", row.key},
                      {"kind", row.kind},
                      {"unit", row.unit},
                      {"default", row.default_text},
                      {"required", row.required},
                      {"range", row.range},
                      {"used_by", row.used_by},
                      {"meaning", row.meaning},
                      {"sensitivity", row.sensitivity}});
    std::cout << json_text(Json{{"keys", keys}}) << "\n";
  } else {
    std::cout << emnet::parameter_listing_text();
  }
  return 0;
}

int main(int argc, char** argv) {
  CLI::App app{
      "emnet: lumped electromechanical network simulator.\n"
      "Euler-Bernoulli beams cut into N segments, driven by dielectric elastomer actuators, as\n"
      "Firestone (mobility) networks: force = current, velocity = voltage."};
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 success; 2 bad input; 3 numerical failure; 4 crosscheck: a difference\n"
      "exceeds its tolerance; 5 computed but outside the model's validity (a deflection above\n"
      "model.deflection_limit of the beam length, default 10 %, or a DEA's field V/d above\n"
      "dea[].breakdown_field): printed with a WARNING and \"validity\" in --json.");
  CommonOptions options;

  auto* static_command = app.add_subcommand(
      "static", "deflection and rotation at every node at rest, and at the probes");
  add_common(static_command, options);

  ModesOptions modes_options;
  auto* modes_command = app.add_subcommand(
      "modes", "poles of the network: frequency, damping ratio, mode shape along the beam");
  add_common(modes_command, options);
  modes_command->add_option("--count", modes_options.count,
                            "number of modes to show (default: every pole for small networks, "
                            "the 20 lowest for large ones)");
  modes_command->add_flag("--shapes", modes_options.shapes, "print the mode shapes");
  modes_command->add_flag("--dense", modes_options.dense,
                          "every finite pole by the dense method, whatever the size, up to 2000 "
                          "unknowns (inclusive; O(n^3): seconds at 1000 unknowns, but not "
                          "stopped by clusters of real poles)");
  modes_command->add_flag("!--no-error-estimate", modes_options.error_estimate,
                          "skip the N/2N discretisation error estimate");

  AcOptions ac_options;
  auto* ac_command = app.add_subcommand(
      "ac",
      "small-signal frequency response of the probes: magnitude and phase.\n"
      "The AC input depends on the scene's drive: antagonistic = the alternating part of the\n"
      "DEA forces (k_F*V^2/2 per DEA, in antiphase; x 4/pi for the square wave's fundamental);\n"
      "switched = the same force level on its one DEA (the 0/k_F*V^2 square wave's +/- part);\n"
      "bias_differential = +v / -v about V0 on the two DEAs (linearised at V0);\n"
      "single = v about V0 on one DEA; none = the scene's loads with their values as amplitudes.");
  add_common(ac_command, options);
  ac_command->add_option("--from", ac_options.from,
                         "start frequency [Hz] (default: scene ac.from)");
  ac_command->add_option("--to", ac_options.to,
                         "stop frequency [Hz] (default: scene ac.to; with --points 1: --from)");
  ac_command->add_option("--points", ac_options.points,
                         "number of frequencies, 1 to 1000000 (default: scene ac.points)");
  ac_command->add_option("--scale", ac_options.scale, "lin or log")
      ->check(CLI::IsMember({"lin", "log"}));
  ac_command->add_option("--plot", ac_options.plot,
                         "write a Bode plot (PNG or SVG, by extension), resonances marked");
  ac_command->add_flag("--reduce", ac_options.reduce,
                       "evaluate the sweep by modal reduction (modes below band/sqrt(tolerance), "
                       "static correction for the rest), checked against the full model");
  ac_command->add_option("--tolerance", ac_options.tolerance,
                         "--reduce: relative error wanted, in (0, 1) (default: the scene's "
                         "model.tolerance, 1e-3)");
  ac_command->add_option("--band", ac_options.band,
                         "--reduce: highest frequency of interest [Hz] (default: --to)");

  TranOptions tran_options;
  auto* tran_command = app.add_subcommand(
      "tran",
      "time response to the scene's drive (square-wave DEA switching) with SUNDIALS IDA, or\n"
      "exactly (--method exact) for linear networks under piecewise-constant sources");
  add_common(tran_command, options);
  tran_command->add_option("--switching", tran_options.switching,
                           "switching frequency [Hz] (default: the scene's drive.frequency)");
  tran_command->add_option("--periods", tran_options.periods, "number of periods (default 10)");
  tran_command->add_option("--rtol", tran_options.rtol, "IDA relative tolerance (default 1e-6)");
  tran_command->add_option("--atol", tran_options.atol,
                           "IDA absolute tolerance for every unknown (default: rtol times a "
                           "scale per kind of unknown from the static state)");
  tran_command->add_option("--max-step", tran_options.max_step,
                           "IDA's largest step [s] (default 0: no limit)");
  tran_command->add_option("--method", tran_options.method, "ida or exact")
      ->check(CLI::IsMember({"ida", "exact"}));
  tran_command
      ->add_option("--start", tran_options.start,
                   "rest (default) or static (the static state under the first "
                   "half-period's drive)")
      ->check(CLI::IsMember({"rest", "static"}));
  tran_command->add_option("--points-per-period", tran_options.points_per_period,
                           "output points per period (default 100)");
  tran_command->add_option("--plot", tran_options.plot,
                           "write a plot of the deflections (PNG/SVG)");

  SweepOptions sweep_options;
  auto* sweep_command = app.add_subcommand(
      "sweep-switching",
      "periodic steady-state peak deflection to the left and to the right against the\n"
      "switching frequency (paper Fig. 14), computed directly: exact for linear networks,\n"
      "Newton shooting over one period otherwise");
  add_common(sweep_command, options);
  sweep_command->add_option("--from", sweep_options.from, "first switching frequency [Hz] (1)");
  sweep_command->add_option("--to", sweep_options.to, "last switching frequency [Hz] (7)");
  sweep_command->add_option("--step", sweep_options.step, "frequency step [Hz] (0.1)");
  sweep_command->add_option("--method", sweep_options.method, "exact (default) or shooting")
      ->check(CLI::IsMember({"exact", "shooting"}));
  sweep_command->add_option("--samples", sweep_options.samples,
                            "samples per period before refining the extremes (default 64 "
                            "for the exact method, whose extremes are global whatever the "
                            "count, also with --reduce; 256 for shooting, which refines the "
                            "largest samples)");
  sweep_command->add_option("--rtol", sweep_options.rtol,
                            "shooting: IDA relative tolerance (1e-9)");
  sweep_command->add_option("--plot", sweep_options.plot,
                            "write the curve (PNG/SVG), resonance marked");
  sweep_command->add_flag("--reduce", sweep_options.reduce,
                          "periodic state of a modal reduction (modes below band/tolerance, "
                          "static correction as a feed-through), checked against the exact one");
  sweep_command->add_option("--tolerance", sweep_options.tolerance,
                            "--reduce: relative error wanted, in (0, 1) (default: the scene's "
                            "model.tolerance, 1e-3)");
  sweep_command->add_option("--band", sweep_options.band,
                            "--reduce: highest frequency of interest [Hz] (default: --to)");

  double target_hz = 0.0;
  int mode_number = 1;
  std::string peak_text;
  auto* identify_command = app.add_subcommand(
      "identify",
      "fit beam.bending_stiffness so that a mode sits at a target frequency (and, with --peak, "
      "damping.loss_factor to a measured peak deflection)");
  add_common(identify_command, options);
  identify_command->add_option("--resonance", target_hz, "target frequency [Hz]")->required();
  identify_command->add_option("--mode", mode_number, "which oscillatory mode (default 1)");
  identify_command->add_option(
      "--peak", peak_text,
      "also fit damping.loss_factor: NAME=VALUE[@VOLTAGE], the periodic peak |deflection| of "
      "output NAME (P4, dx4, tip, ...) under the scene's square-wave drive switched at the "
      "--resonance frequency, e.g. P4=9.3mm@4kV");

  SensitivityCommandOptions sensitivity_options;
  auto* sensitivity_command = app.add_subcommand(
      "sensitivity",
      "derivative of each resonance frequency with respect to every scene parameter, from the\n"
      "eigenvectors (first-order eigenvalue perturbation); --check compares with finite\n"
      "differences of the poles");
  add_common(sensitivity_command, options);
  sensitivity_command->add_option("--modes", sensitivity_options.modes,
                                  "number of lowest oscillatory modes (default 3)");
  sensitivity_command
      ->add_option("--parameter", sensitivity_options.parameters,
                   "a scene key, e.g. beam.bending_stiffness or dea[A].lever_arm (default: every "
                   "non-zero parameter)")
      ->allow_extra_args(false);
  sensitivity_command->add_flag("--check", sensitivity_options.check,
                                "also difference the poles at p(1 +/- 1e-4) and report the "
                                "difference");

  MismatchOptions mismatch_options;
  auto* mismatch_command = app.add_subcommand(
      "mismatch",
      "left/right asymmetry of the periodic swing from a mismatched antagonistic pair: DEA A's\n"
      "electrode area or film thickness changed by +/-X, or the switching overlapping by X*T/2");
  add_common(mismatch_command, options);
  mismatch_command->add_option("--frequency", mismatch_options.frequency,
                               "switching frequency [Hz] (default: the scene's drive.frequency)");
  mismatch_command->add_option("--output", mismatch_options.output,
                               "deflection output (default: the last, e.g. dx4)");
  mismatch_command->add_option("--change", mismatch_options.change,
                               "relative change of each parameter (default 0.05)");

  NetlistOptions netlist_options;
  CLI::App* netlist_command = nullptr;
  add_netlist_command(app, options, netlist_options, netlist_command);

  CrosscheckCommandOptions crosscheck_options;
  CLI::App* crosscheck_command = nullptr;
  add_crosscheck_command(app, options, crosscheck_options, crosscheck_command);

  SchemaOptions schema_options;
  CLI::App* schema_command = add_schema_command(app, schema_options);

  // An unknown command would otherwise be taken for a scene file ("A subcommand is required").
  std::vector<std::string> command_names;
  std::string commands;
  for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    command_names.push_back(command->get_name());
    commands += (commands.empty() ? "" : ", ") + command->get_name();
  }
  if (argc < 2 || (argv[1][0] != '-' && std::find(command_names.begin(), command_names.end(),
                                                  argv[1]) == command_names.end())) {
    std::cerr << "emnet: error: "
              << (argc < 2 ? std::string("a command is required")
                           : "unknown command '" + shown(argv[1]) + "'")
              << "; the commands are " << commands << " (see emnet --help)\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "emnet: error: " << e.what() << " (see emnet --help)\n";
    return 2;
  }

  // Ctrl-C sets a flag that the analyses poll (terminal_progress.hpp); the progress line
  // goes to standard error. `crosscheck` polls none (ngspice runs on its own), so Ctrl-C keeps
  // its default there: it ends the program at once (an output file is renamed into place only
  // when complete).
  std::optional<emnet_cli::InterruptHandler> interrupt_handler;
  if (!*crosscheck_command) interrupt_handler.emplace();
  using Mode = emnet_cli::TerminalProgress::Mode;
  emnet_cli::TerminalProgress reporter("emnet " + app.get_subcommands().front()->get_name(),
                                       options.quiet      ? Mode::quiet
                                       : options.progress ? Mode::forced
                                                          : Mode::automatic);
  options.reporter = &reporter;
  // One message for a failure: after the progress line, control characters escaped; an
  // interruption wins over the failure it caused.
  auto failed = [&](int status, const std::string& kind, const std::string& what) {
    reporter.finish();
    if (emnet_cli::InterruptHandler::interrupted()) {
      std::cerr << "emnet: interrupted (Ctrl-C): stopped, no output file written\n";
      return 130;
    }
    std::cerr << "emnet: " << kind << ": "
              << (status == 2 ? emnet::terminal_text(what) : emnet::terminal_lines(what)) << "\n";
    return status;
  };
  int status = 1;
  try {
    if (*static_command) status = run_static(options);
    if (*modes_command) status = run_modes_command(options, modes_options);
    if (*ac_command) status = run_ac_command(options, ac_options);
    if (*identify_command) status = run_identify(options, target_hz, mode_number, peak_text);
    if (*tran_command) status = run_tran_command(options, tran_options);
    if (*sweep_command) status = run_sweep_command(options, sweep_options);
    if (*sensitivity_command) status = run_sensitivity_command(options, sensitivity_options);
    if (*mismatch_command) status = run_mismatch_command(options, mismatch_options);
    if (*netlist_command) status = run_netlist_command(options, netlist_options);
    if (*crosscheck_command) status = run_crosscheck_command(options, crosscheck_options);
    if (*schema_command) status = run_schema_command(schema_options);
  } catch (const InputError& e) {
    status = failed(2, "error", e.what());
  } catch (const FileError& e) {
    status = failed(2, "error", e.what());
  } catch (const Interrupted& e) {
    status = failed(130, "interrupted", e.what());
  } catch (const NumericalFailure& e) {
    status = failed(3, "numerical failure", e.what());
  } catch (const std::exception& e) {
    status = failed(1, "internal error", e.what());
  }
  reporter.finish();
  // The result printed is output too: a full disk or a closed file behind standard output is
  // an error, not a silent loss.
  std::cout.flush();
  const bool lost = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (lost) {
    std::cerr << "emnet: error: cannot write the result to standard output ("
              << std::strerror(errno) << ")\n";
    return status == 0 ? 2 : status;
  }
  return status;
}
