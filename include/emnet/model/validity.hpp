// Results a small-deflection linear model cannot honestly give: the checks and their messages.
//
// The beam is Euler–Bernoulli with small deflections (sin φ ≈ φ, no shortening along the
// beam, loads that keep their direction) and the DEAs are linear capacitors that never break
// down. Two checks say when a computed result has left that model:
//
// - Deflection: the largest |deflection| computed at an output against model.deflection_limit
//   times beam.length (default 10 %). What the linear theory gets wrong grows as (w/L)². For a
//   cantilever bent by an end moment (how a DEA patch loads a beam) the exact shape is an arc,
//   tip deflection R·(1 − cos θ) with θ = L/R = 2w/L against the linear w = L²/(2R): at
//   w = 0.1·L the linear value is 0.33 % too large and the tip has moved 0.67 % of L toward the
//   clamp, which the model does not have; at 0.2·L 1.3 % and 2.6 %. Under an end force (the
//   elastica, integrated for these numbers) 1.0 % at 0.1·L and 4.0 % at 0.2·L. Past a few
//   tenths of L the numbers describe no real beam (a linear beam deflects without bound).
// - Electric field: the largest voltage across each DEA's film divided by its thickness d
//   (dea[].dielectric_thickness, the nominal film: the model does not thin it under load)
//   against dea[].breakdown_field (default kDefaultBreakdownField, emnet/scene/scene.hpp). Above it
//   the film breaks down and the DEA is a short, not a capacitor.
//
// Each small-kinematics result also states its geometric error, estimated as max((w/L)², ψ²) of
// its largest deflection w and its largest section rotation ψ at the beam's nodes (rotation_probes
// in emnet/model/deformed_shape.hpp; (w/L)² alone where a result computed no rotation). The
// rotation is what sin ψ ≈ ψ and cos ψ ≈ 1 neglect, and it sees what w/L does not: a soft tip
// turning on a stiff body (the tweezer jaw at resonance: w = 12.9 % of L, (w/L)² = 1.66 %, but
// its tip turns by 0.49 rad and the small swing is 16 % above the large model's; ψ² = 24 %).
// Measured against beam.kinematics = "large", the true error is 0.44·ψ² under a tip force (the
// elastica: its tip turns by 1.5·w/L), ψ²/12 under an end moment (the arc), at most 0.25·ψ² for
// the fish fin's swing at resonance and 0.67·ψ² for the tweezer's. An estimate, not a bound: a beam
// whose supports stretch it (clamped at both ends) stiffens far sooner.
//
// With beam.kinematics = "large" the beam has no small-deflection assumption, and the deflection
// check does not apply (the summary says so).
//
// A check fails only strictly above its limit ("at most" the limit is inside). The checks
// judge the values handed to them, so each command passes what it computed: static the state
// at t = 0 (drive_voltages_at_start), the others every level the drive applies
// (drive_peak_voltages). A flagged result is still computed and printed, with a WARNING; the
// program exits with kExitOutsideValidity.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "emnet/scene/scene.hpp"

namespace emnet {

/// Exit status of a command whose result is computed but outside the model's validity.
constexpr int kExitOutsideValidity = 5;

/// The largest |deflection| [m] computed at one output (a probe, dx4, the beam's nodes).
struct DeflectionPeak {
  std::string output;  ///< the output's name
  double peak = 0.0;   ///< [m]
};

/// The largest |voltage| [V] across one DEA's film in what was computed.
struct DeaVoltage {
  std::string dea;       ///< the DEA's name
  double voltage = 0.0;  ///< [V]
  /// How `voltage` was found when it is a bound, not a level of the drive or a computed value:
  /// named in the summary and the violation's message ("" for none).
  std::string bound;
};

/// The small beam's geometric error (above): (w/L)² at a largest |deflection| `peak` [m] of a beam
/// of `length` [m], the tip-force elastica's, relative.
double geometric_error_estimate(double peak, double length);
/// The same from the deflection and the largest |section rotation| ψ [rad]: max((w/L)², ψ²).
double geometric_error_estimate(double peak, double length, double rotation);

/// The largest |section rotation| [rad] a small-kinematics result computed at the beam's nodes
/// (rotation_probes, emnet/model/deformed_shape.hpp), and where.
struct RotationPeak {
  std::string where;  ///< "x = 35 mm"
  double peak = 0.0;  ///< [rad]
};
/// The rotation `peak` [rad] at `position` [m] along the beam, where named in millimetres.
RotationPeak rotation_peak_at(double position, double peak);
/// The larger of two rotations (either may be none).
std::optional<RotationPeak> larger_rotation(const std::optional<RotationPeak>& a,
                                            const std::optional<RotationPeak>& b);

/// The limits a result is checked against.
enum class ValidityCheck { deflection, electric_field };
/// "deflection", "electric_field"
const char* validity_check_name(ValidityCheck check);

/// A computed value beyond its limit.
struct ValidityViolation {
  ValidityCheck check = ValidityCheck::deflection;
  std::string subject;  ///< the output or the DEA
  std::string key;      ///< the scene key of the limit: "model.deflection_limit"
  double value = 0.0;   ///< |w| [m] or V/d [V/m]
  double limit = 0.0;   ///< model.deflection_limit·L [m] or dea[].breakdown_field [V/m]
  std::string message;  ///< one line, with the numbers
};

/// The outcome of check_validity.
struct Validity {
  std::vector<ValidityViolation> violations;
  /// The worst of each check as a fraction of its limit (0 when nothing was checked).
  double deflection_fraction = 0.0;
  double field_fraction = 0.0;  ///< see deflection_fraction
  /// Small kinematics: the estimated relative error of the deflections from the small-deflection
  /// assumption, max((w/L)², ψ²) (above); 0 with large kinematics or no deflection.
  double geometric_error = 0.0;
  /// The largest |section rotation| [rad] the estimate took; 0 when none was computed.
  double largest_rotation = 0.0;
  std::string summary;  ///< one line: the largest values against their limits
  /// Whether nothing exceeds its limit.
  bool within() const { return violations.empty(); }
};

/// Each DEA the drive names with its largest source voltage over the drive: V for the square
/// waves, V0 + v for the sines. The RC loop's capacitor voltage stays within the source's range.
/// Each DEA a [[circuit]] drives (circuit_driven_deas) with the bound circuit_voltage_bound
/// proves (the RC maximum principle over the circuit's sources), its `bound` saying so; none
/// when no bound is known (check_validity then says "field not checked" and why).
std::vector<DeaVoltage> drive_peak_voltages(const Scene& scene);
/// The same at t = 0 (the state `emnet static` and `tran --start static` apply).
std::vector<DeaVoltage> drive_voltages_at_start(const Scene& scene);

/// The violations among `deflections` and `voltages` of `scene` (its beam length, DEA films and
/// limits); a DEA named in `voltages` must be one of the scene's. `rotation`: the result's largest
/// section rotation, which the geometric error estimate then takes (none: the deflection alone).
/// @throws std::invalid_argument for a DEA in `voltages` that the scene does not have
Validity check_validity(const Scene& scene, const std::vector<DeflectionPeak>& deflections,
                        const std::vector<DeaVoltage>& voltages,
                        const std::optional<RotationPeak>& rotation = std::nullopt);

}  // namespace emnet
