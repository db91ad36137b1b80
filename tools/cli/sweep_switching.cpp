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

int run_sweep_command(CommonOptions options, SweepOptions sweep) {
  const emnet::Stopwatch stopwatch;
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
    emnet::check_periodic_memory(model.network.assemble().size(), "--segments");
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
  emnet::check_overlap_fits(base_scene, sweep.to, "--to");
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
      const emnet::Stopwatch build_stopwatch;
      reduced = std::make_unique<emnet::ReducedPeriodicSolver>(system, reduction_settings);
      check->build_seconds = build_stopwatch.seconds();
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
        const emnet::Stopwatch build_stopwatch;
        full = std::make_unique<emnet::PeriodicSolver>(system);
        check->full_build_seconds = build_stopwatch.seconds();
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
    const emnet::OperatingPoint rest = emnet::operating_point(system);
    emnet::ModalOptions modal;
    modal.keep_vectors = false;
    if (system.size() > modal.dense_limit) modal.count = 3;
    const auto modes = emnet::run_modes(system, rest.rest.operating_point, modal);
    if (rest.status.ok && modes.status.ok && !modes.modes.empty())
      markers.push_back({modes.modes[0].frequency_hz,
                         "f1 = " + format("%.6g", modes.modes[0].frequency_hz) + " Hz"});
  }
  if (!results.empty())
    markers.push_back(
        {frequencies[best], "sweep peak " + format("%.6g", frequencies[best]) + " Hz"});
  const double total = stopwatch.seconds();
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

Command add_sweep_switching_command(CLI::App& app, CommonOptions& options) {
  auto sweep_options = std::make_shared<SweepOptions>();
  auto* sweep_command = app.add_subcommand(
      "sweep-switching",
      "periodic steady-state peak deflection to the left and to the right against the\n"
      "switching frequency (paper Fig. 14), computed directly: exact for linear networks,\n"
      "Newton shooting over one period otherwise");
  add_common(sweep_command, options);
  sweep_command->add_option("--from", sweep_options->from, "first switching frequency [Hz] (1)");
  sweep_command->add_option("--to", sweep_options->to, "last switching frequency [Hz] (7)");
  sweep_command->add_option("--step", sweep_options->step, "frequency step [Hz] (0.1)");
  sweep_command->add_option("--method", sweep_options->method, "exact (default) or shooting")
      ->check(CLI::IsMember({"exact", "shooting"}));
  sweep_command->add_option("--samples", sweep_options->samples,
                            "samples per period before refining the extremes (default 64 "
                            "for the exact method, whose extremes are global whatever the "
                            "count, also with --reduce; 256 for shooting, which refines the "
                            "largest samples)");
  sweep_command->add_option("--rtol", sweep_options->rtol,
                            "shooting: IDA relative tolerance (1e-9)");
  sweep_command->add_option("--plot", sweep_options->plot,
                            "write the curve (PNG/SVG), resonance marked");
  sweep_command->add_flag("--reduce", sweep_options->reduce,
                          "periodic state of a modal reduction (modes below band/tolerance, "
                          "static correction as a feed-through), checked against the exact one");
  sweep_command->add_option("--tolerance", sweep_options->tolerance,
                            "--reduce: relative error wanted, in (0, 1) (default: the scene's "
                            "model.tolerance, 1e-3)");
  sweep_command->add_option("--band", sweep_options->band,
                            "--reduce: highest frequency of interest [Hz] (default: --to)");

  return {sweep_command,
          [sweep_options, &options] { return run_sweep_command(options, *sweep_options); }};
}

}  // namespace emnet_cli
