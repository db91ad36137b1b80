// Names of the scene enumerations (as written in scene files) and small Scene helpers.
#include "emnet/scene/scene.hpp"

namespace emnet {

const char* end_condition_name(EndCondition end) {
  switch (end) {
    case EndCondition::clamped:
      return "clamped";
    case EndCondition::free:
      return "free";
    case EndCondition::pinned:
      return "pinned";
    case EndCondition::sliding:
      return "sliding";
  }
  return "?";
}

const char* fluid_name(Fluid fluid) {
  switch (fluid) {
    case Fluid::none:
      return "none";
    case Fluid::air:
      return "air";
    case Fluid::water:
      return "water";
  }
  return "?";
}

const char* drive_kind_name(DriveKind kind) {
  switch (kind) {
    case DriveKind::none:
      return "none";
    case DriveKind::antagonistic:
      return "antagonistic";
    case DriveKind::bias_differential:
      return "bias_differential";
    case DriveKind::single:
      return "single";
    case DriveKind::switched:
      return "switched";
  }
  return "?";
}

double DampingSpec::effective_kelvin_voigt_time() const {
  if (!loss_factor.has_value()) return kelvin_voigt_time;
  constexpr double two_pi = 6.283185307179586476925286766559;
  const double frequency = loss_factor_frequency.value_or(0.0);
  if (!(frequency > 0.0)) return kelvin_voigt_time;  // the reader never lets this happen
  return *loss_factor / (two_pi * frequency);
}

}  // namespace emnet
