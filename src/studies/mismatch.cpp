// Left/right asymmetry from a mismatched antagonistic pair (emnet/studies/mismatch.hpp).
#include "emnet/studies/mismatch.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "emnet/core/option_error.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/studies/periodic_peak.hpp"
#include "emnet/studies/resolve.hpp"

namespace emnet {
namespace {

double asymmetry_of(double left, double right) {
  return (std::abs(left) - right) / (0.5 * (std::abs(left) + right));
}

}  // namespace

void MismatchOptions::validate() const {
  if (!(change > 0.0 && change < 0.5))
    throw OptionError("change", "must be > 0 and < 0.5 (a fraction)");
  if (frequency_hz && (!(*frequency_hz > 0.0) || !std::isfinite(*frequency_hz)))
    throw OptionError("frequency_hz", "must be a positive frequency in Hz (> 0)");
}

MismatchResult run_mismatch(const Scene& given, const MismatchOptions& options) {
  const Stopwatch stopwatch;
  options.validate();
  if (given.drive.kind != DriveKind::antagonistic || given.drive.deas.size() != 2)
    throw InputError(given.file, "drive.kind",
                     "mismatch needs the antagonistic drive of two DEAs (drive.kind = "
                     "\"antagonistic\", drive.deas = [A, B])");
  MismatchResult result;
  // One kinematics for the nominal scene and every changed one.
  const Scene scene = resolve_kinematics(given, LargeKinematicsUse::dynamics, &result.notes);
  result.frequency_hz = options.frequency_hz.value_or(scene.drive.frequency);
  if (!(result.frequency_hz > 0.0) || !std::isfinite(result.frequency_hz))
    throw InputError(scene.file, "drive.frequency", "must be a positive frequency in Hz (> 0)");
  result.output = options.output;
  if (result.output.empty()) {
    const Model model =  // as periodic_extremes
        prepare_model(scene, serving_large_kinematics(LargeKinematicsUse::dynamics));
    const std::vector<ModelOutput> outputs = transient_output_list(model);
    const ModelOutput* chosen = default_deflection_output(outputs);
    if (!chosen) throw InputError(scene.file, "probe", "the scene has no deflection output");
    result.output = chosen->probe.name;
  }
  const std::string& dea_name = scene.drive.deas[0];
  size_t dea = scene.deas.size();
  for (size_t k = 0; k < scene.deas.size(); ++k)
    if (scene.deas[k].name == dea_name) dea = k;
  if (dea == scene.deas.size())
    throw InputError(scene.file, "drive.deas", "no DEA named '" + dea_name + "'");

  struct Case {
    std::string label, key;
    std::function<void(Scene&, double)> apply;  // change by the fraction x
  };
  const double half_period = 0.5 / result.frequency_hz;
  const std::vector<Case> cases = {
      {"electrode area of " + dea_name, "dea." + dea_name + ".electrode_width",
       [dea](Scene& s, double x) { s.deas[dea].electrode_width *= 1.0 + x; }},
      {"film thickness of " + dea_name, "dea." + dea_name + ".dielectric_thickness",
       [dea](Scene& s, double x) { s.deas[dea].dielectric_thickness *= 1.0 + x; }},
      {"switching overlap (of T/2)", "drive.overlap",
       [half_period](Scene& s, double x) { s.drive.overlap = x * half_period; }},
  };
  PeriodicExtremesOptions extremes_options;
  extremes_options.frequency_hz = result.frequency_hz;
  extremes_options.output = result.output;
  extremes_options.field = "output";
  extremes_options.largest_rotation = true;
  std::optional<RotationPeak> rotation;  // the largest over every case
  const long solves = 1 + 2 * static_cast<long>(cases.size());
  auto solve = [&](const Scene& changed, double& left, double& right) {
    if (!keep_going(options.progress, result.periodic_solves, solves, "periodic solves")) {
      result.status = cancelled_status();
      return false;
    }
    const PeriodicExtremesResult extremes = periodic_extremes(changed, extremes_options);
    ++result.periodic_solves;
    result.method = extremes.method;
    if (!extremes.status.ok()) {
      result.status = extremes.status;
      return false;
    }
    left = extremes.minimum;
    right = extremes.maximum;
    rotation = larger_rotation(rotation, extremes.rotation);
    return true;
  };
  auto finished = [&]() -> MismatchResult& {
    result.seconds = stopwatch.seconds();
    return result;
  };
  if (!solve(scene, result.nominal_left, result.nominal_right)) return finished();
  result.nominal_asymmetry = asymmetry_of(result.nominal_left, result.nominal_right);
  for (const Case& c : cases)
    for (const double x : {-options.change, options.change}) {
      Scene changed = scene;
      c.apply(changed, x);
      MismatchRow row{c.label, c.key, x, 0.0, 0.0, 0.0, 0.0};
      if (!solve(changed, row.left, row.right)) return finished();
      row.asymmetry = asymmetry_of(row.left, row.right);
      row.asymmetry_per_unit_change = row.asymmetry / options.change;
      result.rows.push_back(row);
    }
  // A swing of zero to both sides (an output the drive does not move) has no asymmetry.
  bool finite = std::isfinite(result.nominal_asymmetry);
  for (const MismatchRow& row : result.rows) finite = finite && std::isfinite(row.asymmetry);
  if (!finite) {
    result.status = Status::failure("mismatch: the asymmetry of " + result.output +
                                    " is not finite (its swing is zero to both sides)");
    return finished();
  }
  std::vector<DeflectionPeak> peaks{
      {result.output, std::max(std::abs(result.nominal_left), std::abs(result.nominal_right))}};
  for (const MismatchRow& row : result.rows)
    peaks.push_back({result.output + " (" + row.label + " " +
                         format_number("%+.3g", 100.0 * row.change) + " %)",
                     std::max(std::abs(row.left), std::abs(row.right))});
  result.validity = check_validity(scene, peaks, drive_peak_voltages(scene), rotation);
  return finished();
}

}  // namespace emnet
