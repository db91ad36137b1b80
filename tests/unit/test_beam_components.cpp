// Beams made of components: sections, point masses, springs and Timoshenko segments, read from
// scene text and built into networks, against closed forms.
//
// Dynamics. The exact continuum frequencies of the same beam come from the transfer-matrix
// method (tests/unit/transfer_matrix.hpp, an independent reference checked against the textbook
// roots) or from a closed-form frequency equation solved here by bisection. The network lumps
// half of each segment's mass at its ends, so its frequencies converge as O(N⁻²): each test
// checks that doubling N divides the error by 4 (to 15 %: the ratio tends to 4 from a few
// percent off at these N) and bounds the error at the finest N at about twice the measured one
// (measured at N = 80: stepped beam 1.1e-4, 2.7e-4, 5.3e-4; tip mass 1.6e-5, 2.5e-5; rotational
// root spring 6.2e-5, 2.2e-4; elastic clamp 5.3e-5, 2.3e-4, 2.9e-4).
//
// Statics. Every segment network has exactly the flexibility of the exact massless segment
// (Euler–Bernoulli: the cubic Hermite element's; Timoshenko: plus l/(κGA) in the
// translational compliance), and the mesher puts a node at every section boundary, mass,
// spring and load, so nodal statics are exact for every N: the only error is the rounding of a
// sparse LU of a well-conditioned system, hence 1e-10 relative (as test_beam_static.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/model/mesh.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "shipped_scenes.hpp"
#include "transfer_matrix.hpp"

namespace emnet {
namespace {

using emnet::testing::kPi;

// The static value of probe `name` of the scene text `text`.
double static_probe(const std::string& text, const std::string& name) {
  const Scene scene = read_scene_text(text, "test.toml");
  const Model model = prepare_model(scene);
  const System system = model.network.assemble();
  const StaticResult result = solve_static(system);
  EXPECT_TRUE(result.status.ok()) << result.status.message;
  for (const Probe& probe : model.probes)
    if (probe.name == name) return static_probe_value(system, result, probe);
  ADD_FAILURE() << "no probe " << name;
  return 0.0;
}

std::string header(const std::string& beam_keys) {
  return "[scene]\nname = \"t\"\n[beam]\nlength = 0.5\nleft = \"clamped\"\nright = \"free\"\n" +
         beam_keys + "\n";
}

// ---- the mesher -----------------------------------------------------------------------------

TEST(Mesh, UniformGridKeptWhenEveryAttachmentIsOnIt) {
  // The fish fin: N = 7 and DEA ends at 0 and 70 mm = 4/7 of 122.5 mm: the grid L·k/N, bit for
  // bit (shipped scenes keep their networks).
  BeamSpec beam;
  beam.length = 0.1225;
  beam.segments = 7;
  const BeamMesh mesh = mesh_beam(beam, {0.0, 0.07, 0.07, 0.1225});
  ASSERT_TRUE(mesh.uniform);
  ASSERT_EQ(mesh.segments(), 7);
  for (int k = 0; k <= 7; ++k) EXPECT_EQ(mesh.x[static_cast<size_t>(k)], 0.1225 * k / 7);
}

TEST(Mesh, NodeAtEveryAttachmentAndSegmentsSpreadByLength) {
  BeamSpec beam;
  beam.length = 1.0;
  beam.segments = 10;
  MassSpec mass;
  mass.at = 0.33;
  beam.masses.push_back(mass);
  const BeamMesh mesh = mesh_beam(beam, {});
  EXPECT_FALSE(mesh.uniform);
  EXPECT_EQ(mesh.segments(), 10);
  EXPECT_EQ(mesh.raised_from, 0);
  // 0.33 m and 0.67 m share 10 segments by length: a node at the mass, equal segments within
  // each interval, the longest as short as ten can make it (3 and 7: 0.110 m and 0.0957 m;
  // 4 and 6 would leave 0.112 m).
  int at_mass = -1;
  for (size_t k = 0; k < mesh.x.size(); ++k)
    if (mesh.x[k] == 0.33) at_mass = static_cast<int>(k);
  ASSERT_EQ(at_mass, 3);
  for (size_t k = 0; k + 1 < mesh.x.size(); ++k)
    EXPECT_NEAR(mesh.x[k + 1] - mesh.x[k], k < 3 ? 0.33 / 3 : 0.67 / 7, 1e-15);
  // Refinement 2 halves every segment: the N/2N error estimates compare nested meshes.
  beam.refinement = 2;
  const BeamMesh doubled = mesh_beam(beam, {});
  ASSERT_EQ(doubled.segments(), 20);
  for (size_t k = 0; k < mesh.x.size(); ++k) EXPECT_EQ(doubled.x[2 * k], mesh.x[k]);
  for (size_t k = 0; k + 1 < mesh.x.size(); ++k)
    EXPECT_NEAR(doubled.x[2 * k + 1], 0.5 * (mesh.x[k] + mesh.x[k + 1]), 1e-15);
}

TEST(Mesh, SectionsWithTheirOwnCountsAndMoreIntervalsThanSegments) {
  BeamSpec beam;
  beam.length = 0.06;
  beam.segments = 8;
  SectionSpec body, tip;
  body.length = 0.04;
  body.segments = 4;
  tip.length = 0.02;
  beam.sections = {body, tip};
  SpringSpec spring;
  spring.at = 0.05;
  beam.springs.push_back(spring);
  const BeamMesh mesh = mesh_beam(beam, {0.01});
  // Body: its own 4 segments over [0, 0.01] and [0.01, 0.04]; the tip the other 4 of 8 over
  // [0.04, 0.05] and [0.05, 0.06].
  EXPECT_EQ(mesh.segments(), 8);
  EXPECT_EQ(mesh.raised_from, 0);
  int body_segments = 0;
  for (int s : mesh.section) body_segments += s == 0 ? 1 : 0;
  EXPECT_EQ(body_segments, 4);
  beam.sections[0].segments = 0;
  beam.segments = 2;
  const BeamMesh raised = mesh_beam(beam, {0.01});
  EXPECT_EQ(raised.segments(), 4);  // one per interval: [0,.01], [.01,.04], [.04,.05], [.05,.06]
  EXPECT_EQ(raised.raised_from, 2);
}

// ---- stepped cantilever statics ----------------------------------------------------------

// Tip force F on a cantilever of EI1 over [0, a] and EI2 over [a, L], by the unit-load method:
//   w(L) = F·[(L³ − (L − a)³)/(3·EI1) + (L − a)³/(3·EI2)].
TEST(SteppedCantilever, TipDeflectionExactForEveryN) {
  const double force = 1.3, length = 0.5, a = 0.3, ei1 = 2.0, ei2 = 0.5;
  const double exact = force * ((std::pow(length, 3) - std::pow(length - a, 3)) / (3 * ei1) +
                                std::pow(length - a, 3) / (3 * ei2));
  for (int segments : {2, 3, 7, 20}) {
    const std::string text =
        header("segments = " + std::to_string(segments)) +
        "[[section]]\nlength = 0.3\nbending_stiffness = 2.0\nmass_per_length = 0.3\n"
        "[[section]]\nlength = 0.2\nbending_stiffness = 0.5\nmass_per_length = 0.1\n"
        "[[load]]\nkind = \"force\"\nat = 0.5\nvalue = 1.3\n"
        "[[probe]]\nname = \"tip\"\nquantity = \"deflection\"\nat = 0.5\n";
    EXPECT_NEAR(static_probe(text, "tip"), exact, 1e-10 * exact) << "N = " << segments;
  }
}

// ---- Timoshenko ----------------------------------------------------------------------------

// Cantilever, tip force F: w(L) = F·L³/(3EI) + F·L/(κGA) (bending plus shear), for every N.
TEST(Timoshenko, CantileverTipDeflectionExactForEveryN) {
  const double force = 1.3, length = 0.5, ei = 2.0, shear = 40.0;
  const double exact = force * std::pow(length, 3) / (3 * ei) + force * length / shear;
  for (int segments : {1, 3, 10}) {
    const std::string text =
        header("segments = " + std::to_string(segments) +
               "\nbending_stiffness = 2.0\nmass_per_length = 0.3\ntheory = \"timoshenko\"\n"
               "shear_stiffness = 40.0") +
        "[[load]]\nkind = \"force\"\nat = 0.5\nvalue = 1.3\n"
        "[[probe]]\nname = \"tip\"\nquantity = \"deflection\"\nat = 0.5\n"
        "[[probe]]\nname = \"mid\"\nquantity = \"deflection\"\nat = 0.2\n";
    EXPECT_NEAR(static_probe(text, "tip"), exact, 1e-10 * exact) << "N = " << segments;
    // Inside a segment too (N = 1, 3): the shear-corrected shape functions are the exact
    // massless segment's, w(x) = F·x²·(3L − x)/(6EI) + F·x/(κGA).
    const double x = 0.2;
    const double mid = force * x * x * (3 * length - x) / (6 * ei) + force * x / shear;
    EXPECT_NEAR(static_probe(text, "mid"), mid, 1e-10 * exact) << "N = " << segments;
  }
}

// Simply supported Timoshenko beam without rotary inertia (shear only): the continuum
// frequencies are ω_n = ω_n,EB / sqrt(1 + (nπ/L)²·EI/(κGA)), ω_n,EB = (nπ/L)²·sqrt(EI/ρA).
// The lumped-mass network converges to them as O(N⁻²): the error at 2N is a quarter of the
// error at N (to 10 %), and at N = 160 below 1e-4 for the first three modes.
TEST(Timoshenko, SimplySupportedFrequenciesConvergeToTheShearBeam) {
  const double length = 0.5, ei = 2.0, rho_a = 0.3, shear = 400.0;
  auto exact_hz = [&](int n) {
    const double k = n * kPi / length;
    return k * k * std::sqrt(ei / rho_a) / std::sqrt(1 + k * k * ei / shear) / (2 * kPi);
  };
  std::vector<std::vector<double>> errors;
  for (int segments : {40, 80, 160}) {
    const std::string text =
        "[scene]\nname = \"t\"\n[beam]\nlength = 0.5\nleft = \"pinned\"\nright = \"pinned\"\n"
        "segments = " +
        std::to_string(segments) +
        "\nbending_stiffness = 2.0\nmass_per_length = 0.3\ntheory = \"timoshenko\"\n"
        "shear_stiffness = 400.0\n";
    const Model model = prepare_model(read_scene_text(text, "test.toml"));
    const System system = model.network.assemble();
    ModalOptions options;
    options.count = 3;
    const ModalResult modes = run_modes(system, Eigen::VectorXd::Zero(system.size()), options);
    ASSERT_TRUE(modes.status.ok()) << modes.status.message;
    ASSERT_GE(modes.modes.size(), 3u);
    std::vector<double> error;
    for (int n = 1; n <= 3; ++n)
      error.push_back(
          std::abs(modes.modes[static_cast<size_t>(n - 1)].frequency_hz / exact_hz(n) - 1));
    errors.push_back(error);
  }
  for (size_t n = 0; n < 3; ++n) {
    EXPECT_NEAR(errors[0][n] / errors[1][n], 4.0, 0.4) << "mode " << n + 1;
    EXPECT_NEAR(errors[1][n] / errors[2][n], 4.0, 0.4) << "mode " << n + 1;
    EXPECT_LT(errors[2][n], 1e-4) << "mode " << n + 1;
  }
}

// ---- dynamics against the continuum -------------------------------------------------------

// The lowest `count` undamped frequencies [Hz] of the scene text.
std::vector<double> network_frequencies(const std::string& text, int count) {
  const Model model = prepare_model(read_scene_text(text, "test.toml"));
  const System system = model.network.assemble();
  ModalOptions options;
  options.count = count;
  options.keep_vectors = false;
  const ModalResult modes = run_modes(system, Eigen::VectorXd::Zero(system.size()), options);
  EXPECT_TRUE(modes.status.ok()) << modes.status.message;
  std::vector<double> frequencies;
  for (const Mode& mode : modes.modes) frequencies.push_back(mode.frequency_hz);
  frequencies.resize(static_cast<size_t>(count), 0.0);
  return frequencies;
}

// Relative errors of the network's first `exact.size()` frequencies at N = 20, 40, 80 (scene
// text from `scene_of(N)`): O(N⁻²) convergence, and at N = 80 below `finest_bound`.
void expect_second_order_convergence(const std::function<std::string(int)>& scene_of,
                                     const std::vector<double>& exact, double finest_bound) {
  std::vector<std::vector<double>> errors;
  for (int segments : {20, 40, 80}) {
    const std::vector<double> f =
        network_frequencies(scene_of(segments), static_cast<int>(exact.size()));
    std::vector<double> error;
    for (size_t n = 0; n < exact.size(); ++n) error.push_back(std::abs(f[n] / exact[n] - 1));
    errors.push_back(error);
  }
  for (size_t n = 0; n < exact.size(); ++n) {
    ::testing::Test::RecordProperty("mode" + std::to_string(n + 1) + "_errors_N20_40_80",
                                    std::to_string(errors[0][n]) + " " +
                                        std::to_string(errors[1][n]) + " " +
                                        std::to_string(errors[2][n]));
    EXPECT_NEAR(errors[0][n] / errors[1][n], 4.0, 0.6) << "mode " << n + 1;
    EXPECT_NEAR(errors[1][n] / errors[2][n], 4.0, 0.6) << "mode " << n + 1;
    EXPECT_LT(errors[2][n], finest_bound) << "mode " << n + 1;
  }
}

// λ in [low, high] where `equation` changes sign, by bisection to adjacent doubles.
double bisect(const std::function<double(double)>& equation, double low, double high) {
  const bool low_sign = std::signbit(equation(low));
  EXPECT_NE(low_sign, std::signbit(equation(high))) << "no sign change in the bracket";
  for (;;) {
    const double middle = low + (high - low) / 2;
    if (middle <= low || middle >= high) return middle;
    (std::signbit(equation(middle)) == low_sign ? low : high) = middle;
  }
}

const char* kSteppedSections =
    "[[section]]\nlength = 0.3\nbending_stiffness = 2.0\nmass_per_length = 0.3\n"
    "[[section]]\nlength = 0.2\nbending_stiffness = 0.5\nmass_per_length = 0.1\n";

// Two-section stepped cantilever: the transfer-matrix continuum, first three modes.
TEST(SteppedCantilever, ModesConvergeAsNToTheMinus2ToTheContinuum) {
  test_reference::BeamDescription beam;
  beam.sections = {{0.3, 2.0, 0.3}, {0.2, 0.5, 0.1}};
  const std::vector<double> exact = test_reference::natural_frequencies_hz(beam, 3);
  expect_second_order_convergence(
      [](int n) { return header("segments = " + std::to_string(n)) + kSteppedSections; }, exact,
      1e-3);
}

// Cantilever with a tip mass μ·ρA·L: 1 + cos λ cosh λ + μλ(cos λ sinh λ − sin λ cosh λ) = 0,
// f = λ²/(2πL²)·√(EI/ρA); μ = 1 (0.15 kg on a 0.15 kg beam).
TEST(TipMassCantilever, FirstModesConvergeToTheFrequencyEquation) {
  const double length = 0.5, ei = 2.0, rho_a = 0.3, mu = 1.0;
  auto equation = [mu](double lambda) {
    return test_reference::tip_mass_cantilever_equation(lambda, mu);
  };
  std::vector<double> exact;
  for (const auto& [low, high] : {std::pair{0.5, 2.0}, std::pair{3.0, 5.0}}) {
    const double lambda = bisect(equation, low, high);
    exact.push_back(lambda * lambda / (2 * kPi * length * length) * std::sqrt(ei / rho_a));
  }
  // The transfer matrix agrees (its point-mass matrix, independently of the equation).
  test_reference::BeamDescription beam;
  beam.sections = {{length, ei, rho_a}};
  beam.attachments = {{length, mu * rho_a * length}};
  const std::vector<double> by_transfer = test_reference::natural_frequencies_hz(beam, 2);
  for (size_t n = 0; n < 2; ++n) EXPECT_NEAR(by_transfer[n], exact[n], 1e-9 * exact[n]);
  expect_second_order_convergence(
      [](int n) {
        return header("segments = " + std::to_string(n) +
                      "\nbending_stiffness = 2.0\nmass_per_length = 0.3") +
               "[[mass]]\nname = \"tip\"\nat = 0.5\nmass = 0.15\n";
      },
      exact, 5e-5);
}

// Pinned root held by a rotational spring K = k_θ·L/EI, free tip:
// K·(1 + cos λ cosh λ) − λ·(sin λ cosh λ − cos λ sinh λ) = 0; K = 10 gives f/f_clamped = 0.844.
TEST(RotationalRootSpring, FirstModesConvergeToTheFrequencyEquation) {
  const double length = 0.5, ei = 2.0, rho_a = 0.3, stiffness_ratio = 10.0;
  auto equation = [&](double lambda) {
    return test_reference::rotational_spring_root_equation(lambda, stiffness_ratio);
  };
  std::vector<double> exact;
  for (const auto& [low, high] : {std::pair{0.5, 1.875}, std::pair{3.0, 4.69}}) {
    const double lambda = bisect(equation, low, high);
    exact.push_back(lambda * lambda / (2 * kPi * length * length) * std::sqrt(ei / rho_a));
  }
  const double clamped = std::pow(test_reference::cantilever_roots[0], 2) /
                         (2 * kPi * length * length) * std::sqrt(ei / rho_a);
  EXPECT_NEAR(exact[0] / clamped, 0.844, 5e-4);
  const double k_theta = stiffness_ratio * ei / length;  // 40 N*m/rad
  expect_second_order_convergence(
      [k_theta](int n) {
        return "[scene]\nname = \"t\"\n[beam]\nlength = 0.5\nleft = \"pinned\"\n"
               "right = \"free\"\nsegments = " +
               std::to_string(n) +
               "\nbending_stiffness = 2.0\nmass_per_length = 0.3\n"
               "[[spring]]\nname = \"clamp\"\nat = 0\nkind = \"rotational\"\nstiffness = " +
               std::to_string(k_theta) + "\n";
      },
      exact, 5e-4);
}

// An elastic clamp: a free end held by a translational and a rotational spring at x = 0, with a
// point mass inside the beam; the transfer-matrix continuum with the same point matrices.
TEST(ElasticClamp, ModesConvergeToTheTransferMatrixContinuum) {
  test_reference::BeamDescription beam;
  beam.sections = {{0.5, 2.0, 0.3}};
  beam.end_at_start = test_reference::BeamEnd::free;
  test_reference::PointAttachment clamp;
  clamp.translational_spring = 2e4;
  clamp.rotational_spring = 60.0;
  test_reference::PointAttachment sensor;
  sensor.position = 0.35;
  sensor.mass = 0.02;
  sensor.rotary_inertia = 1e-5;
  beam.attachments = {clamp, sensor};
  const std::vector<double> exact = test_reference::natural_frequencies_hz(beam, 3);
  expect_second_order_convergence(
      [](int n) {
        return "[scene]\nname = \"t\"\n[beam]\nlength = 0.5\nleft = \"free\"\n"
               "right = \"free\"\nsegments = " +
               std::to_string(n) +
               "\nbending_stiffness = 2.0\nmass_per_length = 0.3\n"
               "[[spring]]\nat = 0\nkind = \"translational\"\nstiffness = \"2e4 N/m\"\n"
               "[[spring]]\nat = 0\nkind = \"rotational\"\nstiffness = \"60 N*m/rad\"\n"
               "[[mass]]\nat = 0.35\nmass = \"20 g\"\nrotary_inertia = \"1e-5 kg*m^2\"\n";
      },
      exact, 6e-4);
}

// The static tip deflection of the cantilever (EI 2, 0.5 m) with `spring` lines and a tip force
// of 1.3 N, cut into `segments`.
double tip_deflection_with_spring(const std::string& spring, int segments) {
  return static_probe(header("segments = " + std::to_string(segments) +
                             "\nbending_stiffness = 2.0\nmass_per_length = 0.3") +
                          "[[spring]]\n" + spring +
                          "[[load]]\nkind = \"force\"\nat = 0.5\nvalue = 1.3\n"
                          "[[probe]]\nname = \"tip\"\nquantity = \"deflection\"\nat = 0.5\n",
                      "tip");
}

// A translational spring k to ground at the tip of a cantilever: the tip deflection under a
// tip force F is F/(k + 3EI/L³) (the spring and the beam in parallel).
TEST(SpringSupport, TipSpringSharesTheLoadExactly) {
  const double force = 1.3, length = 0.5, ei = 2.0, k = 50.0;
  const double exact = force / (k + 3 * ei / std::pow(length, 3));
  for (int segments : {1, 4})
    EXPECT_NEAR(tip_deflection_with_spring("at = 0.5\nkind = \"translational\"\nstiffness = "
                                           "50\ndamping = 0.1\n",
                                           segments),
                exact, 1e-10 * exact)
        << "N = " << segments;
}

// A translational spring between two points of the beam, x = 0.2 and the tip, on a cantilever
// with a tip force: a spring of stiffness k between the tip and x = a carries the force S that
// makes w(L) − w(a) = S/k, with w from superposing F − S at the tip and S at a (unit loads:
// δ(x, b) = x²(3b − x)/(6EI) for x ≤ b): S = k·(F·(δLL − δaL)) / (1 + k·(δLL − 2δaL + δaa)).
TEST(SpringSupport, SpringBetweenTwoPointsCarriesItsShareExactly) {
  const double force = 1.3, length = 0.5, ei = 2.0, a = 0.2, k = 80.0;
  auto delta = [ei](double x, double b) {  // deflection at x ≤ b under a unit force at b
    return x * x * (3 * b - x) / (6 * ei);
  };
  const double d_ll = delta(length, length), d_al = delta(a, length), d_aa = delta(a, a);
  const double spring = k * force * (d_ll - d_al) / (1 + k * (d_ll - 2 * d_al + d_aa));
  const double exact = (force - spring) * d_ll + spring * d_al;
  for (int segments : {1, 5})
    EXPECT_NEAR(tip_deflection_with_spring(
                    "at = 0.5\nto = 0.2\nkind = \"translational\"\nstiffness = 80\n", segments),
                exact, 1e-10 * exact)
        << "N = " << segments;
}

}  // namespace
}  // namespace emnet
