// The switching sweep (emnet/studies/switching_sweep.hpp): per switching frequency the drive's
// excitation swapped into one assembled System (or a model per frequency when the RC choice is
// "auto"), the periodic state by the exact, shooting or reduced method, its extremes kept; then
// the sweep peak, the reduction's check, f1 and the validity of the peaks.
#include "emnet/studies/switching_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/drive.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/transient_study.hpp"

namespace emnet {
namespace {

int samples_or_default(const SwitchingSweepOptions& options) {
  if (options.samples != 0) return options.samples;
  return options.method == SwitchingSweepMethod::shooting ? 256 : 64;
}

}  // namespace

std::vector<double> switching_frequencies(const SwitchingSweepOptions& options) {
  if (!options.frequencies.empty()) {
    for (double f : options.frequencies)
      if (!(f > 0.0) || !std::isfinite(f))
        throw OptionError(
            "frequencies",
            "every switching frequency must be finite and > 0 Hz, not " + format_number("%.6g", f));
    if (options.frequencies.size() > 100000)
      throw OptionError("frequencies", "at most 100000 frequencies are swept");
    return options.frequencies;
  }
  if (!(options.from > 0.0) || !(options.to >= options.from) || !(options.step > 0.0) ||
      !std::isfinite(options.to))
    throw OptionError::between("step", "step",
                               "need 0 < from <= to and step > 0 (frequencies in Hz)",
                               "{from}/{to}/{step}");
  const double frequency_count =
      std::floor((options.to - options.from) / options.step + 1e-9) + 1.0;
  if (!(frequency_count <= 100000))
    throw OptionError("step", "gives " + format_number("%.6g", frequency_count) +
                                  " frequencies; at most 100000 (inclusive) are swept");
  const long count = static_cast<long>(frequency_count);
  std::vector<double> frequencies;
  frequencies.reserve(static_cast<size_t>(count));
  for (long k = 0; k < count; ++k)
    frequencies.push_back(options.from + options.step * static_cast<double>(k));
  return frequencies;
}

void check_swept_drive(const Scene& scene, const std::vector<std::string>& sources) {
  // (A scene of loads alone, drive kind none without a circuit, keeps its periodic state of
  // constant loads, as before.)
  const std::vector<size_t> switched = switched_sources(scene, sources);
  if (scene.drive.kind == DriveKind::none && !scene.circuit.empty() && switched.empty())
    throw InputError(scene.file, "circuit",
                     "the switching sweep varies the frequency of the [drive] and of the "
                     "[[circuit]]'s periodic sources, but drive.kind is \"none\" and no "
                     "circuit source is periodic (square, sine, pulse with a period)");
}

namespace {

// `options` with SwitchingSweepMethod::automatic replaced by what it chooses (the header), the
// reason in `notes`.
SwitchingSweepOptions resolve_sweep_method(const Model& model, const SwitchingSweepOptions& given,
                                           std::vector<std::string>& notes) {
  SwitchingSweepOptions options = given;
  if (options.method != SwitchingSweepMethod::automatic) return options;
  const System system = model.network.assemble();
  if (system.is_nonlinear() && !options.reduce) {
    options.method = SwitchingSweepMethod::shooting;
    notes.push_back("method: shooting, since the network is nonlinear (" +
                    std::string(model.scene.circuit.empty()
                                    ? "the DEAs' RC loops"
                                    : "DEAs driven through the [[circuit]]") +
                    "); the exact method needs a linear one");
    return options;
  }
  options.method = SwitchingSweepMethod::exact;
  if (options.reduce || system.size() <= options.dense_limit) return options;
  options.reduce = true;
  if (!(options.reduction.band > 0.0)) {
    const std::vector<double> frequencies = switching_frequencies(options);
    options.reduction.band = *std::max_element(frequencies.begin(), frequencies.end());
    options.reduction.tolerance = model.scene.model.tolerance;
  }
  notes.push_back(
      "method: reduced, since the network's " + std::to_string(system.size()) +
      " unknowns are more than the " + std::to_string(options.dense_limit) +
      " up to which the dense exact method is chosen (its time grows as the cube: it would " +
      "need about " + format_number("%.3g", periodic_memory_bytes(system.size()) / 1e9) +
      " GB); modes below f_c with a static correction, checked below");
  return options;
}

}  // namespace

void SwitchingSweepOptions::validate() const {
  switching_frequencies(*this);
  const int samples_used = samples_or_default(*this);
  if (samples_used < 8 || samples_used > 1000000)
    throw OptionError("samples", "must be from 8 to 1000000 (inclusive)");
  if (reduce && method == SwitchingSweepMethod::shooting)
    throw OptionError::between("reduce", "method",
                               "{reduce} replaces the exact method, not shooting");
  if (!valid_relative_tolerance(rtol)) throw OptionError("rtol", kRelativeToleranceRange);
  if (dense_limit < 0) throw OptionError("dense_limit", "must be >= 0 (a number of unknowns)");
}

SwitchingSweepResult run_switching_sweep(const Model& model, const SwitchingSweepOptions& options) {
  return run_switching_sweep(model, model.scene, options);
}

SwitchingSweepResult run_switching_sweep(const Model& model, const Scene& scene,
                                         const SwitchingSweepOptions& given) {
  const Stopwatch stopwatch;
  given.validate();
  std::vector<std::string> method_notes;
  const SwitchingSweepOptions options = resolve_sweep_method(model, given, method_notes);
  const std::vector<double> frequencies = switching_frequencies(options);
  const int samples = samples_or_default(options);
  const bool exact = options.method == SwitchingSweepMethod::exact;
  const std::vector<Probe>& probes = options.outputs;
  if (probes.empty())
    throw InputError(model.scene.file, "probe", "the switching sweep needs at least one output");
  check_swept_drive(scene, options.sources);
  if (options.reduce)
    for (const auto& probe : probes)
      if (probe.quantity != ProbeQuantity::deflection && probe.quantity != ProbeQuantity::rotation)
        throw OptionError("outputs",
                          "{reduce} takes deflections and rotations only: a velocity of the "
                          "reduced model would need the derivative of the square wave's "
                          "feed-through; run without {reduce}",
                          probe.name);
  const double highest = *std::max_element(frequencies.begin(), frequencies.end());
  auto phase = [&](const std::string& what) {
    if (options.phase) options.phase(what);
  };

  SwitchingSweepResult result;
  result.method = options.reduce ? Method::reduced : exact ? Method::exact : Method::shooting;
  result.notes = method_notes;
  auto stop = [&](const Status& status) {
    result.status = status;
    result.seconds = stopwatch.seconds();
    return result;
  };
  auto fail = [&](const std::string& message) { return stop(Status::failure(message)); };
  // Only the drive's excitation changes with the frequency: `model`'s G and C assembled once,
  // the drive sources' waveforms made again per frequency (the same b(t) as a model built at
  // that frequency). With drive.electrical_dynamics = "auto" left in the scene the choice may
  // change with the frequency (its default band is 10 x f): then a model per frequency.
  const bool circuit_switched = !switched_sources(scene, options.sources).empty();
  const bool excitation_only = !scene.drive.electrical_dynamics_auto && !circuit_switched;
  if (circuit_switched) {
    Scene probe_scene = scene;
    for (const std::string& note : set_switching_frequency(probe_scene, highest, options.sources))
      result.notes.push_back(note);
    result.notes.push_back(
        "the circuit's periodic sources switched at each sweep frequency (a model per "
        "frequency), each keeping its levels, duty, rise and fall; a delay keeps its fraction "
        "of the period");
  } else if (!excitation_only)
    result.notes.push_back(
        "drive.electrical_dynamics = \"auto\": a model prepared per switching frequency (the "
        "choice of the DEAs' RC dynamics may change with it)");
  System swept;
  if (excitation_only) {
    const Stopwatch model_stopwatch;
    swept = model.network.assemble();
    result.model_seconds += model_stopwatch.seconds();
  }
  // The exact method's memory is checked on the assembled system (the one the sweep swaps
  // excitations into; with a model per frequency, the given model's, of the same size).
  if (exact && !options.reduce)
    check_periodic_memory(excitation_only ? swept.size() : model.network.assemble().size(),
                          "segments");
  if (!(scene.drive.rise_time < 0.5 / highest))
    throw OptionError::in_file("to", scene.file, "drive.rise_time",
                               "must be < half the shortest period of the sweep (" +
                                   format_with_unit(0.5 / highest, "s") + " at {to} " +
                                   format_with_unit(highest, "Hz") + ")");
  check_overlap_fits(scene, highest, "to");

  auto system_at = [&](double f) -> const System& {
    if (excitation_only) {
      const Stopwatch excitation_stopwatch;
      swept.set_excitation(drive_excitation(model, swept.excitation(), f));
      result.excitation_seconds += excitation_stopwatch.seconds();
    } else {
      const Stopwatch model_stopwatch;
      Scene at = scene;
      set_switching_frequency(at, f, options.sources);
      swept = prepare_model(at).network.assemble();
      result.model_seconds += model_stopwatch.seconds();
    }
    return swept;
  };

  std::shared_ptr<const PeriodicSolver> solver = options.solver;
  std::unique_ptr<ReducedPeriodicSolver> reduced;
  std::optional<SwitchingSweepReductionCheck> check;
  if (options.reduce) check.emplace();
  // The reduced periodic state at frequency f (the sweep and its check); nullopt when the
  // reduction failed (result.status set).
  std::string reduction_failure;
  auto reduced_at = [&](const System& system, double f) -> std::optional<PeriodicResult> {
    if (!reduced) {
      phase("modal reduction (" + std::to_string(system.size()) + " unknowns)");
      const Stopwatch build_stopwatch;
      reduced = std::make_unique<ReducedPeriodicSolver>(system, options.reduction);
      check->build_seconds = build_stopwatch.seconds();
      result.decomposition_seconds += check->build_seconds;
    }
    if (!reduced->reduction().status.ok()) {
      reduction_failure = "sweep-switching --reduce: " + reduced->reduction().status.message;
      return std::nullopt;
    }
    return reduced->solve(system, probes, 1.0 / f, samples);
  };

  // Per frequency only the extremes are kept (the samples of one period are dropped).
  result.outputs.resize(probes.size());
  for (size_t p = 0; p < probes.size(); ++p) {
    result.outputs[p].probe = probes[p];
    result.outputs[p].left.reserve(frequencies.size());
    result.outputs[p].right.reserve(frequencies.size());
  }
  std::vector<double> solve_seconds_at;  // per frequency, for the reduction check
  const long count = static_cast<long>(frequencies.size());
  for (long k = 0; k < count; ++k) {
    const double f = frequencies[static_cast<size_t>(k)];
    const System& system = system_at(f);
    result.unknowns = system.size();
    if (exact && !options.reduce && !solver) {
      phase("eigen-decomposition of the state matrix (" + std::to_string(system.size()) +
            " unknowns, dense; one step, no estimate inside it)");
      const Stopwatch decomposition_stopwatch;
      solver = std::make_shared<const PeriodicSolver>(system);
      result.decomposition_seconds += decomposition_stopwatch.seconds();
    }
    if (!keep_going(options.progress, k, count, "switching frequencies")) {
      result.cancelled = true;
      return stop(cancelled_status());
    }
    PeriodicResult r;
    if (options.reduce) {
      std::optional<PeriodicResult> solved = reduced_at(system, f);
      if (!solved) return fail(reduction_failure);
      r = std::move(*solved);
    } else if (exact) {
      r = solver->solve(system, probes, 1.0 / f, samples);
    } else {
      r = run_periodic_shooting(system, probes, 1.0 / f, options.rtol, samples, options.progress);
    }
    if (!r.status.ok())
      return fail("sweep-switching at " + format_with_unit(f, "Hz") + ": " + r.status.message);
    for (size_t p = 0; p < probes.size(); ++p)
      if (!std::isfinite(r.minimum[p]) || !std::isfinite(r.maximum[p]))
        return fail("non-finite result for a peak of " + probes[p].name);
    if (!std::isfinite(r.periodicity_residual))
      return fail("sweep-switching at " + format_with_unit(f, "Hz") +
                  ": non-finite periodicity residual");
    for (size_t p = 0; p < probes.size(); ++p) {
      result.outputs[p].left.push_back(r.minimum[p]);
      result.outputs[p].right.push_back(r.maximum[p]);
    }
    result.solve_seconds += r.seconds;
    result.worst_periodicity_residual =
        std::max(result.worst_periodicity_residual, r.periodicity_residual);
    solve_seconds_at.push_back(r.seconds);
    result.frequencies.push_back(f);
    ++result.solves;
  }

  result.solver = solver;
  // The resonance of the sweep: the frequency of the largest peak-to-peak at the last output
  // (dx4 or the tip).
  const size_t main_output = probes.size() - 1;
  const SwitchingSweepOutput& main = result.outputs[main_output];
  size_t best = 0;
  for (size_t k = 0; k < result.frequencies.size(); ++k)
    if (main.right[k] - main.left[k] > main.right[best] - main.left[best]) best = k;
  result.peak_output = main_output;
  if (!result.frequencies.empty()) {
    result.peak_index = best;
    result.peak_frequency = result.frequencies[best];
    result.peak_left = main.left[best];
    result.peak_right = main.right[best];
  }

  std::vector<DeflectionPeak> peaks;
  for (size_t p = 0; p < probes.size(); ++p) {
    if (probes[p].quantity != ProbeQuantity::deflection) continue;
    peaks.push_back({probes[p].name, 0.0});
    for (size_t k = 0; k < result.frequencies.size(); ++k)
      peaks.back().peak = std::max({peaks.back().peak, std::abs(result.outputs[p].left[k]),
                                    std::abs(result.outputs[p].right[k])});
  }
  result.validity = check_validity(model.scene, peaks, drive_peak_voltages(model.scene));

  if (check && !result.frequencies.empty()) {
    // The full exact method at the first, the largest-swing and the last frequency, against the
    // reduced solution there (solved again: the sweep keeps no samples).
    phase("checking the reduction");
    const Stopwatch check_stopwatch;
    check->model = reduced->reduction();
    check->tolerance = options.reduction.tolerance;
    std::vector<size_t> picked{0, best, result.frequencies.size() - 1};
    std::sort(picked.begin(), picked.end());
    picked.erase(std::unique(picked.begin(), picked.end()), picked.end());
    // The reference: the full exact method where its dense decomposition is the automatic
    // choice's size, else a reduction with ten times the cut-off.
    check->against_full = result.unknowns <= options.dense_limit;
    std::unique_ptr<PeriodicSolver> full;
    std::unique_ptr<ReducedPeriodicSolver> wider;
    ReductionOptions wider_options = options.reduction;
    wider_options.cutoff_hz = 10.0 * check->model.cutoff_hz;
    check->reference = check->against_full
                           ? "the full exact periodic solution"
                           : "a reduction with ten times the cut-off (" +
                                 format_with_unit(wider_options.cutoff_hz, "Hz") + ")";
    auto reference_at = [&](const System& system, double f) {
      if (check->against_full) {
        if (!full) {
          const Stopwatch build_stopwatch;
          full = std::make_unique<PeriodicSolver>(system);
          check->full_build_seconds = build_stopwatch.seconds();
        }
        return full->solve(system, probes, 1.0 / f, samples);
      }
      if (!wider) {
        phase("checking against a reduction with ten times the cut-off");
        const Stopwatch build_stopwatch;
        wider = std::make_unique<ReducedPeriodicSolver>(system, wider_options);
        check->full_build_seconds = build_stopwatch.seconds();
        check->reference += ", " + std::to_string(wider->reduction().kept_modes) + " mode(s) and " +
                            std::to_string(wider->reduction().kept_real_poles) +
                            " real pole(s) against " + std::to_string(check->model.kept_modes) +
                            " and " + std::to_string(check->model.kept_real_poles);
      }
      if (!wider->reduction().status.ok()) {
        PeriodicResult failed;
        failed.status = wider->reduction().status.with_context("the wider reduction: ");
        return failed;
      }
      return wider->solve(system, probes, 1.0 / f, samples);
    };
    for (size_t k : picked) {
      if (cancel_requested(options.progress)) {
        result.cancelled = true;
        return stop(cancelled_status());
      }
      const double f = result.frequencies[k];
      const System& system = system_at(f);
      const PeriodicResult exact_there = reference_at(system, f);
      if (!exact_there.status.ok())
        return fail("sweep-switching --reduce check at " + format_with_unit(f, "Hz") + ": " +
                    exact_there.status.message);
      const std::optional<PeriodicResult> again = reduced_at(system, f);
      if (!again) return fail(reduction_failure);
      if (!again->status.ok())
        return fail("sweep-switching --reduce at " + format_with_unit(f, "Hz") + ": " +
                    again->status.message);
      // Per frequency: the fastest check solve (the first also fills per-probe caches).
      check->full_solve_seconds = check->full_solve_seconds > 0.0
                                      ? std::min(check->full_solve_seconds, exact_there.seconds)
                                      : exact_there.seconds;
      check->reduced_solve_seconds =
          check->reduced_solve_seconds > 0.0
              ? std::min({check->reduced_solve_seconds, solve_seconds_at[k], again->seconds})
              : std::min(solve_seconds_at[k], again->seconds);
      double error = periodic_difference(*again, exact_there);
      if (!check->against_full) {  // and what neither reduction keeps: the edge estimate
        std::vector<double> scale;
        for (const std::vector<double>& values : again->values) {
          double largest = 0.0;
          for (double v : values) largest = std::max(largest, std::abs(v));
          scale.push_back(largest);
        }
        const double edge = reduced->edge_error_estimate(system, probes, scale);
        check->edge_estimates.push_back(edge);
        error = std::max(error, edge);
      }
      if (!std::isfinite(error))
        return fail("sweep-switching --reduce check at " + format_with_unit(f, "Hz") +
                    ": non-finite difference between the reduced and the full solution");
      check->frequencies.push_back(f);
      check->errors.push_back(error);
      check->measured_error = std::max(check->measured_error, error);
    }
    check->tolerance_met = check->measured_error <= check->tolerance;
    result.check_seconds = check_stopwatch.seconds();
    result.reduction = std::move(check);
  }

  if (options.first_mode) {
    phase("modes for the resonance marker");
    const Stopwatch modes_stopwatch;
    const System system = model.network.assemble();
    const OperatingPoint rest = operating_point(system);
    ModalOptions modal;
    modal.keep_vectors = false;
    if (system.size() > modal.dense_limit) modal.count = 3;
    const ModalResult modes = run_modes(system, rest.rest.operating_point, modal);
    if (rest.status.ok() && modes.status.ok() && !modes.modes.empty() &&
        std::isfinite(modes.modes[0].frequency_hz))
      result.first_mode_hz = modes.modes[0].frequency_hz;
    result.first_mode_seconds = modes_stopwatch.seconds();
  }
  result.seconds = stopwatch.seconds();
  return result;
}

SweptModel prepare_swept_model(const Scene& scene, SwitchingSweepMethod method,
                               const std::vector<std::string>& probe_texts,
                               const PrepareOptions& prepare, double highest_hz) {
  SweptModel swept{prepare_model(scene, prepare), scene, {}};
  check_swept_drive(swept.model.scene);
  if (method == SwitchingSweepMethod::shooting) return swept;
  const bool automatic = method == SwitchingSweepMethod::automatic;
  for (const auto& text : probe_texts)
    if (asks_for_dea_electrics(text)) {
      if (automatic) return swept;  // the RC loop is asked for: shooting (run_switching_sweep)
      throw OptionError("probe",
                        "the exact periodic method models the DEAs as ideal voltage-driven "
                        "forces, without the RC loop whose voltage and current this probe asks "
                        "for; use the shooting method",
                        text);
    }
  const bool nonlinear = swept.model.network.assemble().is_nonlinear();
  if (nonlinear && !swept.model.scene.circuit.empty() && automatic) return swept;
  if (nonlinear && !swept.model.scene.circuit.empty())
    throw InputError(swept.model.scene.file, "circuit",
                     "the exact periodic method models the DEAs as ideal voltage-driven forces, "
                     "but this scene drives them through its [[circuit]] elements, whose "
                     "electrical loops it needs; use the shooting method");
  if (nonlinear) {
    double tau = 0.0;
    for (const auto& dea : swept.model.deas)
      tau = std::max(tau, dea.electrode_resistance * dea.capacitance);
    swept.notes.push_back(
        "exact method: DEAs as ideal voltage-driven forces, the electrical model the scene "
        "gives them (drive.electrical_dynamics) set aside (their RC time constant " +
        format_with_unit(tau, "s") + " is " + format_number("%.2g", tau * highest_hz) +
        " of the shortest period); the shooting method integrates the full "
        "model");
    set_electrical_dynamics(swept.scene, false);
    swept.model = prepare_model(swept.scene, prepare);
    // The rebuilt model's own note would say the scene set it false; the note above says why.
    auto& notes = swept.model.notes;
    notes.erase(std::remove_if(notes.begin(), notes.end(),
                               [](const std::string& note) {
                                 return note.rfind("DEA electrical dynamics left out", 0) == 0;
                               }),
                notes.end());
  }
  return swept;
}

std::vector<Probe> switching_sweep_outputs(const Model& model,
                                           const std::vector<std::string>& probe_texts) {
  std::vector<Probe> outputs;
  for (const auto& probe : transient_outputs(model, probe_texts))
    if (!probe_texts.empty() || probe.unit == "m") outputs.push_back(probe);
  if (outputs.empty())
    throw InputError(model.scene.file, "probe", "the scene has no deflection output");
  return outputs;
}

}  // namespace emnet
