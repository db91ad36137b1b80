// Beams made of components: sections, point masses, springs and Timoshenko segments, read from
// scene text and built into networks, against closed forms.
//
// Statics. Every segment network has exactly the flexibility of the exact massless segment
// (Euler–Bernoulli: the cubic Hermite element's; Timoshenko: plus l/(κGA) in the
// translational compliance), and the mesher puts a node at every section boundary, mass,
// spring and load, so nodal statics are exact for every N: the only error is the rounding of a
// sparse LU of a well-conditioned system, hence 1e-10 relative (as test_beam_static.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "emnet/analysis/analysis.hpp"
#include "emnet/model/mesh.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"

namespace emnet {
namespace {

constexpr double pi = 3.14159265358979323846;

// The static value of probe `name` of the scene text `text`.
double static_probe(const std::string& text, const std::string& name) {
  const Scene scene = read_scene_text(text, "test.toml");
  const Model model = prepare_model(scene);
  const System system = model.network.assemble();
  const StaticResult result = solve_static(system);
  EXPECT_TRUE(result.status.ok) << result.status.message;
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
  // each interval, none much longer than L/N (the greedy spread of 5, doubled: 4 and 6).
  int at_mass = -1;
  for (size_t k = 0; k < mesh.x.size(); ++k)
    if (mesh.x[k] == 0.33) at_mass = static_cast<int>(k);
  ASSERT_EQ(at_mass, 4);
  for (size_t k = 0; k + 1 < mesh.x.size(); ++k)
    EXPECT_NEAR(mesh.x[k + 1] - mesh.x[k], k < 4 ? 0.33 / 4 : 0.67 / 6, 1e-15);
  // 2N halves every segment: the N/2N error estimates compare nested meshes.
  beam.segments = 20;
  const BeamMesh doubled = mesh_beam(beam, {});
  ASSERT_EQ(doubled.segments(), 20);
  for (size_t k = 0; k < mesh.x.size(); ++k) EXPECT_NEAR(doubled.x[2 * k], mesh.x[k], 1e-15);
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
    const double k = n * pi / length;
    return k * k * std::sqrt(ei / rho_a) / std::sqrt(1 + k * k * ei / shear) / (2 * pi);
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
    ASSERT_TRUE(modes.status.ok) << modes.status.message;
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

}  // namespace
}  // namespace emnet
