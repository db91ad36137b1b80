// The switching sweep: the periodic steady state of a model whose square-wave drive switches at
// each of a list of frequencies, reduced to the periodic minimum ("left" peak) and maximum
// ("right" peak) of every output per frequency.
//
// Per switching frequency f only the drive's excitation b(t) changes (period T = 1/f): the
// model's G and C are assembled once and emnet::drive_excitation makes the drive sources'
// waveforms again at f (the same b(t) as a model built at f). With drive.electrical_dynamics =
// "auto" left in the scene the RC choice may change with f, so then a model is prepared per
// frequency from the scene. Methods (emnet/analysis/periodic.hpp):
//   exact     PeriodicSolver: one eigen-decomposition of the state equation C·y' + G·y = b(t)
//             for the whole sweep, the periodic state in closed form per frequency, extremes
//             global (a curvature-bounded search between samples, then Newton); a linear
//             network only.
//   shooting  run_periodic_shooting: Newton on one period of IDA per frequency (any network).
//   reduce    (exact only) ReducedPeriodicSolver: the same closed form in the modal coordinates
//             of the modes below band/tolerance with the static correction as a feed-through,
//             for a cascade the beam's truncated part exact at the squares' exponents
//             (emnet/analysis/modal_reduction.hpp); checked against the full exact method at
//             the first, the largest-swing and the last frequency: the error of the peaks it
//             reports (extremes_difference), judged against the tolerance, and of every sample
//             (periodic_difference), both relative to each output's largest |value|.
// The sweep peak is the frequency of the largest peak-to-peak (max − min) of the last output.
// f1 (optional) is the network's lowest mode about its operating point, a plot marker.
//
// Units: frequencies in Hz, peaks in each output's unit (Probe::unit), times in seconds.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/model/deformed_shape.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/scene/scene.hpp"
#include "emnet/studies/resolve.hpp"

namespace emnet {

// automatic: exact where the swept network is linear (after prepare_swept_model, a [drive]'s
// DEAs are ideal voltage-driven forces) or an exact cascade (DEAs driven through a [[circuit]],
// their force the only nonlinearity), shooting otherwise; with exact, the reduction (`reduce`,
// at the model's tolerance and the sweep's top as band) above `dense_limit` unknowns (for a
// cascade: the reduced cascade). The choice and its reason are in the result's notes.
enum class SwitchingSweepMethod { automatic, exact, shooting };

struct SwitchingSweepOptions {
  // The switching frequencies [Hz]; when empty, from, from + step, … up to `to` (inclusive).
  std::vector<double> frequencies;
  double from = 1.0, to = 7.0, step = 0.1;
  SwitchingSweepMethod method = SwitchingSweepMethod::automatic;
  // Samples per period; 0: the method's default (64 exact, 256 shooting). The exact method's
  // extremes are global whatever the count; shooting refines the largest samples by a parabola.
  int samples = 0;
  // The caller reads each output's extremes only (left, right), not its samples: with samples 0
  // the closed-form methods (exact, reduced) then sample 32 points a period, which their global
  // extremes search needs no more of. Fewer samples leave wider gaps for the search to halve:
  // instructions of a 20-variant study, 16 / 24 / 32 samples: the fish fin 573 / 568 / 569
  // million, the tweezer jaw's reduced cascade 3.40 / 3.10 / 2.99 billion; 64 cost the fin 9 %
  // more than 16.
  bool extremes_only = false;
  double rtol = 1e-9;  // shooting: IDA's relative tolerance
  bool reduce = false;
  ReductionOptions reduction;  // with `reduce`
  // With `reduce`: check the reduction against the full exact method (or a wider reduction) at
  // a few frequencies (result.reduction). False where the caller has checked it on a like
  // network (a design study's nominal scene, its variants unchecked).
  bool check_reduction = true;
  // With `reduce`: a reduction already made for the model's network (a design study's variant,
  // its two sweeps), as `solver`; made here when null.
  std::shared_ptr<const ReducedPeriodicSolver> reduced_solver;
  // The outputs whose peaks are swept; at least one. With `reduce`, deflections and rotations.
  std::vector<Probe> outputs;
  bool first_mode = true;  // compute f1 (the lowest mode), for a plot marker
  // The validity's geometric error from the largest rotation at the beam's nodes (small
  // kinematics): one more periodic solve at the sweep's peak (by shooting, one period of IDA
  // from the periodic state found there). False where the caller does not use the validity (the
  // estimate is then (w/L)² alone).
  bool largest_rotation = true;
  // One report per frequency; cancelled: a failed Status "cancelled" and `cancelled` set.
  Progress* progress = nullptr;
  // Told each step without counts ("eigen-decomposition of the state matrix (…)"), if set.
  std::function<void(const std::string&)> phase;
  // The exact method: a PeriodicSolver already made for the model's network (its G and C), so
  // that several sweeps of one network decompose it once (a design study's variant); made here
  // when null. A solver of another network fails the sweep ("the network differs").
  std::shared_ptr<const PeriodicSolver> solver;
  // The [[circuit]] sources whose frequency the sweep varies (circuit[].name); empty: every
  // periodic source (set_switching_frequency in emnet/model/drive.hpp). With switched sources
  // a model is prepared per frequency.
  std::vector<std::string> sources;
  // Unknowns up to which `automatic` takes the dense exact method (above: the reduction) and a
  // reduction is checked against the full exact method (above: against a wider reduction).
  int dense_limit = kPeriodicDenseAutomaticUnknowns;
  // > 0: the beam's deformed shape at this many instants over one period of the periodic state
  // at the sweep peak (result.shape), from 2 to 100000; 0: none.
  int shape_instants = 0;

  /// The checks of the options alone (the frequencies, samples from 8 to 1000000 after the
  /// default, reduce with the exact method only, rtol, dense_limit, shape_instants), as
  /// run_switching_sweep makes them first.
  /// @throws OptionError naming the field ("samples"; "step" for from/to/step)
  void validate() const;
};

// The periodic extremes of one output over the sweep: left[k], right[k] at frequencies[k].
struct SwitchingSweepOutput {
  Probe probe;
  std::vector<double> left, right;  // periodic minimum and maximum [probe.unit]
};

// The reduced sweep against the full exact one at a few frequencies. Above the dense limit
// (SwitchingSweepOptions::dense_limit), where the full one is not computed, the error at each
// check frequency is the larger of the difference from a reduction with ten times the cut-off
// and the edge estimate of what the reduction truncates (ReducedPeriodicSolver::
// edge_error_estimate; it covers poles neither reduction found, e.g. beyond a cluster that stops
// Arnoldi): estimates, not bounds.
struct SwitchingSweepReductionCheck {
  bool against_full = true;            // false: the wider reduction and the edge estimate
  std::string reference;               // "the full exact periodic solution", or the wider reduction
  std::vector<double> edge_estimates;  // per check frequency, when not against_full
  ModalReduction model;                // what was kept (modes, real poles, cut-off)
  double build_seconds = 0.0;          // poles, left vectors, static solves
  std::vector<double> frequencies, errors;  // check frequencies [Hz], periodic_difference there
  double measured_error = 0.0;              // the largest of errors
  // Against the full solution: the error of what the sweep reports, each output's periodic
  // minimum and maximum (per check frequency, the largest |difference| relative to the output's
  // largest |value|). A reduced cascade leaves out only transients right after the switching
  // edges, where the samples differ and the extremes of a deflection seldom lie.
  std::vector<double> extreme_errors;
  double measured_extremes_error = 0.0;  // the largest of extreme_errors
  bool cascade = false;                  // the reduced cascade (ReducedPeriodicSolver)
  double tolerance = 0.0;                // the reduction's tolerance
  // stated_error() <= tolerance.
  bool tolerance_met = false;
  // The error the sweep states: against the full solution measured_extremes_error, otherwise the
  // estimate measured_error.
  double stated_error() const { return against_full ? measured_extremes_error : measured_error; }
  double full_build_seconds = 0.0;     // the reference's decomposition (or reduction)
  double full_solve_seconds = 0.0;     // per frequency: the reference's fastest solve
  double reduced_solve_seconds = 0.0;  // the same for the reduced solves there
};

struct SwitchingSweepResult {
  Status status;
  bool cancelled = false;         // stopped by options.progress (status "cancelled")
  Method method = Method::exact;  // exact, shooting or reduced
  std::vector<double> frequencies;
  std::vector<SwitchingSweepOutput> outputs;
  // The sweep peak: the largest peak-to-peak of the last output.
  size_t peak_index = 0;  // into frequencies
  double peak_frequency = 0.0;
  double peak_left = 0.0, peak_right = 0.0;               // of the last output there
  size_t peak_output = 0;                                 // outputs.size() - 1
  std::optional<SwitchingSweepReductionCheck> reduction;  // with `reduce`
  std::optional<double> first_mode_hz;                    // f1, when asked and found
  // With options.shape_instants: the beam over one period at the sweep peak.
  std::optional<DeformedShape> shape;
  // The exact method's solver (made here or given), for another sweep of the same network.
  std::shared_ptr<const PeriodicSolver> solver;
  // With `reduce`: the reduction (made here or given), for another sweep of the same network.
  std::shared_ptr<const ReducedPeriodicSolver> reduced_solver;
  Validity validity;  // of the deflection peaks over the sweep and the drive's voltages
  // Accuracy: the largest periodicity residual of the periodic solves.
  double worst_periodicity_residual = 0.0;
  // Cost.
  long solves = 0;                     // periodic solves of the sweep (checks not counted)
  long period_runs = 0;                // shooting: their one-period IDA runs (0 otherwise)
  int unknowns = 0;                    // of the swept network
  double model_seconds = 0.0;          // models prepared and assembled
  double excitation_seconds = 0.0;     // the drive's excitation made and set per frequency
  double decomposition_seconds = 0.0;  // PeriodicSolver's decomposition or the reduction's build
  double solve_seconds = 0.0;          // the periodic solves (their own seconds, summed)
  double check_seconds = 0.0;          // the reduction check
  double first_mode_seconds = 0.0;
  double seconds = 0.0;  // everything
  std::vector<std::string> notes;
};

// The switching frequencies of from/to/step (throws OptionError naming the field "step" when
// 0 < from <= to, step > 0 fails or they are more than 100000) or `frequencies` as given (each
// finite and > 0; else OptionError naming "frequencies").
std::vector<double> switching_frequencies(const SwitchingSweepOptions& options);
// InputError (scene file, "circuit") for a scene with nothing to switch: drive.kind "none"
// with a [[circuit]] none of whose `sources` (empty: all its sources) is periodic, or a named
// source that is missing or not periodic (switched_sources in emnet/model/drive.hpp).
void check_swept_drive(const Scene& scene, const std::vector<std::string>& sources = {});

// The model a sweep runs on, and the scene it varies. For the exact method the network must be
// linear: when the scene's DEAs have their electrical model (a nonlinear network), the model is
// rebuilt with drive.electrical_dynamics = false (ideal voltage-driven DEAs) and `notes` says so
// with the RC time constant against the shortest period (1/highest_hz). InputError: the swept
// drive (check_swept_drive); with the exact method an electrical probe among `probe_texts`
// (dea_voltage, dea_current: OptionError naming the field "probe" and the text), or a nonlinear
// scene driven through its
// [[circuit]] (naming "circuit").
struct SweptModel {
  Model model;
  Scene scene;  // the read scene, with drive.electrical_dynamics = false where it was set so
  std::vector<std::string> notes;
};
SweptModel prepare_swept_model(const Scene& scene, SwitchingSweepMethod method,
                               const std::vector<std::string>& probe_texts,
                               const PrepareOptions& prepare, double highest_hz);

// The outputs a sweep follows: the deflections of the recorded outputs (transient_output_list),
// or, given `probe_texts`, each of those (an output name or a probe of parse_probe). InputError
// naming "probe" when there is none.
std::vector<Probe> switching_sweep_outputs(const Model& model,
                                           const std::vector<std::string>& probe_texts);

// The sweep of `model` (outputs, f1 and validity are of it). `scene`: the scene the sweep
// varies, normally model's own read scene with segments chosen; when its
// drive.electrical_dynamics is "auto" a model is prepared from it per frequency, else `model`'s
// excitation is swapped. Input errors (options, a rise time or DEA overlap that does not fit
// the shortest period, a dense state matrix too large, a velocity output with `reduce`) throw
// InputError; numerical failure, a non-finite peak and cancellation are the Status.
SwitchingSweepResult run_switching_sweep(const Model& model, const Scene& scene,
                                         const SwitchingSweepOptions& options);
// The same with scene = model.scene.
SwitchingSweepResult run_switching_sweep(const Model& model, const SwitchingSweepOptions& options);

// max over outputs of the largest |difference| of `swept`'s peaks (left, right) from
// `reference`'s over the frequencies, relative to that output's largest |peak| in `reference`:
// how a reduced sweep's printed numbers compare with the exact one's (same frequencies and
// outputs).
double extremes_difference(const SwitchingSweepResult& swept,
                           const SwitchingSweepResult& reference);

}  // namespace emnet
