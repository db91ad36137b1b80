#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli/common.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/output_file.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/terminal_text.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/scene/parameter_listing.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/segment_selection.hpp"
#include "emnet/studies/sensitivity.hpp"
#include "emnet/verification/crosscheck.hpp"

namespace emnet_cli {

using emnet::InputError;
using Json = nlohmann::ordered_json;

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
  const emnet::Stopwatch stopwatch;
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
  seconds = stopwatch.seconds();
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
  const emnet::Stopwatch stopwatch;
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
  const double total = stopwatch.seconds();
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

Command add_modes_command(CLI::App& app, CommonOptions& options) {
  auto modes_options = std::make_shared<ModesOptions>();
  auto* modes_command = app.add_subcommand(
      "modes", "poles of the network: frequency, damping ratio, mode shape along the beam");
  add_common(modes_command, options);
  modes_command->add_option("--count", modes_options->count,
                            "number of modes to show (default: every pole for small networks, "
                            "the 20 lowest for large ones)");
  modes_command->add_flag("--shapes", modes_options->shapes, "print the mode shapes");
  modes_command->add_flag("--dense", modes_options->dense,
                          "every finite pole by the dense method, whatever the size, up to 2000 "
                          "unknowns (inclusive; O(n^3): seconds at 1000 unknowns, but not "
                          "stopped by clusters of real poles)");
  modes_command->add_flag("!--no-error-estimate", modes_options->error_estimate,
                          "skip the N/2N discretisation error estimate");

  return {modes_command,
          [modes_options, &options] { return run_modes_command(options, *modes_options); }};
}

}  // namespace emnet_cli
