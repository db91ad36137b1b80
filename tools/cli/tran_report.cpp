// The tran command's report (tran.hpp): the text table, --json (emnet/report/transient_json.hpp),
// --csv and --plot of a transient result.
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "cli/tran.hpp"
#include "emnet/report/plot.hpp"
#include "emnet/report/transient_json.hpp"

namespace emnet_cli {

namespace {

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
  if (!input.tran.plot.empty()) {
    const PlottedOutputs& plotted = input.plotted;
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
        input.tran.plot,
        input.model.scene.name + ": " + drive_summary(input.model.scene) + ", " + result.method,
        "time [s]", plotted.axis_label, series));
  }
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
        model.scene.name, model.automatic_choices, input.start_text,   frequency, tran.periods,
        tran.rtol,        input.validity,          input.total_seconds};
    std::cout << json_text(emnet::to_json(result, probes, run)) << "\n";
    write_tran_files(input);
    return validity_exit(input.validity);
  }
  print_header(model, input.system);
  std::cout << "transient: " << shown(result.method) << ", " << format("%.6g", tran.periods)
            << " periods of " << si(frequency, "Hz") << " (" << si(input.end_time, "s")
            << "), start " << input.start_text << "\n";
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
  print_validity(input.validity);
  return validity_exit(input.validity);
}

}  // namespace emnet_cli
