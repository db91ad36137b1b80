// The left/right asymmetry of the periodic swing when the antagonistic pair is not identical:
// DEA A's electrode area (electrode width) or film thickness changed by ±X, or the switching
// overlapping (A on X·T/2 longer, both on together; −X: a dead time). The paper (Sect. 3)
// explains its larger left-side deflection by such tolerances.
//
//   asymmetry = (|left| − right) / ((|left| + right)/2)     [-]
//
// with left the periodic minimum of the output (the negative side) and right its maximum
// (periodic_peak.hpp: DEAs as ideal voltage-driven forces): > 0 when the swing is larger to the
// left. On the fish fin DEA A pulls to the left, so a stronger A (wider electrode, thinner film)
// gives a positive asymmetry. In the linear network a force mismatch x_F of A adds a constant
// force to the symmetric square wave, every extreme becoming ±(1 + x_F/2)·P + (x_F/2)·S (P the
// symmetric peak, S the static deflection with A alone on): a static offset that the resonance
// does not amplify, so asymmetry = x_F·|S| / ((1 + x_F/2)·P), linear in small changes.
// With large kinematics the superposition no longer holds: each periodic state is shot
// (periodic_peak.hpp), at about 0.1-1 s each on the fin instead of milliseconds; "auto"
// kinematics are chosen once, on the given scene, for every case.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "emnet/analysis/method.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

struct MismatchOptions {
  std::optional<double> frequency_hz;  // the switching frequency; default drive.frequency [Hz]
  // An output of the model's recorded outputs (transient_output_list, emnet/model/outputs.hpp),
  // or a probe of the scene; "": default_deflection_output (the last dx_k, dx4 on the fish fin).
  std::string output;
  double change = 0.05;          // X, the relative change of each parameter, in (0, 0.5)
  Progress* progress = nullptr;  // one report per periodic solve; cancelled: Status "cancelled"

  /// The checks of the options alone, as run_mismatch makes them first.
  /// @throws OptionError naming "change" (outside (0, 0.5)) or "frequency_hz" (given, not > 0)
  void validate() const;
};

struct MismatchRow {
  std::string label;    // "electrode area of A"
  std::string key;      // the parameter changed: "dea.A.electrode_width", "drive.overlap"
  double change = 0.0;  // −X or +X
  double left = 0.0, right = 0.0;          // the periodic minimum and maximum of the output
  double asymmetry = 0.0;                  // [-], see above
  double asymmetry_per_unit_change = 0.0;  // asymmetry / X
};

struct MismatchResult {
  Status status;
  std::string output;         // the output compared
  double frequency_hz = 0.0;  // the switching frequency
  double nominal_left = 0.0, nominal_right = 0.0, nominal_asymmetry = 0.0;  // no mismatch
  // Electrode area, film thickness, overlap; each at −X then +X.
  std::vector<MismatchRow> rows;
  Validity validity;  // of every peak computed, at the drive's levels
  int periodic_solves = 0;
  /// How the periodic states were found (periodic_peak.hpp): exact (a linear network) or
  /// shooting (beam.kinematics = "large").
  Method method = Method::exact;
  std::vector<std::string> notes;
  double seconds = 0.0;
};

// Throws OptionError for bad options (MismatchOptions::validate) or an unknown output (field
// "output"), InputError for a scene without the antagonistic drive of two DEAs (key drive.kind)
// or whose drive.frequency is not positive; a numerical failure (including a
// non-finite asymmetry) is the Status.
MismatchResult run_mismatch(const Scene& scene, const MismatchOptions& options);

}  // namespace emnet
