// The tran command's report (tran.hpp): the text table, --json (emnet/report/transient_json.hpp),
// --csv and --plot of a transient result (the response in the table's units, each unit in its
// own panel, over a panel of the drive).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "cli/tran.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/circuit.hpp"
#include "emnet/model/drive.hpp"
#include "emnet/network/waveform.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/report/transient_json.hpp"

namespace emnet_cli {

namespace {

// `waveform` at `times` and, so that its edges are drawn where they are, at each of its
// breakpoints inside the run both before (its value an instant earlier) and at the edge.
emnet::LineSeries sampled_waveform(const emnet::Waveform& waveform,
                                   const std::vector<double>& times, std::string label,
                                   std::string unit) {
  emnet::LineSeries line{std::move(label), {}, {}, std::move(unit)};
  if (times.empty()) return line;
  std::vector<double> edges;
  waveform.breakpoints(times.front(), times.back(), edges);
  std::sort(edges.begin(), edges.end());
  const double instant = 1e-9 * std::max(std::abs(times.back() - times.front()), 1e-300);
  size_t e = 0;
  for (double t : times) {
    for (; e < edges.size() && edges[e] <= t; ++e) {
      line.x.push_back(edges[e]);
      line.y.push_back(waveform.value(edges[e] - instant));
      line.x.push_back(edges[e]);
      line.y.push_back(waveform.value(edges[e]));
    }
    line.x.push_back(t);
    line.y.push_back(waveform.value(t));
  }
  return line;
}

// The response, each unit in its own panel (lengths in mm as in every plot: plot_unit); under it
// the drive: the DEA voltages among the outputs and, dashed, the voltage (or current) of every
// source that drives the network: the drive's own sources on the DEAs it names, the circuit's
// sources.
void write_tran_plot(const TranReportInput& input) {
  const auto& probes = input.plot_probes;
  const auto& times = input.result.times;
  const emnet::Scene& scene = input.model.scene;
  std::vector<emnet::LineSeries> series;
  bool dea_voltages = false;  // the sources are dashed when DEA voltages are drawn beside them
  for (size_t k : input.plotted.indices) {
    const size_t in_table = input.probes.size();
    const PlotUnit shown = plot_unit(probes[k].unit);
    std::vector<double> values =
        k < in_table ? input.result.values[k] : input.plot_only_values[k - in_table];
    for (double& value : values) value *= shown.scale;
    series.push_back(
        {probes[k].name + " (" + probes[k].description + ")", times, values, shown.unit});
    dea_voltages |= probes[k].quantity == emnet::ProbeQuantity::dea_voltage;
  }
  if (scene.drive.kind != emnet::DriveKind::none) {
    for (const std::string& dea : scene.drive.deas) {
      if (emnet::circuit_drives_dea(scene, dea)) continue;
      // In the colour of the DEA's own voltage, when that is drawn.
      int colour = -1;
      for (size_t k = 0; k < input.plotted.indices.size(); ++k)
        if (probes[input.plotted.indices[k]].name == "u_" + dea ||
            probes[input.plotted.indices[k]].name == "dea_voltage:" + dea)
          colour = static_cast<int>(k);
      series.push_back(sampled_waveform(emnet::dea_drive(scene.drive, dea).voltage, times,
                                        "DEA " + dea + " drive source voltage", "V"));
      series.back().dashed = dea_voltages;
      series.back().colour = colour;
    }
  }
  for (const emnet::CircuitSpec& element : scene.circuit) {
    if (!emnet::is_source(element.kind)) continue;
    const bool voltage = element.kind == emnet::CircuitKind::voltage_source;
    series.push_back(sampled_waveform(
        emnet::circuit_waveform(element), times,
        "circuit " + element.name + (voltage ? " source voltage" : " source current"),
        voltage ? "V" : "A"));
    series.back().dashed = dea_voltages;
  }
  emnet::LinePlotOptions options;
  options.axis_labels = axis_labels("");
  options.reference_lines = deflection_limit_lines(input.validity);
  options.output = plot_output(input.options, input.tran.plot_script);
  stop_if_interrupted();
  check_plot(emnet::write_line_plot(
      input.tran.plot, scene.name + ": " + drive_summary(scene) + ", " + input.result.method_text(),
      "time [s]", series, options));
}

void write_tran_files(const TranReportInput& input) {
  const auto& options = input.options;
  const auto& probes = input.probes;
  const auto& result = input.result;
  if (!options.csv.empty()) {
    std::vector<std::string> header{"time_s"};
    for (const auto& probe : probes) header.push_back(probe.name + "_" + probe.unit);
    write_csv_rows(options.csv, header, result.times.size(), [&](size_t i, auto& row) {
      row.push_back(result.times[i]);
      for (const auto& series : result.values) row.push_back(series[i]);
    });
  }
  if (!input.tran.plot.empty()) write_tran_plot(input);
}

}  // namespace

int report_tran(const TranReportInput& input) {
  const auto& options = input.options;
  const auto& tran = input.tran;
  const auto& model = input.model;
  const auto& probes = input.probes;
  const auto& result = input.result;
  const double frequency = model.scene.drive.frequency;
  const auto& st = result.statistics;
  if (options.json) {
    const emnet::TransientRunDescription run{
        model.scene.name, model.automatic_choices, input.start_text,    frequency,  tran.periods,
        tran.rtol,        input.validity,          input.total_seconds, input.shape};
    std::cout << json_text(emnet::to_json(result, probes, run)) << "\n";
    write_tran_files(input);
    write_shape(input.tran.shape, input.shape, input.model, "last period of the transient",
                input.options, false);
    return validity_exit(input.validity);
  }
  print_header(model, input.system);
  std::cout << "transient: " << shown(result.method_text()) << ", " << format("%.6g", tran.periods)
            << " periods of " << si(frequency, "Hz") << " (" << si(input.end_time, "s")
            << "), start " << input.start_text << "\n";
  if (result.method == emnet::Method::ida)
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
            << milliseconds(input.total_seconds) << "\n\n";
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
  write_tran_files(input);
  if (!tran.plot.empty()) std::cout << "plot written to " << shown(tran.plot) << "\n";
  write_shape(input.tran.shape, input.shape, input.model, "last period of the transient",
              input.options, true);
  print_validity(input.validity);
  return validity_exit(input.validity);
}

}  // namespace emnet_cli
