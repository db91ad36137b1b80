// The AC study: the small-signal response of a prepared model's probes over a frequency grid,
// with what the program's `ac` command reports beside it.
//
//   - The sweep: (G + J_g + jω·C)·Y = B_ac at every frequency (run_ac: the full model), or the
//     modal reduction with static correction checked against the full model at a few
//     frequencies (run_ac_reduced, analysis/modal_reduction.hpp). AcSweepMethod::automatic
//     reduces a large network's long sweep, where one reduction costs what 200–300 full solves
//     do (fish fin, 1000 points: N = 300 0.22 → 0.06 s, N = 10 000 7.4 → 2 s as a command),
//     and keeps the reduced sweep only when its check meets the tolerance: otherwise it solves
//     every frequency on the full model and says why in a note.
//   - Every response value finite: a NaN or an infinity in the sweep fails the study, naming
//     the probe and the frequency (run_ac and run_ac_reduced check their values).
//   - The resonances in the band [sweep.from, sweep.to], for the Bode plot's markers: the
//     oscillatory kept modes of the reduced model, else the poles the pole-residue sweep used
//     (every pole), else the modes of the full model (run_modes without vectors; at most 10
//     above the dense method's size limit). f = |Im s|/(2π) [Hz].
//   - Validity: each deflection probe's largest |response| [m] against the scene's deflection
//     limit, and the drive's peak DEA voltages against breakdown (model/validity.hpp). Every
//     drive's AC input has the scene's own amplitude, so these are deflection amplitudes.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/network/output.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

/// Why the scene gives the AC analysis no input (B_ac = 0), in its own terms: "nothing excites
/// the AC analysis: drive.kind = \"none\" and no [[load]], so every response would be zero; …".
std::string no_ac_input_reason(const Scene& scene);

/// Checks that `system` (of `model`) has an AC input.
/// @throws InputError naming the scene's file and drive.kind, with no_ac_input_reason, when the
///         system has no AC input (System::b_ac = 0)
void require_ac_input(const Model& model, const System& system);

/// How run_ac_study evaluates its sweep.
enum class AcSweepMethod {
  automatic,  ///< reduced above kAcReductionUnknowns unknowns for kAcReductionPoints
              ///< frequencies or more when the check meets the tolerance, else full
  full,       ///< the full model at every frequency (run_ac: pole-residue or direct)
  reduced,    ///< the modal reduction, whatever its check finds (reported)
};

/// The automatic method reduces a sweep of a network with more unknowns than this …
inline constexpr int kAcReductionUnknowns = 2000;
/// … and at least this many frequencies.
inline constexpr int kAcReductionPoints = 500;

/// What run_ac_study sweeps and how.
struct AcStudyOptions {
  AcSpec sweep;               ///< from, to [Hz], points, log: the grid is frequency_grid of these
  std::vector<Probe> probes;  ///< the responses computed
  AcSweepMethod method = AcSweepMethod::automatic;  ///< full model or modal reduction
  /// The reduction's band and tolerance when it reduces; unset: band = sweep.to, tolerance =
  /// the scene's model.tolerance.
  std::optional<ReductionOptions> reduction;
  Progress* progress = nullptr;  ///< the phases and the full sweep's frequencies
};

/// Which step of the study failed (Status::ok false), so that a caller can name it.
enum class AcStudyStage { none, reduction, sweep };

/// The sweep, its resonances and validity, or the stage that failed.
struct AcStudyResult {
  /// Failure: the analysis's message (run_ac's, run_ac_reduced's), in `failed_stage`.
  Status status;
  AcStudyStage failed_stage = AcStudyStage::none;  ///< none on success
  AcResult ac;                                 ///< the sweep (the reduced model's with `reduction`)
  std::optional<AcReductionResult> reduction;  ///< set when the sweep is the reduced one
  std::vector<double> resonances_hz;           ///< in [from, to] of the grid, increasing
  std::vector<double> resonance_damping_ratios;  ///< each resonance's damping ratio −Re s/|s|
  std::vector<DeflectionPeak> peaks;             ///< per deflection probe, its largest |response|
  Validity validity;  ///< the deflection amplitudes and DEA voltages against their limits
  /// What the input cannot reach: a circuit-driven DEA whose operating voltage is 0 V, whose
  /// k_F·V² force has no part linear in the AC input (2·k_F·u₀·U = 0).
  std::vector<std::string> notes;
};

/// The study on a model already built and its operating point (the static state, or zero for
/// a linear network: analysis/operating_point.hpp). A failure of the reduction or the sweep is
/// the result's status, in `failed_stage`.
/// @throws InputError when the system has no AC input (require_ac_input), or when the input
///         reaches no output (every response exactly zero, e.g. a circuit source's ac about a
///         DEA at 0 V), naming "circuit" with the notes
/// @throws OptionError (an InputError) when `options.reduction` is out of range (also when the
///         method is full, so that a bad option is found whatever the network's size)
AcStudyResult run_ac_study(const Model& model, const System& system,
                           const Eigen::VectorXd& operating_point, const AcStudyOptions& options);

}  // namespace emnet
