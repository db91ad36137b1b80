// The periodic extremes of one output of a scene under its square-wave drive: the minimum and
// maximum over one period of the periodic steady state, used by identify (the peak a loss
// factor is fitted to) and mismatch (the left/right swing).
//
// The drive is switched at `frequency_hz` (drive.frequency is replaced), with the DEAs as ideal
// voltage-driven forces (drive.electrical_dynamics = false): the exact periodic method
// (analysis/periodic.hpp) needs a linear network, and on the fish fin the full DEA model moves
// the peak at 5 Hz by 5e-4 relative. The exact method's extremes are global extrema of a sum of
// exponentials, found to 1e-11 of the largest |value| and then refined by Newton to rounding.
//
// With beam.kinematics = "large" (or "auto" choosing it) the network is nonlinear and the
// periodic state is found by shooting (IDA at rtol 1e-9, 256 samples a period, the largest
// samples refined by a parabola): on the fin at 400 V it agrees with the small network's exact
// state to 3e-7 of the swing; PeriodicExtremesResult::method says which was used.
//
// Units: those of the output (a deflection in m).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "emnet/analysis/method.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

/// IDA's relative tolerance of a shot periodic state (large kinematics); its periodicity
/// residual is held to max(kResidualLimit, 1000 × this) (analysis/periodic.hpp).
inline constexpr double kPeriodicPeakShootingRtol = 1e-9;

struct PeriodicExtremesOptions {
  double frequency_hz = 0.0;  // the switching frequency [Hz]
  // An output of transient_output_list (emnet/model/outputs.hpp: dx4, u_A, ...), else a probe
  // of the scene (P4, tip).
  std::string output;
  // The field of the calling study's Options that OptionErrors name: the one that gave the
  // output and the frequency (mismatch's "output", identify's "peak").
  std::string field = "output";
  // Also the largest |rotation| at the beam's nodes over the period (small kinematics), for the
  // geometric error of a study's validity check.
  bool largest_rotation = false;

  /// The checks of the options alone, as periodic_extremes makes them first.
  /// @throws OptionError naming "frequency_hz" when it is not a finite frequency > 0
  void validate() const;
};

struct PeriodicExtremesResult {
  Status status;                  // failure: "periodic state: <why>", or a non-finite extreme
  double minimum = 0.0;           // the output's smallest value over one period (the left swing)
  double maximum = 0.0;           // its largest (the right swing)
  double peak = 0.0;              // max(|minimum|, |maximum|)
  Method method = Method::exact;  // exact (a linear network) or shooting (large kinematics)
  std::optional<RotationPeak> rotation;  // with options.largest_rotation and small kinematics
  double seconds = 0.0;
};

// Throws OptionError (naming options.field) when the drive's overlap does not fit the period at
// options.frequency_hz, the exact method would need too much memory, or there is no output of
// that name; a numerical failure is the Status.
PeriodicExtremesResult periodic_extremes(Scene scene, const PeriodicExtremesOptions& options);

}  // namespace emnet
