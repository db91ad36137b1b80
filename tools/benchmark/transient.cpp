// Benchmark sections 2 and 3, transient: the fish fin with the ideal drive, 50 periods, IDA at
// several tolerances, the exact method and ngspice's .tran, against run_transient_exact.
#include "bench.hpp"

namespace emnet_bench {

struct TranContext {
  emnet::Model model;
  emnet::System system;
  std::vector<emnet::Probe> probes;
  double period = 0.2, end_time = 10.0;
  std::vector<double> outputs;  // emnet's 100 per period
};

TranContext tran_context(const Settings& settings) {
  TranContext context{build(settings.fishfin(), ideal_drive), {}, {}};
  context.system = context.model.network.assemble();
  context.probes = deflection_probes(context.model);
  context.period = 1.0 / context.model.scene.drive.frequency;
  const int periods = settings.quick ? 5 : 50;
  context.end_time = periods * context.period;
  for (int k = 0; k <= periods * 100; ++k) context.outputs.push_back(k * context.period / 100.0);
  return context;
}

namespace {

// The exact method from the scene file, in process and as `emnet tran --method exact`; the
// reference of the section. `breakdown` gets where run_transient_exact's time goes.
MethodRow exact_transient_row(const Settings& settings, const TranContext& context,
                              const emnet::TransientOptions& options, int periods,
                              std::string& breakdown) {
  MethodRow row{"emnet", "exact", "–"};
  row.error = 0.0;
  row.in_process = measure(
      [&] {
        const auto start = Clock::now();
        const emnet::Model m = build(settings.fishfin(), ideal_drive);
        emnet::run_transient_exact(m.network.assemble(), deflection_probes(m), options);
        return seconds_since(start);
      },
      10, 3.0);
  bool ok = true;
  row.whole_process = measure_process(
      emnet_cli(settings, "tran", {"--method", "exact", "--periods", std::to_string(periods)}), 10,
      3.0, ok);
  // Where its time goes: the same run with outputs only at the period boundaries.
  emnet::TransientOptions sparse = options;
  sparse.output_times.clear();
  for (int k = 0; k <= periods; ++k) sparse.output_times.push_back(k * context.period);
  const Timing few_outputs = measure(
      [&] { return emnet::run_transient_exact(context.system, context.probes, sparse).seconds; },
      10, 2.0);
  const Timing all_outputs = measure(
      [&] { return emnet::run_transient_exact(context.system, context.probes, options).seconds; },
      10, 2.0);
  breakdown =
      "run_transient_exact alone: " + time_text(all_outputs.median) + " with " +
      std::to_string(options.output_times.size()) + " outputs, " + time_text(few_outputs.median) +
      " with " + std::to_string(sparse.output_times.size()) +
      " (one per period): the outputs cost " +
      time_text((all_outputs.median - few_outputs.median) /
                (options.output_times.size() - sparse.output_times.size())) +
      " each, " +
      format("%.0f", 100.0 * (all_outputs.median - few_outputs.median) / all_outputs.median) +
      " % of the run";
  row.note = "the reference (rounding only)";
  return row;
}

// IDA at `rtol` from the scene file, in process and as `emnet tran --method ida`.
MethodRow ida_transient_row(const Settings& settings, const emnet::TransientOptions& options,
                            double rtol, const emnet::TransientResult& exact, int periods) {
  MethodRow row{"emnet", "IDA", "rtol " + format("%.0e", rtol)};
  emnet::TransientOptions ida = options;
  ida.relative_tolerance = rtol;
  emnet::TransientResult result;
  row.in_process = measure(
      [&] {
        const auto start = Clock::now();
        const emnet::Model m = build(settings.fishfin(), ideal_drive);
        result = emnet::run_transient_ida(m.network.assemble(), deflection_probes(m), ida);
        return seconds_since(start);
      },
      3, 2.0);
  row.error = result.status.ok() ? run_error(result.values, exact.values) : NAN;
  row.note = std::to_string(result.statistics.steps) + " steps";
  bool ok = true;
  row.whole_process = measure_process(emnet_cli(settings, "tran",
                                                {"--method", "ida", "--rtol", format("%g", rtol),
                                                 "--periods", std::to_string(periods)}),
                                      3, 2.0, ok);
  if (!ok) row.note += "; the program failed";
  return row;
}

// One ngspice setting of the transient: default options (the deck's .options line removed) or
// tightened.
struct SpiceTranSetting {
  std::string name;
  double reltol;  // 0: ngspice's defaults
  double max_step_per_period;
};

// ngspice's .tran with `setting`, in process and as `ngspice -b`, compared with the exact method
// at ngspice's own time points away from the switching edges. `edge_width` gets the deck's ε.
MethodRow ngspice_transient_row(const Settings& settings, const TranContext& context,
                                const emnet::TransientOptions& options,
                                const SpiceTranSetting& setting, const std::string& deck_name,
                                double& edge_width) {
  emnet::SpiceDeckOptions deck_options;
  deck_options.analysis = emnet::SpiceAnalysis::tran;
  deck_options.outputs = context.probes;
  deck_options.end_time = context.end_time;
  deck_options.output_step = context.period / 100.0;
  deck_options.relative_tolerance = setting.reltol > 0.0 ? setting.reltol : 1e-3;
  if (setting.max_step_per_period > 0.0)
    deck_options.max_step = context.period / setting.max_step_per_period;
  const emnet::SpiceDeck deck = emnet::write_spice_deck(context.model, deck_options);
  edge_width = deck_options.edge_fraction * 0.5 * context.period;
  const std::string text = setting.reltol > 0.0 ? deck.text : remove_options_line(deck.text);
  const std::string path = write_deck(settings, deck_name, text);
  MethodRow row{"ngspice", ".tran", setting.name};
  emnet::NgspiceResult result;
  row.in_process = measure(
      [&] {
        const auto start = Clock::now();
        result = emnet::run_ngspice(text, in_process_ngspice());
        return seconds_since(start);
      },
      3, 3.0);
  if (result.status.ok() && result.scale()) {
    const SpicePoints points = spice_points_away_from_edges(
        result, deck, context.probes.size(), context.period, edge_width, context.end_time);
    emnet::TransientOptions at = options;
    at.output_times = points.kept;
    const emnet::TransientResult reference =
        emnet::run_transient_exact(context.system, context.probes, at);
    row.error = run_error(points.values, reference.values);
    row.note = std::to_string(result.scale()->real_values.size()) + " time points";
  } else {
    row.note = "ngspice failed: " + result.status.message;
  }
  bool ok = true;
  row.whole_process = ngspice_process(settings, path, 3, 3.0, ok);
  if (!ok) row.note += "; whole process failed";
  return row;
}

// The subsection's text: what is compared, the table, and where the exact method's time goes.
std::string transient_markdown(int periods, double edge_width, const std::vector<MethodRow>& rows,
                               const std::string& exact_breakdown) {
  std::ostringstream md;
  md << "### Transient: " << periods << " periods at 5 Hz, fish fin (ideal drive), from rest\n\n"
     << "emnet: 100 outputs per period; in-process times run from the scene file to the result; "
        "whole process is `emnet tran … --method exact|ida`. Error: the largest |difference| "
        "over the run and over the deflection outputs (P2..P4, tip, dx2..dx4), relative to each "
        "output's peak, against the exact method. ngspice: the exported deck, output step T/100, "
        "max step = output step unless stated; \"default\" removes the deck's `.options` line "
        "(reltol 1e-3, ngspice's abstol and vntol); the tightened decks set vntol 1e-12, "
        "abstol 1e-15. ngspice is compared at its own time points, against the exact method "
        "evaluated there, excluding ±10ε = ±"
     << time_text(10.0 * edge_width)
     << " around every switching edge (the deck switches by linear edges of width ε centred "
        "on the instants).\n\n"
     << method_table(rows) << "\nWhere the exact method's time goes: " << exact_breakdown << ".\n";
  return md.str();
}

}  // namespace

Section tran_section(const Settings& settings, std::vector<ParetoPoint>& pareto) {
  TranContext context = tran_context(settings);
  const int periods = static_cast<int>(std::lround(context.end_time / context.period));
  emnet::TransientOptions options;
  options.end_time = context.end_time;
  options.output_times = context.outputs;
  const emnet::TransientResult exact =
      emnet::run_transient_exact(context.system, context.probes, options);
  std::string exact_breakdown;
  std::vector<MethodRow> rows{
      exact_transient_row(settings, context, options, periods, exact_breakdown)};
  const std::vector<double> tolerances =
      settings.quick ? std::vector<double>{1e-3, 1e-6}
                     : std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  for (double rtol : tolerances)
    rows.push_back(ida_transient_row(settings, options, rtol, exact, periods));
  const std::vector<SpiceTranSetting> spice_settings =
      settings.quick
          ? std::vector<SpiceTranSetting>{{"default", 0.0, 0.0}}
          : std::vector<SpiceTranSetting>{
                {"default", 0.0, 0.0},      {"reltol 1e-4", 1e-4, 0.0},
                {"reltol 1e-5", 1e-5, 0.0}, {"reltol 1e-6", 1e-6, 0.0},
                {"reltol 1e-7", 1e-7, 0.0}, {"reltol 1e-6, max step T/1000", 1e-6, 1000.0}};
  double edge_width = 0.0;
  for (size_t k = 0; k < spice_settings.size(); ++k)
    rows.push_back(ngspice_transient_row(settings, context, options, spice_settings[k],
                                         "fishfin-tran-" + std::to_string(k), edge_width));
  for (const auto& row : rows) {
    const std::string series = row.tool + " " + row.method;
    pareto.push_back({series + " in-process", row.setting == "–" ? "" : row.setting,
                      row.in_process.median, row.error});
    pareto.push_back({series + " whole process", "", row.whole_process.median, row.error});
  }
  Section section;
  section.headline = headline(rows);
  section.markdown = transient_markdown(periods, edge_width, rows, exact_breakdown);
  return section;
}

}  // namespace emnet_bench
