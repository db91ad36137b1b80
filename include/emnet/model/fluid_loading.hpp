// Fluid loading of a thin rectangular beam vibrating in a viscous fluid (scene [environment]).
//
// Source: J. E. Sader, "Frequency response of cantilever beams immersed in viscous fluids with
// applications to the atomic force microscope", J. Appl. Phys. 84(1), 64–76 (1998),
// doi:10.1063/1.368002, Eqs. (2)–(3), (18)–(21).
//
// A beam of width b oscillating at ω normal to its plane in an unbounded incompressible fluid
// (density ρ [kg/m³], dynamic viscosity η [Pa·s]) feels, per unit length, the force
//     F(ω) = (π/4)·ρ·b²·ω²·Γ(ω)·W(ω)                      (W: deflection phasor [m])
// i.e. (with F = −m_a·ẅ − c_a·ẇ and ẅ = −ω²W, ẇ = iωW) an added mass and a damping per length
//     m_a = (π/4)·ρ·b²·Γ_r        [kg/m]
//     c_a = (π/4)·ρ·b²·ω·Γ_i      [N·s/m²]
// Γ = Γ_r + iΓ_i is the hydrodynamic function of the Reynolds number Re = ρ·ω·b²/(4η):
//     Γ(Re)      = Ω(Re)·Γ_circ(Re)
//     Γ_circ(Re) = 1 + 4i·K₁(−i√(iRe)) / (√(iRe)·K₀(−i√(iRe)))   (cylinder of diameter b)
// K₀, K₁: modified Bessel functions of the second kind; Ω(τ = log₁₀Re): Sader's rational
// correction for the rectangular section (Eq. 21), accurate to 0.1 % against his numerical
// solution for 1e-6 ≤ Re ≤ 1e4. Outside that range Ω is extrapolated (it tends to 1 for large
// Re), and the caller says so.
//
// Large Re: Γ_circ → 1 + 2√2·(1 + i)/√Re, so m_a → ρπb²/4, the potential-flow added mass of a
// plate of width b (that of the cylinder of diameter b). Assumptions: the beam is slender
// (length ≫ b), its amplitude small against b (linear, no vortex shedding), the fluid unbounded
// and incompressible, Γ taken at one frequency for all modes (exact for the mode at that
// frequency).
#pragma once

#include <complex>

namespace emnet {

/// e^z·K₀(z) and e^z·K₁(z) for Re z > 0, by the trapezoidal rule on
/// K_ν(z) = ∫₀^∞ exp(−z·cosh t)·cosh(νt) dt (exponentially convergent; relative error ~1e-14).
struct ScaledBesselK01 {
  std::complex<double> k0;  ///< e^z·K₀(z)
  std::complex<double> k1;  ///< e^z·K₁(z)
};
/// The ScaledBesselK01 at `z`.
/// @throws std::invalid_argument unless Re z > 0
ScaledBesselK01 scaled_bessel_k01(std::complex<double> z);

/// Γ_circ(Re): the hydrodynamic function of a circular cylinder of diameter b, Re > 0.
/// @throws std::invalid_argument unless Re is finite and > 0
std::complex<double> circular_cylinder_hydrodynamic_function(double reynolds);
/// Ω(Re): Sader's correction from the circular to the rectangular section, Re > 0.
/// @throws std::invalid_argument unless Re is finite and > 0
std::complex<double> rectangular_section_correction(double reynolds);
/// Γ(Re) = Ω·Γ_circ for a thin rectangular beam of width b.
std::complex<double> rectangular_beam_hydrodynamic_function(double reynolds);

/// The lowest Re at which Ω is accurate (see above); below it Ω is extrapolated.
inline constexpr double kSaderCorrectionMinimumReynolds = 1e-6;
/// The highest Re at which Ω is accurate; above it Ω is extrapolated.
inline constexpr double kSaderCorrectionMaximumReynolds = 1e4;

/// The fluid loading per length of a beam at one frequency.
struct FluidLoading {
  double frequency = 0.0;               ///< [Hz] at which Γ is evaluated
  double reynolds = 0.0;                ///< Re = ρωb²/(4η)
  std::complex<double> hydrodynamic{};  ///< Γ
  double added_mass_per_length = 0.0;   ///< m_a [kg/m]
  double damping_per_length = 0.0;      ///< c_a [N·s/m²]
};

/// Added mass and damping per length of a plate of `width` b in a fluid (`density` ρ,
/// `dynamic_viscosity` η) at `frequency` f [Hz] > 0.
/// @param density            ρ [kg/m³]
/// @param dynamic_viscosity  η [Pa·s]
/// @param width              b [m]
/// @throws std::invalid_argument unless density, viscosity, width and frequency are > 0
FluidLoading rectangular_beam_fluid_loading(double density, double dynamic_viscosity, double width,
                                            double frequency);

}  // namespace emnet
