// The modes study: the poles of a scene's network about its operating point, with what the
// program's `modes` command reports beside them.
//
//   - The model (prepare_model) and its operating point (analysis/operating_point.hpp: the
//     static state, else zero for a linear network, with a note).
//   - The modes (run_modes), at most `count` oscillatory ones, each failing the study when its
//     frequency or damping ratio is not finite.
//   - Per mode the discretisation error against the continuum beam, estimated from N and 2N
//     segments, the mode of 2N being the one of most alike shape (match_refined_modes, modal
//     assurance at least kModeShapeMatchLimit; a mode without a match has no estimate, a note):
//     lumped-mass convergence is O(N⁻²), so f∞ ≈ f2N + (f2N − fN)/3 and the error of fN is
//     estimated as |fN − f∞| / f∞ (richardson_errors, studies/segment_selection.hpp). Not estimated
//     above kModesErrorEstimateSegmentLimit segments or when not asked.
//   - The mode shapes along the beam: deflection w(x) and rotation φ(x) = dw/dx [1/m] at the
//     beam nodes, from the velocity eigenvector over the pole (w = v/s), scaled so that the
//     largest nodal deflection is 1 (both by the same complex divisor).
//   - The rigid-body motions (pole s = 0) in words: "translation", "rotation about x = … mm",
//     or, for more than one, "translation and rotation (a free body)".
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene.hpp"
#include "emnet/studies/resolve.hpp"

namespace emnet {

// Unknowns up to which `dense` runs: a dense eigen-decomposition is O(n³) (measured on the fish
// fin: 606 unknowns 0.75 s, 1206 unknowns 6.5 s; 2000 about half a minute).
constexpr int kDenseModesLimit = 2000;
// Segments up to which the N/2N error estimate is computed (the 2N model is built and solved).
constexpr int kModesErrorEstimateSegmentLimit = 1000;
// Modal assurance criterion (|aᴴb|²/(‖a‖²‖b‖²) of the shapes at the N mesh's beam nodes) from
// which a mode of 2N is the same mode as one of N. The limit is a choice: a refined mode keeps
// its shape and distinct modes differ in theirs; the correlations the shipped scenes reach are
// not yet measured.
constexpr double kModeShapeMatchLimit = 0.9;

struct ModesStudyOptions {
  int count = 0;               // oscillatory modes kept (0: the analysis's default request)
  bool dense = false;          // every pole by the dense method, up to kDenseModesLimit unknowns
  bool error_estimate = true;  // the N/2N discretisation error estimate
  bool shapes = false;         // the mode shapes along the beam
  // how the scene's remaining "auto" keys are resolved; the study prepares large kinematics
  // for dynamics itself (LargeKinematicsUse::dynamics, whatever large_kinematics says here)
  PrepareOptions prepare;
  Progress* progress = nullptr;  // the phases, the static solve and the modal analysis

  /// The checks of the options alone, as run_modes_study makes them first.
  /// @throws OptionError naming "count" when it is negative
  void validate() const;
};

// A mode's shape at the beam nodes, largest nodal |deflection| = 1.
struct ModeShape {
  std::vector<double> x_m;                       // node positions [m]
  std::vector<std::complex<double>> deflection;  // w / divisor (unit-free)
  std::vector<std::complex<double>> rotation;    // φ / divisor [1/m]
  std::complex<double> divisor = 1.0;            // the largest nodal deflection of the vector
};

struct ModesStudyMode {
  Mode mode;
  // Relative discretisation error of the frequency, from N and 2N segments; valid when
  // discretisation_error_estimated.
  double discretisation_error = 0.0;
  bool discretisation_error_estimated = false;
  double shape_correlation = 0.0;  // modal assurance with its 2N match, when estimated
  ModeShape shape;                 // filled when ModesStudyOptions::shapes
};

struct ModesStudyResult {
  // Failure: the operating point's message, "modes: <why>" from the analysis, or
  // "non-finite result for <quantity> of mode <k>".
  Status status;
  Model model;                        // as built (notes include the operating point's, if any)
  System system;                      // assembled from it
  StaticResult rest;                  // the operating point
  ModalResult modal;                  // as the analysis returned it (every pole it found)
  std::vector<ModesStudyMode> modes;  // at most `count`, with estimates and shapes
  // Each mode whose rounding error cannot be bounded: "mode k (f Hz): reason".
  std::vector<std::string> unbounded;
  std::vector<std::string> rigid_body_motions;  // names, see above
  // Whether the N/2N estimate was computed (not when not asked, nor above
  // kModesErrorEstimateSegmentLimit segments: then a note says which).
  bool error_estimate_computed = false;
  double seconds_model = 0.0, seconds_operating_point = 0.0, seconds_modal = 0.0,
         seconds_error_estimate = 0.0, seconds = 0.0;
  std::vector<std::string> notes;
};

// Throws OptionError (ModesStudyOptions::validate; the field "dense" when `dense` is asked for a
// network of more than kDenseModesLimit unknowns); every numerical failure is in the Status.
ModesStudyResult run_modes_study(const Scene& scene, const ModesStudyOptions& options = {});

// A mode's shape along the beam (see above).
ModeShape mode_shape(const Model& model, const Mode& mode);

// Each probe's value in a mode, relative to the mode's largest nodal deflection: the
// quantity's phasor Σ c·y / s^integrations (a deflection is the velocity over s) over the
// divisor. The mode's shape (its divisor) is found once for all the probes.
std::vector<std::complex<double>> mode_probe_values(const Model& model, const Mode& mode,
                                                    const std::vector<Probe>& probes);

// A rigid-body motion in words: its deflection w(x) = a + b·x along the beam is a translation
// (|b|·L ≤ 1e-9·max|w| at the ends), or a rotation about the point where w = 0.
std::string rigid_body_motion_name(const Model& model, const Eigen::VectorXd& motion);

}  // namespace emnet
