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
#include "switching_sweep_method.hpp"

namespace emnet {
namespace {

int samples_or_default(const SwitchingSweepOptions& options) {
  if (options.samples != 0) return options.samples;
  if (options.method == SwitchingSweepMethod::shooting) return 256;
  return options.extremes_only ? 32 : 64;
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
  if (shape_instants != 0 && (shape_instants < 2 || shape_instants > 100000))
    throw OptionError("shape_instants", "must be 0 (no shape) or from 2 to 100000 (inclusive)");
}

SwitchingSweepResult run_switching_sweep(const Model& model, const SwitchingSweepOptions& options) {
  return run_switching_sweep(model, model.scene, options);
}

namespace {

// What the sweep refuses before it solves: no output, a drive that nothing switches, and for the
// reduced model an output other than a deflection or rotation.
void check_sweep_outputs(const Model& model, const Scene& scene,
                         const SwitchingSweepOptions& options) {
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
}

// Per output, the largest magnitude of its samples over the period (the edge estimate's scale).
std::vector<double> largest_magnitude_per_output(const PeriodicResult& solution) {
  std::vector<double> scale;
  for (const std::vector<double>& values : solution.values) {
    double largest = 0.0;
    for (double v : values) largest = std::max(largest, std::abs(v));
    scale.push_back(largest);
  }
  return scale;
}

// What the reduction is checked against: the full exact method where its dense decomposition is
// the automatic choice's size, else a reduction with ten times the cut-off. Each is made at its
// first use, as it is costly.
class ReductionCheckReference {
 public:
  ReductionCheckReference(SwitchingSweepReductionCheck& check, const SwitchingSweepOptions& options,
                          int samples)
      : check_(check), options_(options), samples_(samples), wider_options_(options.reduction) {
    wider_options_.cutoff_hz = 10.0 * check_.model.cutoff_hz;
    check_.reference = check_.against_full
                           ? "the full exact periodic solution"
                           : "a reduction with ten times the cut-off (" +
                                 format_with_unit(wider_options_.cutoff_hz, "Hz") + ")";
  }

  PeriodicResult solution_at(const System& system, double f) {
    if (check_.against_full) return full_exact_solution_at(system, f);
    return wider_reduction_solution_at(system, f);
  }

 private:
  PeriodicResult full_exact_solution_at(const System& system, double f) {
    if (!full_) {
      const Stopwatch build_stopwatch;
      full_ = std::make_unique<PeriodicSolver>(system);
      check_.full_build_seconds = build_stopwatch.seconds();
    }
    return full_->solve(system, options_.outputs, 1.0 / f, samples_);
  }

  PeriodicResult wider_reduction_solution_at(const System& system, double f) {
    if (!wider_) {
      if (options_.phase) options_.phase("checking against a reduction with ten times the cut-off");
      const Stopwatch build_stopwatch;
      wider_ = std::make_unique<ReducedPeriodicSolver>(system, wider_options_);
      check_.full_build_seconds = build_stopwatch.seconds();
      check_.reference += ", " + std::to_string(wider_->reduction().kept_modes) + " mode(s) and " +
                          std::to_string(wider_->reduction().kept_real_poles) +
                          " real pole(s) against " + std::to_string(check_.model.kept_modes) +
                          " and " + std::to_string(check_.model.kept_real_poles);
    }
    if (!wider_->reduction().status.ok()) {
      PeriodicResult failed;
      failed.status = wider_->reduction().status.with_context("the wider reduction: ");
      return failed;
    }
    return wider_->solve(system, options_.outputs, 1.0 / f, samples_);
  }

  SwitchingSweepReductionCheck& check_;
  const SwitchingSweepOptions& options_;
  const int samples_;
  ReductionOptions wider_options_;
  std::unique_ptr<PeriodicSolver> full_;
  std::unique_ptr<ReducedPeriodicSolver> wider_;
};

// One run of the sweep: the state its phases share (the swept System, the solvers, the result so
// far). A phase that stops the run (a failure, a cancel) returns its Status.
class SwitchingSweepRun {
 public:
  SwitchingSweepRun(const Model& model, const Scene& scene, const SwitchingSweepOptions& options,
                    std::vector<std::string> method_notes, double decomposition_seconds,
                    const Stopwatch& stopwatch)
      : model_(model),
        scene_(scene),
        options_(options),
        stopwatch_(stopwatch),
        frequencies_(switching_frequencies(options)),
        samples_(samples_or_default(options)),
        exact_(options.method == SwitchingSweepMethod::exact),
        probes_(options.outputs),
        highest_(*std::max_element(frequencies_.begin(), frequencies_.end())),
        solver_(options.solver) {
    result_.method = options.reduce ? Method::reduced : exact_ ? Method::exact : Method::shooting;
    result_.notes = std::move(method_notes);
    result_.decomposition_seconds = decomposition_seconds;
    if (options.reduce) check_.emplace();
  }

  SwitchingSweepResult run() {
    decide_what_changes_per_frequency();
    assemble_once_and_check_the_sweep_fits();
    if (const std::optional<Status> stopped = solve_every_frequency()) return stopped_by(*stopped);
    result_.solver = solver_;
    result_.reduced_solver = reduced_;
    find_the_sweep_peak();
    check_validity_of_the_deflection_peaks();
    if (check_ && options_.check_reduction && !result_.frequencies.empty())
      if (const std::optional<Status> stopped = check_the_reduction()) return stopped_by(*stopped);
    if (options_.shape_instants > 0 && !result_.frequencies.empty())
      if (const std::optional<Status> stopped = find_the_deformed_shape())
        return stopped_by(*stopped);
    if (options_.first_mode) find_the_first_mode_for_the_resonance_marker();
    return finished();
  }

 private:
  void phase(const std::string& what) const {
    if (options_.phase) options_.phase(what);
  }

  SwitchingSweepResult finished() {
    result_.seconds = stopwatch_.seconds();
    return std::move(result_);
  }

  SwitchingSweepResult stopped_by(const Status& status) {
    result_.status = status;
    return finished();
  }

  // Only the sources' excitation changes with the frequency: `model`'s G and C assembled once,
  // the drive sources' and the switched circuit sources' waveforms made again per frequency
  // (the same b(t) as a model built at that frequency; rebuilding it took about 20 ms of the
  // tweezer jaw's 61-frequency sweep). With drive.electrical_dynamics = "auto" left in the scene
  // the choice may change with the frequency (its default band is 10 x f): then a model per
  // frequency.
  void decide_what_changes_per_frequency() {
    circuit_switched_ = !switched_sources(scene_, options_.sources).empty();
    excitation_only_ = !scene_.drive.electrical_dynamics_auto;
    if (circuit_switched_) {
      Scene probe_scene = scene_;
      for (const std::string& note :
           set_switching_frequency(probe_scene, highest_, options_.sources))
        result_.notes.push_back(note);
      result_.notes.push_back(
          "the circuit's periodic sources switched at each sweep frequency, each keeping its "
          "levels, duty, rise and fall; a delay keeps its fraction of the period");
    } else if (!excitation_only_)
      result_.notes.push_back(
          "drive.electrical_dynamics = \"auto\": a model prepared per switching frequency (the "
          "choice of the DEAs' RC dynamics may change with it)");
  }

  void assemble_once_and_check_the_sweep_fits() {
    if (excitation_only_) {
      const Stopwatch model_stopwatch;
      swept_ = model_.network.assemble();
      result_.model_seconds += model_stopwatch.seconds();
    }
    // The exact method's memory is checked on the assembled system (the one the sweep swaps
    // excitations into; with a model per frequency, the given model's, of the same size).
    if (exact_ && !options_.reduce)
      check_periodic_memory(excitation_only_ ? swept_.size() : model_.network.assemble().size(),
                            "segments");
    if (!(scene_.drive.rise_time < 0.5 / highest_))
      throw OptionError::in_file("to", scene_.file, "drive.rise_time",
                                 "must be < half the shortest period of the sweep (" +
                                     format_with_unit(0.5 / highest_, "s") + " at {to} " +
                                     format_with_unit(highest_, "Hz") + ")");
    check_overlap_fits(scene_, highest_, "to");
  }

  const System& system_at(double f) {
    if (excitation_only_) {
      const Stopwatch excitation_stopwatch;
      Excitation excitation = drive_excitation(model_, swept_.excitation(), f);
      if (circuit_switched_) {
        Scene at = scene_;
        set_switching_frequency(at, f, options_.sources);
        excitation = circuit_excitation(model_, at, excitation);
      }
      swept_.set_excitation(std::move(excitation));
      result_.excitation_seconds += excitation_stopwatch.seconds();
    } else {
      const Stopwatch model_stopwatch;
      Scene at = scene_;
      set_switching_frequency(at, f, options_.sources);
      swept_ = prepare_model(at, served_by_the_sweep(at, PrepareOptions{})).network.assemble();
      result_.model_seconds += model_stopwatch.seconds();
    }
    return swept_;
  }

  // The reduced periodic state at frequency f (the sweep and its check); nullopt when the
  // reduction failed (the message in reduction_failure_).
  std::optional<PeriodicResult> reduced_solution_at(const System& system, double f) {
    return reduced_solution_at(system, f, probes_, samples_);
  }
  std::optional<PeriodicResult> reduced_solution_at(const System& system, double f,
                                                    const std::vector<Probe>& probes, int samples) {
    if (!reduced_ && options_.reduced_solver) reduced_ = options_.reduced_solver;
    if (!reduced_) {
      phase("modal reduction (" + std::to_string(system.size()) + " unknowns)");
      const Stopwatch build_stopwatch;
      reduced_ = std::make_shared<const ReducedPeriodicSolver>(system, options_.reduction);
      check_->build_seconds = build_stopwatch.seconds();
      result_.decomposition_seconds += check_->build_seconds;
    }
    if (!reduced_->reduction().status.ok()) {
      reduction_failure_ =
          "switching sweep, reduced model: " + reduced_->reduction().status.message;
      return std::nullopt;
    }
    return reduced_->solve(system, probes, 1.0 / f, samples);
  }

  // The beam's shape over one period at the sweep peak (options.shape_instants): the periodic
  // state there again, with every node's deflection (and x displacement) as its probes.
  std::optional<Status> find_the_deformed_shape() {
    phase("the deformed shape at the sweep peak");
    const double f = result_.peak_frequency;
    const ShapeProbes shape = shape_probes(model_);
    const std::optional<PeriodicResult> solved =
        periodic_solution_at(system_at(f), f, &shape.probes, options_.shape_instants);
    if (!solved) return Status::failure(reduction_failure_);
    if (!solved->status.ok())
      return Status::failure("deformed shape at " + format_with_unit(f, "Hz") + ": " +
                             solved->status.message);
    result_.shape = deformed_shape(shape, solved->times, solved->values);
    result_.shape->frequency = f;
    return std::nullopt;
  }

  void decompose_the_state_matrix_once(const System& system) {
    phase("eigen-decomposition of the state matrix (" + std::to_string(system.size()) +
          " unknowns, dense; one step, no estimate inside it)");
    const Stopwatch decomposition_stopwatch;
    solver_ = std::make_shared<const PeriodicSolver>(system);
    result_.decomposition_seconds += decomposition_stopwatch.seconds();
  }

  // By the reduced, exact or shooting method; nullopt as reduced_solution_at. `probes` and
  // `samples`: the sweep's own unless given (the deformed shape's).
  std::optional<PeriodicResult> periodic_solution_at(const System& system, double f,
                                                     const std::vector<Probe>* probes = nullptr,
                                                     int samples = 0) {
    const std::vector<Probe>& outputs = probes ? *probes : probes_;
    if (samples == 0) samples = samples_;
    if (options_.reduce) return reduced_solution_at(system, f, outputs, samples);
    if (exact_) return solver_->solve(system, outputs, 1.0 / f, samples);
    // Continuation: Newton starts from the linearisation's periodic state plus the previous
    // frequencies' nonlinear parts, extrapolated.
    const Eigen::VectorXd guess = continuation_guess(f);
    PeriodicResult solution =
        run_periodic_shooting(system, outputs, 1.0 / f, options_.rtol, samples, options_.progress,
                              guess.size() ? &guess : nullptr, &shooting_cache_);
    if (solution.status.ok()) {
      before_previous_ = std::move(previous_);
      previous_ = {f, solution.start_state - solution.linear_start_state};
    } else {
      previous_ = before_previous_ = {};
    }
    return solution;
  }

  std::optional<Status> failure_of_the_periodic_solution(const PeriodicResult& r, double f) const {
    if (!r.status.ok())
      return Status::failure("sweep-switching at " + format_with_unit(f, "Hz") + ": " +
                             r.status.message);
    for (size_t p = 0; p < probes_.size(); ++p)
      if (!std::isfinite(r.minimum[p]) || !std::isfinite(r.maximum[p]))
        return Status::failure("non-finite result for a peak of " + probes_[p].name);
    if (!std::isfinite(r.periodicity_residual))
      return Status::failure("sweep-switching at " + format_with_unit(f, "Hz") +
                             ": non-finite periodicity residual");
    return std::nullopt;
  }

  // Per frequency only the extremes are kept (the samples of one period are dropped).
  void keep_the_extremes(double f, const PeriodicResult& r) {
    for (size_t p = 0; p < probes_.size(); ++p) {
      result_.outputs[p].left.push_back(r.minimum[p]);
      result_.outputs[p].right.push_back(r.maximum[p]);
    }
    result_.solve_seconds += r.seconds;
    result_.worst_periodicity_residual =
        std::max(result_.worst_periodicity_residual, r.periodicity_residual);
    solve_seconds_at_.push_back(r.seconds);
    result_.period_runs += r.period_runs;
    result_.frequencies.push_back(f);
    ++result_.solves;
  }

  std::optional<Status> solve_every_frequency() {
    result_.outputs.resize(probes_.size());
    for (size_t p = 0; p < probes_.size(); ++p) {
      result_.outputs[p].probe = probes_[p];
      result_.outputs[p].left.reserve(frequencies_.size());
      result_.outputs[p].right.reserve(frequencies_.size());
    }
    const long count = static_cast<long>(frequencies_.size());
    for (long k = 0; k < count; ++k) {
      const double f = frequencies_[static_cast<size_t>(k)];
      const System& system = system_at(f);
      result_.unknowns = system.size();
      if (exact_ && !options_.reduce && !solver_) decompose_the_state_matrix_once(system);
      if (!keep_going(options_.progress, k, count, "switching frequencies")) {
        result_.cancelled = true;
        return cancelled_status();
      }
      const std::optional<PeriodicResult> solved = periodic_solution_at(system, f);
      if (!solved) return Status::failure(reduction_failure_);
      if (std::optional<Status> failed = failure_of_the_periodic_solution(*solved, f))
        return failed;
      keep_the_extremes(f, *solved);
      start_states_.push_back(solved->start_state);  // shooting's; empty from the others
    }
    return std::nullopt;
  }

  // The resonance of the sweep: the frequency of the largest peak-to-peak at the last output
  // (dx4 or the tip).
  void find_the_sweep_peak() {
    const size_t main_output = probes_.size() - 1;
    const SwitchingSweepOutput& main = result_.outputs[main_output];
    size_t best = 0;
    for (size_t k = 0; k < result_.frequencies.size(); ++k)
      if (main.right[k] - main.left[k] > main.right[best] - main.left[best]) best = k;
    result_.peak_output = main_output;
    if (!result_.frequencies.empty()) {
      result_.peak_index = best;
      result_.peak_frequency = result_.frequencies[best];
      result_.peak_left = main.left[best];
      result_.peak_right = main.right[best];
      peak_start_state_ = start_states_[best];
    }
  }

  void check_validity_of_the_deflection_peaks() {
    std::vector<DeflectionPeak> peaks;
    for (size_t p = 0; p < probes_.size(); ++p) {
      if (probes_[p].quantity != ProbeQuantity::deflection) continue;
      peaks.push_back({probes_[p].name, 0.0});
      for (size_t k = 0; k < result_.frequencies.size(); ++k)
        peaks.back().peak = std::max({peaks.back().peak, std::abs(result_.outputs[p].left[k]),
                                      std::abs(result_.outputs[p].right[k])});
    }
    result_.validity = check_validity(model_.scene, peaks, drive_peak_voltages(model_.scene),
                                      rotation_at_the_sweep_peak());
  }

  // The largest |rotation| at the beam's nodes over the period at the sweep's peak, for the
  // geometric error (one more periodic solve, or one period of IDA); none with large kinematics
  // or where it fails.
  std::optional<RotationPeak> rotation_at_the_sweep_peak() {
    if (!options_.largest_rotation) return std::nullopt;
    const RotationProbes rotations = rotation_probes(model_);
    if (rotations.probes.empty() || result_.frequencies.empty()) return std::nullopt;
    const double f = result_.peak_frequency;
    const std::optional<PeriodicResult> solved = rotation_solution_at(f, rotations.probes);
    if (!solved || !solved->status.ok()) return std::nullopt;
    std::vector<double> peaks;
    for (size_t p = 0; p < rotations.probes.size(); ++p)
      peaks.push_back(std::max(std::abs(solved->minimum[p]), std::abs(solved->maximum[p])));
    return largest_rotation(rotations, peaks);
  }

  // The periodic state at the sweep peak f for the rotation probes: by shooting, one period of
  // IDA from the periodic start already found there (on the tweezer jaw half a one-frequency
  // sweep's time went to solving it again); otherwise solved again (the exact method's
  // solve is cheap, the reduced one does not keep its start).
  std::optional<PeriodicResult> rotation_solution_at(double f, const std::vector<Probe>& probes) {
    if (peak_start_state_.size() > 0)
      return sample_periodic_state(system_at(f), probes, 1.0 / f, options_.rtol, samples_,
                                   peak_start_state_, options_.progress);
    return periodic_solution_at(system_at(f), f, &probes);
  }

  // The first, the largest-swing (the sweep peak) and the last frequency, each once.
  std::vector<size_t> reduction_check_indices() const {
    std::vector<size_t> picked{0, result_.peak_index, result_.frequencies.size() - 1};
    std::sort(picked.begin(), picked.end());
    picked.erase(std::unique(picked.begin(), picked.end()), picked.end());
    return picked;
  }

  // Per frequency: the fastest check solve (the first also fills per-probe caches).
  void keep_the_fastest_check_solves(size_t k, double reference_seconds, double reduced_seconds) {
    SwitchingSweepReductionCheck& check = *check_;
    check.full_solve_seconds = check.full_solve_seconds > 0.0
                                   ? std::min(check.full_solve_seconds, reference_seconds)
                                   : reference_seconds;
    check.reduced_solve_seconds =
        check.reduced_solve_seconds > 0.0
            ? std::min({check.reduced_solve_seconds, solve_seconds_at_[k], reduced_seconds})
            : std::min(solve_seconds_at_[k], reduced_seconds);
  }

  std::optional<Status> check_the_reduction_at(size_t k, ReductionCheckReference& reference) {
    SwitchingSweepReductionCheck& check = *check_;
    const double f = result_.frequencies[k];
    const System& system = system_at(f);
    const PeriodicResult exact_there = reference.solution_at(system, f);
    if (!exact_there.status.ok())
      return Status::failure("switching sweep, reduced model's check at " +
                             format_with_unit(f, "Hz") + ": " + exact_there.status.message);
    const std::optional<PeriodicResult> again = reduced_solution_at(system, f);
    if (!again) return Status::failure(reduction_failure_);
    if (!again->status.ok())
      return Status::failure("switching sweep, reduced model at " + format_with_unit(f, "Hz") +
                             ": " + again->status.message);
    keep_the_fastest_check_solves(k, exact_there.seconds, again->seconds);
    double error = periodic_difference(*again, exact_there);
    if (check.against_full) {
      const double extremes = extremes_difference(*again, exact_there);
      check.extreme_errors.push_back(extremes);
      check.measured_extremes_error = std::max(check.measured_extremes_error, extremes);
    } else {  // and what neither reduction keeps: the edge estimate
      // A reduced cascade's own estimate of its truncated transients (both reductions stop at
      // the same cluster, so their difference does not see them).
      const double edge = std::max(
          reduced_->edge_error_estimate(system, probes_, largest_magnitude_per_output(*again)),
          again->truncation_estimate);
      check.edge_estimates.push_back(edge);
      error = std::max(error, edge);
    }
    if (!std::isfinite(error))
      return Status::failure("switching sweep, reduced model's check at " +
                             format_with_unit(f, "Hz") +
                             ": non-finite difference between the reduced and the full solution");
    check.frequencies.push_back(f);
    check.errors.push_back(error);
    check.measured_error = std::max(check.measured_error, error);
    return std::nullopt;
  }

  // The reduced solution (solved again: the sweep keeps no samples) against a reference at a few
  // frequencies of the sweep.
  std::optional<Status> check_the_reduction() {
    phase("checking the reduction");
    const Stopwatch check_stopwatch;
    SwitchingSweepReductionCheck& check = *check_;
    check.model = reduced_->reduction();
    check.tolerance = options_.reduction.tolerance;
    check.against_full = result_.unknowns <= options_.dense_limit;
    ReductionCheckReference reference(check, options_, samples_);
    for (size_t k : reduction_check_indices()) {
      if (cancel_requested(options_.progress)) {
        result_.cancelled = true;
        return cancelled_status();
      }
      if (std::optional<Status> failed = check_the_reduction_at(k, reference)) return failed;
    }
    check.cascade = reduced_->cascade();
    check.tolerance_met = check.stated_error() <= check.tolerance;
    result_.check_seconds = check_stopwatch.seconds();
    result_.reduction = std::move(check_);
    return std::nullopt;
  }

  void find_the_first_mode_for_the_resonance_marker() {
    phase("modes for the resonance marker");
    const Stopwatch modes_stopwatch;
    const System system = model_.network.assemble();
    const OperatingPoint rest = operating_point(system);
    ModalOptions modal;
    modal.keep_vectors = false;
    if (system.size() > modal.dense_limit) modal.count = 3;
    const ModalResult modes = run_modes(system, rest.rest.operating_point, modal);
    if (rest.status.ok() && modes.status.ok() && !modes.modes.empty() &&
        std::isfinite(modes.modes[0].frequency_hz))
      result_.first_mode_hz = modes.modes[0].frequency_hz;
    result_.first_mode_seconds = modes_stopwatch.seconds();
  }

  const Model& model_;
  const Scene& scene_;
  const SwitchingSweepOptions& options_;
  const Stopwatch& stopwatch_;
  const std::vector<double> frequencies_;
  const int samples_;
  const bool exact_;
  const std::vector<Probe>& probes_;
  const double highest_;
  bool excitation_only_ = true;
  bool circuit_switched_ = false;  // periodic [[circuit]] sources switched with the sweep
  System swept_;
  std::shared_ptr<const PeriodicSolver> solver_;
  std::shared_ptr<const ReducedPeriodicSolver> reduced_;
  std::optional<SwitchingSweepReductionCheck> check_;
  std::string reduction_failure_;
  std::vector<double> solve_seconds_at_;  // per frequency, for the reduction check
  // Shooting: the nonlinear part of a periodic state at t = 0 (its unknowns less the
  // linearisation's periodic state's) and its switching frequency [Hz].
  struct SolvedState {
    double frequency = 0.0;
    Eigen::VectorXd nonlinear_part;
  };
  SolvedState previous_, before_previous_;  // the last two solved, or empty
  ShootingCache shooting_cache_;            // the linearisation, made at the first frequency
  // Shooting: the periodic start state at each frequency solved, and at the sweep peak.
  std::vector<Eigen::VectorXd> start_states_;
  Eigen::VectorXd peak_start_state_;

  // The nonlinear part at f, added to the linearisation's periodic state there: the straight
  // line through the last two (the secant predictor of continuation), the last one alone, or
  // none. The linear part follows a resonance exactly; on the fin at 4 kV with large
  // kinematics carrying only the nonlinear part cut the sweep's one-period runs from 312 to 246.
  Eigen::VectorXd continuation_guess(double f) const {
    const Eigen::VectorXd& last = previous_.nonlinear_part;
    const Eigen::VectorXd& before = before_previous_.nonlinear_part;
    if (last.size() == 0) return {};
    if (before.size() != last.size()) return last;
    const double t = (f - previous_.frequency) / (previous_.frequency - before_previous_.frequency);
    return last + t * (last - before);
  }
  SwitchingSweepResult result_;
};

}  // namespace

SwitchingSweepResult run_switching_sweep(const Model& model, const Scene& scene,
                                         const SwitchingSweepOptions& given) {
  const Stopwatch stopwatch;
  given.validate();
  std::vector<std::string> method_notes;
  double decomposition_seconds = 0.0;
  const SwitchingSweepOptions options =
      resolve_sweep_method(model, given, method_notes, decomposition_seconds);
  check_sweep_outputs(model, scene, options);
  SwitchingSweepRun sweep(model, scene, options, std::move(method_notes), decomposition_seconds,
                          stopwatch);
  return sweep.run();
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

double extremes_difference(const SwitchingSweepResult& swept,
                           const SwitchingSweepResult& reference) {
  double worst = 0.0;
  for (std::size_t p = 0; p < reference.outputs.size(); ++p) {
    const SwitchingSweepOutput &e = reference.outputs[p], &r = swept.outputs[p];
    double largest = 0.0, difference = 0.0;
    for (std::size_t k = 0; k < e.left.size(); ++k) {
      largest = std::max({largest, std::abs(e.left[k]), std::abs(e.right[k])});
      difference = std::max(
          {difference, std::abs(r.left[k] - e.left[k]), std::abs(r.right[k] - e.right[k])});
    }
    worst = std::max(worst, largest > 0.0 ? difference / largest : difference);
  }
  return worst;
}

}  // namespace emnet
