// Fluid loading of a thin rectangular beam (Sader 1998): see include/emnet/model/fluid_loading.hpp.
#include "emnet/model/fluid_loading.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "emnet/core/constants.hpp"

namespace emnet {

namespace {

// Horner evaluation of c[0] + c[1]·τ + … + c[n]·τⁿ.
template <std::size_t N>
double polynomial(const double (&coefficients)[N], double tau) {
  double sum = 0.0;
  for (std::size_t k = N; k-- > 0;) sum = sum * tau + coefficients[k];
  return sum;
}

}  // namespace

// K_ν(z)·e^z = ∫₀^∞ exp(−z·(cosh t − 1))·cosh(νt) dt, Re z > 0. The integrand is analytic in
// a strip about the real axis and decays double-exponentially, so the trapezoidal rule
// converges exponentially in 1/h. Step: h ≤ 0.05 resolves the strip (error ~exp(−π²/(2h)));
// for large |z| the integrand is a Gaussian of width ~1/√|z|, resolved by h ≤ 0.3/√|z|
// (error ~exp(−(2π/h)²·cos(arg z)/(2|z|)) < 1e-16 for |arg z| ≤ π/4). The sum stops where
// Re z·(cosh t − 1) = 45: the tail is below e⁻⁴⁵ relative to the integral.
ScaledBesselK01 scaled_bessel_k01(std::complex<double> z) {
  if (!(z.real() > 0.0)) throw std::invalid_argument("scaled_bessel_k01: needs Re z > 0");
  const double magnitude = std::abs(z);
  const double step = std::min(0.05, 0.3 / std::sqrt(magnitude));
  const double end = std::acosh(1.0 + 45.0 / z.real());
  const int steps = static_cast<int>(std::ceil(end / step));
  ScaledBesselK01 sum{0.5, 0.5};  // t = 0: weight 1/2, integrands 1 and cosh 0 = 1
  for (int k = 1; k <= steps; ++k) {
    const double t = k * step;
    const std::complex<double> decay = std::exp(-z * (std::cosh(t) - 1.0));
    sum.k0 += decay;
    sum.k1 += decay * std::cosh(t);
  }
  sum.k0 *= step;
  sum.k1 *= step;
  return sum;
}

// Sader Eq. (18). With z = −i√(iRe) (arg z = −π/4, so Re z > 0): √(iRe) = i·z and
// Γ_circ = 1 + 4i·K₁(z)/(i·z·K₀(z)) = 1 + 4·K₁(z)/(z·K₀(z)); the e^z scaling cancels.
std::complex<double> circular_cylinder_hydrodynamic_function(double reynolds) {
  if (!(reynolds > 0.0) || !std::isfinite(reynolds))
    throw std::invalid_argument("hydrodynamic function: needs a finite Reynolds number > 0");
  const std::complex<double> i(0.0, 1.0);
  const std::complex<double> z = -i * std::sqrt(i * reynolds);
  const ScaledBesselK01 k = scaled_bessel_k01(z);
  return 1.0 + 4.0 * k.k1 / (z * k.k0);
}

// Sader Eq. (21a, b), τ = log₁₀ Re.
std::complex<double> rectangular_section_correction(double reynolds) {
  if (!(reynolds > 0.0) || !std::isfinite(reynolds))
    throw std::invalid_argument("hydrodynamic function: needs a finite Reynolds number > 0");
  const double tau = std::log10(reynolds);
  static const double real_numerator[] = {0.91324,  -0.48274,   0.46842,   -0.12886,
                                          0.044055, -0.0035117, 0.00069085};
  static const double real_denominator[] = {1.0,      -0.56964,   0.48690,   -0.13444,
                                            0.045155, -0.0035862, 0.00069085};
  static const double imaginary_numerator[] = {-0.024134,   -0.029256,   0.016294,
                                               -0.00010961, 0.000064577, -0.000044510};
  static const double imaginary_denominator[] = {1.0,      -0.59702,  0.55182,  -0.18357,
                                                 0.079156, -0.014369, 0.0028361};
  return {polynomial(real_numerator, tau) / polynomial(real_denominator, tau),
          polynomial(imaginary_numerator, tau) / polynomial(imaginary_denominator, tau)};
}

std::complex<double> rectangular_beam_hydrodynamic_function(double reynolds) {
  return rectangular_section_correction(reynolds) *
         circular_cylinder_hydrodynamic_function(reynolds);
}

FluidLoading rectangular_beam_fluid_loading(double density, double dynamic_viscosity, double width,
                                            double frequency) {
  if (!(density > 0.0 && dynamic_viscosity > 0.0 && width > 0.0 && frequency > 0.0))
    throw std::invalid_argument(
        "fluid loading: density, viscosity, width and frequency must be > 0");
  FluidLoading loading;
  const double omega = 2.0 * kPi * frequency;
  const double section = 0.25 * kPi * density * width * width;  // (π/4)·ρ·b² [kg/m]
  loading.frequency = frequency;
  loading.reynolds = density * omega * width * width / (4.0 * dynamic_viscosity);
  loading.hydrodynamic = rectangular_beam_hydrodynamic_function(loading.reynolds);
  loading.added_mass_per_length = section * loading.hydrodynamic.real();
  loading.damping_per_length = section * omega * loading.hydrodynamic.imag();
  return loading;
}

}  // namespace emnet
