// The static study: what `emnet static` reports of a model's static state (solve_static, through
// the operating point with require_static): the deflection w [m] and rotation φ [rad] at every
// beam node, each probe's static value (static_probe_value) and the validity of the deflections
// (the nodes' largest and each deflection probe's) with the drive's voltages at t = 0.
// Nodal values are exact for any N (Hermite statics); between nodes the segment's shape
// functions. With large kinematics the deflection check does not apply (the model has no small-
// deflection assumption) and the nodal values carry an error of order N⁻².
#pragma once

#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/validity.hpp"

namespace emnet {

/// What the static study reports of a static state.
struct StaticStudyValues {
  /// per beam node: {x [m], w [m], φ [rad]}, and with large kinematics the x displacement u [m]
  std::vector<std::vector<double>> nodes;
  std::vector<double> probe_values;  ///< one per probe, in the probe's unit
  Validity validity;  ///< the deflections and the drive's voltages at t = 0 against their limits
};

/// The names of the columns of StaticStudyValues::nodes for `model`, as the JSON and CSV of
/// `emnet static` write them: x_m, deflection_m, rotation_rad, and with large kinematics
/// axial_displacement_m.
std::vector<std::string> static_node_columns(const Model& model);

/// What the nodal values' discretisation error is, in words: none for small kinematics
/// (Hermite statics), of order N⁻² in the deflected shape for large (docs/model.md, Large
/// deflection).
std::string static_discretisation(const Model& model);

/// The study's values from a solved static state `rest` of `system` (model.network.assemble()).
StaticStudyValues static_study_values(const Model& model, const System& system,
                                      const StaticResult& rest, const std::vector<Probe>& probes);

}  // namespace emnet
