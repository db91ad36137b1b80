// Benchmark section 3, AC: the fish fin's 1000-point sweep by run_ac and by ngspice's .ac,
// against a dense complex solve at ngspice's own frequencies.
#include "bench.hpp"

namespace emnet_bench {

AcContext ac_context(const Settings& settings) {
  AcContext context{build(settings.fishfin(), ideal_drive), {}, {}, {}, {}};
  context.system = context.model.network.assemble();
  context.rest = emnet::solve_static(context.system);
  context.probes = deflection_probes(context.model);
  const auto& spec = context.model.scene.ac;
  context.grid = emnet::frequency_grid(spec.from, spec.to, spec.points, spec.log);
  return context;
}

// AC: emnet's run_ac and ngspice's .ac over the scene's 1000 points, against a dense solve.
Section ac_section(const Settings& settings, std::vector<ParetoPoint>& pareto) {
  const AcContext context = ac_context(settings);
  const emnet::Model& model = context.model;
  const emnet::System& system = context.system;
  const emnet::StaticResult& rest = context.rest;
  const auto& probes = context.probes;
  const auto& spec = model.scene.ac;
  const auto& grid = context.grid;
  const Eigen::MatrixXd g = Eigen::MatrixXd(emnet::linearised_g(system, rest.operating_point));
  const Eigen::MatrixXd c = Eigen::MatrixXd(system.C);
  const Eigen::VectorXcd b = system.b_ac();
  // Dense reference: [probe][frequency]; frequencies ≤ 0 left out (NaN).
  auto reference_at = [&](const std::vector<double>& frequencies) {
    std::vector<std::vector<std::complex<double>>> values(
        probes.size(), std::vector<std::complex<double>>(frequencies.size(), NAN));
    for (size_t k = 0; k < frequencies.size(); ++k) {
      if (!(frequencies[k] > 0.0)) continue;
      const double omega = 2.0 * M_PI * frequencies[k];
      const Eigen::MatrixXcd a = g.cast<std::complex<double>>() +
                                 std::complex<double>(0.0, omega) * c.cast<std::complex<double>>();
      const Eigen::VectorXcd y = a.fullPivLu().solve(b);
      for (size_t p = 0; p < probes.size(); ++p)
        values[p][k] = emnet::probe_phasor(probes[p], y, omega);
    }
    return values;
  };
  auto ac_error = [&](const std::vector<std::vector<std::complex<double>>>& values,
                      const std::vector<std::vector<std::complex<double>>>& reference) {
    double worst = 0.0;
    for (size_t p = 0; p < reference.size(); ++p) {
      double peak = 0.0;
      for (const auto& v : reference[p])
        if (std::isfinite(v.real())) peak = std::max(peak, std::abs(v));
      if (!(peak > 0.0)) continue;
      for (size_t k = 0; k < reference[p].size(); ++k)
        if (std::isfinite(reference[p][k].real()))
          worst = std::max(worst, std::abs(values[p][k] - reference[p][k]) / peak);
    }
    return worst;
  };
  std::vector<MethodRow> rows;
  {
    const emnet::AcResult result = emnet::run_ac(system, rest.operating_point, grid, probes);
    MethodRow row{"emnet", "run_ac (" + emnet::method_name(result.method) + ")",
                  std::to_string(grid.size()) + " points"};
    row.error = ac_error(result.values, reference_at(grid));
    // In-process: from the scene file to the result, as `emnet ac` does it.
    row.in_process =
        measure([&] { return fishfin_ac_from_scene_seconds(settings, grid); }, 20, 2.0);
    const Timing analysis_only = measure(
        [&] { return emnet::run_ac(system, rest.operating_point, grid, probes).seconds; }, 20, 1.0);
    bool ok = true;
    row.whole_process = measure_process(emnet_cli(settings, "ac", {}), 10, 3.0, ok);
    // The floor of any whole-process time: starting the program and printing its help.
    bool help_ok = true;
    const Timing start_up = measure_process({settings.emnet, "--help"}, 10, 2.0, help_ok);
    row.note = "in-process from the scene file; run_ac alone " + time_text(analysis_only.median) +
               "; `emnet --help` as a whole process " + time_text(start_up.median) +
               (ok ? "" : "; the program failed");
    rows.push_back(row);
  }
  {
    emnet::SpiceDeckOptions options;
    options.analysis = emnet::SpiceAnalysis::ac;
    options.outputs = probes;
    const emnet::SpiceDeck deck = emnet::write_spice_deck(model, options);
    const std::string path = write_deck(settings, "fishfin-ac", deck.text);
    MethodRow row{"ngspice", ".ac", "default options"};
    emnet::NgspiceResult result;
    row.in_process = measure(
        [&] {
          const auto start = Clock::now();
          result = emnet::run_ngspice(deck.text, in_process_ngspice());
          return seconds_since(start);
        },
        10, 3.0);
    if (result.status.ok() && result.scale()) {
      std::vector<double> frequencies;
      for (const auto& v : result.scale()->complex_values) frequencies.push_back(v.real());
      if (frequencies.empty()) frequencies = result.scale()->real_values;
      std::vector<std::vector<std::complex<double>>> values(probes.size());
      for (size_t p = 0; p < probes.size(); ++p) {
        const emnet::NgspiceVector* vector = result.find(deck.outputs[p].vector);
        if (vector) values[p] = vector->complex_values;
        values[p].resize(frequencies.size(), NAN);
      }
      row.error = ac_error(values, reference_at(frequencies));
    } else {
      row.note = "ngspice failed: " + result.status.message;
    }
    bool ok = true;
    row.whole_process = ngspice_process(settings, path, 10, 3.0, ok);
    if (!ok) row.note += " whole process failed";
    rows.push_back(row);
  }
  for (const auto& row : rows) {
    pareto.push_back(
        {row.tool + " " + row.method + " in-process", "", row.in_process.median, row.error});
    pareto.push_back(
        {row.tool + " " + row.method + " whole process", "", row.whole_process.median, row.error});
  }
  Section section;
  section.headline = headline(rows);
  std::ostringstream md;
  md << "### AC: 1000 points, fish fin (ideal drive)\n\n"
     << "The scene's sweep (" << spec.points << " points, " << spec.from << "–" << spec.to
     << " Hz, linear), every deflection output. Error: the largest |Y − Y_ref| over frequencies "
        "f > 0, relative to that output's peak |Y_ref|; Y_ref by a dense full-pivoting complex "
        "LU of (G + J_g + jωC)·Y = B_ac at the tool's own frequencies. ngspice's deck writes "
        "12 significant digits and integrates deflections with a 1 F ‖ 1 GΩ leak (1.6e-9 "
        "relative at 0.1 Hz, more towards 0 Hz).\n\n"
     << method_table(rows);
  section.markdown = md.str();
  return section;
}

}  // namespace emnet_bench
