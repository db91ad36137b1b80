// emnet sweep-switching's report: the text table (peaks per frequency, the largest swing, the
// markers), --json, --csv and --plot of an emnet::SwitchingSweepResult.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/sweep_switching.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/report/switching_sweep_json.hpp"

namespace emnet_cli {

namespace {

// The peaks against the switching frequency: one colour per output, its left extreme solid and
// its right one dashed, one legend entry per output; each unit in its panel, lengths in mm as
// in every plot (plot_unit).
void write_sweep_plot(const SweepReportInput& input,
                      const std::vector<emnet::PlotMarker>& markers) {
  const auto& outputs = input.result.outputs;
  const auto& frequencies = input.result.frequencies;
  bool all_deflections = true;
  for (size_t p : input.plotted.indices) all_deflections &= outputs[p].probe.unit == "m";
  std::vector<emnet::LineSeries> series;
  int colour = 0;
  for (size_t p : input.plotted.indices) {
    const emnet::Probe& probe = outputs[p].probe;
    const PlotUnit shown = plot_unit(probe.unit);
    emnet::LineSeries left{
        probe.name + " (" + probe.description + ")", frequencies, {}, shown.unit};
    emnet::LineSeries right{probe.name + " right", frequencies, {}, shown.unit};
    for (size_t k = 0; k < frequencies.size(); ++k) {
      left.y.push_back(outputs[p].left[k] * shown.scale);
      right.y.push_back(outputs[p].right[k] * shown.scale);
    }
    left.colour = right.colour = colour++;
    right.dashed = true;
    right.in_legend = false;
    series.push_back(std::move(left));
    series.push_back(std::move(right));
  }
  emnet::LinePlotOptions options;
  options.markers = markers;
  options.legend_note =
      "solid: peak to the left (negative side); dashed: peak to the right (positive side)";
  options.axis_labels = axis_labels("peak ");
  options.reference_lines = deflection_limit_lines(input.result.validity);
  options.output = plot_output(input.options, input.plot_script);
  stop_if_interrupted();
  check_plot(emnet::write_line_plot(input.plot,
                                    input.model.scene.name + ": periodic steady-state peak " +
                                        (all_deflections ? "deflection" : "values") +
                                        " vs switching frequency",
                                    "switching frequency [Hz]", series, options));
}

// The CSV table (one row per frequency: each output's left and right extreme) and the plot.
void write_sweep_files(const SweepReportInput& input,
                       const std::vector<emnet::PlotMarker>& markers) {
  const CommonOptions& options = input.options;
  const auto& outputs = input.result.outputs;
  const auto& frequencies = input.result.frequencies;
  if (!options.csv.empty()) {
    std::vector<std::string> header{"switching_frequency_hz"};
    for (const auto& output : outputs) {
      header.push_back(output.probe.name + "_left_" + output.probe.unit);
      header.push_back(output.probe.name + "_right_" + output.probe.unit);
    }
    write_csv_rows(options.csv, header, frequencies.size(), [&](size_t k, auto& row) {
      row.push_back(frequencies[k]);
      for (const auto& output : outputs) {
        row.push_back(output.left[k]);
        row.push_back(output.right[k]);
      }
    });
  }
  if (!input.plot.empty()) write_sweep_plot(input, markers);
}

// The reduced model, its check's errors against the reference and the costs, in text.
void print_reduction_check(const emnet::SwitchingSweepReductionCheck& check,
                           const emnet::SwitchingSweepResult& result) {
  const auto& m = check.model;
  const size_t count = result.frequencies.size();
  const double reduced_sweep = check.build_seconds + result.solve_seconds;
  const double full_sweep =
      check.full_build_seconds + static_cast<double>(count) * check.full_solve_seconds;
  std::cout << "reduced: modal coordinates of " << m.kept_modes << " mode(s) and "
            << m.kept_real_poles << " real pole(s) below f_c = band/tol = " << si(m.cutoff_hz, "Hz")
            << " (band " << si(m.band_hz, "Hz") << ", tolerance " << format("%.3g", m.tolerance)
            << (check.cascade
                    ? "), the beam's truncated part exact at the squared voltages' exponents "
                      "but for its transients after each edge; "
                    : "), static correction as a direct feed-through; ")
            << m.full_unknowns << " unknowns in the full network\n"
            << "  error against " << check.reference
            << (check.against_full ? ""
                : check.cascade    ? ", or the truncated poles' transients at the switching "
                                     "edges where larger (an estimate)"
                                   : ", or the static correction's error at the switching "
                                     "edges where larger (an estimate)")
            << " (every sample, relative to each probe's largest |deflection|):";
  for (size_t k = 0; k < check.frequencies.size(); ++k)
    std::cout << " " << format("%.2e", check.errors[k]) << " at " << si(check.frequencies[k], "Hz")
              << (k + 1 < check.frequencies.size() ? "," : "");
  if (check.against_full) {
    std::cout << "\n  error of the peaks this sweep prints (each output's periodic minimum and "
                 "maximum, same basis):";
    for (size_t k = 0; k < check.frequencies.size(); ++k)
      std::cout << " " << format("%.2e", check.extreme_errors[k]) << " at "
                << si(check.frequencies[k], "Hz") << (k + 1 < check.frequencies.size() ? "," : "");
  }
  std::cout << "\n  tolerance " << format("%.3g", m.tolerance)
            << (check.against_full ? " on the peaks" : " on the estimate")
            << (check.tolerance_met ? ": met" : ": NOT MET") << "\n";
  if (!check.tolerance_met)
    std::cout << tolerance_warning(check.stated_error(), m.tolerance) << "\n";
  std::cout << "  cost: reduced sweep " << milliseconds(reduced_sweep) << " (reduction "
            << milliseconds(check.build_seconds) << " + " << count << " solves)";
  if (!check.against_full) {
    std::cout << "; the check's wider reduction " << milliseconds(check.full_build_seconds) << " + "
              << milliseconds(check.full_solve_seconds) << " per frequency\n";
    return;
  }
  std::cout << "; full exact sweep, estimated from the check ("
            << milliseconds(check.full_build_seconds) << " decomposition + "
            << milliseconds(check.full_solve_seconds)
            << " per frequency): " << milliseconds(full_sweep) << " -> the reduced path is "
            << (reduced_sweep <= full_sweep
                    ? format("%.2g", full_sweep / reduced_sweep) + "x faster"
                    : format("%.2g", reduced_sweep / full_sweep) +
                          "x SLOWER (the full eigen-decomposition is small here)")
            << "\n";
}

// The peaks per frequency, deflections in mm when every output is one (as the default outputs
// are), else each output in its own unit, named in its column; then the largest swing.
void print_sweep_table(const emnet::SwitchingSweepResult& result) {
  const auto& outputs = result.outputs;
  const auto& frequencies = result.frequencies;
  bool all_deflections = true;
  for (const auto& output : outputs) all_deflections &= output.probe.unit == "m";
  auto column_unit = [&](const emnet::Probe& probe) {
    return all_deflections ? std::string() : " [" + probe.unit + "]";
  };
  auto in_table = [&](double value) { return all_deflections ? value * 1e3 : value; };
  std::printf("%10s", "f [Hz]");
  for (const auto& output : outputs)
    std::printf(" %12s %12s",
                shown(output.probe.name + " left" + column_unit(output.probe)).c_str(),
                shown(output.probe.name + " right" + column_unit(output.probe)).c_str());
  std::printf(all_deflections ? "   [mm]\n" : "\n");
  for (size_t k = 0; k < frequencies.size(); ++k) {
    std::printf("%10.7g", frequencies[k]);
    for (const auto& output : outputs)
      std::printf(" %12.6g %12.6g", in_table(output.left[k]), in_table(output.right[k]));
    std::printf("\n");
  }
  if (frequencies.empty()) return;
  // The largest peak-to-peak among the outputs in the main output's unit (swings in other
  // units do not compare), not the main output's own.
  const size_t main_probe = result.peak_output;
  size_t widest = main_probe, at = result.peak_index;
  auto swing = [&](size_t p, size_t k) { return outputs[p].right[k] - outputs[p].left[k]; };
  for (size_t p = 0; p < outputs.size(); ++p) {
    if (outputs[p].probe.unit != outputs[main_probe].probe.unit) continue;
    for (size_t k = 0; k < frequencies.size(); ++k)
      if (swing(p, k) > swing(widest, at)) widest = p, at = k;
  }
  const std::string unit = all_deflections ? "mm" : outputs[widest].probe.unit;
  std::printf("largest swing of %s at %.7g Hz: %.6g %s left, %.6g %s right\n",
              shown(outputs[widest].probe.name).c_str(), frequencies[at],
              in_table(outputs[widest].left[at]), shown(unit).c_str(),
              in_table(outputs[widest].right[at]), shown(unit).c_str());
}

}  // namespace

int report_switching_sweep(const SweepReportInput& input) {
  const CommonOptions& options = input.options;
  const emnet::Model& model = input.model;
  const emnet::SwitchingSweepResult& result = input.result;
  const std::vector<double>& frequencies = result.frequencies;
  const size_t count = frequencies.size();
  const auto& check = result.reduction;
  std::vector<emnet::PlotMarker> markers;
  if (result.first_mode_hz)
    markers.push_back(
        {*result.first_mode_hz, "f1 = " + format("%.6g", *result.first_mode_hz) + " Hz"});
  if (count > 0)
    markers.push_back({frequencies[result.peak_index],
                       "sweep peak " + format("%.6g", frequencies[result.peak_index]) + " Hz"});
  const double total = input.total_seconds;
  end_progress(options);
  if (check && !check->tolerance_met)
    std::cerr << tolerance_warning(check->stated_error(), check->tolerance) << "\n";
  if (options.json) {
    std::cout << json_text(emnet::to_json(result, model, input.notes, total)) << "\n";
    write_sweep_files(input, markers);
    write_shape(input.shape, input.result.shape, input.model, "periodic state", options, false);
    return validity_exit(result.validity);
  }
  const std::string method = emnet::method_name(result.method);  // exact, shooting, reduced
  print_header(model, model.network.assemble());
  for (const auto& note : input.notes) std::cout << "note: " << shown(note) << "\n";
  std::cout << "periodic steady state, " << method
            << (method == "reduced"
                    ? " (modal coordinates of the kept modes, closed-form periodic state, "
                      "global extremes: bounded search, then Newton)"
                : method == "exact" ? " (one eigen-decomposition, closed-form periodic state, "
                                      "global extremes: bounded search, then Newton)"
                                    : " (Newton shooting on one period of IDA)")
            << ", " << count << " switching frequencies\n"
            << "accuracy: worst periodicity residual "
            << format("%.2g", result.worst_periodicity_residual) << "\ncost: periodic solves "
            << milliseconds(result.solve_seconds)
            << (result.period_runs > 0
                    ? " (" + std::to_string(result.period_runs) + " one-period IDA runs)"
                    : std::string())
            << ", total " << milliseconds(total) << "\n";
  if (check) print_reduction_check(*check, result);
  std::cout << "\n";
  print_sweep_table(result);
  for (const auto& m : markers) std::cout << "marker: " << m.label << "\n";
  write_sweep_files(input, markers);
  if (!input.plot.empty()) std::cout << "plot written to " << shown(input.plot) << "\n";
  write_shape(input.shape, input.result.shape, input.model, "periodic state", options, true);
  print_validity(result.validity);
  return validity_exit(result.validity);
}

}  // namespace emnet_cli
