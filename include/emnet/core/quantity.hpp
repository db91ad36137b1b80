// The physical quantities an output can measure, with their SI units. Shared by the scene
// (what a probe asks for) and the network's outputs (what a linear functional of the unknowns
// stands for), so it sits below both.
#pragma once

namespace emnet {

enum class ProbeQuantity {
  deflection,        // w [m]: the time integral of a velocity
  velocity,          // v [m/s]
  rotation,          // φ [rad]: the time integral of an angular velocity
  angular_velocity,  // Ω [rad/s]
  dea_voltage,       // u [V] across a DEA's capacitance
  dea_current        // i [A] into a DEA
};
const char* probe_quantity_name(ProbeQuantity quantity);  // "deflection", …
const char* probe_unit(ProbeQuantity quantity);           // "m", "m/s", "rad", …

}  // namespace emnet
