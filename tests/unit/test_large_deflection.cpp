// Static large deflection (beam.kinematics = "large") against exact solutions.
//
// References:
//   - the circular arc of a cantilever under an end moment M (exact, any rotation): radius
//     R = EI/M, tip at x = R·sin(L/R), y = R·(1 − cos(L/R)); rotation ψ(x) = M·x/EI.
//     The network's own exact answer: the moment is M in every segment, so ψ at the nodes is
//     exact, each chord's angle is the mean of its ends' (no shear force) and the tip is the sum
//     of the chords, l·(cos θ_k, sin θ_k): the midpoint rule of ∫(cos ψ, sin ψ)dx, converging
//     as N⁻².
//   - the elastica under a dead tip load P (Bisshopp and Drucker, Q. Appl. Math. 3 (1945) 272):
//     with k² = (1 + sin ψ₀)/2, sin φ₁ = 1/(k·√2) and α = P·L²/EI,
//       √α = K(k) − F(k, φ₁),  y_tip/L = 1 − 2·(E(k) − E(k, φ₁))/√α,  x_tip/L = √(2·sin ψ₀/α),
//     ψ₀ the tip rotation (the root in k by bisection to rounding).
//   - the small-kinematics network in the small-load limit: the two agree to the geometric
//     nonlinearity, of relative order (w/L)².
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "elastica.hpp"
#include "emnet/elements/corotational_segment.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "fixtures.hpp"

namespace emnet {
namespace {

using testing::beam_probe;
using testing::cantilever_scene;
using testing::load;

constexpr double kLength = 0.5, kBendingStiffness = 2.0;

struct Tip {
  double x, y, rotation;  ///< x along the undeformed beam from the clamp [m], y [m], ψ [rad]
};

// The static tip of a large-kinematics cantilever of N segments under `loads`.
Tip large_tip(int segments, const std::vector<LoadSpec>& loads, StaticResult* solved = nullptr) {
  Scene scene = cantilever_scene(segments, kLength, kBendingStiffness);
  scene.beam.kinematics = BeamKinematics::large;
  scene.loads = loads;
  scene.probes = {beam_probe("u", ProbeQuantity::axial_displacement, kLength),
                  beam_probe("w", ProbeQuantity::deflection, kLength),
                  beam_probe("psi", ProbeQuantity::rotation, kLength)};
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const StaticResult result = solve_static(system);
  EXPECT_TRUE(result.status.ok()) << result.status.message;
  if (solved) *solved = result;
  return {kLength + static_probe_value(system, result, model.probes[0]),
          static_probe_value(system, result, model.probes[1]),
          static_probe_value(system, result, model.probes[2])};
}

// ---- the circular arc ---------------------------------------------------------------------

class CircularArc : public ::testing::TestWithParam<double> {};

// The network's tip is the midpoint rule of the arc to rounding (its own exact solution), and
// the rotation is exact: the only error is rounding in Newton's last step (tolerance 1e-12 on
// the step), so 1e-10 of L.
TEST_P(CircularArc, TipIsTheMidpointRuleOfTheArcAndTheRotationIsExact) {
  const double tip_angle = GetParam(), moment = tip_angle * kBendingStiffness / kLength;
  for (int segments : {8, 32}) {
    const Tip tip = large_tip(segments, {load(LoadKind::moment, kLength, moment)});
    const double l = kLength / segments;
    double x = 0.0, y = 0.0;
    for (int k = 0; k < segments; ++k) {
      const double chord_angle = moment * (k + 0.5) * l / kBendingStiffness;
      x += l * std::cos(chord_angle);
      y += l * std::sin(chord_angle);
    }
    EXPECT_NEAR(tip.rotation, tip_angle, 1e-10 * std::max(1.0, tip_angle)) << "N=" << segments;
    EXPECT_NEAR(tip.x, x, 1e-10 * kLength) << "N=" << segments;
    EXPECT_NEAR(tip.y, y, 1e-10 * kLength) << "N=" << segments;
  }
}

// Against the continuum arc: the error falls as N⁻² (the midpoint rule's order, measured from
// N = 16, 32, 64 between 1.95 and 2.05: its next term is of relative order N⁻²), and at N = 64
// it is within 1.2 times the Richardson estimate |f_64 − f_32|/3 that the N⁻² law gives.
TEST_P(CircularArc, ConvergesToTheArcAsNToTheMinusTwo) {
  const double tip_angle = GetParam(), moment = tip_angle * kBendingStiffness / kLength;
  const double radius = kBendingStiffness / moment;
  const double exact_x = radius * std::sin(tip_angle), exact_y = radius * (1 - std::cos(tip_angle));
  std::vector<double> error_x, error_y, tip_x, tip_y;
  for (int segments : {16, 32, 64}) {
    const Tip tip = large_tip(segments, {load(LoadKind::moment, kLength, moment)});
    tip_x.push_back(tip.x);
    tip_y.push_back(tip.y);
    error_x.push_back(tip.x - exact_x);
    error_y.push_back(tip.y - exact_y);
  }
  for (const auto& [error, values, name] :
       {std::tuple{error_x, tip_x, "x"}, std::tuple{error_y, tip_y, "y"}}) {
    if (std::abs(error[2]) < 1e-12 * kLength) continue;  // a tip coordinate that is exact
    const double order = std::log2(error[1] / error[2]);
    EXPECT_GT(order, 1.95) << name << " angle " << tip_angle;
    EXPECT_LT(order, 2.05) << name << " angle " << tip_angle;
    const double estimate = std::abs(values[2] - values[1]) / 3.0;
    EXPECT_LE(std::abs(error[2]), 1.2 * estimate) << name << " angle " << tip_angle;
  }
}

// Up to a full circle: a quarter, a half (tip above the clamp), and the whole (tip on it).
INSTANTIATE_TEST_SUITE_P(TipAngles, CircularArc, ::testing::Values(0.5, M_PI / 2, M_PI, 2 * M_PI));

// ---- the elastica under a dead tip load ------------------------------------------------------

struct Elastica {
  double x, y, rotation;  ///< the tip, relative to L, and ψ₀
};

// Bisshopp and Drucker's solution for α = P·L²/EI (see the top of the file).
Elastica elastica(double alpha) {
  auto length_parameter = [](double k) {
    const double phi1 = std::asin(1.0 / (k * std::sqrt(2.0)));
    return std::comp_ellint_1(k) - std::ellint_1(k, phi1);
  };
  double low = 1.0 / std::sqrt(2.0), high = 1.0;
  for (int i = 0; i < 200 && high - low > 1e-16; ++i) {
    const double middle = 0.5 * (low + high);
    (length_parameter(middle) < std::sqrt(alpha) ? low : high) = middle;
  }
  const double k = 0.5 * (low + high), phi1 = std::asin(1.0 / (k * std::sqrt(2.0)));
  const double sin_tip = 2 * k * k - 1;
  return {std::sqrt(2 * sin_tip / alpha),
          1 - 2 * (std::comp_ellint_2(k) - std::ellint_2(k, phi1)) / std::sqrt(alpha),
          std::asin(sin_tip)};
}

// The elliptic-integral reference against the shooting solution (elastica.hpp: EI·ψ'' = −P·cos ψ,
// Runge-Kutta, independent of the elliptic integrals), and against the linear limit
// (tip deflection α/3, rotation α/2; the next terms are of relative order α²).
TEST(ElasticaReference, EllipticIntegralsMatchShootingAndTheLinearLimit) {
  const Elastica tiny = elastica(1e-4);
  EXPECT_NEAR(tiny.y, 1e-4 / 3, 1e-11);
  EXPECT_NEAR(tiny.rotation, 1e-4 / 2, 1e-11);
  for (double alpha : {0.5, 1.0, 2.0, 5.0, 10.0}) {
    const Elastica elliptic = elastica(alpha);
    const testing::ElasticaTip shot = testing::elastica_by_shooting(0.0, alpha);
    EXPECT_NEAR(elliptic.x, shot.x, 1e-9) << alpha;
    EXPECT_NEAR(elliptic.y, shot.y, 1e-9) << alpha;
    EXPECT_NEAR(elliptic.rotation, shot.rotation, 1e-9) << alpha;
  }
}

class ElasticaTipLoad : public ::testing::TestWithParam<double> {};

// The network converges to the elastica as N⁻² (measured order from N = 16, 32, 64 between 1.9
// and 2.1) and at N = 64 its error is within 1.2 times the Richardson estimate.
TEST_P(ElasticaTipLoad, ConvergesToBisshoppAndDrucker) {
  const double alpha = GetParam(), force = alpha * kBendingStiffness / (kLength * kLength);
  const Elastica exact = elastica(alpha);
  std::vector<Tip> tips;
  for (int segments : {16, 32, 64})
    tips.push_back(large_tip(segments, {load(LoadKind::force, kLength, force)}));
  auto check = [&](double Tip::*coordinate, double reference, const char* name) {
    const double e16 = tips[0].*coordinate - reference, e32 = tips[1].*coordinate - reference,
                 e64 = tips[2].*coordinate - reference;
    const double order = std::log2(e32 / e64);
    EXPECT_GT(order, 1.9) << name << " alpha " << alpha << " e16 " << e16;
    EXPECT_LT(order, 2.1) << name << " alpha " << alpha;
    EXPECT_LE(std::abs(e64), 1.2 * std::abs(tips[2].*coordinate - tips[1].*coordinate) / 3.0)
        << name << " alpha " << alpha;
  };
  check(&Tip::x, exact.x * kLength, "x");
  check(&Tip::y, exact.y * kLength, "y");
  check(&Tip::rotation, exact.rotation, "rotation");
}

INSTANTIATE_TEST_SUITE_P(LoadParameters, ElasticaTipLoad,
                         ::testing::Values(0.5, 1.0, 2.0, 5.0, 10.0));

// ---- the small beam's stated geometric error ----------------------------------------------

// A small-kinematics result states its geometric error as (w/L)² of its largest deflection
// (emnet/model/validity.hpp). Against the exact solutions: under a tip force the linear tip
// deflection α/3 is off the elastica's by that much (the estimate is the elastica's: within
// 15 % of the true error at w = 0.05, 0.1 and 0.2·L); under an end moment the arc's error,
// ψ²/12 with ψ = 2w/L, is a third of it. With the largest rotation ψ the estimate is
// max((w/L)², ψ²): the elastica's tip turns by α/2 = 1.5·w/L, so its true error is 1/2.25 of
// the estimate (within 15 %), the arc's 1/12 of it (0.0833 to 3 digits: the next term is ψ⁴).
TEST(GeometricErrorEstimate, IsTheTipForceElasticasAndBoundsTheArcs) {
  Scene scene = cantilever_scene(4, kLength, kBendingStiffness);
  for (const double fraction : {0.05, 0.1, 0.2}) {
    const double linear = fraction * kLength;
    const Validity validity = check_validity(scene, {{"tip", linear}}, {});
    EXPECT_DOUBLE_EQ(validity.geometric_error, fraction * fraction);
    const double alpha = 3 * fraction;  // linear tip deflection α/3 of L
    const double elastica_error =
        std::abs(linear - elastica(alpha).y * kLength) / (elastica(alpha).y * kLength);
    EXPECT_NEAR(elastica_error / validity.geometric_error, 1.0, 0.15) << "w/L " << fraction;
    const double psi = 2 * fraction;  // the arc of the same linear tip deflection
    const double radius = kLength / psi;
    const double arc = radius * (1 - std::cos(psi));
    const double arc_error = (linear - arc) / arc;
    EXPECT_LT(arc_error, 0.4 * validity.geometric_error) << "w/L " << fraction;
    EXPECT_GT(arc_error, 0.3 * validity.geometric_error) << "w/L " << fraction;
    const Validity elastica_turned =
        check_validity(scene, {{"tip", linear}}, {}, RotationPeak{"x = L", alpha / 2});
    EXPECT_DOUBLE_EQ(elastica_turned.geometric_error, alpha * alpha / 4);
    EXPECT_NEAR(elastica_error / elastica_turned.geometric_error, 1 / 2.25, 0.15 / 2.25);
    const Validity arc_turned =
        check_validity(scene, {{"tip", linear}}, {}, RotationPeak{"x = L", psi});
    EXPECT_NEAR(arc_error / arc_turned.geometric_error, 1.0 / 12, 0.002) << "w/L " << fraction;
  }
  scene.beam.kinematics = BeamKinematics::large;
  EXPECT_EQ(check_validity(scene, {{"tip", 0.5 * kLength}}, {}).geometric_error, 0.0);
}

// ---- the small-load limit ---------------------------------------------------------------

// The nodal deflections and rotations of `scene` with small and with large kinematics.
struct BothKinematics {
  std::vector<double> small, large;
  double largest_deflection = 0.0;
};

// At the large model's nodes (it has one at every probe, which the small model may lack; the
// small model's shape functions are exact between its nodes).
BothKinematics solve_both(Scene scene) {
  BothKinematics both;
  std::vector<double> positions;
  for (BeamKinematics kinematics : {BeamKinematics::large, BeamKinematics::small}) {
    scene.beam.kinematics = kinematics;
    const Model model = build_model(scene);
    const System system = model.network.assemble();
    const StaticResult result = solve_static(system);
    EXPECT_TRUE(result.status.ok()) << scene.name << ": " << result.status.message;
    if (kinematics == BeamKinematics::large) positions = model.beam.x;
    std::vector<double>& values = kinematics == BeamKinematics::small ? both.small : both.large;
    for (double x : positions)
      for (ProbeQuantity quantity : {ProbeQuantity::deflection, ProbeQuantity::rotation}) {
        values.push_back(
            static_probe_value(system, result, model.make_probe(beam_probe("p", quantity, x))));
        if (quantity == ProbeQuantity::deflection)
          both.largest_deflection = std::max(both.largest_deflection, std::abs(values.back()));
      }
  }
  return both;
}

// Under loads that deflect the beam by about 1e-5 of its length, the large network's nodal
// deflections and rotations equal the small network's: the two differ by the geometric
// nonlinearity, of relative order (w/L)² = 1e-10, and by Newton's rounding (1e-12 on the step):
// 1e-8 of the largest value leaves room for both and for nothing else. Where both ends hold the
// beam along x, stretching stiffens it by a relative EA·w²/EI (the membrane effect), so those
// scenes are loaded to w ~ 1e-8 m, where that is 1e-11. Every end condition that
// has a static state, and every component of the beam: sections, Timoshenko shear, point masses,
// translational and rotational springs, Kelvin-Voigt damping (no static effect), an axial
// stiffness, loads and a DEA's moment pair (the fish fin, driven at 4 V instead of 4 kV).
TEST(LargeKinematicsSmallLoadLimit, EqualsTheSmallNetworkForEveryEndAndComponent) {
  std::vector<Scene> scenes;
  {
    Scene tip = cantilever_scene(8);
    tip.name = "clamped-free, tip force and moment";
    tip.loads = {load(LoadKind::force, 0.5, 1e-4), load(LoadKind::moment, 0.5, 2e-5)};
    scenes.push_back(tip);
  }
  {
    Scene shear = cantilever_scene(6);
    shear.name = "Timoshenko, axial stiffness, Kelvin-Voigt";
    shear.beam.theory = BeamTheory::timoshenko;
    shear.beam.shear_stiffness = 50.0;
    shear.beam.axial_stiffness = 1e4;
    shear.damping.kelvin_voigt_time = 1e-3;
    shear.loads = {load(LoadKind::force, 0.3, 1e-4)};
    scenes.push_back(shear);
  }
  {
    Scene parts = cantilever_scene(10);
    parts.name = "sections, a point mass and springs";
    SectionSpec stiff, soft;
    stiff.length = 0.2, stiff.bending_stiffness = 5.0, stiff.mass_per_length = 0.4;
    soft.length = 0.3, soft.bending_stiffness = 1.0, soft.mass_per_length = 0.2;
    parts.beam.sections = {stiff, soft};
    MassSpec mass;
    mass.at = 0.35, mass.mass = 0.01, mass.rotary_inertia = 1e-6;
    parts.beam.masses = {mass};
    SpringSpec translational, rotational;
    translational.at = 0.25, translational.stiffness = 30.0;
    rotational.at = 0.5, rotational.kind = SpringKind::rotational, rotational.stiffness = 0.5;
    parts.beam.springs = {translational, rotational};
    parts.loads = {load(LoadKind::force, 0.45, -1e-4)};
    scenes.push_back(parts);
  }
  for (const auto& [left, right] : {std::pair{EndCondition::pinned, EndCondition::pinned},
                                    std::pair{EndCondition::clamped, EndCondition::clamped},
                                    std::pair{EndCondition::clamped, EndCondition::sliding},
                                    std::pair{EndCondition::pinned, EndCondition::sliding}}) {
    Scene ends = cantilever_scene(9);
    ends.beam.left = left, ends.beam.right = right;
    ends.name = std::string(end_condition_name(left)) + "-" + end_condition_name(right);
    ends.loads = {load(LoadKind::force, 0.3, 1e-6), load(LoadKind::moment, 0.4, 1e-8)};
    ends.beam.axial_stiffness = 1e5;  // held along x at both ends: needs EA (see below)
    scenes.push_back(ends);
  }
  scenes.push_back(read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml",
                              {"drive.voltage=4 V", "drive.electrical_dynamics=false"}));
  for (const Scene& scene : scenes) {
    const BothKinematics both = solve_both(scene);
    ASSERT_EQ(both.small.size(), both.large.size()) << scene.name;
    EXPECT_GT(both.largest_deflection, 0.0) << scene.name;
    double largest = 0.0;
    for (double value : both.small) largest = std::max(largest, std::abs(value));
    for (size_t k = 0; k < both.small.size(); ++k)
      EXPECT_NEAR(both.large[k], both.small[k], 1e-8 * largest) << scene.name << " value " << k;
  }
}

// An elastic clamp (a free end held by translational, rotational and axial springs at x = 0,
// the tweezer's and the gripper's holder) with large kinematics: its small-load limit is the
// small network with the same translational and rotational springs (the axial one acts along x
// only, which the small network does not have), to 1e-8 as above. Without the axial spring the
// beam would be free along x and is refused; the small network refuses an axial spring.
TEST(LargeKinematicsEnds, AnElasticClampNeedsItsAxialSpring) {
  Scene scene = cantilever_scene(6);
  scene.beam.left = EndCondition::free;
  SpringSpec translational, rotational, axial;
  translational.stiffness = 500.0;
  rotational.kind = SpringKind::rotational;
  rotational.stiffness = 20.0;
  axial.kind = SpringKind::axial;
  axial.stiffness = 1e4;
  scene.beam.springs = {translational, rotational};
  scene.loads = {load(LoadKind::force, 0.5, 1e-4)};
  const BothKinematics without_axial_spring = [&] {
    Scene small = scene;
    small.beam.kinematics = BeamKinematics::small;
    BothKinematics both;
    const Model model = build_model(small);
    const System system = model.network.assemble();
    const StaticResult result = solve_static(system);
    EXPECT_TRUE(result.status.ok()) << result.status.message;
    for (double x : model.beam.x)
      for (ProbeQuantity quantity : {ProbeQuantity::deflection, ProbeQuantity::rotation})
        both.small.push_back(
            static_probe_value(system, result, model.make_probe(beam_probe("p", quantity, x))));
    return both;
  }();
  scene.beam.kinematics = BeamKinematics::large;
  EXPECT_THROW(build_model(scene), InputError);  // free along x
  scene.beam.springs.push_back(axial);
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const StaticResult result = solve_static(system);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  double largest = 0.0;
  for (double value : without_axial_spring.small) largest = std::max(largest, std::abs(value));
  size_t k = 0;
  for (double x : model.beam.x)
    for (ProbeQuantity quantity : {ProbeQuantity::deflection, ProbeQuantity::rotation})
      EXPECT_NEAR(
          static_probe_value(system, result, model.make_probe(beam_probe("p", quantity, x))),
          without_axial_spring.small[k++], 1e-8 * largest);
  scene.beam.kinematics = BeamKinematics::small;
  EXPECT_THROW(build_model(scene), std::logic_error);  // the reader refuses it first
}

// An inextensible beam held along x at both ends cannot deflect: refused, naming the key.
TEST(LargeKinematicsEnds, InextensibleBetweenTwoHeldEndsIsRefused) {
  Scene scene = cantilever_scene(4);
  scene.beam.kinematics = BeamKinematics::large;
  scene.beam.right = EndCondition::pinned;
  try {
    build_model(scene);
    FAIL() << "accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "beam.axial_stiffness");
  }
  scene.beam.axial_stiffness = 1e5;
  EXPECT_NO_THROW(build_model(scene));
  // Sections that each give their own EA make the beam extensible without beam.axial_stiffness;
  // one section without it leaves that section inextensible.
  SectionSpec first, second;
  first.length = second.length = 0.25;
  first.bending_stiffness = second.bending_stiffness = 2.0;
  first.mass_per_length = second.mass_per_length = 0.3;
  first.axial_stiffness = second.axial_stiffness = 1e5;
  scene.beam.axial_stiffness = 0.0;
  scene.beam.sections = {first, second};
  EXPECT_NO_THROW(build_model(scene));
  scene.beam.sections[1].axial_stiffness.reset();
  EXPECT_THROW(build_model(scene), InputError);
}

// The reader refuses a spring of kind "axial" with small kinematics, naming the key, and reads it
// with large.
TEST(LargeKinematicsProbes, AnAxialSpringNeedsLargeKinematics) {
  const std::string scene_text = R"([scene]
name = "clamp"
[beam]
length = 0.5
segments = 4
bending_stiffness = 2.0
mass_per_length = 0.3
left = "free"
KINEMATICS
[[spring]]
at = 0
kind = "translational"
stiffness = 100.0
[[spring]]
at = 0
kind = "rotational"
stiffness = 10.0
[[spring]]
at = 0
kind = "axial"
stiffness = 1000.0
)";
  auto with = [&](const std::string& kinematics) {
    std::string text = scene_text;
    text.replace(text.find("KINEMATICS"), 10, kinematics);
    return text;
  };
  try {
    read_scene_text(with(""), "clamp.toml");
    FAIL() << "accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "spring[2].kind");
  }
  EXPECT_NO_THROW(build_model(read_scene_text(with("kinematics = \"large\""), "clamp.toml")));
}

// A small-kinematics scene that asks for the axial displacement is refused (it has none at first
// order); a large one answers it.
TEST(LargeKinematicsProbes, AxialDisplacementNeedsLargeKinematics) {
  Scene scene = cantilever_scene(4);
  scene.probes = {beam_probe("u", ProbeQuantity::axial_displacement, 0.5)};
  EXPECT_THROW(build_model(scene), InputError);
  scene.beam.kinematics = BeamKinematics::large;
  EXPECT_NO_THROW(build_model(scene));
}

// ---- reactions ---------------------------------------------------------------------------

// The static values of `scene`'s probes, in order.
std::vector<double> static_probes(const Scene& scene) {
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  EXPECT_TRUE(rest.status.ok()) << scene.name << ": " << rest.status.message;
  std::vector<double> values;
  for (const Probe& probe : model.probes) values.push_back(static_probe_value(system, rest, probe));
  return values;
}

// The supports' forces and moments on the deflected beam balance its dead loads (the free body of
// the whole beam; the network's internal forces cancel exactly, so only Newton's residual,
// ~1e-12, is left: 1e-9 of the load):
//   cantilever, tip force P at α = 3 (tip 0.60·L across, 0.17·L in): R_y = −P, R_x = 0 and the
//   moment M = −(L + u_tip)·P, the load's arm shortened by the deflection (the small beam's
//   −L·P is 17 % off);
//   pinned–pinned with a soft axis (EA = 1e3 N), a force P at a = 0.2 m of 0.5 m deflecting it
//   by more than 5 % of its length: the ends pull along x with equal and opposite forces (the
//   membrane tension, here more than 0.1·P), R_y,0 + R_y,L = −P, and about the left pin L·R_y,L +
//   (a + u_a)·P = 0.
TEST(LargeKinematicsReactions, BalanceTheDeadLoadsOfTheDeflectedBeam) {
  {
    Scene tip = cantilever_scene(16);
    tip.name = "cantilever at alpha = 3";
    tip.beam.kinematics = BeamKinematics::large;
    const double p = 3.0 * 2.0 / (0.5 * 0.5);
    tip.loads = {load(LoadKind::force, 0.5, p)};
    tip.probes = {beam_probe("u", ProbeQuantity::axial_displacement, 0.5),
                  beam_probe("Ry", ProbeQuantity::reaction_force, 0.0),
                  beam_probe("Rx", ProbeQuantity::axial_reaction_force, 0.0),
                  beam_probe("M", ProbeQuantity::reaction_moment, 0.0)};
    const std::vector<double> v = static_probes(tip);
    EXPECT_NEAR(v[1], -p, 1e-9 * p);
    EXPECT_NEAR(v[2], 0.0, 1e-9 * p);
    EXPECT_NEAR(v[3], -(0.5 + v[0]) * p, 1e-9 * p * 0.5);
    EXPECT_LT(v[0], -0.1 * 0.5);  // the tip moved in: the arm is shorter
  }
  {
    Scene pinned = cantilever_scene(20);
    pinned.name = "pinned-pinned, soft axis";
    pinned.beam.kinematics = BeamKinematics::large;
    pinned.beam.left = pinned.beam.right = EndCondition::pinned;
    pinned.beam.axial_stiffness = 1e3;
    const double p = 60.0, a = 0.2, length = 0.5;
    pinned.loads = {load(LoadKind::force, a, p)};
    pinned.probes = {beam_probe("u", ProbeQuantity::axial_displacement, a),
                     beam_probe("w", ProbeQuantity::deflection, a),
                     beam_probe("Ry0", ProbeQuantity::reaction_force, 0.0),
                     beam_probe("RyL", ProbeQuantity::reaction_force, length),
                     beam_probe("Rx0", ProbeQuantity::axial_reaction_force, 0.0),
                     beam_probe("RxL", ProbeQuantity::axial_reaction_force, length)};
    const std::vector<double> v = static_probes(pinned);
    EXPECT_GT(v[1], 0.05 * length);
    EXPECT_LT(v[4], -0.1 * p);  // the left pin pulls the stretched beam back
    EXPECT_NEAR(v[4] + v[5], 0.0, 1e-9 * p);
    EXPECT_NEAR(v[2] + v[3], -p, 1e-9 * p);
    EXPECT_NEAR(length * v[3] + (a + v[0]) * p, 0.0, 1e-9 * p * length);
  }
}

// Under small loads the large network's reactions are the small network's (the geometric terms
// are of relative order (w/L)² = 1e-10: 1e-8 of the load), at either end, for a cantilever
// (R_y and M at the clamp) and a clamped–clamped beam with EA (both ends); the small network has
// no axial reaction and refuses it.
TEST(LargeKinematicsReactions, SmallLoadsGiveTheSmallNetworksReactions) {
  Scene tip = cantilever_scene(8);
  tip.loads = {load(LoadKind::force, 0.5, 1e-4), load(LoadKind::moment, 0.3, 2e-5)};
  tip.probes = {beam_probe("R", ProbeQuantity::reaction_force, 0.0),
                beam_probe("M", ProbeQuantity::reaction_moment, 0.0)};
  Scene both = cantilever_scene(9);
  both.beam.right = EndCondition::clamped;
  both.beam.axial_stiffness = 1e5;
  both.loads = {load(LoadKind::force, 0.3, 1e-6)};
  both.probes = {beam_probe("R0", ProbeQuantity::reaction_force, 0.0),
                 beam_probe("M0", ProbeQuantity::reaction_moment, 0.0),
                 beam_probe("RL", ProbeQuantity::reaction_force, 0.5),
                 beam_probe("ML", ProbeQuantity::reaction_moment, 0.5)};
  for (Scene scene : {tip, both}) {
    const std::vector<double> small = static_probes(scene);
    scene.beam.kinematics = BeamKinematics::large;
    const std::vector<double> large = static_probes(scene);
    double load_scale = 0.0;
    for (const LoadSpec& l : scene.loads) load_scale = std::max(load_scale, std::abs(l.value));
    ASSERT_EQ(small.size(), large.size());
    for (std::size_t k = 0; k < small.size(); ++k) {
      EXPECT_NE(small[k], 0.0) << scene.probes[k].name;
      EXPECT_NEAR(large[k], small[k], 1e-8 * load_scale) << scene.probes[k].name;
    }
  }
  tip.probes = {beam_probe("Rx", ProbeQuantity::axial_reaction_force, 0.0)};
  EXPECT_THROW(build_model(tip), InputError);
  // With large kinematics a reaction force is an output of the scene's probes only (the end
  // segment then carries it as unknowns): asked afterwards, it is refused naming the quantity.
  tip.probes.clear();
  tip.beam.kinematics = BeamKinematics::large;
  const Model without = build_model(tip);
  try {
    static_cast<void>(without.parse_probe("reaction_force@0"));
    ADD_FAILURE() << "a reaction force not asked by the scene was built";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "quantity");
  }
  EXPECT_NO_THROW(static_cast<void>(without.parse_probe("reaction_moment@0")));
}

}  // namespace
}  // namespace emnet

namespace emnet {
namespace {

// ---- beam.kinematics = "auto" ---------------------------------------------------------------

// The kinematics "auto" chose for `overrides` of `path` (beam.kinematics=auto added), prepared
// for `use`, and the choice.
std::pair<BeamKinematics, AutomaticChoice> automatic_kinematics(const std::string& path,
                                                                std::vector<std::string> overrides,
                                                                LargeKinematicsUse use) {
  overrides.push_back("beam.kinematics=auto");
  PrepareOptions options;
  options.large_kinematics = use;
  const Model model = prepare_model(read_scene(path, overrides), options);
  for (const AutomaticChoice& choice : model.automatic_choices)
    if (choice.key == "beam.kinematics") return {model.scene.beam.kinematics, choice};
  ADD_FAILURE() << "no choice for beam.kinematics";
  return {model.scene.beam.kinematics, {}};
}

// Large where the small beam's max((w/L)², ψ²) exceeds model.tolerance: the reference
// cantilever's tip load deflects it 4.17 % of L and turns its tip by P·L²/(2·EI) = 1.5·w/L
// (3.9e-3 > 1e-3), 40 N 167 %; with model.tolerance = 0.01 the default load stays small. The fish
// fin's tip rotation at resonance is estimated from its AC response (4/pi x its amplitude:
// 0.1497 rad, within 1 % of the periodic state's 0.1498 rad at 6.39 Hz, the rotation's peak over
// a 0.01 Hz sweep): large for the dynamics with EA, small without EA, for an analysis that
// refuses large kinematics, and at a hundredth of the drive's force (400 V).
TEST(KinematicsAuto, LargeWhereTheSmallBeamsGeometricErrorExceedsTheTolerance) {
  const std::string cantilever = std::string(EMNET_SOURCE_DIR) + "/netlists/cantilever.toml";
  const std::string fin = std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml";
  const auto stat = LargeKinematicsUse::static_state, dyn = LargeKinematicsUse::dynamics;
  const auto [loaded, choice] = automatic_kinematics(cantilever, {}, stat);
  EXPECT_EQ(loaded, BeamKinematics::large);
  EXPECT_NEAR(choice.estimated_error, std::pow(1.5 * 0.0417, 2), 1e-4);
  EXPECT_EQ(automatic_kinematics(cantilever, {"load[0].value=40 N"}, stat).first,
            BeamKinematics::large);
  EXPECT_EQ(automatic_kinematics(cantilever, {"model.tolerance=0.01"}, stat).first,
            BeamKinematics::small);
  const auto [resonant, fin_choice] =
      automatic_kinematics(fin, {"beam.axial_stiffness=200 kN"}, dyn);
  EXPECT_EQ(resonant, BeamKinematics::large);
  EXPECT_NEAR(std::sqrt(fin_choice.estimated_error), 0.1498, 0.01 * 0.1498);
  const auto without_ea = automatic_kinematics(fin, {}, dyn);
  EXPECT_EQ(without_ea.first, BeamKinematics::small);
  EXPECT_NE(without_ea.second.reason.find("beam.axial_stiffness"), std::string::npos);
  EXPECT_EQ(
      automatic_kinematics(fin, {"beam.axial_stiffness=200 kN"}, LargeKinematicsUse::refused).first,
      BeamKinematics::small);
  EXPECT_EQ(
      automatic_kinematics(fin, {"beam.axial_stiffness=200 kN", "drive.voltage=400 V"}, dyn).first,
      BeamKinematics::small);
}

// "auto" is read as a value of beam.kinematics, and the keys only large kinematics use
// (beam.axial_stiffness, a spring of kind "axial") are accepted with it.
TEST(KinematicsAuto, TheLargeOnlyKeysAreAcceptedWithAuto) {
  const std::string fin = std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml";
  const Scene scene = read_scene(fin, {"beam.kinematics=auto", "beam.axial_stiffness=1 kN"});
  EXPECT_TRUE(scene.beam.kinematics_auto);
  EXPECT_EQ(scene.beam.kinematics, BeamKinematics::small);
  EXPECT_EQ(unresolved_keys(scene), std::vector<std::string>{"beam.kinematics"});
}

}  // namespace
}  // namespace emnet
