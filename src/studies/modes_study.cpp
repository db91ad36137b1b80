// The modes study (emnet/studies/modes_study.hpp): model, operating point, modes, the N/2N
// discretisation error estimate, mode shapes and the names of the rigid-body motions.
#include "emnet/studies/modes_study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "emnet/analysis/operating_point.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"
#include "emnet/studies/segment_selection.hpp"

namespace emnet {

namespace {

// A mode of the 2N mesh: its frequency and its shape at the N mesh's beam nodes.
struct RefinedMode {
  double frequency_hz = 0.0;
  Eigen::VectorXcd shape;
};

std::string millimetres_text(double metres) {
  char text[48];
  std::snprintf(text, sizeof text, "%.6g mm", metres * 1e3);
  return text;
}

// A mode's deflection and rotation·L (L the beam's length, so both are lengths) at the
// positions `x` along the beam of `model`: the vector the modal assurance criterion compares.
Eigen::VectorXcd shape_at(const Model& model, const Mode& mode, const std::vector<double>& x) {
  Eigen::VectorXcd shape(2 * static_cast<Eigen::Index>(x.size()));
  for (size_t i = 0; i < x.size(); ++i) {
    std::complex<double> w = 0.0, slope = 0.0;
    for (const auto& [index, c] : model.beam.deflection_terms(x[i])) w += c * mode.vector[index];
    for (const auto& [index, c] : model.beam.slope_terms(x[i])) slope += c * mode.vector[index];
    shape[static_cast<Eigen::Index>(2 * i)] = w / mode.pole;
    shape[static_cast<Eigen::Index>(2 * i + 1)] = slope / mode.pole * model.beam.length;
  }
  return shape;
}

// Modal assurance criterion |aᴴb|² / (‖a‖²‖b‖²): 1 for the same shape, 0 for orthogonal ones
// (0 when either is zero).
double modal_assurance(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
  const double norms = a.squaredNorm() * b.squaredNorm();
  return norms > 0.0 ? std::norm(a.dot(b)) / norms : 0.0;
}

// The modes of `scene` with every segment halved (2N segments), each as its frequency and its shape
// at the coarse beam nodes `x` (empty when its modal analysis fails: the estimate is then left out,
// not the study); a failed operating point of the refined model fails the study.
// The prepare options of the study's models: the modal analysis serves large kinematics
// linearised about the deflected state (LargeKinematicsUse::dynamics).
PrepareOptions modes_prepare_options(const ModesStudyOptions& options) {
  PrepareOptions prepare = options.prepare;
  prepare.large_kinematics = LargeKinematicsUse::dynamics;
  return prepare;
}

Status refined_modes(const Scene& scene, const ModesStudyOptions& options, int count,
                     const std::vector<double>& x, std::vector<RefinedMode>& refined) {
  Scene doubled = scene;
  doubled.beam.refinement = 2;  // every segment of N halved: the nested 2N mesh
  report_phase(options.progress, "building the network");
  const Model fine_model = prepare_model(doubled, modes_prepare_options(options));
  const System fine_system = fine_model.network.assemble();
  OperatingPointOptions point_options;
  point_options.static_options.progress = options.progress;
  const OperatingPoint point = operating_point(fine_system, point_options);
  if (!point.status.ok()) return point.status;
  ModalOptions modal_options;
  modal_options.count = count;
  modal_options.keep_vectors = true;
  const ModalResult fine = run_modes(fine_system, point.rest.operating_point, modal_options);
  if (fine.status.ok())
    for (const auto& mode : fine.modes)
      refined.push_back({mode.frequency_hz, shape_at(fine_model, mode, x)});
  return Status::success();
}

}  // namespace

ModeShape mode_shape(const Model& model, const Mode& mode) {
  ModeShape shape;
  shape.x_m = model.beam.x;
  for (double x : model.beam.x) {
    std::complex<double> w = 0.0, slope = 0.0;
    for (const auto& [index, c] : model.beam.deflection_terms(x)) w += c * mode.vector[index];
    for (const auto& [index, c] : model.beam.slope_terms(x)) slope += c * mode.vector[index];
    shape.deflection.push_back(w / mode.pole);  // w = v/s
    shape.rotation.push_back(slope / mode.pole);
  }
  std::complex<double> largest = 0.0;
  for (auto v : shape.deflection)
    if (std::abs(v) > std::abs(largest)) largest = v;
  if (std::abs(largest) > 0.0) {
    for (auto& v : shape.deflection) v /= largest;
    for (auto& v : shape.rotation) v /= largest;
    shape.divisor = largest;
  }
  return shape;
}

std::vector<std::complex<double>> mode_probe_values(const Model& model, const Mode& mode,
                                                    const std::vector<Probe>& probes) {
  for (const Probe& probe : probes)
    if (!is_linear(probe))
      throw std::invalid_argument("mode_probe_values: probe '" + probe.name +
                                  "' has squares; pass linearised_probe(probe, operating point)");
  std::vector<std::complex<double>> values;
  if (probes.empty()) return values;
  const std::complex<double> divisor = mode_shape(model, mode).divisor;
  for (const Probe& probe : probes) {
    std::complex<double> value = 0.0;
    for (const auto& [index, c] : probe.terms) value += c * mode.vector[index];
    for (int k = 0; k < probe.integrations; ++k) value /= mode.pole;
    values.push_back(value / divisor);
  }
  return values;
}

std::string rigid_body_motion_name(const Model& model, const Eigen::VectorXd& motion) {
  auto deflection = [&](double x) {
    double w = 0.0;
    for (const auto& [index, c] : model.beam.deflection_terms(x)) w += c * motion[index];
    return w;
  };
  const double length = model.beam.length;
  const double w0 = deflection(0.0), w1 = deflection(length);
  const double slope = (w1 - w0) / length;
  if (std::abs(slope) * length <= 1e-9 * std::max(std::abs(w0), std::abs(w1))) return "translation";
  double pivot = -w0 / slope;
  if (std::abs(pivot) <= 1e-9 * length) pivot = 0.0;  // no "-0"
  return "rotation about x = " + millimetres_text(pivot);
}

namespace {

// Pairs each mode of N with the unused mode of 2N whose shape at the N mesh's beam nodes is
// most alike (modal assurance criterion), not by index: an index match pairs different modes
// when the two meshes find different sets (a pole pair that crosses the mode rule, a mode the
// iterative solver did not reach). A best correlation below kModeShapeMatchLimit is no match:
// its correlation is NaN and a note names the mode.
void match_refined_modes(ModesStudyResult& result, const std::vector<Mode>& modes,
                         const std::vector<RefinedMode>& refined, std::vector<double>& errors,
                         std::vector<double>& correlations) {
  std::vector<bool> used(refined.size(), false);
  for (size_t k = 0; k < modes.size(); ++k) {
    const Eigen::VectorXcd coarse = shape_at(result.model, modes[k], result.model.beam.x);
    double best = 0.0;
    size_t best_index = refined.size();
    for (size_t j = 0; j < refined.size(); ++j) {
      const double mac = used[j] ? 0.0 : modal_assurance(coarse, refined[j].shape);
      if (mac > best) {
        best = mac;
        best_index = j;
      }
    }
    if (best >= kModeShapeMatchLimit) {
      used[best_index] = true;
      errors.push_back(richardson_error(modes[k].frequency_hz, refined[best_index].frequency_hz));
      correlations.push_back(best);
    } else {
      result.notes.push_back(
          "mode " + std::to_string(k + 1) + " (" + format_number("%.6g Hz", modes[k].frequency_hz) +
          "): no mode of the 2N mesh has its shape (best modal assurance " +
          format_number("%.3g", best) + ", below " + format_number("%.2g", kModeShapeMatchLimit) +
          "); its discretisation error is not estimated");
      errors.push_back(std::numeric_limits<double>::quiet_NaN());
      correlations.push_back(std::numeric_limits<double>::quiet_NaN());
    }
  }
}

}  // namespace

void ModesStudyOptions::validate() const {
  if (count < 0) throw OptionError("count", "must be >= 0 (0: the default request)");
}

namespace {

void build_the_network(const Scene& scene, const ModesStudyOptions& options,
                       ModesStudyResult& result) {
  const Stopwatch stopwatch;
  report_phase(options.progress, "building the network");
  result.model = prepare_model(scene, modes_prepare_options(options));
  result.system = result.model.network.assemble();
  result.seconds_model = stopwatch.seconds();
}

Status find_the_operating_point(const ModesStudyOptions& options, ModesStudyResult& result) {
  OperatingPointOptions point_options;
  point_options.static_options.progress = options.progress;
  OperatingPoint point = operating_point(result.system, point_options);
  result.seconds_operating_point = point.seconds;
  if (!point.status.ok()) return point.status;
  if (point.about_zero) {
    result.model.notes.push_back(point.note);
    result.notes.push_back(point.note);
  }
  result.rest = std::move(point.rest);
  return Status::success();
}

Status run_the_modal_analysis(const ModesStudyOptions& options, ModesStudyResult& result) {
  ModalOptions modal_options;
  modal_options.count = options.count;
  modal_options.keep_vectors = true;
  modal_options.progress = options.progress;
  if (options.dense) {
    if (result.system.size() > kDenseModesLimit)
      throw OptionError("dense", "the network has " + std::to_string(result.system.size()) +
                                     " unknowns; a dense eigen-decomposition is limited to " +
                                     std::to_string(kDenseModesLimit) +
                                     " (inclusive; it grows as n^3)");
    modal_options.dense_limit = 2 * kDenseModesLimit;  // the pencil has the mass velocities too
  }
  result.modal = run_modes(result.system, result.rest.operating_point, modal_options);
  result.seconds_modal = result.modal.seconds;
  if (!result.modal.status.ok()) return result.modal.status.with_context("modes: ");
  if (cancel_requested(options.progress)) return cancelled_status();
  return Status::success();
}

// The modes asked for, each checked finite; those whose error is not bounded are listed.
Status check_the_modes_asked_for(const ModesStudyOptions& options, ModesStudyResult& result,
                                 std::vector<Mode>& modes) {
  modes = result.modal.modes;
  if (options.count > 0 && static_cast<int>(modes.size()) > options.count)
    modes.resize(static_cast<size_t>(options.count));
  for (size_t k = 0; k < modes.size(); ++k) {
    const std::string which = " of mode " + std::to_string(k + 1);
    if (!std::isfinite(modes[k].frequency_hz))
      return Status::failure("non-finite result for a modal frequency" + which);
    if (!std::isfinite(modes[k].damping_ratio))
      return Status::failure("non-finite result for a damping ratio" + which);
    if (!std::isfinite(modes[k].natural_frequency_hz))
      return Status::failure("non-finite result for a natural frequency" + which);
    if (!modes[k].error_bounded) {
      char frequency[32];
      std::snprintf(frequency, sizeof frequency, "%.6g", modes[k].frequency_hz);
      result.unbounded.push_back("mode " + std::to_string(k + 1) + " (" + frequency +
                                 " Hz): " + modes[k].unbounded_reason);
    }
  }
  return Status::success();
}

// The N/2N estimate, per mode in `errors` and `correlations` (NaN error: no match at 2N), or a
// note saying why it is not made.
Status estimate_the_discretisation_errors(const Scene& scene, const ModesStudyOptions& options,
                                          const std::vector<Mode>& modes, ModesStudyResult& result,
                                          std::vector<double>& errors,
                                          std::vector<double>& correlations) {
  result.error_estimate_computed =
      options.error_estimate && scene.beam.segments <= kModesErrorEstimateSegmentLimit;
  if (!result.error_estimate_computed) {
    result.notes.push_back(options.error_estimate
                               ? "discretisation error not estimated (N > " +
                                     std::to_string(kModesErrorEstimateSegmentLimit) + ")"
                               : "discretisation error not estimated (not asked)");
    return Status::success();
  }
  const Stopwatch stopwatch;
  std::vector<RefinedMode> refined;
  // From the scene as given (not as resolved for N): its "auto" keys are resolved for 2N.
  const Status status =
      refined_modes(scene, options, std::max<int>(static_cast<int>(modes.size()) + 2, 6),
                    result.model.beam.x, refined);
  if (!status.ok()) return status;
  if (!refined.empty()) match_refined_modes(result, modes, refined, errors, correlations);
  result.seconds_error_estimate = stopwatch.seconds();
  return Status::success();
}

Status collect_the_modes(const ModesStudyOptions& options, const std::vector<Mode>& modes,
                         const std::vector<double>& errors, const std::vector<double>& correlations,
                         ModesStudyResult& result) {
  for (size_t k = 0; k < modes.size(); ++k) {
    ModesStudyMode entry;
    entry.mode = modes[k];
    if (k < errors.size() && !std::isnan(correlations[k])) {
      entry.shape_correlation = correlations[k];
      if (!std::isfinite(errors[k]))
        return Status::failure("non-finite result for a discretisation error estimate of mode " +
                               std::to_string(k + 1));
      entry.discretisation_error = errors[k];
      entry.discretisation_error_estimated = true;
    }
    if (options.shapes) entry.shape = mode_shape(result.model, modes[k]);
    result.modes.push_back(std::move(entry));
  }
  return Status::success();
}

void name_the_rigid_body_motions(ModesStudyResult& result) {
  for (const auto& motion : result.modal.rigid_body_modes)
    result.rigid_body_motions.push_back(rigid_body_motion_name(result.model, motion));
  if (result.rigid_body_motions.size() > 1)
    result.rigid_body_motions = {"translation and rotation (a free body)"};
}

}  // namespace

ModesStudyResult run_modes_study(const Scene& scene, const ModesStudyOptions& options) {
  const Stopwatch total;
  options.validate();
  ModesStudyResult result;
  auto stopped_by = [&](Status status) {
    result.status = std::move(status);
    result.seconds = total.seconds();
    return result;
  };
  build_the_network(scene, options, result);
  if (Status found = find_the_operating_point(options, result); !found.ok())
    return stopped_by(found);
  if (Status solved = run_the_modal_analysis(options, result); !solved.ok())
    return stopped_by(solved);
  std::vector<Mode> modes;
  if (Status finite = check_the_modes_asked_for(options, result, modes); !finite.ok())
    return stopped_by(finite);
  std::vector<double> errors, correlations;  // per mode; NaN error: no match at 2N
  if (Status estimated =
          estimate_the_discretisation_errors(scene, options, modes, result, errors, correlations);
      !estimated.ok())
    return stopped_by(estimated);
  if (Status collected = collect_the_modes(options, modes, errors, correlations, result);
      !collected.ok())
    return stopped_by(collected);
  name_the_rigid_body_motions(result);
  result.seconds = total.seconds();
  return result;
}

}  // namespace emnet
