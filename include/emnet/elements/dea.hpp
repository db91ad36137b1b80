// Dielectric elastomer actuator (DEA) transducer: nonlinear, electrostatic, on one beam face.
//
// Electrical side: the film is a capacitor C₀ = ε₀·ε_r·A_e/d between its electrode nodes
// (e+, e−) with A_e = electrode width × length (≈ 0.85 nF for the paper's fin). The electrode
// resistance is a separate Conductance in series (built by the model builder).
//
// Force (paper Eq. 16, docs/model.md, The DEA transducer): the face is pushed longitudinally with
//     F = k_F · u²,    k_F = ε₀·ε_r·d'·w_e / (2·d²)       [N/V²]
// u = capacitor voltage y_e+ − y_e−, d = dielectric thickness, d' = thickness in Eq. 16,
// w_e = electrode width. Paper film: 0.055 N at 3 kV, 0.097 N at 4 kV.
//
// Mechanical side: the DEA lengthens its face. The face's elongation rate is a linear
// functional of the beam's across values, ẋ = Σ_k c_k·y_k (for a DEA over [x0, x1] on the
// top face at lever arm z: ẋ = −z·(Ω(x1) − Ω(x0)), Ω(x) Hermite-interpolated, so c holds
// rotation-node and, between nodes, velocity-node coefficients). The force does work F·ẋ, so
// it enters as generalised through quantities F·c_k into nodes k: for a span over whole
// segments a moment pair, +z·F at x0 and −z·F at x1 on the top face, the signs swapped on the
// bottom face (docs/model.md, The DEA transducer). Sign: an energised top-face DEA bends the
// beam toward −w.
//
// Back-coupling (optional): with C(x) = C₀ + 2·k_F·x the current into the capacitor gains
// i_b = u·(dC/dx)·ẋ = 2·k_F·u·ẋ (electrical power u·i_b = 2·F·ẋ: half to the mechanics, half
// to the field energy). Linearised at a bias U₀ this is a gyrator with K = 2·k_F·U₀.
//
// In g(y):  g[k] −= F·c_k (mechanical rows);  g[e±] ±= i_b (when back_coupling).
// AC: a direct small-signal force amplitude `ac_force` [N] may be stamped as ac_force·c_k
// (used by the antagonistic drive, whose AC input is the DEA force itself).
#pragma once

#include <utility>
#include <vector>

#include "emnet/network/network.hpp"

namespace emnet {

/// A DEA transducer (see above).
class Dea : public Element {
 public:
  /// One term c_k·y_k of the face's elongation rate ẋ.
  struct Coupling {
    NodeId node;
    double coefficient;  ///< ẋ = Σ coefficient·y_node [m/s per unit across]
  };
  /// @param capacitance     C₀ [F]
  /// @param force_constant  k_F [N/V²]
  /// @param coupling        the terms of ẋ
  /// @param back_coupling   add the back-coupling current i_b
  /// @param ac_force        the direct small-signal force amplitude [N]
  Dea(std::string name, NodeId electrode_plus, NodeId electrode_minus, double capacitance,
      double force_constant, std::vector<Coupling> coupling, bool back_coupling,
      double ac_force = 0.0)
      : Element(std::move(name)),
        electrode_plus_(electrode_plus),
        electrode_minus_(electrode_minus),
        capacitance_(capacitance),
        force_constant_(force_constant),
        coupling_(std::move(coupling)),
        back_coupling_(back_coupling),
        ac_force_(ac_force) {}
  const char* kind() const override { return "dea"; }
  void stamp(Stamper& s) const override;
  bool is_nonlinear() const override { return true; }
  void add_nonlinear(const Eigen::VectorXd& y, int branch_offset, Eigen::VectorXd& g,
                     std::vector<Eigen::Triplet<double>>* jacobian) const override;
  /// u = y_e+ − y_e−, d = k_F·c; false with the back-coupling.
  bool squared_source(LinearTerms& voltage, LinearTerms& direction) const override;

  /// F = k_F·u² for a given capacitor voltage u.
  double force(double voltage) const { return force_constant_ * voltage * voltage; }
  double capacitance() const { return capacitance_; }
  double force_constant() const { return force_constant_; }
  NodeId electrode_plus() const { return electrode_plus_; }
  NodeId electrode_minus() const { return electrode_minus_; }
  const std::vector<Coupling>& coupling() const { return coupling_; }
  bool back_coupling() const { return back_coupling_; }
  double ac_force() const { return ac_force_; }

 private:
  double across(const Eigen::VectorXd& y, NodeId node) const {
    return node == ground ? 0.0 : y[node];
  }
  NodeId electrode_plus_, electrode_minus_;
  double capacitance_;
  double force_constant_;
  std::vector<Coupling> coupling_;
  bool back_coupling_;
  double ac_force_;
};

/// k_F of paper Eq. 16: ε₀·ε_r·d'·w_e / (2·d²) [N/V²].
/// @param dielectric_thickness  d [m]
/// @param force_thickness       d' [m]
/// @param electrode_width       w_e [m]
double dea_force_constant(double relative_permittivity, double dielectric_thickness,
                          double force_thickness, double electrode_width);
/// C₀ = ε₀·ε_r·w_e·length / d [F].
/// @param dielectric_thickness  d [m]
/// @param electrode_width       w_e [m]
/// @param electrode_length      length [m]
double dea_capacitance(double relative_permittivity, double dielectric_thickness,
                       double electrode_width, double electrode_length);
constexpr double vacuum_permittivity = 8.8541878128e-12;  ///< ε₀ [F/m] (CODATA 2018)

}  // namespace emnet
