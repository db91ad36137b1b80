// emnet sweep-switching: the periodic steady-state peaks against the switching frequency.
// Parses the options, builds the model and its outputs, calls emnet::run_switching_sweep
// (emnet/studies/switching_sweep.hpp) and hands the result to report_switching_sweep
// (sweep_switching_report.cpp).
#include "cli/sweep_switching.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/option_names.hpp"
#include "cli/shape_output.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/model/model.hpp"
#include "emnet/studies/switching_sweep.hpp"

namespace emnet_cli {

using emnet::InputError;

namespace {

struct SweepOptions {
  double from = 1.0, to = 7.0, step = 0.1;
  std::string method = "auto";
  int samples = 0;  // 0: the method's default
  double rtol = 1e-9;
  std::string plot;
  bool plot_script = false;
  bool reduce = false;
  std::string tolerance, band;       // --reduce
  std::vector<std::string> sources;  // --source: the circuit sources switched (default all)
  ShapeOptions shape;                // --shape at the sweep peak
};

int run_sweep_command(CommonOptions options, const SweepOptions& sweep) {
  const emnet::Stopwatch stopwatch;
  emnet::SwitchingSweepOptions study;
  study.from = sweep.from;
  study.to = sweep.to;
  study.step = sweep.step;
  study.method = sweep.method == "shooting" ? emnet::SwitchingSweepMethod::shooting
                 : sweep.method == "exact"  ? emnet::SwitchingSweepMethod::exact
                                            : emnet::SwitchingSweepMethod::automatic;
  study.samples = sweep.samples;
  study.rtol = sweep.rtol;
  study.reduce = sweep.reduce;
  study.sources = sweep.sources;
  study.shape_instants = shape_instants(sweep.shape);
  study.validate();
  check_plot_options(sweep.plot, sweep.plot_script);
  if (!sweep.reduce && (!sweep.tolerance.empty() || !sweep.band.empty()))
    throw InputError("--tolerance/--band", "--reduce", "--tolerance and --band need --reduce");
  show_phase(options, "building the network");
  emnet::PrepareOptions prepare;
  prepare.electrical_probe_requested = electrical_probe_requested(options);
  emnet::SweptModel swept = emnet::prepare_swept_model(load_scene(options), study.method,
                                                       options.probes, prepare, sweep.to);
  const emnet::Model& model = swept.model;
  std::vector<std::string>& notes = swept.notes;
  study.outputs = emnet::switching_sweep_outputs(model, options.probes);
  const PlottedOutputs plotted =
      sweep.plot.empty() ? PlottedOutputs{} : plotted_outputs(study.outputs, options);
  const double count = static_cast<double>(emnet::switching_frequencies(study).size());
  check_stored_values(count * (2.0 * study.outputs.size() + 1.0),
                      std::to_string(static_cast<long>(count)) + " frequencies x " +
                          std::to_string(study.outputs.size()) + " outputs x 2 extremes",
                      "--step", "raise --step or give fewer --probe");
  if (sweep.reduce)
    study.reduction =
        reduction_options(sweep.tolerance, sweep.band, sweep.to, model.scene.model.tolerance);
  study.progress = progress_of(options);
  study.phase = [&options](const std::string& what) { show_phase(options, what); };
  // The scene read once; only the drive frequency varies.
  const emnet::SwitchingSweepResult result = emnet::run_switching_sweep(model, swept.scene, study);
  if (result.cancelled) throw Interrupted("interrupted");
  if (!result.status.ok()) throw NumericalFailure(result.status.message);
  notes.insert(notes.end(), result.notes.begin(), result.notes.end());
  SweepReportInput report{options, model, result, notes};
  report.plot = sweep.plot;
  report.plot_script = sweep.plot_script;
  report.shape = sweep.shape;
  report.plotted = plotted;
  report.total_seconds = stopwatch.seconds();
  return report_switching_sweep(report);
}

}  // namespace

Command add_sweep_switching_command(CLI::App& app, CommonOptions& options) {
  auto sweep_options = std::make_shared<SweepOptions>();
  auto* sweep_command = app.add_subcommand(
      "sweep-switching",
      "periodic steady-state peak deflection to the left and to the right against the\n"
      "switching frequency (paper Fig. 14), computed directly: exact for linear networks,\n"
      "Newton shooting over one period otherwise");
  add_common(sweep_command, options);
  sets_fields(sweep_command->add_option("--from", sweep_options->from,
                                        "first switching frequency [Hz] (1)"),
              {"from"});
  sets_fields(
      sweep_command->add_option("--to", sweep_options->to, "last switching frequency [Hz] (7)"),
      {"to"});
  sets_fields(sweep_command->add_option("--step", sweep_options->step, "frequency step [Hz] (0.1)"),
              {"step"});
  sets_fields(sweep_command
                  ->add_option("--method", sweep_options->method,
                               "auto (default: exact for a linear network, reduced above 1000 "
                               "unknowns, shooting where the DEAs are driven through a nonlinear "
                               "[[circuit]] or the beam has large kinematics), exact or shooting")
                  ->check(CLI::IsMember({"auto", "exact", "shooting"})),
              {"method"});
  sets_fields(sweep_command->add_option("--samples", sweep_options->samples,
                                        "samples per period before refining the extremes "
                                        "(default 64 for the exact method, whose extremes are "
                                        "global whatever the count, also with --reduce; 256 for "
                                        "shooting, which refines the largest samples)"),
              {"samples"});
  sets_fields(sweep_command->add_option("--rtol", sweep_options->rtol,
                                        "shooting: IDA relative tolerance (1e-9)"),
              {"rtol"});
  add_plot_options(sweep_command, sweep_options->plot, sweep_options->plot_script,
                   "the peaks against the switching frequency (each output in one colour, "
                   "its left peak solid and its right peak dashed), f1 and the sweep's peak "
                   "marked");
  sets_fields(sweep_command->add_flag("--reduce", sweep_options->reduce,
                                      "periodic state of a modal reduction (modes below "
                                      "band/tolerance, static correction as a feed-through), "
                                      "checked against the exact one"),
              {"reduce"});
  sets_fields(sweep_command->add_option("--source", sweep_options->sources,
                                        "a [[circuit]] source whose frequency is swept "
                                        "(repeatable; default every periodic source: square, "
                                        "sine, pulse with a period), keeping its levels, duty, "
                                        "rise/fall and its delay as a fraction of the period"),
              {"sources"});
  add_reduction_tolerance_and_band(sweep_command, sweep_options->tolerance, sweep_options->band);
  add_shape_options(sweep_command, sweep_options->shape,
                    "over one period at the sweep peak (the largest swing)");

  return {sweep_command,
          [sweep_options, &options] { return run_sweep_command(options, *sweep_options); }};
}

}  // namespace emnet_cli
