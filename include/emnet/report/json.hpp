// JSON of results, as the program's --json prints them: nlohmann::ordered_json (keys in the
// order written), so that a front-end can put them into its own object and print them with
// json_text. Numbers are written as they are; every Result given here has a finite value in
// each field written (a non-finite one fails the analysis or study that produced it).
//
// The header exposes nlohmann's type, so the library links nlohmann_json publicly (it is
// header-only, and the installed package already finds it: cmake/emnetConfig.cmake.in).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/model/deformed_shape.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/network/output.hpp"
#include "emnet/scene/scene.hpp"
#include "emnet/studies/modes_study.hpp"
#include "emnet/studies/sensitivity.hpp"

namespace emnet {

/// A JSON value of the reports, keys in the order written.
using Json = nlohmann::ordered_json;

/// `json` as text, indented by 2; strings with invalid UTF-8 (a name given in an override) are
/// written with U+FFFD instead of failing.
std::string json_text(const Json& json);

/// "validity": status ("within" or "OUTSIDE"), summary, the two fractions of their limits, the
/// small beam's geometric_error_estimate (emnet/model/validity.hpp; 0 with large kinematics), and
/// each violation (check, subject, key, value, limit, message).
Json to_json(const Validity& validity);

/// "shape": the beam's deformed shape (emnet/model/deformed_shape.hpp): frequency_hz and
/// period_s (0 for a transient), times_s, reference_x_m (the nodes along the undeformed beam),
/// x_m and y_m ([instant][node], the fixed frame's).
Json to_json(const DeformedShape& shape);

/// "automatic_choices": what each "auto" key became (key, value, reason, estimated_error,
/// tolerance, band_hz [from, to], seconds).
Json to_json(const std::vector<AutomaticChoice>& automatic_choices);

/// The mesh built: "segments" (the model's segment count, which the attachments can raise above
/// beam.segments) and, when they did, "segments_asked" (beam.segments). Into `out`.
void add_mesh_json(Json& out, const Model& model);

/// A reduced model: status ("met" / "NOT MET" from `tolerance_met`), tolerance, band_hz,
/// cutoff_hz, kept_modes, kept_real_poles, truncated_poles, full_unknowns, modal_method.
Json to_json(const ModalReduction& reduction, bool tolerance_met);

/// The modes study: scene, automatic_choices, segments, modes (frequency_hz, damping_ratio,
/// natural_frequency_hz, pole [re, im], relative_residual, error_bounded, the error bounds or
/// unbounded_reason, discretisation_error_estimate when estimated, shape [{x_m, deflection,
/// deflection_imag}] when computed, the value at each of `probes` per unit largest
/// deflection), real_poles, rigid_body_modes, method, complete, pencil_size, cost (modal,
/// error bound, error estimate and `total_seconds`), and status "NOT BOUNDED" when a mode's
/// rounding error is not bounded.
/// @param total_seconds  the whole command, from its start [s]
Json to_json(const ModesStudyResult& result, const std::vector<Probe>& probes,
             double total_seconds);

/// The sensitivity study of `scene`: scene, automatic_choices, segments, the modes (frequency,
/// natural frequency, pole), per parameter (key, value, unit) each mode's pole, frequency and
/// natural-frequency derivatives and normalised sensitivities (with `with_check` the finite-
/// difference reference, its difference and error estimate), left_vector_residual, cost.
/// @param total_seconds  the whole command, from its start [s]
Json to_json(const SensitivityResult& result, const Scene& scene, bool with_check,
             double total_seconds);

/// The static state of `model`: scene, automatic_choices, segments, nodes [{x_m, deflection_m,
/// rotation_rad[, axial_displacement_m]}] from `nodes` (static_node_columns), probes [{name,
/// description, unit, value}] with `probe_values` (one per probe), accuracy (relative_residual,
/// newton_iterations, discretisation), cost (solve and `total_seconds`), validity.
/// @param total_seconds  the whole command, from its start [s]
Json to_json(const Model& model, const StaticResult& rest,
             const std::vector<std::vector<double>>& nodes, const std::vector<Probe>& probes,
             const std::vector<double>& probe_values, const Validity& validity,
             double total_seconds);

}  // namespace emnet
