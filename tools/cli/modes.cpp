// The `modes` command: parses its options, runs the modes study (emnet/studies/modes_study.hpp)
// and reports it as a table, --json (emnet/report/json.hpp) or --csv.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/common.hpp"
#include "cli/option_names.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/report/json.hpp"
#include "emnet/studies/modes_study.hpp"

namespace emnet_cli {

namespace {

// A probe with squares (dea_force) in a mode shape: its small-signal part about the operating
// point, as its description says.
std::vector<emnet::Probe> probes_in_the_mode_shapes(const CommonOptions& options,
                                                    const emnet::ModesStudyResult& study) {
  std::vector<emnet::Probe> probes =
      options.probes.empty() ? std::vector<emnet::Probe>{} : selected_probes(study.model, options);
  for (emnet::Probe& probe : probes)
    probe = emnet::linearised_probe(probe, study.rest.operating_point);
  return probes;
}

void write_the_modes_csv(const CommonOptions& options, const emnet::ModesStudyResult& study) {
  if (options.csv.empty()) return;
  std::vector<std::vector<double>> rows;
  for (size_t k = 0; k < study.modes.size(); ++k) {
    const emnet::Mode& mode = study.modes[k].mode;
    rows.push_back({static_cast<double>(k + 1), mode.frequency_hz, mode.damping_ratio,
                    mode.natural_frequency_hz, mode.pole.real(), mode.pole.imag(),
                    mode.pole_error / (2 * pi), mode.error_bounded ? 1.0 : 0.0});
  }
  write_csv(options.csv,
            {"mode", "frequency_hz", "damping_ratio", "natural_frequency_hz", "pole_real",
             "pole_imag", "frequency_error_bound_hz", "error_bounded"},
            rows);
}

// The method, what was found, the rule, the accuracy and the cost, above the table.
void print_what_the_modes_are(const emnet::ModesStudyResult& study,
                              const emnet::ModesStudyOptions& asked, double total) {
  const emnet::ModalResult& result = study.modal;
  const std::vector<std::string>& rigid_names = study.rigid_body_motions;
  std::cout << "modes: " << emnet::method_name(result.method)
            << (result.complete ? " (every finite pole of the pencil)"
                                : " shift-invert Arnoldi (the poles nearest 0)")
            << ", " << study.modes.size() << " oscillatory shown, " << result.real_poles.size()
            << " real pole(s)"
            << (result.overdamped_pairs.empty()
                    ? std::string()
                    : ", " + std::to_string(result.overdamped_pairs.size()) + " overdamped pair(s)")
            << (rigid_names.empty() ? "" : ", rigid-body motion: " + rigid_names.front()) << "\n"
            << (result.note.empty() ? "" : "note: " + result.note + "\n")
            << "rule: " << emnet::kModeRule << "\n"
            << "accuracy: 'rounding' bounds each frequency's error from the computation "
               "(first order: residual in extended precision times the pole's condition); "
               "discretisation error vs the continuum beam "
            << (study.error_estimate_computed
                    ? "estimated from N and 2N segments (Richardson, O(N^-2))"
                : asked.error_estimate ? "not estimated (N > 1000)"
                                       : "not estimated (--no-error-estimate)")
            << "\ncost: modes " << milliseconds(result.seconds) << " (of which error bounds "
            << milliseconds(result.bound_seconds) << "), error estimate "
            << milliseconds(study.seconds_error_estimate) << ", total " << milliseconds(total)
            << "\n\n";
}

void print_the_table_of_modes(const emnet::ModesStudyResult& study) {
  // Each mode's rounding error bound, relative to its damped frequency.
  auto frequency_error = [](const emnet::Mode& mode) {
    return mode.pole_error / std::max(std::abs(mode.pole.imag()), 1e-300);
  };
  std::printf("%5s %16s %14s %16s %12s %14s\n", "mode", "freq [Hz]", "damping ratio",
              "natural f [Hz]", "rounding", "discr. error");
  for (size_t k = 0; k < study.modes.size(); ++k) {
    const emnet::ModesStudyMode& entry = study.modes[k];
    const emnet::Mode& mode = entry.mode;
    const std::string err =
        entry.discretisation_error_estimated ? format("%.2g", entry.discretisation_error) : "-";
    const std::string bound =
        mode.error_bounded ? format("%.2g", frequency_error(mode)) : "unbounded";
    std::printf("%5zu %16.9g %14.6g %16.9g %12s %14s\n", k + 1, mode.frequency_hz,
                mode.damping_ratio, mode.natural_frequency_hz, bound.c_str(), err.c_str());
  }
}

// The overdamped pairs, the real poles and a rigid-body motion: poles that are not modes.
void print_the_poles_that_are_not_modes(const emnet::ModesStudyResult& study) {
  const emnet::ModalResult& result = study.modal;
  if (!result.overdamped_pairs.empty()) {
    std::printf("\n%zu overdamped pair(s) (damping ratio >= 1/sqrt(2), not numbered as modes):",
                result.overdamped_pairs.size());
    for (const auto& pair : result.overdamped_pairs)
      std::printf(" %.4g Hz (zeta %.3g)", pair.frequency_hz, pair.damping_ratio);
    std::printf("\n");
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
        unbounded_real == 0 ? ""
                            : (", " + std::to_string(unbounded_real) +
                               " of them not bounded individually (clusters of nearly equal poles)")
                                  .c_str());
  }
  if (!study.rigid_body_motions.empty())
    std::cout << "\nrigid-body motion (pole s = 0): " << study.rigid_body_motions.front() << "\n";
}

// Along the beam with --shapes, and at the probes asked for.
void print_the_mode_shapes(const emnet::ModesStudyResult& study,
                           const emnet::ModesStudyOptions& asked,
                           const std::vector<emnet::Probe>& probes) {
  if (asked.shapes)
    for (size_t k = 0; k < study.modes.size(); ++k) {
      std::cout << "\nmode " << k + 1 << " shape (deflection, largest = 1):\n";
      const emnet::ModeShape& shape = study.modes[k].shape;
      for (size_t i = 0; i < shape.x_m.size(); ++i)
        std::printf("  x = %10.6g mm  %+.6f\n", shape.x_m[i] * 1e3, shape.deflection[i].real());
    }
  if (probes.empty()) return;
  std::cout << "\nmode shape at the probes (per unit largest nodal deflection; real and "
               "imaginary part):\n";
  for (size_t k = 0; k < study.modes.size(); ++k) {
    const std::vector<std::complex<double>> values =
        emnet::mode_probe_values(study.model, study.modes[k].mode, probes);
    for (size_t j = 0; j < probes.size(); ++j) {
      const emnet::Probe& probe = probes[j];
      const std::complex<double> value = values[j];
      std::printf("  mode %zu  %-10s %-36s %+.6g %+.6g %s\n", k + 1, shown(probe.name).c_str(),
                  shown(probe.description).c_str(), value.real(), value.imag(),
                  shown(probe.unit).c_str());
    }
  }
}

// Refused after the result is printed, before any output file is written.
void refuse_modes_whose_error_is_unbounded(const emnet::ModesStudyResult& study) {
  if (study.unbounded.empty()) return;
  std::string message = "modes: the error of these modes cannot be bounded:";
  for (const auto& line : study.unbounded) message += "\n  " + line;
  throw NumericalFailure(message);
}

}  // namespace

int run_modes_command(const CommonOptions& options, const emnet::ModesStudyOptions& asked) {
  const emnet::Stopwatch stopwatch;
  const emnet::Scene scene = load_scene(options);
  emnet::ModesStudyOptions study_options = asked;
  study_options.prepare.electrical_probe_requested = electrical_probe_requested(options);
  study_options.progress = progress_of(options);
  const emnet::ModesStudyResult study = emnet::run_modes_study(scene, study_options);
  stop_if_interrupted();
  if (!study.status.ok()) throw NumericalFailure(study.status.message);
  const double total = stopwatch.seconds();
  const std::vector<emnet::Probe> probes = probes_in_the_mode_shapes(options, study);
  end_progress(options);
  if (options.json) {
    std::cout << json_text(emnet::to_json(study, probes, total)) << "\n";
  } else {
    print_header(study.model, study.system);
    print_what_the_modes_are(study, asked, total);
    print_the_table_of_modes(study);
    print_the_poles_that_are_not_modes(study);
    print_the_mode_shapes(study, asked, probes);
  }
  refuse_modes_whose_error_is_unbounded(study);
  write_the_modes_csv(options, study);
  return 0;
}

Command add_modes_command(CLI::App& app, CommonOptions& options) {
  auto modes_options = std::make_shared<emnet::ModesStudyOptions>();
  auto* modes_command = app.add_subcommand(
      "modes", "poles of the network: frequency, damping ratio, mode shape along the beam");
  add_common(modes_command, options);
  sets_fields(modes_command->add_option("--count", modes_options->count,
                                        "number of modes to show (default: every pole for small "
                                        "networks, the 20 lowest for large ones)"),
              {"count"});
  modes_command->add_flag("--shapes", modes_options->shapes, "print the mode shapes");
  sets_fields(modes_command->add_flag("--dense", modes_options->dense,
                                      "every finite pole by the dense method, whatever the size, "
                                      "up to 2000 unknowns (inclusive; O(n^3): seconds at 1000 "
                                      "unknowns, but not stopped by clusters of real poles)"),
              {"dense"});
  modes_command->add_flag("!--no-error-estimate", modes_options->error_estimate,
                          "skip the N/2N discretisation error estimate");

  return {modes_command,
          [modes_options, &options] { return run_modes_command(options, *modes_options); }};
}

}  // namespace emnet_cli
