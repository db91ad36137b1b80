// Exact continuum natural frequencies of a piecewise-uniform beam by the transfer-matrix method:
// an independent reference for the beam tests (it uses Eigen only, none of emnet's model code).
//
// Units: SI. Lengths m, bending stiffness EI N·m², mass per length ρA kg/m, shear stiffness κGA N,
// rotary inertia per length ρI kg·m, point mass kg, point rotary inertia kg·m², springs N/m and
// N·m/rad, frequencies Hz (natural_frequencies_hz) or rad/s (ω elsewhere).
//
// State vector y = (w, φ, M, Q) at a cross-section x, beam along +x from x = 0 to x = L:
//   w  deflection, positive along +z;
//   φ  rotation of the cross-section, positive turning +x towards +z (Euler–Bernoulli: φ = w');
//   M  bending moment, M = EI φ' (positive when it makes the beam sag with w'' > 0);
//   Q  = −S with S = κGA (w' − φ) the transverse shear force; Euler–Bernoulli: Q = M' = EI w'''.
// Harmonic motion e^{iωt} turns the equations of motion into y' = A(ω) y with
//   w' = φ − Q/κGA,   φ' = M/EI,   M' = Q − ρI ω² φ,   Q' = ρA ω² w.
// κGA = ∞ and ρI = 0 is the Euler–Bernoulli beam; finite κGA with ρI = 0 is the Timoshenko beam
// without rotary inertia (shear deformation only); finite κGA with ρI > 0 the full Timoshenko beam.
//
// Euler–Bernoulli field matrix of a section of length l, β⁴ = ρA ω²/EI, z = βl, with the
// Krylov–Duncan functions S = (cosh z + cos z)/2, T = (sinh z + sin z)/2, U = (cosh z − cos z)/2,
// V = (sinh z − sin z)/2:
//        | S        T/β      U/(EIβ²)  V/(EIβ³) |
//   F =  | βV       S        T/(EIβ)   U/(EIβ²) |     y(x + l) = F y(x)
//        | EIβ²U    EIβV     S         T/β      |
//        | EIβ³T    EIβ²U    βV        S        |
// It is evaluated times e^{−z} (no cosh overflow, entries O(1)), which only multiplies the
// frequency determinant by a positive factor. Timoshenko sections use e^{(Â−I)z} of the same system
// made dimensionless with the length 1/β (scaling and squaring, Taylor series). Sections are
// applied in pieces of z ≤ 4, to a dimensionless two-column basis re-orthonormalised after each
// piece (see frequency_determinant), so high modes keep full precision.
//
// Point matrix at an attachment (mass m, rotary inertia J, spring k_t and k_θ to ground): w and φ
// are continuous, Q⁺ = Q⁻ + (m ω² − k_t) w,  M⁺ = M⁻ + (k_θ − J ω²) φ.
//
// Ends: clamped w = φ = 0; pinned w = M = 0; sliding φ = Q = 0; free M = Q = 0. With
// P = F_n ⋯ P_1 F_1 the product from x = 0 to x = L, the two unknown components at x = 0 (columns)
// must make the two prescribed components at x = L (rows) vanish: the frequency equation is the
// 2×2 determinant of that sub-block of P. An elastically restrained end is a pinned or free (or
// sliding) end with a spring attachment at x = 0 or x = L: e.g. pinned + k_θ at x = 0 gives
// EI w''(0) = k_θ w'(0).
//
// Root finding: the determinant (see frequency_determinant), in long double, is scanned on a
// uniform grid of Λ = Σ β_i l_i (spacing scan_step, default π/100; the roots of uniform beams are
// ~π apart in Λ) starting at Λ = 10⁻³, and every sign change is bisected to adjacent doubles in ω.
// Rigid-body modes (ω = 0, free–free or pinned–free) are not returned: only roots with Λ > 10⁻³
// are, so an elastic mode below Λ = 10⁻³ would be taken for a rigid one, and two roots closer than
// scan_step (possible with a point mass on a soft spring) could be missed.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace emnet::test_reference {

using Matrix4 = Eigen::Matrix<long double, 4, 4>;
constexpr double pi = 3.14159265358979323846;

enum class BeamEnd { clamped, pinned, sliding, free };

struct BeamSection {
  double length = 0;                                                 // m
  double bending_stiffness = 0;                                      // EI, N·m²
  double mass_per_length = 0;                                        // ρA, kg/m
  double shear_stiffness = std::numeric_limits<double>::infinity();  // κGA, N (∞: Euler–Bernoulli)
  double rotary_inertia_per_length = 0;                              // ρI, kg·m (Timoshenko only)
};

struct PointAttachment {
  double position = 0;              // m from x = 0, anywhere in [0, L]
  double mass = 0;                  // kg
  double rotary_inertia = 0;        // kg·m²
  double translational_spring = 0;  // N/m to ground
  double rotational_spring = 0;     // N·m/rad to ground
};

struct BeamDescription {
  std::vector<BeamSection> sections;  // in order from x = 0
  std::vector<PointAttachment> attachments;
  BeamEnd end_at_start = BeamEnd::clamped;  // x = 0
  BeamEnd end_at_finish = BeamEnd::free;    // x = L
};

// β⁴ = ρA ω²/EI.
inline long double bending_wavenumber(const BeamSection& section, long double omega) {
  return std::sqrt(omega) *
         std::pow((long double)section.mass_per_length / section.bending_stiffness, 0.25L);
}

// Euler–Bernoulli field matrix times e^{−βl}. Below z = 2 the all-positive power series
// (S = Σ z^{4k}/(4k)!, T = Σ z^{4k+1}/(4k+1)!, ...) give S, T/z, U/z², V/z³ without cancellation.
inline Matrix4 euler_bernoulli_field_matrix(const BeamSection& section, long double length,
                                            long double omega) {
  const long double beta = bending_wavenumber(section, omega), z = beta * length;
  const long double ei = section.bending_stiffness, scale = std::exp(-z);
  long double s, t_over_z, u_over_z2, v_over_z3;
  if (z < 2) {
    long double term = 1, z4 = z * z * z * z;
    s = t_over_z = u_over_z2 = v_over_z3 = 0;
    for (int k = 0; k < 40 && term > 1e-25L; ++k) {
      s += term;
      t_over_z += term / ((4 * k + 1));
      u_over_z2 += term / ((4 * k + 1) * (4 * k + 2));
      v_over_z3 += term / ((4 * k + 1) * (4 * k + 2) * (4 * k + 3));
      term *= z4 / ((4 * k + 1) * (4 * k + 2) * (4 * k + 3) * (4 * k + 4));
    }
    s *= scale, t_over_z *= scale, u_over_z2 *= scale, v_over_z3 *= scale;
  } else {  // e^{−z} cosh z = (1 + e^{−2z})/2, e^{−z} sinh z = (1 − e^{−2z})/2
    const long double e2 = std::exp(-2 * z), c = scale * std::cos(z), sn = scale * std::sin(z);
    s = ((1 + e2) / 2 + c) / 2;
    t_over_z = ((1 - e2) / 2 + sn) / 2 / z;
    u_over_z2 = ((1 + e2) / 2 - c) / 2 / (z * z);
    v_over_z3 = ((1 - e2) / 2 - sn) / 2 / (z * z * z);
  }
  const long double l = length, t = t_over_z * z, u = u_over_z2 * z * z, v = v_over_z3 * z * z * z;
  const long double b = beta, b2 = beta * beta, b3 = b2 * beta;
  Matrix4 f;
  f << s, l * t_over_z, l * l * u_over_z2 / ei, l * l * l * v_over_z3 / ei,  //
      b * v, s, l * t_over_z / ei, l * l * u_over_z2 / ei,                   //
      ei * b2 * u, ei * b * v, s, l * t_over_z,                              //
      ei * b3 * t, ei * b2 * u, b * v, s;
  return f;
}

// Field matrix of any section (Timoshenko or Euler–Bernoulli) as e^{−βl} e^{A l}: in the
// variables (βw, φ, M/(EIβ), Q/(EIβ²)) and ξ = βx the system is Â = [0 1 0 −a; 0 0 1 0;
// 0 −c 0 1; 1 0 0 0] with a = EIβ²/κGA, c = ρIω²/(EIβ²).
inline Matrix4 general_field_matrix(const BeamSection& section, long double length,
                                    long double omega) {
  const long double beta = bending_wavenumber(section, omega), z = beta * length;
  const long double ei = section.bending_stiffness;
  const long double a = ei * beta * beta / section.shear_stiffness;
  const long double c = section.rotary_inertia_per_length * omega * omega / (ei * beta * beta);
  Matrix4 dimensionless;
  dimensionless << -1, 1, 0, -a, 0, -1, 1, 0, 0, -c, -1, 1, 1, 0, 0, -1;
  dimensionless *= z;
  int squarings = 0;
  for (long double norm = dimensionless.cwiseAbs().rowwise().sum().maxCoeff(); norm > 0.25L;
       norm /= 2)
    ++squarings;
  dimensionless /= std::ldexp(1.0L, squarings);
  Matrix4 exponential = Matrix4::Identity(), term = Matrix4::Identity();
  for (int k = 1; k <= 30; ++k) {
    term = term * dimensionless / (long double)k;
    exponential += term;
  }
  for (int i = 0; i < squarings; ++i) exponential = exponential * exponential;
  const Eigen::Matrix<long double, 4, 1> to_dimensionless(beta, 1, 1 / (ei * beta),
                                                          1 / (ei * beta * beta));
  return to_dimensionless.cwiseInverse().asDiagonal() * exponential * to_dimensionless.asDiagonal();
}

inline Matrix4 section_field_matrix(const BeamSection& section, long double length,
                                    long double omega) {
  const bool euler_bernoulli =
      std::isinf(section.shear_stiffness) && section.rotary_inertia_per_length == 0;
  return euler_bernoulli ? euler_bernoulli_field_matrix(section, length, omega)
                         : general_field_matrix(section, length, omega);
}

inline Matrix4 point_matrix(const PointAttachment& point, long double omega) {
  Matrix4 p = Matrix4::Identity();
  const long double omega2 = omega * omega;
  p(2, 1) = point.rotational_spring - point.rotary_inertia * omega2;
  p(3, 0) = point.mass * omega2 - point.translational_spring;
  return p;
}

inline double total_length(const BeamDescription& beam) {
  double length = 0;
  for (const BeamSection& section : beam.sections) length += section.length;
  return length;
}

// Calls apply(matrix) with the field and point matrices from x = 0 to x = L in order; sections are
// split at attachments and into pieces of βl ≤ 4.
template <class Apply>
void walk_beam(const BeamDescription& beam, long double omega, Apply&& apply) {
  std::vector<PointAttachment> points = beam.attachments;
  std::stable_sort(points.begin(), points.end(),
                   [](const auto& a, const auto& b) { return a.position < b.position; });
  const double length = total_length(beam);
  for (const PointAttachment& point : points)
    if (point.position < 0 || point.position > length * (1 + 1e-12))
      throw std::invalid_argument("transfer matrix: attachment outside the beam");
  size_t next_point = 0;
  long double section_start = 0;
  for (size_t i = 0; i < beam.sections.size(); ++i) {
    const BeamSection& section = beam.sections[i];
    const auto field = [&](long double piece) {
      const long double pieces = std::ceil(bending_wavenumber(section, omega) * piece / 4);
      for (int k = 0; k < std::max(1.0L, pieces); ++k)
        apply(section_field_matrix(section, piece / std::max(1.0L, pieces), omega));
    };
    const long double section_end = section_start + section.length;
    const bool last = i + 1 == beam.sections.size();
    long double x = section_start;
    while (next_point < points.size() && (points[next_point].position < section_end || last)) {
      const long double position =
          std::clamp<long double>(points[next_point].position, x, last ? section_end : 1e300L);
      if (position > x) field(position - x);
      apply(point_matrix(points[next_point++], omega));
      x = position;
    }
    if (section_end > x) field(section_end - x);
    section_start = section_end;
  }
}

// P = F_n ⋯ P_1 F_1, the product of field and point matrices from x = 0 to x = L.
inline Matrix4 overall_transfer_matrix(const BeamDescription& beam, long double omega) {
  Matrix4 product = Matrix4::Identity();
  walk_beam(beam, omega, [&](const Matrix4& matrix) { product = matrix * product; });
  return product;
}

// Indices of the state components that are unknown at the start (free to be nonzero)...
inline std::array<int, 2> unknown_components(BeamEnd end) {
  switch (end) {
    case BeamEnd::clamped:
      return {2, 3};  // M, Q
    case BeamEnd::pinned:
      return {1, 3};  // φ, Q
    case BeamEnd::sliding:
      return {0, 2};  // w, M
    case BeamEnd::free:
      return {0, 1};  // w, φ
  }
  return {0, 0};
}
// ... and of those prescribed to vanish at the finish.
inline std::array<int, 2> prescribed_components(BeamEnd end) {
  switch (end) {
    case BeamEnd::clamped:
      return {0, 1};
    case BeamEnd::pinned:
      return {0, 2};
    case BeamEnd::sliding:
      return {1, 3};
    case BeamEnd::free:
      return {2, 3};
  }
  return {0, 0};
}

// The 2×2 determinant of the rows prescribed at x = L and the columns unknown at x = 0, up to a
// positive factor. Computed without forming P: the two columns are carried along, in the
// dimensionless state (βw, φ, M/(EIβ), Q/(EIβ²)) of the first section, and orthonormalised by
// Gram–Schmidt after every matrix (positive diagonal R, so the sign is kept). Forming P instead
// loses about e^Λ·10⁻¹⁹ to cancellation between its growing solutions.
inline long double frequency_determinant(const BeamDescription& beam, long double omega) {
  const BeamSection& first = beam.sections.front();
  const long double beta = bending_wavenumber(first, omega), ei = first.bending_stiffness;
  const Eigen::Matrix<long double, 4, 1> scale(beta, 1, 1 / (ei * beta), 1 / (ei * beta * beta));
  const auto cols = unknown_components(beam.end_at_start);
  const auto rows = prescribed_components(beam.end_at_finish);
  Eigen::Matrix<long double, 4, 2> basis = Eigen::Matrix<long double, 4, 2>::Zero();
  basis(cols[0], 0) = basis(cols[1], 1) = 1;
  walk_beam(beam, omega, [&](const Matrix4& matrix) {
    basis = scale.asDiagonal() * (matrix * (scale.cwiseInverse().asDiagonal() * basis));
    basis.col(0).normalize();
    for (int pass = 0; pass < 2; ++pass)
      basis.col(1) -= basis.col(0).dot(basis.col(1)) * basis.col(0);
    basis.col(1).normalize();
  });
  return basis(rows[0], 0) * basis(rows[1], 1) - basis(rows[0], 1) * basis(rows[1], 0);
}

// The first `count` nonzero natural angular frequencies [rad/s], ascending.
inline std::vector<double> natural_angular_frequencies(const BeamDescription& beam, int count,
                                                       double scan_step = pi / 100) {
  if (beam.sections.empty()) throw std::invalid_argument("transfer matrix: no sections");
  long double phase_per_sqrt_omega = 0;  // Λ = √ω Σ l_i (ρA_i/EI_i)^{1/4}
  for (const BeamSection& section : beam.sections)
    phase_per_sqrt_omega += section.length * bending_wavenumber(section, 1);
  const auto omega_at = [&](double phase) {
    return (double)std::pow(phase / phase_per_sqrt_omega, 2);
  };
  const auto sign = [&](double omega) { return std::signbit(frequency_determinant(beam, omega)); };
  std::vector<double> roots;
  double lower = omega_at(1e-3);
  bool lower_sign = sign(lower);
  for (int k = 1; (int)roots.size() < count; ++k) {
    double upper = omega_at(1e-3 + k * scan_step);
    const bool upper_sign = sign(upper);
    if (upper_sign != lower_sign) {
      double low = lower, high = upper;
      for (;;) {
        const double middle = low + (high - low) / 2;
        if (middle <= low || middle >= high) break;
        (sign(middle) == lower_sign ? low : high) = middle;
      }
      roots.push_back(low + (high - low) / 2);
    }
    lower = upper, lower_sign = upper_sign;
  }
  return roots;
}

inline std::vector<double> natural_frequencies_hz(const BeamDescription& beam, int count,
                                                  double scan_step = pi / 100) {
  std::vector<double> frequencies = natural_angular_frequencies(beam, count, scan_step);
  for (double& f : frequencies) f /= 2 * pi;
  return frequencies;
}

// ---- Closed forms used by the tests (λ = βL) ----

// Uniform clamped–free beam, 1 + cos λ cosh λ = 0.
constexpr double cantilever_roots[] = {1.875104069, 4.694091133, 7.854757438, 10.99554073,
                                       14.13716839};

// Clamped–free beam with a tip point mass μ ρA L (no rotary inertia), divided by cosh λ:
// 1 + cos λ cosh λ + μ λ (cos λ sinh λ − sin λ cosh λ) = 0.
inline double tip_mass_cantilever_equation(double lambda, double mass_ratio) {
  return 1 / std::cosh(lambda) + std::cos(lambda) +
         mass_ratio * lambda * (std::cos(lambda) * std::tanh(lambda) - std::sin(lambda));
}

// Pinned at x = 0 with a rotational spring K = k_θ L/EI, free at L, divided by cosh λ:
// with w = A cos βx + B sin βx + C cosh βx + D sinh βx, w(0) = 0, EI w''(0) = k_θ w'(0),
// w''(L) = w'''(L) = 0 give K (1 + cos λ cosh λ) − λ (sin λ cosh λ − cos λ sinh λ) = 0
// (K → ∞: cantilever; K → 0: pinned–free tan λ = tanh λ; small K: λ⁴ ≈ 3K, rigid rocking).
inline double rotational_spring_root_equation(double lambda, double stiffness_ratio) {
  return stiffness_ratio * (1 / std::cosh(lambda) + std::cos(lambda)) -
         lambda * (std::sin(lambda) - std::cos(lambda) * std::tanh(lambda));
}

// Simply supported Timoshenko beam, mode n, k = nπ/L, ω_EB² = EI k⁴/ρA. Without rotary inertia
// ω_n = ω_EB / √(1 + k² EI/κGA); with it ω² is the lower root of
// (κGA k² − ρA ω²)(EI k² + κGA − ρI ω²) − (κGA k)² = 0.
inline double simply_supported_shear_beam_omega(const BeamSection& section, double length, int n) {
  const double k = n * pi / length;
  const double euler_bernoulli =
      k * k * std::sqrt(section.bending_stiffness / section.mass_per_length);
  return euler_bernoulli /
         std::sqrt(1 + k * k * section.bending_stiffness / section.shear_stiffness);
}
inline double simply_supported_timoshenko_omega(const BeamSection& section, double length, int n) {
  const double k = n * pi / length, ga = section.shear_stiffness, ei = section.bending_stiffness;
  const double ra = section.mass_per_length, ri = section.rotary_inertia_per_length;
  // a ω⁴ − b ω² + c = 0; the lower root as 2c/(b + √(b² − 4ac)), exact when ρI = 0 too.
  const double a = ra * ri, b = ra * (ei * k * k + ga) + ri * ga * k * k,
               c = ga * k * k * ei * k * k;
  return std::sqrt(2 * c / (b + std::sqrt(b * b - 4 * a * c)));
}

}  // namespace emnet::test_reference
