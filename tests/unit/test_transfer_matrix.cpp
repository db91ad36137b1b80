// Self-tests of the transfer-matrix continuum reference (transfer_matrix.hpp), each against an
// independent result: textbook roots of uniform beams, the beam itself split differently, a fine
// Hermite finite-element model with Richardson extrapolation, and the closed-form frequency
// equations of the tip-mass cantilever, the spring-hinged cantilever and the simply supported
// Timoshenko beam (those equations solved here by their own bracketing and bisection).
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <cmath>
#include <functional>
#include <random>

#include "transfer_matrix.hpp"

namespace emnet::test_reference {
namespace {

constexpr double beam_length = 0.8, beam_bending_stiffness = 2.3, beam_mass_per_length = 0.47;

BeamSection uniform_section(double length = beam_length) {
  return {length, beam_bending_stiffness, beam_mass_per_length};
}

BeamDescription uniform_beam(BeamEnd start, BeamEnd finish) {
  BeamDescription beam;
  beam.sections = {uniform_section()};
  beam.end_at_start = start, beam.end_at_finish = finish;
  return beam;
}

// λ = βL of the uniform beam at frequency f [Hz].
double dimensionless_root(double frequency_hz) {
  const double omega = 2 * pi * frequency_hz;
  return beam_length *
         std::pow(omega * omega * beam_mass_per_length / beam_bending_stiffness, 0.25);
}

std::vector<double> dimensionless_roots(const BeamDescription& beam, int count) {
  std::vector<double> roots = natural_frequencies_hz(beam, count);
  for (double& root : roots) root = dimensionless_root(root);
  return roots;
}

// The first `count` roots of g above `start`: sign changes on a grid, then bisection to adjacent
// doubles. Independent of the transfer-matrix code's root finder.
std::vector<double> roots_by_bisection(const std::function<double(double)>& g, int count,
                                       double start = 1e-3, double step = 1e-2) {
  std::vector<double> roots;
  for (double low = start; (int)roots.size() < count; low += step) {
    double a = low, b = low + step;
    if (std::signbit(g(a)) == std::signbit(g(b))) continue;
    for (double m = a + (b - a) / 2; m > a && m < b; m = a + (b - a) / 2)
      (std::signbit(g(m)) == std::signbit(g(a)) ? a : b) = m;
    roots.push_back(a);
  }
  return roots;
}

void expect_relative(const std::vector<double>& actual, const std::vector<double>& expected,
                     double tolerance, const char* what) {
  ASSERT_EQ(actual.size(), expected.size()) << what;
  for (size_t i = 0; i < actual.size(); ++i)
    for (size_t i = 0; i < actual.size(); ++i)
      EXPECT_NEAR(actual[i] / expected[i], 1, tolerance) << what << ", mode " << i + 1;
}

// 1. Uniform beams against textbook roots λ = βL (printed to 10 digits): 1e-9 relative in λ
// (measured 4e-10, the printed digits' rounding).
TEST(TransferMatrix, UniformBeamsMatchTextbookRoots) {
  const std::vector<double> cantilever(std::begin(cantilever_roots), std::end(cantilever_roots));
  expect_relative(dimensionless_roots(uniform_beam(BeamEnd::clamped, BeamEnd::free), 5), cantilever,
                  1e-9, "clamped-free");
  expect_relative(dimensionless_roots(uniform_beam(BeamEnd::pinned, BeamEnd::pinned), 5),
                  {pi, 2 * pi, 3 * pi, 4 * pi, 5 * pi}, 1e-9, "pinned-pinned");
  // High modes, where cosh βL ~ 1e26: pinned–pinned nπ and clamped–free (2n − 1)π/2 (whose
  // difference from the exact root, ~2e^{−λ}, is below 1e-14 relative from n = 10), 1e-12.
  std::vector<double> pinned_pinned_high, cantilever_high;
  for (int n = 1; n <= 20; ++n) pinned_pinned_high.push_back(n * pi);
  for (int n = 10; n <= 20; ++n) cantilever_high.push_back((2 * n - 1) * pi / 2);
  expect_relative(dimensionless_roots(uniform_beam(BeamEnd::pinned, BeamEnd::pinned), 20),
                  pinned_pinned_high, 1e-12, "pinned-pinned, 20 modes");
  std::vector<double> cantilever_20 =
      dimensionless_roots(uniform_beam(BeamEnd::clamped, BeamEnd::free), 20);
  cantilever_20.erase(cantilever_20.begin(), cantilever_20.begin() + 9);
  expect_relative(cantilever_20, cantilever_high, 1e-12, "clamped-free, modes 10 to 20");
  const std::vector<double> clamped_clamped = {4.730040745, 7.853204624, 10.99560784};
  expect_relative(dimensionless_roots(uniform_beam(BeamEnd::clamped, BeamEnd::clamped), 3),
                  clamped_clamped, 1e-9, "clamped-clamped");
  // Free–free: the two rigid-body modes are not returned; the elastic roots equal clamped–clamped.
  expect_relative(dimensionless_roots(uniform_beam(BeamEnd::free, BeamEnd::free), 3),
                  clamped_clamped, 1e-9, "free-free");
  expect_relative(dimensionless_roots(uniform_beam(BeamEnd::clamped, BeamEnd::pinned), 2),
                  {3.926602312, 7.068582745}, 1e-9, "clamped-pinned");
  // Pinned–free and sliding–free: tan λ = tanh λ again, after the rigid rocking/translation.
  expect_relative(dimensionless_roots(uniform_beam(BeamEnd::pinned, BeamEnd::free), 2),
                  {3.926602312, 7.068582745}, 1e-9, "pinned-free");
  expect_relative(dimensionless_roots(uniform_beam(BeamEnd::sliding, BeamEnd::free), 2),
                  {2.365020372, 5.497803919}, 1e-9, "sliding-free");
}

// The closed-form Euler–Bernoulli field matrix equals the matrix exponential of the same system
// (κGA = ∞, ρI = 0) entry by entry, relative to the largest entry of its row,
// to 1e-15 (measured 8e-17), from a very short section (series branch) to βl = 76.
TEST(TransferMatrix, EulerBernoulliFieldMatrixEqualsMatrixExponential) {
  const BeamSection section = uniform_section();
  for (double omega : {1e-4, 0.3, 40.0, 900.0, 2.0e4}) {
    for (double length : {1e-6, 0.01, 0.2, 0.8}) {
      const Matrix4 closed = euler_bernoulli_field_matrix(section, length, omega);
      const Matrix4 exponential = general_field_matrix(section, length, omega);
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          const long double scale = closed.row(i).cwiseAbs().maxCoeff();
          EXPECT_NEAR((double)(closed(i, j) / scale), (double)(exponential(i, j) / scale), 1e-15)
              << "omega " << omega << " length " << length << " entry " << i << j;
        }
    }
  }
}

// 2. Stepped beams.
BeamDescription stepped_cantilever() {
  BeamDescription beam;
  beam.sections = {{0.32, 5.1, 0.83}, {0.48, 1.7, 0.35}};
  return beam;
}

TEST(TransferMatrix, EqualSectionsEqualUniformBeam) {  // 1e-12 relative (measured 0), 15 modes
  for (BeamEnd end : {BeamEnd::free, BeamEnd::pinned}) {
    BeamDescription split = uniform_beam(BeamEnd::clamped, end);
    split.sections = {uniform_section(0.27), uniform_section(beam_length - 0.27)};
    expect_relative(natural_frequencies_hz(split, 15),
                    natural_frequencies_hz(uniform_beam(BeamEnd::clamped, end), 15), 1e-12,
                    "two equal sections");
  }
}

TEST(TransferMatrix, ExtraSplitDoesNotMoveSteppedBeamFrequencies) {  // 1e-11 (measured 4e-16)
  const BeamDescription beam = stepped_cantilever();
  const std::vector<double> reference = natural_frequencies_hz(beam, 15);
  BeamDescription split_sections = beam;
  split_sections.sections = {
      {0.1, 5.1, 0.83}, {0.22, 5.1, 0.83}, {0.4, 1.7, 0.35}, {0.08, 1.7, 0.35}};
  expect_relative(natural_frequencies_hz(split_sections, 15), reference, 1e-11, "sections split");
  BeamDescription empty_attachments = beam;
  empty_attachments.attachments = {{0.05}, {0.32}, {0.61}, {0.8}};
  expect_relative(natural_frequencies_hz(empty_attachments, 15), reference, 1e-11,
                  "split by attachments without mass or springs");
}

// Hermite cubic elements, consistent mass, clamped at x = 0. The Ritz quotients use the element
// strain energy in chord-relative end rotations θ_a = φ_a − Δw/h, θ_b = φ_b − Δw/h,
// U = (EI/2h)(4θ_a² + 4θ_aθ_b + 4θ_b²), free of the cancellation of K's raw quadratic form;
// eigenpairs by subspace iteration with K⁻¹M and a Rayleigh–Ritz step.
std::vector<double> hermite_cantilever_omegas(const BeamDescription& beam, int elements,
                                              int count) {
  std::vector<double> h, ei, rho_a;
  const double element_length = total_length(beam) / elements;
  for (const BeamSection& section : beam.sections)
    for (long n = std::lround(section.length / element_length); n > 0; --n)
      h.push_back(section.length / std::lround(section.length / element_length)),
          ei.push_back(section.bending_stiffness), rho_a.push_back(section.mass_per_length);
  const int dofs = 2 * (int)h.size();
  std::vector<Eigen::Triplet<double>> stiffness_entries, mass_entries;
  for (size_t e = 0; e < h.size(); ++e) {
    const double l = h[e], k = ei[e] / (l * l * l), m = rho_a[e] * l / 420;
    const double ke[4][4] = {{12 * k, 6 * l * k, -12 * k, 6 * l * k},
                             {6 * l * k, 4 * l * l * k, -6 * l * k, 2 * l * l * k},
                             {-12 * k, -6 * l * k, 12 * k, -6 * l * k},
                             {6 * l * k, 2 * l * l * k, -6 * l * k, 4 * l * l * k}};
    const double me[4][4] = {{156 * m, 22 * l * m, 54 * m, -13 * l * m},
                             {22 * l * m, 4 * l * l * m, 13 * l * m, -3 * l * l * m},
                             {54 * m, 13 * l * m, 156 * m, -22 * l * m},
                             {-13 * l * m, -3 * l * l * m, -22 * l * m, 4 * l * l * m}};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const int row = 2 * (int)e - 2 + i, col = 2 * (int)e - 2 + j;  // node 0 is clamped
        if (row < 0 || col < 0) continue;
        stiffness_entries.emplace_back(row, col, ke[i][j]);
        mass_entries.emplace_back(row, col, me[i][j]);
      }
  }
  Eigen::SparseMatrix<double> stiffness(dofs, dofs), mass(dofs, dofs);
  stiffness.setFromTriplets(stiffness_entries.begin(), stiffness_entries.end());
  mass.setFromTriplets(mass_entries.begin(), mass_entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(stiffness);
  const auto strain_energy_form = [&](const Eigen::MatrixXd& x) {
    Eigen::MatrixXd form = Eigen::MatrixXd::Zero(x.cols(), x.cols());
    for (size_t e = 0; e < h.size(); ++e) {
      Eigen::MatrixXd theta(2, x.cols());
      for (int c = 0; c < x.cols(); ++c) {
        const double wa = e == 0 ? 0 : x(2 * e - 2, c), pa = e == 0 ? 0 : x(2 * e - 1, c);
        const double chord = (x(2 * e, c) - wa) / h[e];
        theta(0, c) = pa - chord, theta(1, c) = x(2 * e + 1, c) - chord;
      }
      form +=
          ei[e] / h[e] * theta.transpose() * (Eigen::Matrix2d() << 4, 2, 2, 4).finished() * theta;
    }
    return form;
  };
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  Eigen::MatrixXd x =
      Eigen::MatrixXd::NullaryExpr(dofs, count + 4, [&] { return uniform(generator); });
  Eigen::VectorXd eigenvalues;
  for (int iteration = 0; iteration < 25; ++iteration) {
    const Eigen::MatrixXd y = factor.solve(mass * x);
    const Eigen::MatrixXd reduced_mass = y.transpose() * (mass * y);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ritz(strain_energy_form(y),
                                                                   reduced_mass);
    x = y * ritz.eigenvectors(), eigenvalues = ritz.eigenvalues();
  }
  std::vector<double> omegas;
  for (int i = 0; i < count; ++i) omegas.push_back(std::sqrt(eigenvalues(i)));
  return omegas;
}

// Stepped cantilever vs Hermite elements, N = 200 and 400 (section boundary on a node), Richardson
// with the h⁴ error of consistent-mass Hermite elements: 1e-11 relative over 4 modes (measured
// 4e-13; N = 400 alone: 4e-10, tolerance 1e-9).
TEST(TransferMatrix, SteppedCantileverMatchesFineHermiteElements) {
  const BeamDescription beam = stepped_cantilever();
  const std::vector<double> coarse = hermite_cantilever_omegas(beam, 200, 4);
  const std::vector<double> fine = hermite_cantilever_omegas(beam, 400, 4);
  std::vector<double> extrapolated;
  for (size_t i = 0; i < fine.size(); ++i)
    extrapolated.push_back(fine[i] + (fine[i] - coarse[i]) / 15);
  expect_relative(natural_angular_frequencies(beam, 4), extrapolated, 1e-11, "Hermite, Richardson");
  expect_relative(natural_angular_frequencies(beam, 4), fine, 1e-9, "Hermite, N = 400");
}

// 3. Tip mass μ ρA L: vs 1 + cos λ cosh λ + μλ(cos λ sinh λ − sin λ cosh λ) = 0, 1e-12 in λ
// (measured 2e-16).
TEST(TransferMatrix, TipMassMatchesFrequencyEquation) {
  for (double mass_ratio : {0.1, 1.0, 5.0}) {
    BeamDescription beam = uniform_beam(BeamEnd::clamped, BeamEnd::free);
    PointAttachment tip{beam_length};
    tip.mass = mass_ratio * beam_mass_per_length * beam_length;
    beam.attachments = {tip};
    expect_relative(dimensionless_roots(beam, 5),
                    roots_by_bisection(
                        [&](double l) { return tip_mass_cantilever_equation(l, mass_ratio); }, 5),
                    1e-12, "tip mass");
  }
}

// 4. Pinned root with a rotational spring K = k_θ L/EI, free tip: vs its frequency equation
// (1e-12 in λ; measured 2e-16), and f₁/f₁(clamped) = 0.743, 0.844, 0.912, 0.962 for K = 5, 10, 20,
// 50 to the 3 printed digits. (K = 20 gives 0.91248: 0.912, not 0.913.)
TEST(TransferMatrix, RotationalRootSpringMatchesFrequencyEquation) {
  const double ratios[] = {0.743, 0.844, 0.912, 0.962};
  const double stiffness_ratios[] = {5, 10, 20, 50};
  for (int i = 0; i < 4; ++i) {
    const double stiffness_ratio = stiffness_ratios[i];
    BeamDescription beam = uniform_beam(BeamEnd::pinned, BeamEnd::free);
    PointAttachment root{0};
    root.rotational_spring = stiffness_ratio * beam_bending_stiffness / beam_length;
    beam.attachments = {root};
    const std::vector<double> roots = dimensionless_roots(beam, 4);
    expect_relative(
        roots,
        roots_by_bisection(
            [&](double l) { return rotational_spring_root_equation(l, stiffness_ratio); }, 4),
        1e-12, "rotational root spring");
    EXPECT_NEAR(std::pow(roots[0] / cantilever_roots[0], 2), ratios[i], 5e-4)
        << "K " << stiffness_ratio;
  }
}

// 5. Simply supported Timoshenko beam: the shear-only closed form and the quadratic frequency
// equation with rotary inertia, 1e-13 relative (measured 4e-16), 5 modes (all below the cutoff
// √(κGA/ρI)).
TEST(TransferMatrix, SimplySupportedTimoshenkoMatchesClosedForms) {
  BeamSection section{1.0, 1.0, 1.0, 400.0, 0.0};
  for (double rotary_inertia : {0.0, 2e-3}) {
    section.rotary_inertia_per_length = rotary_inertia;
    BeamDescription beam;
    beam.sections = {section};
    beam.end_at_start = beam.end_at_finish = BeamEnd::pinned;
    std::vector<double> closed_form;
    for (int n = 1; n <= 5; ++n)
      closed_form.push_back(rotary_inertia == 0
                                ? simply_supported_shear_beam_omega(section, 1.0, n)
                                : simply_supported_timoshenko_omega(section, 1.0, n));
    expect_relative(natural_angular_frequencies(beam, 5), closed_form, 1e-13, "Timoshenko");
  }
  section.rotary_inertia_per_length = 0;  // the two closed forms agree without rotary inertia
  EXPECT_NEAR(simply_supported_timoshenko_omega(section, 1.0, 3) /
                  simply_supported_shear_beam_omega(section, 1.0, 3),
              1, 1e-14);
}

// 6. Translational spring k to ground at a cantilever's tip: λ₁ → 3.926602312 (clamped–pinned)
// as k → ∞, the gap falling like 1/k (7.3e-3, 7.3e-6, 7.3e-9): below 1e-8 relative at
// k = 1e9 EI/L³.
TEST(TransferMatrix, TipSpringTendsToClampedPinned) {
  double previous_gap = 1e300;
  for (double k : {1e3, 1e6, 1e9}) {
    BeamDescription beam = uniform_beam(BeamEnd::clamped, BeamEnd::free);
    PointAttachment tip{beam_length};
    tip.translational_spring = k * beam_bending_stiffness / std::pow(beam_length, 3);
    beam.attachments = {tip};
    const double gap = 1 - dimensionless_roots(beam, 1)[0] / 3.926602312;
    EXPECT_GT(gap, 0);
    EXPECT_LT(gap, previous_gap * 2e-3) << "k " << k;
    previous_gap = gap;
  }
  EXPECT_LT(previous_gap, 1e-8);
}

}  // namespace
}  // namespace emnet::test_reference
