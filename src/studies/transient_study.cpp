// The transient study (emnet/studies/transient_study.hpp).
#include "emnet/studies/transient_study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "emnet/core/errors.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/model/drive.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/scene/parameters.hpp"

namespace emnet {

std::vector<Probe> transient_outputs(const Model& model, const std::vector<std::string>& texts) {
  std::vector<Probe> outputs = probes_of(transient_output_list(model));
  if (texts.empty()) return outputs;
  std::vector<Probe> probes;
  for (const auto& text : texts) {
    const auto named = std::find_if(outputs.begin(), outputs.end(),
                                    [&](const Probe& probe) { return probe.name == text; });
    probes.push_back(named != outputs.end() ? *named : model.parse_probe(text));
  }
  return probes;
}

namespace {

// `voltages` with each DEA of `judged` (circuit_dea_voltage_probes, computed with the outputs so
// that the field check has a value where the circuit gives no bound: an inductor, a current
// source or back-coupling) that has no proven bound there at the largest |value| of its
// `values` [V] (at the output times: a peak between them is missed, so a bound, which never
// is, is kept where there is one).
void judge_computed_voltages(std::vector<DeaVoltage>& voltages,
                             const std::vector<CircuitDeaVoltageProbe>& judged,
                             const std::vector<std::vector<double>>& values) {
  for (size_t k = 0; k < judged.size() && k < values.size(); ++k) {
    const std::string& name = judged[k].dea;
    double largest = 0.0;
    for (double v : values[k]) largest = std::max(largest, std::abs(v));
    const bool bounded = std::any_of(voltages.begin(), voltages.end(),
                                     [&](const DeaVoltage& v) { return v.dea == name; });
    if (!bounded)
      voltages.push_back({name, largest, "the largest computed at the output times, no bound"});
  }
}

}  // namespace

void TransientStudyOptions::validate() const {
  auto refuse = [](const std::string& field, const std::string& why) {
    throw OptionError(field, why);
  };
  if (switching_hz && (!(*switching_hz > 0.0) || !std::isfinite(*switching_hz)))
    refuse("switching_hz", "must be a positive frequency in Hz (> 0)");
  if (!(periods > 0.0) || periods > 1e6)
    refuse("periods", "must be > 0 and at most 1e6 (inclusive)");
  if (!valid_relative_tolerance(rtol)) refuse("rtol", kRelativeToleranceRange);
  if (!(atol >= 0.0) || !std::isfinite(atol)) refuse("atol", "must be >= 0");
  // IDA weighs each unknown's error by 1/(rtol·|y| + atol) and sums the squares: below 1e-150
  // the squares of an unknown at zero overflow, and IDA failed with a misleading "tstop ...
  // behind t".
  if (atol > 0.0 && atol < 1e-150)
    refuse("atol",
           "must be 0 (a scale per unknown) or at least 1e-150: below that IDA's error weights "
           "1/atol overflow when squared");
  if (!(max_step >= 0.0) || !std::isfinite(max_step))
    refuse("max_step", "must be >= 0 (0: no limit)");
  if (points_per_period < 2 || points_per_period > 100000)
    refuse("points_per_period", "must be from 2 to 100000 (inclusive)");
  if (shape_instants != 0 && (shape_instants < 2 || shape_instants > points_per_period))
    refuse("shape_instants", "must be 0 (no shape) or from 2 to the points per period (" +
                                 std::to_string(points_per_period) +
                                 "): the shape is drawn at output times");
}

namespace {

// The shape at `instants` of the last period's output times (evenly among them), from the shape
// probes' values at every output time.
DeformedShape last_period_shape(const ShapeProbes& probes, const std::vector<double>& times,
                                const std::vector<std::vector<double>>& values, int per_period,
                                int instants, double frequency) {
  const size_t last = times.size() - 1;
  const size_t first = last >= static_cast<size_t>(per_period) ? last - per_period : 0;
  const size_t span = last - first;
  std::vector<size_t> picked;
  for (int s = 0; s < instants; ++s) {
    const size_t k = first + (span * static_cast<size_t>(s) + instants / 2) / instants + 1;
    if (picked.empty() || k != picked.back()) picked.push_back(std::min(k, last));
  }
  std::vector<double> at;
  std::vector<std::vector<double>> picked_values(values.size());
  for (size_t k : picked) at.push_back(times[k]);
  for (size_t p = 0; p < values.size(); ++p)
    for (size_t k : picked) picked_values[p].push_back(values[p][k]);
  DeformedShape shape = deformed_shape(probes, at, picked_values);
  shape.frequency = frequency;
  return shape;
}

}  // namespace

TransientStudyResult run_transient_study(Scene scene, const TransientStudyOptions& options) {
  const Stopwatch stopwatch;
  options.validate();
  auto refuse = [](const std::string& field, const std::string& why) {
    throw OptionError(field, why);
  };
  if (options.switching_hz)
    set_switching_frequency(scene, *options.switching_hz);  // drive and periodic sources
  TransientStudyResult study;
  PrepareOptions prepare = options.prepare;
  // IDA serves large kinematics; the exact method not, so "auto" stays small for it (explicit
  // "large" is refused below, naming the method).
  const bool exact_auto = options.method == TransientMethod::exact && scene.beam.kinematics_auto;
  prepare.large_kinematics =
      exact_auto ? LargeKinematicsUse::refused : LargeKinematicsUse::dynamics;
  study.model = prepare_model(scene, prepare);
  study.system = study.model.network.assemble();
  const Model& model = study.model;
  study.frequency_hz = model.scene.drive.frequency;
  if (!(study.frequency_hz > 0.0))
    throw OptionError::in_file(
        "switching_hz", model.scene.file, "drive.frequency",
        "a transient needs a drive with a frequency > 0 (or {switching_hz})");
  if (options.method == TransientMethod::exact && model.beam.kinematics == BeamKinematics::large)
    refuse("method",
           "the exact method needs a linear network, and beam.kinematics = \"large\" makes the "
           "beam nonlinear; use the ida method");
  if (options.method == TransientMethod::exact && study.system.is_nonlinear())
    refuse("method",
           "the exact method needs a linear network, and this scene's DEAs have their "
           "electrical model (nonlinear); set drive.electrical_dynamics=false for ideal "
           "voltage-driven DEAs, or use the ida method");
  study.outputs = transient_outputs(model, options.outputs);
  const double count = std::round(options.periods * options.points_per_period);
  if (count < 1.0)
    refuse("periods",
           "periods x points-per-period must be >= 0.5, for at least one output step after t = 0");
  const ShapeProbes shape = options.shape_instants > 0 ? shape_probes(model) : ShapeProbes{};
  const double stored =
      (count + 1.0) * (static_cast<double>(study.outputs.size() + shape.probes.size()) + 1.0);
  if (stored > kTransientMaximumStoredValues) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "%.0f output times x (%zu outputs + the time) would store %.3g values (%.3g GB "
                  "of doubles); at most %.0f values (%.0f MB) are stored (inclusive): lower the "
                  "periods or the points per period, or ask fewer outputs",
                  count + 1.0, study.outputs.size(), stored, 8.0 * stored / 1e9,
                  kTransientMaximumStoredValues, 8.0 * kTransientMaximumStoredValues / 1e6);
    refuse("periods", text);
  }
  const double period = 1.0 / study.frequency_hz;
  TransientOptions transient;
  transient.end_time = options.periods * period;
  transient.relative_tolerance = options.rtol;
  transient.absolute_tolerance = options.atol;
  transient.max_step = options.max_step;
  transient.start = options.start;
  transient.progress = options.progress;
  const long outputs = static_cast<long>(count);
  transient.output_times.reserve(static_cast<size_t>(outputs) + 1);
  for (long k = 0; k <= outputs; ++k)
    transient.output_times.push_back(transient.end_time * static_cast<double>(k) / outputs);
  study.end_time = transient.end_time;
  const std::vector<CircuitDeaVoltageProbe> judged = circuit_dea_voltage_probes(model);
  std::vector<Probe> computed = study.outputs;
  for (const CircuitDeaVoltageProbe& one : judged) computed.push_back(one.probe);
  computed.insert(computed.end(), shape.probes.begin(), shape.probes.end());
  // The rotations for the geometric error, within what may be stored beside the outputs.
  const double spare = std::floor(kTransientMaximumStoredValues / (count + 1.0)) -
                       static_cast<double>(study.outputs.size() + shape.probes.size()) - 1.0;
  const RotationProbes rotations =
      rotation_probes(model, static_cast<size_t>(std::clamp(spare, 0.0, 64.0)));
  computed.insert(computed.end(), rotations.probes.begin(), rotations.probes.end());
  study.result = options.method == TransientMethod::exact
                     ? run_transient_exact(study.system, computed, transient)
                     : run_transient_ida(study.system, computed, transient);
  std::optional<RotationPeak> rotation;
  if (study.result.status.ok() && !rotations.probes.empty()) {
    auto& values = study.result.values;
    std::vector<double> peaks;
    for (auto it = values.end() - static_cast<long>(rotations.probes.size()); it != values.end();
         ++it) {
      peaks.push_back(0.0);
      for (double v : *it) peaks.back() = std::max(peaks.back(), std::abs(v));
    }
    values.resize(values.size() - rotations.probes.size());
    rotation = largest_rotation(rotations, peaks);
  }
  if (study.result.status.ok() && !shape.probes.empty()) {
    auto& values = study.result.values;
    const std::vector<std::vector<double>> shape_values(
        values.end() - static_cast<long>(shape.probes.size()), values.end());
    values.resize(values.size() - shape.probes.size());
    study.shape =
        last_period_shape(shape, study.result.times, shape_values, options.points_per_period,
                          options.shape_instants, study.frequency_hz);
  }
  std::vector<std::vector<double>> judged_values;
  if (study.result.status.ok() && !judged.empty()) {
    judged_values.assign(study.result.values.end() - static_cast<long>(judged.size()),
                         study.result.values.end());
    study.result.values.resize(study.outputs.size());
  }
  study.start_text =
      options.start == StartState::static_
          ? "the static state under the drive's first half-period"
          : "at rest (every unknown zero before t = 0; the drive switches on at t = 0)";
  if (!study.result.status.ok()) {
    study.status = study.result.status.with_context("tran: ");
    study.seconds = stopwatch.seconds();
    return study;
  }
  std::vector<DeflectionPeak> peaks;
  for (size_t k = 0; k < study.outputs.size(); ++k)
    if (study.outputs[k].quantity == ProbeQuantity::deflection) {
      peaks.push_back({study.outputs[k].name, 0.0});
      for (double v : study.result.values[k])
        peaks.back().peak = std::max(peaks.back().peak, std::abs(v));
    }
  std::vector<DeaVoltage> voltages = drive_peak_voltages(model.scene);
  judge_computed_voltages(voltages, judged, judged_values);
  study.validity = check_validity(model.scene, peaks, voltages, rotation);
  study.seconds = stopwatch.seconds();
  return study;
}

}  // namespace emnet
