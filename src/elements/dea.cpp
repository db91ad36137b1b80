// DEA transducer: see include/emnet/elements/dea.hpp for equations, signs and sources.
#include "emnet/elements/dea.hpp"

namespace emnet {

double dea_force_constant(double relative_permittivity, double dielectric_thickness,
                          double force_thickness, double electrode_width) {
  return vacuum_permittivity * relative_permittivity * force_thickness * electrode_width /
         (2.0 * dielectric_thickness * dielectric_thickness);
}

double dea_capacitance(double relative_permittivity, double dielectric_thickness,
                       double electrode_width, double electrode_length) {
  return vacuum_permittivity * relative_permittivity * electrode_width * electrode_length /
         dielectric_thickness;
}

void Dea::stamp(Stamper& s) const {
  s.c_between(electrode_plus_, electrode_minus_, capacitance_);
  if (ac_force_ != 0.0)
    for (const Coupling& c : coupling_) s.ac(c.node, ac_force_ * c.coefficient);
}

bool Dea::squared_source(LinearTerms& voltage, LinearTerms& direction) const {
  if (back_coupling_) return false;
  voltage.clear();
  direction.clear();
  if (electrode_plus_ != ground) voltage.emplace_back(electrode_plus_, 1.0);
  if (electrode_minus_ != ground) voltage.emplace_back(electrode_minus_, -1.0);
  for (const Coupling& c : coupling_)
    if (c.node != ground) direction.emplace_back(c.node, force_constant_ * c.coefficient);
  return true;
}

void Dea::add_nonlinear(const Eigen::VectorXd& y, int /*branch_offset*/, Eigen::VectorXd& g,
                        std::vector<Eigen::Triplet<double>>* jacobian) const {
  const double u = across(y, electrode_plus_) - across(y, electrode_minus_);
  const double force = force_constant_ * u * u;
  const double dforce_du = 2.0 * force_constant_ * u;
  auto add_jacobian_u = [&](int row, double value) {  // ∂/∂u → columns e+ (+), e− (−)
    if (!jacobian || row == ground) return;
    if (electrode_plus_ != ground) jacobian->emplace_back(row, electrode_plus_, value);
    if (electrode_minus_ != ground) jacobian->emplace_back(row, electrode_minus_, -value);
  };
  double elongation_rate = 0.0;
  for (const Coupling& c : coupling_) {
    if (c.node == ground) continue;
    elongation_rate += c.coefficient * y[c.node];
    g[c.node] -= force * c.coefficient;
    add_jacobian_u(c.node, -dforce_du * c.coefficient);
  }
  if (!back_coupling_) return;
  const double current = 2.0 * force_constant_ * u * elongation_rate;
  const double dcurrent_du = 2.0 * force_constant_ * elongation_rate;
  for (int side = 0; side < 2; ++side) {
    const NodeId row = side == 0 ? electrode_plus_ : electrode_minus_;
    const double sign = side == 0 ? 1.0 : -1.0;
    if (row == ground) continue;
    g[row] += sign * current;
    add_jacobian_u(row, sign * dcurrent_du);
    if (jacobian)
      for (const Coupling& c : coupling_)
        if (c.node != ground)
          jacobian->emplace_back(row, c.node, sign * 2.0 * force_constant_ * u * c.coefficient);
  }
}

}  // namespace emnet
