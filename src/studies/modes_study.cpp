// The modes study (emnet/studies/modes_study.hpp): model, operating point, modes, the N/2N
// discretisation error estimate, mode shapes and the names of the rigid-body motions.
#include "emnet/studies/modes_study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "emnet/analysis/operating_point.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/studies/segment_selection.hpp"

namespace emnet {

namespace {

void show_phase(Progress* progress, const char* what) {
  if (progress) progress->report(0, 0, what);
}

std::string millimetres_text(double metres) {
  char text[48];
  std::snprintf(text, sizeof text, "%.6g mm", metres * 1e3);
  return text;
}

// The frequencies of the modes of `scene` refined to 2N segments (empty when its modal
// analysis fails: the estimate is then left out, not the study); a failed operating point of
// the refined model fails the study.
Status refined_frequencies(const Scene& scene, const ModesStudyOptions& options, int count,
                           std::vector<double>& frequencies) {
  Scene doubled = scene;
  doubled.beam.segments = 2 * scene.beam.segments;
  doubled.beam.auto_segments = false;
  for (SectionSpec& section : doubled.beam.sections) section.segments *= 2;
  show_phase(options.progress, "building the network");
  const Model fine_model = prepare_model(doubled, options.prepare);
  const System fine_system = fine_model.network.assemble();
  OperatingPointOptions point_options;
  point_options.static_options.progress = options.progress;
  const OperatingPoint point = operating_point(fine_system, point_options);
  if (!point.status.ok) return point.status;
  ModalOptions modal_options;
  modal_options.count = count;
  modal_options.keep_vectors = false;
  const ModalResult fine = run_modes(fine_system, point.rest.operating_point, modal_options);
  if (fine.status.ok)
    for (const auto& mode : fine.modes) frequencies.push_back(mode.frequency_hz);
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

std::complex<double> mode_probe_value(const Model& model, const Mode& mode, const Probe& probe) {
  if (!is_linear(probe))
    throw std::invalid_argument("mode_probe_value: probe '" + probe.name +
                                "' has squares; pass linearised_probe(probe, operating point)");
  const std::complex<double> divisor = mode_shape(model, mode).divisor;
  std::complex<double> value = 0.0;
  for (const auto& [index, c] : probe.terms) value += c * mode.vector[index];
  for (int k = 0; k < probe.integrations; ++k) value /= mode.pole;
  return value / divisor;
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

ModesStudyResult run_modes_study(const Scene& scene, const ModesStudyOptions& options) {
  const Stopwatch total;
  ModesStudyResult result;
  {
    const Stopwatch stopwatch;
    show_phase(options.progress, "building the network");
    result.model = prepare_model(scene, options.prepare);
    result.system = result.model.network.assemble();
    result.seconds_model = stopwatch.seconds();
  }
  {
    OperatingPointOptions point_options;
    point_options.static_options.progress = options.progress;
    OperatingPoint point = operating_point(result.system, point_options);
    result.seconds_operating_point = point.seconds;
    if (!point.status.ok) {
      result.status = point.status;
      result.seconds = total.seconds();
      return result;
    }
    if (point.about_zero) {
      result.model.notes.push_back(point.note);
      result.notes.push_back(point.note);
    }
    result.rest = std::move(point.rest);
  }
  ModalOptions modal_options;
  modal_options.count = options.count;
  modal_options.keep_vectors = true;
  modal_options.progress = options.progress;
  if (options.dense) {
    if (result.system.size() > kDenseModesLimit)
      throw InputError("--dense", "--dense",
                       "the network has " + std::to_string(result.system.size()) +
                           " unknowns; a dense eigen-decomposition is limited to " +
                           std::to_string(kDenseModesLimit) + " (inclusive; it grows as n^3)");
    modal_options.dense_limit = 2 * kDenseModesLimit;  // the pencil has the mass velocities too
  }
  result.modal = run_modes(result.system, result.rest.operating_point, modal_options);
  result.seconds_modal = result.modal.seconds;
  if (!result.modal.status.ok) {
    result.status = Status::failure("modes: " + result.modal.status.message);
    result.seconds = total.seconds();
    return result;
  }
  if (cancel_requested(options.progress)) {
    result.status = cancelled_status();
    result.seconds = total.seconds();
    return result;
  }
  std::vector<Mode> modes = result.modal.modes;
  if (options.count > 0 && static_cast<int>(modes.size()) > options.count)
    modes.resize(static_cast<size_t>(options.count));
  for (size_t k = 0; k < modes.size(); ++k) {
    const std::string which = " of mode " + std::to_string(k + 1);
    if (!std::isfinite(modes[k].frequency_hz))
      result.status = Status::failure("non-finite result for a modal frequency" + which);
    else if (!std::isfinite(modes[k].damping_ratio))
      result.status = Status::failure("non-finite result for a damping ratio" + which);
    else if (!std::isfinite(modes[k].natural_frequency_hz))
      result.status = Status::failure("non-finite result for a natural frequency" + which);
    if (!result.status.ok) {
      result.seconds = total.seconds();
      return result;
    }
    if (!modes[k].error_bounded) {
      char frequency[32];
      std::snprintf(frequency, sizeof frequency, "%.6g", modes[k].frequency_hz);
      result.unbounded.push_back("mode " + std::to_string(k + 1) + " (" + frequency +
                                 " Hz): " + modes[k].unbounded_reason);
    }
  }
  result.error_estimate_computed =
      options.error_estimate && scene.beam.segments <= kModesErrorEstimateSegmentLimit;
  std::vector<double> errors;
  if (result.error_estimate_computed) {
    const Stopwatch stopwatch;
    std::vector<double> refined;
    // From the scene as given (not as resolved for N): its "auto" keys are resolved for 2N.
    const Status status = refined_frequencies(
        scene, options, std::max<int>(static_cast<int>(modes.size()) + 2, 6), refined);
    if (!status.ok) {
      result.status = status;
      result.seconds = total.seconds();
      return result;
    }
    if (!refined.empty()) {
      std::vector<double> coarse;
      for (const auto& mode : modes) coarse.push_back(mode.frequency_hz);
      errors = richardson_errors(coarse, refined);
    }
    result.seconds_error_estimate = stopwatch.seconds();
  } else {
    result.notes.push_back(options.error_estimate
                               ? "discretisation error not estimated (N > " +
                                     std::to_string(kModesErrorEstimateSegmentLimit) + ")"
                               : "discretisation error not estimated (not asked)");
  }
  for (size_t k = 0; k < modes.size(); ++k) {
    ModesStudyMode entry;
    entry.mode = modes[k];
    if (k < errors.size()) {
      if (!std::isfinite(errors[k])) {
        result.status =
            Status::failure("non-finite result for a discretisation error estimate of mode " +
                            std::to_string(k + 1));
        result.seconds = total.seconds();
        return result;
      }
      entry.discretisation_error = errors[k];
      entry.discretisation_error_estimated = true;
    }
    if (options.shapes) entry.shape = mode_shape(result.model, modes[k]);
    result.modes.push_back(std::move(entry));
  }
  for (const auto& motion : result.modal.rigid_body_modes)
    result.rigid_body_motions.push_back(rigid_body_motion_name(result.model, motion));
  if (result.rigid_body_motions.size() > 1)
    result.rigid_body_motions = {"translation and rotation (a free body)"};
  result.seconds = total.seconds();
  return result;
}

}  // namespace emnet
