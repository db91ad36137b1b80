// The AC study (studies/ac_study.hpp): the sweep, its finiteness, the resonances in the band
// and the validity of its deflection amplitudes.
#include "emnet/studies/ac_study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "emnet/core/constants.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/deformed_shape.hpp"
#include "emnet/model/outputs.hpp"

namespace emnet {

std::string no_ac_input_reason(const Scene& scene) {
  const auto& drive = scene.drive;
  std::string why;
  switch (drive.kind) {
    case DriveKind::none:
      why = "drive.kind = \"none\"";
      break;
    case DriveKind::antagonistic:
    case DriveKind::switched:
      why = "the " + std::string(drive_kind_name(drive.kind)) +
            " drive at drive.voltage = " + format_with_unit(drive.voltage, "V");
      break;
    case DriveKind::bias_differential:
    case DriveKind::single:
      why = "drive.kind = \"" + std::string(drive_kind_name(drive.kind)) +
            "\" with drive.bias = " + format_with_unit(drive.bias, "V") +
            " and drive.amplitude = " + format_with_unit(drive.amplitude, "V") +
            " (at a bias of 0 V a V^2 force has no part linear in v: it acts at 0 and 2f)";
      break;
  }
  return "nothing excites the AC analysis: " + why +
         (scene.loads.empty() ? " and no [[load]]" : " and loads of zero value") +
         ", so every response would be zero; set a drive with a small-signal part or a load";
}

void require_ac_input(const Model& model, const System& system) {
  if (system.b_ac().norm() == 0.0)
    throw InputError(model.scene.file, "drive.kind", no_ac_input_reason(model.scene));
}

namespace {

// A note per circuit-driven DEA with its electrical model whose voltage at the operating point
// is 0 V (within 1e-9 of the largest DEA voltage there, or exactly): an AC input through the
// circuit moves nothing through it.
std::vector<std::string> zero_voltage_dea_notes(const Model& model,
                                                const Eigen::VectorXd& operating_point) {
  std::vector<std::pair<std::string, double>> voltages;
  double largest = 0.0;
  for (const CircuitDeaVoltageProbe& one : circuit_dea_voltage_probes(model)) {
    double u = 0.0;
    for (const auto& [index, c] : one.probe.terms) u += c * operating_point[index];
    voltages.emplace_back(one.dea, std::abs(u));
    largest = std::max(largest, std::abs(u));
  }
  std::vector<std::string> notes;
  for (const auto& [name, u] : voltages)
    if (u <= 1e-9 * largest)
      notes.push_back("DEA " + name +
                      " is at 0 V at the operating point (its sources at t = 0): its force "
                      "k_F*V^2 has no part linear in an AC input (2*k_F*V0*v = 0), so the input "
                      "moves nothing through it");
  return notes;
}

// The largest |rotation| at the beam's nodes in the AC response at `frequency` [Hz] (the largest
// deflection's), for the geometric error; none with large kinematics or where the solve fails.
std::optional<RotationPeak> largest_rotation_at(const Model& model, const System& system,
                                                const Eigen::VectorXd& operating_point,
                                                double frequency) {
  const RotationProbes rotations = rotation_probes(model);
  if (rotations.probes.empty() || !(frequency > 0.0)) return std::nullopt;
  const AcResult response = run_ac(system, operating_point, {frequency}, rotations.probes);
  if (!response.status.ok()) return std::nullopt;
  std::vector<double> peaks;
  for (const auto& values : response.values) peaks.push_back(std::abs(values.at(0)));
  return largest_rotation(rotations, peaks);
}

// The reduction's options, as given or the scene's tolerance, a band of 0 made the sweep's top.
// @throws OptionError when they are out of range (validate)
ReductionOptions reduction_options(const Model& model, const AcStudyOptions& options) {
  ReductionOptions reduction;
  if (options.reduction)
    reduction = *options.reduction;
  else
    reduction.tolerance = model.scene.model.tolerance;
  if (reduction.band == 0.0) reduction.band = options.sweep.to;
  validate(reduction);
  return reduction;
}

// Whether the sweep is to be reduced (AcStudyOptions::method).
bool reduces(const AcStudyOptions& options, const System& system, size_t points) {
  switch (options.method) {
    case AcSweepMethod::full:
      return false;
    case AcSweepMethod::reduced:
      return true;
    case AcSweepMethod::automatic:
      return system.size() > kAcReductionUnknowns &&
             points >= static_cast<size_t>(kAcReductionPoints);
  }
  return false;
}

// Why the automatic method solved the full model after all: the reduction failed, or its check
// missed the tolerance.
std::string full_model_note(const System& system, const AcReductionResult& reduction) {
  const std::string why =
      !reduction.status.ok()
          ? "failed (" + reduction.status.message + ")"
          : "measured " + format_number("%.3g", reduction.measured_error) +
                " against the full model at its check frequencies, above its tolerance " +
                format_number("%.3g", reduction.model.tolerance);
  return "the modal reduction (automatic for " + std::to_string(system.size()) +
         " unknowns, above " + std::to_string(kAcReductionUnknowns) + ") " + why +
         ": every frequency was solved on the full model";
}

// The sweep by the options' method into `result` (ac, reduction, a note on the automatic
// method's choice); on failure the stage in `failed`.
Status sweep_by_method(const Model& model, const System& system,
                       const Eigen::VectorXd& operating_point, const std::vector<double>& grid,
                       const std::vector<Probe>& probes, const AcStudyOptions& options,
                       AcStudyResult& result, AcStudyStage& failed) {
  // Given options are checked whatever the method; the defaults only where they are used (a
  // one-point sweep at 0 Hz has no band).
  if (options.reduction) reduction_options(model, options);
  if (reduces(options, system, grid.size())) {
    const ReductionOptions reduction = reduction_options(model, options);
    report_phase(options.progress, "modal reduction and its check");
    result.reduction = run_ac_reduced(system, operating_point, grid, probes, reduction);
    const bool automatic = options.method == AcSweepMethod::automatic;
    if (automatic && !(result.reduction->status.ok() && result.reduction->tolerance_met)) {
      result.notes.push_back(full_model_note(system, *result.reduction));
      result.reduction.reset();
    } else {
      failed = AcStudyStage::reduction;
      if (!result.reduction->status.ok()) return result.reduction->status;
      result.ac = result.reduction->ac;
      failed = AcStudyStage::sweep;
      if (!result.ac.status.ok()) return result.ac.status;
      if (automatic)
        result.notes.push_back(
            "the sweep is the modal reduction's, chosen automatically for " +
            std::to_string(system.size()) + " unknowns and " + std::to_string(grid.size()) +
            " frequencies (above " + std::to_string(kAcReductionUnknowns) + " and from " +
            std::to_string(kAcReductionPoints) +
            "): its error is measured against the full model at " +
            std::to_string(result.reduction->check_frequencies.size()) + " frequencies");
      return Status::success();
    }
  }
  AcOptions sweep_options;
  sweep_options.progress = options.progress;
  result.ac = run_ac(system, operating_point, grid, probes, sweep_options);
  failed = AcStudyStage::sweep;
  return result.ac.status.ok() ? Status::success() : result.ac.status;
}

// The resonances as (frequency [Hz], damping ratio −Re s/|s|): the reduced model's kept modes,
// else the pole-residue sweep's poles, else the full model's modes (a failed modal analysis only
// leaves the plot without markers).
std::vector<std::pair<double, double>> resonances_of(const AcStudyResult& result,
                                                     const System& system,
                                                     const Eigen::VectorXd& operating_point,
                                                     const AcStudyOptions& options) {
  std::vector<std::pair<double, double>> resonances;
  if (result.reduction) {
    for (const auto& kept : result.reduction->model.kept)
      if (kept.oscillatory && is_resonance(kept.pole))
        resonances.emplace_back(std::abs(kept.pole.imag()) / kTwoPi,
                                -kept.pole.real() / std::abs(kept.pole));
    std::sort(resonances.begin(), resonances.end());
  } else if (!result.ac.poles.empty()) {
    // The pole-residue sweep has every pole already (to rounding, checked through the sweep).
    // Oscillatory as run_modes counts them (|Im s| above kNearlyReal·|s|), and not a pole at 0
    // within rounding of the largest (invariants of the state equation that no source
    // excites).
    double largest = 0.0;
    for (const auto& pole : result.ac.poles) largest = std::max(largest, std::abs(pole));
    for (const auto& pole : result.ac.poles)
      if (pole.imag() > 0.0 && std::abs(pole) > 1e-9 * largest && is_resonance(pole))
        resonances.emplace_back(pole.imag() / kTwoPi, -pole.real() / std::abs(pole));
    std::sort(resonances.begin(), resonances.end());
  } else {
    // Markers: frequency and damping ratio only (no error bounds). A large network's lowest 3
    // first, 10 when all 3 lie in the band (the 10 took 6 s of the fin's AC at N = 10 000).
    ModalOptions modal_options;
    modal_options.keep_vectors = false;
    modal_options.error_bounds = false;
    const bool large = system.size() > modal_options.dense_limit;
    if (large) modal_options.count = 3;
    report_phase(options.progress, "modes for the resonance markers");
    ModalResult modes = run_modes(system, operating_point, modal_options);
    if (large && modes.status.ok() && modes.modes.size() == 3 &&
        modes.modes.back().frequency_hz <= options.sweep.to) {
      modal_options.count = 10;
      modes = run_modes(system, operating_point, modal_options);
    }
    if (modes.status.ok())
      for (const auto& mode : modes.modes)
        resonances.emplace_back(mode.frequency_hz, mode.damping_ratio);
  }
  return resonances;
}

}  // namespace

AcStudyResult run_ac_study(const Model& model, const System& system,
                           const Eigen::VectorXd& operating_point, const AcStudyOptions& options) {
  AcStudyResult result;
  require_ac_input(model, system);
  const std::vector<double> grid =
      frequency_grid(options.sweep.from, options.sweep.to, options.sweep.points, options.sweep.log);
  // The small-signal part of each probe (a DEA force's 2·k_F·u₀·U), as the sweep evaluates it.
  std::vector<Probe> probes;
  for (const Probe& probe : options.probes)
    probes.push_back(linearised_probe(probe, operating_point));
  AcStudyStage failed = AcStudyStage::none;
  if (Status swept =
          sweep_by_method(model, system, operating_point, grid, probes, options, result, failed);
      !swept.ok()) {
    result.status = std::move(swept);
    result.failed_stage = failed;
    return result;
  }
  const std::vector<std::pair<double, double>> resonances =
      resonances_of(result, system, operating_point, options);
  for (const auto& [f, zeta] : resonances)
    if (f >= options.sweep.from && f <= options.sweep.to) {
      result.resonances_hz.push_back(f);
      result.resonance_damping_ratios.push_back(zeta);
    }

  std::vector<std::string> notes = zero_voltage_dea_notes(model, operating_point);
  notes.insert(notes.end(), result.notes.begin(), result.notes.end());  // the method's
  result.notes = std::move(notes);
  bool every_response_zero = true;
  for (const auto& values : result.ac.values)
    for (const auto& v : values) every_response_zero &= v == 0.0;
  if (every_response_zero && !result.ac.values.empty()) {
    std::string why;
    for (const std::string& note : result.notes) why += "; " + note;
    throw InputError(
        model.scene.file, "circuit",
        "the AC input reaches no output: every response is exactly zero" +
            (why.empty() ? std::string(" (the input and the outputs are not coupled)") : why));
  }
  size_t peak_frequency = 0;
  double largest_deflection = -1.0;
  for (size_t k = 0; k < probes.size(); ++k)
    if (probes[k].quantity == ProbeQuantity::deflection) {
      result.peaks.push_back({probes[k].name, 0.0});
      const auto& values = result.ac.values[k];
      for (size_t i = 0; i < values.size(); ++i) {
        result.peaks.back().peak = std::max(result.peaks.back().peak, std::abs(values[i]));
        if (std::abs(values[i]) > largest_deflection)
          largest_deflection = std::abs(values[i]), peak_frequency = i;
      }
    }
  const std::optional<RotationPeak> rotation =
      largest_deflection >= 0.0 && peak_frequency < result.ac.frequencies.size()
          ? largest_rotation_at(model, system, operating_point,
                                result.ac.frequencies[peak_frequency])
          : std::nullopt;
  result.validity =
      check_validity(model.scene, result.peaks, drive_peak_voltages(model.scene), rotation);
  result.status = Status::success();
  return result;
}

}  // namespace emnet
