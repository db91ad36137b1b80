// The periodic extremes of one output under the square-wave drive
// (emnet/studies/periodic_peak.hpp).
#include "emnet/studies/periodic_peak.hpp"

#include <algorithm>
#include <cmath>

#include "emnet/analysis/periodic.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/model/deformed_shape.hpp"
#include "emnet/model/drive.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/studies/resolve.hpp"

namespace emnet {

void PeriodicExtremesOptions::validate() const {
  if (!(frequency_hz > 0.0) || !std::isfinite(frequency_hz))
    throw OptionError("frequency_hz", "must be a positive frequency in Hz (> 0)");
}

PeriodicExtremesResult periodic_extremes(Scene scene, const PeriodicExtremesOptions& options) {
  const Stopwatch stopwatch;
  options.validate();
  PeriodicExtremesResult result;
  check_overlap_fits(scene, options.frequency_hz, options.field);
  scene.drive.electrical_dynamics = false;
  scene.drive.electrical_dynamics_auto = false;
  scene.drive.frequency = options.frequency_hz;
  const Model model =  // large kinematics served by shooting
      prepare_model(scene, serving_large_kinematics(LargeKinematicsUse::dynamics));
  const System system = model.network.assemble();
  const bool shooting = system.is_nonlinear();
  if (!shooting) check_periodic_memory(system.size(), "segments");
  // The model's recorded outputs first (dx_k replaces P_k there), then the scene's own probes
  // (P4 is still a probe of the scene).
  std::vector<Probe> probes;
  for (const auto& probe : probes_of(transient_output_list(model)))
    if (probe.name == options.output) probes.push_back(probe);
  for (const auto& probe : model.probes)
    if (probes.empty() && probe.name == options.output) probes.push_back(probe);
  if (probes.empty())
    throw OptionError(options.field, "no deflection output named '" + options.output + "'");
  const RotationProbes rotations =
      options.largest_rotation ? rotation_probes(model) : RotationProbes{};
  probes.insert(probes.end(), rotations.probes.begin(), rotations.probes.end());
  const double period = 1.0 / options.frequency_hz;
  const PeriodicResult periodic =
      shooting ? run_periodic_shooting(system, probes, period, kPeriodicPeakShootingRtol, 256)
               : PeriodicSolver(system).solve(system, probes, period, 256);
  result.method = periodic.method;
  result.seconds = stopwatch.seconds();
  if (!periodic.status.ok()) {
    result.status = periodic.status.with_context("periodic state: ");
    return result;
  }
  if (!std::isfinite(periodic.minimum[0])) {
    result.status = Status::failure("non-finite result for a periodic minimum");
    return result;
  }
  if (!std::isfinite(periodic.maximum[0])) {
    result.status = Status::failure("non-finite result for a periodic maximum");
    return result;
  }
  result.minimum = periodic.minimum[0];
  result.maximum = periodic.maximum[0];
  result.peak = std::max(std::abs(result.minimum), std::abs(result.maximum));
  std::vector<double> rotation_peaks;
  for (size_t p = 1; p < probes.size(); ++p)
    rotation_peaks.push_back(
        std::max(std::abs(periodic.minimum[p]), std::abs(periodic.maximum[p])));
  result.rotation = largest_rotation(rotations, rotation_peaks);
  return result;
}

}  // namespace emnet
