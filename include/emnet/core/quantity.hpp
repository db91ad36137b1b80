// The physical quantities an output can measure, with their SI units. Shared by the scene
// (what a probe asks for) and the network's outputs (what a linear functional of the unknowns
// stands for), so it sits below both.
#pragma once

#include <vector>

namespace emnet {

/// The physical quantity an output measures.
enum class ProbeQuantity {
  deflection,        ///< w [m]: the time integral of a velocity
  velocity,          ///< v [m/s]
  rotation,          ///< φ [rad]: the time integral of an angular velocity
  angular_velocity,  ///< Ω [rad/s]
  dea_voltage,       ///< u [V] across a DEA's capacitance
  dea_current,       ///< i [A] into a DEA
  reaction_force,    ///< R [N]: the force a support exerts on the beam, positive along +w
  reaction_moment,   ///< M_R [N·m]: the moment a support exerts on the beam, positive as +ψ
  spring_force,  ///< k·Δ + c·Δ' [N or N·m] a [[spring]] carries (positive stretched, see model)
  strain,        ///< ε [-] at a face: ∓z·dψ/dx (top face compressed bending toward +w)
  dea_force,     ///< k_F·u² [N] a DEA pushes its face with
  /// u [m]: the fixed-frame x displacement (along the undeformed beam; large kinematics only)
  axial_displacement,
  /// R_x [N]: the force a support exerts on the beam along +x (large kinematics only)
  axial_reaction_force
};
/// Whether `quantity` is the motion of a point of the beam: a displacement (deflection,
/// axial_displacement), a rotation, or one of their rates.
bool is_beam_motion(ProbeQuantity quantity);
/// Every quantity, in the order scene files and messages list them.
const std::vector<ProbeQuantity>& probe_quantities();
/// "deflection", …
const char* probe_quantity_name(ProbeQuantity quantity);
/// "m", "m/s", "rad", …; "" for the dimensionless strain. spring_force: "N" (a rotational
/// spring's probe says "N*m" in its own unit).
const char* probe_unit(ProbeQuantity quantity);

}  // namespace emnet
