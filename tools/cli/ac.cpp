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
  return emnet::to_json(m, tolerance_met);
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
  const emnet::Stopwatch stopwatch;
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
  const double total = stopwatch.seconds();
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

Command add_ac_command(CLI::App& app, CommonOptions& options) {
  auto ac_options = std::make_shared<AcOptions>();
  auto* ac_command = app.add_subcommand(
      "ac",
      "small-signal frequency response of the probes: magnitude and phase.\n"
      "The AC input depends on the scene's drive: antagonistic = the alternating part of the\n"
      "DEA forces (k_F*V^2/2 per DEA, in antiphase; x 4/pi for the square wave's fundamental);\n"
      "switched = the same force level on its one DEA (the 0/k_F*V^2 square wave's +/- part);\n"
      "bias_differential = +v / -v about V0 on the two DEAs (linearised at V0);\n"
      "single = v about V0 on one DEA; none = the scene's loads with their values as amplitudes.");
  add_common(ac_command, options);
  ac_command->add_option("--from", ac_options->from,
                         "start frequency [Hz] (default: scene ac.from)");
  ac_command->add_option("--to", ac_options->to,
                         "stop frequency [Hz] (default: scene ac.to; with --points 1: --from)");
  ac_command->add_option("--points", ac_options->points,
                         "number of frequencies, 1 to 1000000 (default: scene ac.points)");
  ac_command->add_option("--scale", ac_options->scale, "lin or log")
      ->check(CLI::IsMember({"lin", "log"}));
  ac_command->add_option("--plot", ac_options->plot,
                         "write a Bode plot (PNG or SVG, by extension), resonances marked");
  ac_command->add_flag("--reduce", ac_options->reduce,
                       "evaluate the sweep by modal reduction (modes below band/sqrt(tolerance), "
                       "static correction for the rest), checked against the full model");
  ac_command->add_option("--tolerance", ac_options->tolerance,
                         "--reduce: relative error wanted, in (0, 1) (default: the scene's "
                         "model.tolerance, 1e-3)");
  ac_command->add_option("--band", ac_options->band,
                         "--reduce: highest frequency of interest [Hz] (default: --to)");

  return {ac_command, [ac_options, &options] { return run_ac_command(options, *ac_options); }};
}

}  // namespace emnet_cli
