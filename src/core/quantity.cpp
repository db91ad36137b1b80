// Names and units of the output quantities; see include/emnet/core/quantity.hpp.
#include "emnet/core/quantity.hpp"

namespace emnet {

const std::vector<ProbeQuantity>& probe_quantities() {
  static const std::vector<ProbeQuantity> all = {ProbeQuantity::deflection,
                                                 ProbeQuantity::velocity,
                                                 ProbeQuantity::rotation,
                                                 ProbeQuantity::angular_velocity,
                                                 ProbeQuantity::dea_voltage,
                                                 ProbeQuantity::dea_current,
                                                 ProbeQuantity::reaction_force,
                                                 ProbeQuantity::reaction_moment,
                                                 ProbeQuantity::spring_force,
                                                 ProbeQuantity::strain,
                                                 ProbeQuantity::dea_force,
                                                 ProbeQuantity::axial_displacement,
                                                 ProbeQuantity::axial_reaction_force};
  return all;
}

bool is_beam_motion(ProbeQuantity quantity) {
  return quantity == ProbeQuantity::deflection || quantity == ProbeQuantity::velocity ||
         quantity == ProbeQuantity::rotation || quantity == ProbeQuantity::angular_velocity ||
         quantity == ProbeQuantity::axial_displacement;
}

const char* probe_quantity_name(ProbeQuantity quantity) {
  switch (quantity) {
    case ProbeQuantity::deflection:
      return "deflection";
    case ProbeQuantity::velocity:
      return "velocity";
    case ProbeQuantity::rotation:
      return "rotation";
    case ProbeQuantity::angular_velocity:
      return "angular_velocity";
    case ProbeQuantity::dea_voltage:
      return "dea_voltage";
    case ProbeQuantity::dea_current:
      return "dea_current";
    case ProbeQuantity::reaction_force:
      return "reaction_force";
    case ProbeQuantity::reaction_moment:
      return "reaction_moment";
    case ProbeQuantity::spring_force:
      return "spring_force";
    case ProbeQuantity::strain:
      return "strain";
    case ProbeQuantity::dea_force:
      return "dea_force";
    case ProbeQuantity::axial_displacement:
      return "axial_displacement";
    case ProbeQuantity::axial_reaction_force:
      return "axial_reaction_force";
  }
  return "?";
}

const char* probe_unit(ProbeQuantity quantity) {
  switch (quantity) {
    case ProbeQuantity::deflection:
    case ProbeQuantity::axial_displacement:
      return "m";
    case ProbeQuantity::velocity:
      return "m/s";
    case ProbeQuantity::rotation:
      return "rad";
    case ProbeQuantity::angular_velocity:
      return "rad/s";
    case ProbeQuantity::dea_voltage:
      return "V";
    case ProbeQuantity::dea_current:
      return "A";
    case ProbeQuantity::reaction_force:
    case ProbeQuantity::axial_reaction_force:
    case ProbeQuantity::spring_force:
    case ProbeQuantity::dea_force:
      return "N";
    case ProbeQuantity::reaction_moment:
      return "N*m";
    case ProbeQuantity::strain:
      return "";
  }
  return "?";
}

}  // namespace emnet
