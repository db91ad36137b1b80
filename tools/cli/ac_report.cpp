// The ac command's report: the text table (header, input, sweep, method, accuracy and cost,
// resonances, |value| and phase per probe and frequency, each probe's peak), --json
// (emnet/report/ac_json.hpp), --csv (magnitude and phase per probe) and --plot (a Bode plot
// titled with its input in short, the resonances that show as a peak marked). Phase =
// arg(value)·180/π [deg].
#include <cmath>
#include <complex>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "cli/ac.hpp"
#include "cli/common.hpp"
#include "emnet/core/units.hpp"
#include "emnet/report/ac_json.hpp"
#include "emnet/report/plot.hpp"

namespace emnet_cli {

namespace {

void write_ac_files(const AcReportInput& in, const std::vector<emnet::PlotMarker>& markers) {
  const auto& options = in.options;
  const auto& probes = in.probes;
  const auto& grid = in.result.ac.frequencies;
  const auto& values = in.result.ac.values;
  if (!options.csv.empty()) {
    std::vector<std::string> header{"frequency_hz"};
    for (const auto& probe : probes) {
      header.push_back(probe.name + "_magnitude_" + probe.unit);
      header.push_back(probe.name + "_phase_deg");
    }
    write_csv_rows(options.csv, header, grid.size(), [&](size_t f, auto& row) {
      row.push_back(grid[f]);
      for (size_t k = 0; k < probes.size(); ++k) {
        row.push_back(std::abs(values[k][f]));
        row.push_back(std::arg(values[k][f]) * 180.0 / pi);
      }
    });
  }
  if (!in.plot.empty()) {
    std::vector<emnet::BodeSeries> series;
    for (size_t k = 0; k < probes.size(); ++k)
      series.push_back({probes[k].name + ": " + probes[k].description, probes[k].unit, values[k]});
    const std::string input = emnet::ac_input_summary(in.prepared.model.scene);
    stop_if_interrupted();
    check_plot(emnet::write_bode_plot(
        in.plot,
        in.prepared.model.scene.name + ": small-signal response" +
            (input.empty() ? std::string(" (no AC input)") : " to " + input),
        grid, series, markers, in.spec.log, plot_output(in.options, in.plot_script)));
  }
}

// The method, accuracy and cost lines of a reduced sweep.
void print_reduction(const AcReportInput& in) {
  const auto& r = *in.result.reduction;
  const auto& m = r.model;
  const auto& probes = in.probes;
  std::cout << "method: modal reduction with static correction: band " << si(m.band_hz, "Hz")
            << ", tolerance " << format("%.3g", m.tolerance)
            << " -> cut-off f_c = band/sqrt(tol) = " << si(m.cutoff_hz, "Hz") << "\n"
            << "  kept " << m.kept_modes << " mode(s) and " << m.kept_real_poles
            << " real pole(s) of a " << m.full_unknowns << "-unknown network ("
            << emnet::method_name(m.modal_method) << "); " << m.truncated_poles
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
            << "), evaluation " << milliseconds(r.evaluate_seconds) << " ("
            << in.result.ac.frequencies.size() << " points), check "
            << milliseconds(r.check_seconds) << " (full model, " << r.check_frequencies.size()
            << " points), total " << milliseconds(in.total_seconds) << "\n";
}

// The table of |value| and phase per frequency, then each probe's peak on the grid.
void print_table(const AcReportInput& in) {
  const auto& probes = in.probes;
  const auto& grid = in.result.ac.frequencies;
  const auto& values = in.result.ac.values;
  std::printf("%14s", "f [Hz]");
  for (const auto& probe : probes)
    std::printf(" %16s %11s", shown("|" + probe.name + "| [" + probe.unit + "]").c_str(),
                shown(probe.name + " [deg]").c_str());
  std::printf("\n");
  // The rows as printf("%14.6g", " %16.6e %11.3f"…) would write them, formatted at once.
  std::string rows;
  rows.reserve(grid.size() * (15 + 29 * probes.size()));
  for (size_t f = 0; f < grid.size(); ++f) {
    emnet::append_number(rows, grid[f], 'g', 6, 14);
    for (size_t k = 0; k < probes.size(); ++k) {
      rows += ' ';
      emnet::append_number(rows, std::abs(values[k][f]), 'e', 6, 16);
      rows += ' ';
      emnet::append_number(rows, std::arg(values[k][f]) * 180.0 / pi, 'f', 3, 11);
    }
    rows += '\n';
  }
  std::fwrite(rows.data(), 1, rows.size(), stdout);
  for (size_t k = 0; k < probes.size(); ++k) {
    size_t best = 0;
    for (size_t f = 0; f < grid.size(); ++f)
      if (std::abs(values[k][f]) > std::abs(values[k][best])) best = f;
    std::printf("peak of %s: %.6e %s at %.7g Hz (grid spacing limits this to +/- half a step)\n",
                shown(probes[k].name).c_str(), std::abs(values[k][best]),
                shown(probes[k].unit).c_str(), grid[best]);
  }
}

}  // namespace

int report_ac(const AcReportInput& in) {
  const auto& options = in.options;
  const auto& result = in.result;
  const auto& scene = in.prepared.model.scene;
  if (result.reduction && !result.reduction->tolerance_met)
    std::cerr << tolerance_warning(result.reduction->measured_error,
                                   result.reduction->model.tolerance)
              << "\n";
  // The plot marks the resonances that show as a peak (emnet::resonance_shows_peak).
  std::vector<emnet::PlotMarker> markers;
  for (size_t k = 0; k < result.resonances_hz.size(); ++k)
    if (emnet::resonance_shows_peak(result.resonance_damping_ratios[k])) {
      const double f = result.resonances_hz[k];
      markers.push_back({f, "f = " + format("%.6g", f) + " Hz"});
    }
  const std::string input = ac_input_description(scene, in.spec.to);
  if (options.json) {
    std::cout << json_text(
                     emnet::to_json(result, in.prepared.model, in.probes, input, in.total_seconds))
              << "\n";
    write_ac_files(in, markers);
    return validity_exit(result.validity);
  }
  print_header(in.prepared.model, in.prepared.system);
  for (const std::string& note : result.notes) std::cout << "note: " << shown(note) << "\n";
  std::cout << input << "\n"
            << "sweep: " << result.ac.frequencies.size() << " points, " << si(in.spec.from, "Hz")
            << " to " << si(in.spec.to, "Hz") << (in.spec.log ? " (log)" : " (lin)") << "\n";
  if (result.reduction) {
    print_reduction(in);
  } else {
    const emnet::AcResult& ac = result.ac;
    if (ac.method == emnet::Method::pole_residue)
      std::cout << "method: pole-residue form (every pole, O(poles) per frequency), checked "
                   "against the direct solve at "
                << ac.check_points << " frequencies\n"
                << "accuracy: largest difference there " << format("%.2g", ac.check_deviation)
                << " of each output's peak; worst relative residual of the direct solves "
                << format("%.2g", ac.max_relative_residual) << "\n";
    else
      std::cout << "method: direct sparse solve at every frequency"
                << (ac.note.empty() ? std::string() : " (" + ac.note + ")") << "\n"
                << "accuracy: worst relative residual of the complex solves "
                << format("%.2g", ac.max_relative_residual) << "\n";
    std::cout << "cost: sweep " << milliseconds(result.ac.seconds) << ", total "
              << milliseconds(in.total_seconds) << "\n";
  }
  for (const auto& m : markers) std::cout << "resonance in band: " << m.label << "\n";
  std::cout << "\n";
  print_table(in);
  write_ac_files(in, markers);
  if (!in.plot.empty()) std::cout << "Bode plot written to " << shown(in.plot) << "\n";
  print_validity(result.validity);
  return validity_exit(result.validity);
}

}  // namespace emnet_cli
