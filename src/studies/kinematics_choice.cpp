// beam.kinematics = "auto" (kinematics_choice.hpp).
//
// The estimate is that of every small-kinematics result (emnet/model/validity.hpp):
// max((w/L)², ψ²) of the largest deflection and section rotation. Both are the small network's,
// before any analysis: the static state under the loads and the drive at t = 0 and, for the dynamic
// analyses, the AC response to the drive's alternating part at every node, at the band's ends and
// its damped modes, times 4/π for a square-wave drive (its fundamental: at the fish fin's resonance
// 13.24 mm against the periodic swing's 13.16 mm). An analysis that refuses large kinematics
// computes nothing: it stays small.
#include "kinematics_choice.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <optional>
#include <string>

#include "emnet/analysis/analysis.hpp"
#include "emnet/core/constants.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/deformed_shape.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/studies/segment_selection.hpp"

namespace emnet {

namespace {

// The largest deflection [m] and where it comes from, in words.
struct LargestDeflection {
  double value = 0.0;
  std::string where = "no load or drive deflects the beam";
  double rotation = 0.0;  // the largest |section rotation| at the nodes [rad], anywhere
};

void take(LargestDeflection& largest, double value, const std::string& where) {
  if (std::isfinite(value) && value > largest.value) largest = {value, where};
}

// The AC response's largest amplitude over the band: at each mode in it (its damped frequency,
// within ζ² of the peak) and at the band's ends, by a sparse LU per frequency (no more than the
// modes in the band: a grid would cost an LU per point at every size of network).
void take_ac_response(const Scene& scene, const System& system, const StaticResult& rest,
                      const std::vector<Probe>& nodes, const std::vector<Probe>& rotations,
                      LargestDeflection& largest) {
  if (system.b_ac().norm() == 0.0) return;
  BandOfInterest band;
  try {
    band = band_of_interest(scene, "beam.kinematics");
  } catch (const InputError&) {
    return;  // no band: the static state alone (the reason says which it took)
  }
  const Eigen::VectorXd point =
      rest.status.ok() ? rest.operating_point : Eigen::VectorXd::Zero(system.size());
  std::vector<double> frequencies = {band.from, band.to};
  ModalOptions modal;
  modal.keep_vectors = false;
  modal.error_bounds = false;
  const ModalResult modes = run_modes(system, point, modal);
  // An undamped mode's resonance has no finite swing to estimate from (the small network's own
  // periodic state grows without bound there): only damped modes are counted.
  if (modes.status.ok())
    for (const auto& mode : modes.modes)
      if (mode.frequency_hz >= band.from && mode.frequency_hz <= band.to &&
          mode.damping_ratio > 1e-6)
        frequencies.push_back(mode.frequency_hz);
  const Eigen::SparseMatrix<double> g = linearised_g(system, point);
  const bool square =
      scene.drive.kind == DriveKind::antagonistic || scene.drive.kind == DriveKind::switched;
  const double factor = square ? 4.0 / kPi : 1.0;
  for (const double f : frequencies) {
    if (!(f > 0.0)) continue;
    const double omega = kTwoPi * f;
    double residual = 0.0;
    const Eigen::VectorXcd y = small_signal_phasors(system, g, omega, &residual);
    if (!(residual <= kResidualLimit)) continue;
    for (const Probe& probe : nodes)
      take(largest, factor * std::abs(probe_phasor(probe, y, omega)),
           std::string(square ? "4/pi x " : "") + "the AC amplitude at " +
               format_number("%.5g", f) + " Hz (band " + band.source + ")");
    for (const Probe& probe : rotations)
      largest.rotation =
          std::max(largest.rotation, factor * std::abs(probe_phasor(probe, y, omega)));
  }
}

// `with_ac`: the dynamic analyses' swing too (the static analysis has the static state only).
LargestDeflection largest_small_deflection(const Scene& scene, bool with_ac) {
  Scene small = scene;
  small.beam.kinematics = BeamKinematics::small;
  small.beam.kinematics_auto = false;
  const Model model = build_model(small);
  const System system = model.network.assemble();
  const ShapeProbes nodes = shape_probes(model);
  const RotationProbes rotations = rotation_probes(model);
  LargestDeflection largest;
  const StaticResult rest = solve_static(system);
  if (rest.status.ok()) {
    for (const Probe& probe : nodes.probes)
      take(largest, std::abs(static_probe_value(system, rest, probe)), "the static state");
    for (const Probe& probe : rotations.probes)
      largest.rotation =
          std::max(largest.rotation, std::abs(static_probe_value(system, rest, probe)));
  }
  if (with_ac) take_ac_response(scene, system, rest, nodes.probes, rotations.probes, largest);
  return largest;
}

// Why `scene` cannot take large kinematics for `use` ("" when it can).
std::string why_not_large(const Scene& scene, LargeKinematicsUse use) {
  if (use == LargeKinematicsUse::dynamics && !extensible(scene.beam))
    return "the dynamic analyses need beam.axial_stiffness (EA) with large kinematics";
  Scene large = scene;
  large.beam.kinematics = BeamKinematics::large;
  large.beam.kinematics_auto = false;
  try {
    build_model(large);
  } catch (const InputError& error) {
    return std::string("the beam cannot take large kinematics: ") + error.what();
  }
  return "";
}

}  // namespace

AutomaticChoice choose_kinematics(const Scene& scene, LargeKinematicsUse use) {
  const auto start = std::chrono::steady_clock::now();
  AutomaticChoice choice;
  choice.key = "beam.kinematics";
  choice.tolerance = scene.model.tolerance;
  if (use == LargeKinematicsUse::refused) {  // nothing to choose: no estimate is computed
    choice.value = "small";
    choice.reason =
        "beam.kinematics = \"auto\": small: this analysis takes small kinematics "
        "only (its result states its geometric error)";
    return choice;
  }
  const LargestDeflection largest =
      largest_small_deflection(scene, use == LargeKinematicsUse::dynamics);
  const double fraction = largest.value / scene.beam.length;
  choice.estimated_error =
      geometric_error_estimate(largest.value, scene.beam.length, largest.rotation);
  const bool wanted = choice.estimated_error > scene.model.tolerance;
  const std::string obstacle = wanted ? why_not_large(scene, use) : "";
  const bool large = wanted && obstacle.empty();
  choice.value = large ? "large" : "small";
  choice.reason = "beam.kinematics = \"auto\": " + choice.value + ": the small beam's largest " +
                  "deflection " + format_number("%.4g", largest.value * 1e3) + " mm (" +
                  largest.where + ") = " + format_number("%.3g", 100 * fraction) +
                  " % of L, its largest rotation " + format_number("%.3g", largest.rotation) +
                  " rad, a geometric error ~max((w/L)^2, psi^2) = " +
                  format_number("%.3g", choice.estimated_error) + (wanted ? " > " : " <= ") +
                  "model.tolerance " + format_number("%.3g", scene.model.tolerance) +
                  (obstacle.empty() ? "" : "; small all the same: " + obstacle);
  choice.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return choice;
}

}  // namespace emnet
