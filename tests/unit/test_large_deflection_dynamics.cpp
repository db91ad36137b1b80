// Modes, AC and IDA transients with large kinematics (beam.kinematics = "large") against exact
// solutions.
//
// References:
//   - the tangent stiffness of the exact elastica: a massless cantilever carrying a point mass m
//     at its tip, deflected by a dead tip load, vibrates about that state with ω² = the smallest
//     eigenvalue of K/m, K = C⁻¹ the tip's 2×2 tangent stiffness, C = ∂(x, y)/∂(P_x, P_y) the
//     tip's compliance, by central differences of the elastica EI·ψ'' = −P_y·cos ψ + P_x·sin ψ
//     solved by shooting (elastica.hpp); the AC response to a tip
//     force at a frequency far below the mode is that compliance;
//   - a rigid bar on a torsion spring k with a tip mass m under a step moment M: the exact angle
//     θ(t) = (M/k)·(1 − cos ωt), ω² = k/(m·L²), at any amplitude (the mass moves on the circle,
//     its inertia about the pivot is m·L² at every angle), the tip at L·(cos θ, sin θ);
//   - the energy of an undamped free vibration, constant;
//   - identify's round trip: the stiffness whose deflected state has a given first mode.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "elastica.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/elements/corotational_segment.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/studies/identify.hpp"
#include "emnet/studies/resolve.hpp"
#include "fixtures.hpp"

namespace emnet {
namespace {

using testing::beam_probe;
using testing::cantilever_scene;
using testing::kBeamLength;
using testing::kBeamStiffness;
using testing::kTipMass;
using testing::load;
using testing::tip_mass_cantilever;

// ---- the tangent stiffness of the elastica ------------------------------------------------

// The tip compliance C = ∂(x, y)/∂(P_x, P_y) at the dead load (0, α) (lengths in L, forces in
// EI/L²), by central differences of step 1e-4·α (their error, of order 1e-8·C, is below what the
// tests resolve).
std::array<double, 4> elastica_tip_compliance(double alpha) {
  const double h = 1e-4 * alpha;
  using testing::elastica_by_shooting;
  const testing::ElasticaTip x_plus = elastica_by_shooting(h, alpha),
                             x_minus = elastica_by_shooting(-h, alpha),
                             y_plus = elastica_by_shooting(0, alpha + h),
                             y_minus = elastica_by_shooting(0, alpha - h);
  return {(x_plus.x - x_minus.x) / (2 * h), (y_plus.x - y_minus.x) / (2 * h),
          (x_plus.y - x_minus.y) / (2 * h), (y_plus.y - y_minus.y) / (2 * h)};
}

// The first frequency [Hz] of the deflected network, and its AC tip response (x, y) per unit
// tip force at 1e-6 of it (where the dynamic part of the response is 1e-12 of it).
struct Linearised {
  double frequency = 0.0;
  double compliance_x = 0.0, compliance_y = 0.0;
};

Linearised linearise(int segments, double alpha) {
  const Scene scene = tip_mass_cantilever(segments, alpha);
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  EXPECT_TRUE(rest.status.ok()) << rest.status.message;
  ModalOptions options;
  options.count = 1;
  const ModalResult modes = run_modes(system, rest.operating_point, options);
  EXPECT_TRUE(modes.status.ok()) << modes.status.message;
  Linearised result;
  if (modes.modes.empty()) return result;
  result.frequency = modes.modes[0].natural_frequency_hz;
  const double force = scene.loads[0].value;  // also the AC magnitude
  const AcResult ac = run_ac(system, rest.operating_point, {1e-6 * result.frequency}, model.probes);
  EXPECT_TRUE(ac.status.ok()) << ac.status.message;
  result.compliance_x = ac.values[0][0].real() / force;
  result.compliance_y = ac.values[1][0].real() / force;
  return result;
}

class DeflectedElastica : public ::testing::TestWithParam<double> {};

// The first mode and the quasi-static AC response about the deflected state converge to the
// exact elastica's tangent (measured order from N = 16, 32, 64 between 1.8 and 2.2), and at N = 64
// the error is within 1.5 times the Richardson estimate: linearisation with the geometric terms
// (a tip load along y puts the deflected beam in tension, which raises the frequency).
TEST_P(DeflectedElastica, FirstModeAndAcFollowTheTangentStiffness) {
  const double alpha = GetParam();
  const std::array<double, 4> c = elastica_tip_compliance(alpha);
  // K = C⁻¹ in SI: lengths L, forces EI/L², so compliance C·L³/EI.
  const double scale = kBeamLength * kBeamLength * kBeamLength / kBeamStiffness;
  const double cxx = c[0] * scale, cxy = c[1] * scale, cyx = c[2] * scale, cyy = c[3] * scale;
  const double det = cxx * cyy - cxy * cyx;
  const double kxx = cyy / det, kxy = -cxy / det, kyx = -cyx / det, kyy = cxx / det;
  const double trace = kxx + kyy, product = kxx * kyy - kxy * kyx;
  const double smallest = 0.5 * (trace - std::sqrt(trace * trace - 4 * product));
  const double exact_frequency = std::sqrt(smallest / kTipMass) / (2 * M_PI);
  std::vector<Linearised> runs;
  for (int segments : {16, 32, 64}) runs.push_back(linearise(segments, alpha));
  auto check = [&](double Linearised::*value, double reference, const char* name) {
    const double e32 = runs[1].*value - reference, e64 = runs[2].*value - reference;
    const double order = std::log2(e32 / e64);
    EXPECT_GT(order, 1.8) << name << " alpha " << alpha << " e16 " << runs[0].*value - reference
                          << " e32 " << e32 << " e64 " << e64 << " of " << reference;
    EXPECT_LT(order, 2.2) << name << " alpha " << alpha;
    EXPECT_LE(std::abs(e64), 1.5 * std::abs(runs[2].*value - runs[1].*value) / 3.0)
        << name << " alpha " << alpha;
  };
  check(&Linearised::frequency, exact_frequency, "frequency");
  check(&Linearised::compliance_y, cyy, "compliance y");
  check(&Linearised::compliance_x, cyx, "compliance x");
}

INSTANTIATE_TEST_SUITE_P(LoadParameters, DeflectedElastica, ::testing::Values(1.0, 3.0));

// ---- IDA: the rigid bar on a torsion spring ---------------------------------------------------

// A stiff bar (EI = 1e6 N·m², against the spring's 1 N·m/rad: its bending adds 2.5e-7 rad) of
// 5e-8 kg (against the tip's 0.1 kg: its inertia is 2e-7 of the tip's) on a torsion spring at a
// pin, with Kelvin-Voigt damping that makes the bar's own modes overdamped and leaves the
// pendulum mode alone (the spring has no damper), under a step moment that turns it to 1 rad.
// Small and large kinematics give the same angle, the large one with its tip on the circle. IDA
// at rtol 1e-8: its global error over the two periods is 3e-6 rad (measured, either model), so
// 1e-5 rad; the tip on the circle to 1e-5 of L (the angle's error times L, and the axial
// stretch under the centripetal force, 1e-7 of L).
TEST(RigidBarOnATorsionSpring, AngleIsTheExactPendulumAndTheTipIsOnTheCircle) {
  const double moment = 0.5, stiffness = 1.0, mass = 0.1;
  const double omega = std::sqrt(stiffness / (mass * kBeamLength * kBeamLength));
  for (BeamKinematics kinematics : {BeamKinematics::small, BeamKinematics::large}) {
    Scene scene = cantilever_scene(4, kBeamLength, 1e6, 1e-7);
    scene.damping.kelvin_voigt_time = 1e-3;
    scene.beam.left = EndCondition::pinned;
    scene.beam.kinematics = kinematics;
    scene.beam.axial_stiffness = 1e6;
    SpringSpec spring;
    spring.kind = SpringKind::rotational;
    spring.stiffness = stiffness;
    scene.beam.springs = {spring};
    MassSpec tip;
    tip.at = kBeamLength;
    tip.mass = mass;
    scene.beam.masses = {tip};
    scene.loads = {load(LoadKind::moment, kBeamLength, moment)};
    scene.probes = {beam_probe("psi", ProbeQuantity::rotation, kBeamLength),
                    beam_probe("w", ProbeQuantity::deflection, kBeamLength)};
    const bool large = kinematics == BeamKinematics::large;
    if (large)
      scene.probes.push_back(beam_probe("u", ProbeQuantity::axial_displacement, kBeamLength));
    const Model model = build_model(scene);
    const System system = model.network.assemble();
    TransientOptions options;
    options.end_time = 2 * 2 * M_PI / omega;
    for (int i = 0; i <= 16; ++i) options.output_times.push_back(options.end_time * i / 16);
    options.relative_tolerance = 1e-8;
    const TransientResult result = run_transient_ida(system, model.probes, options);
    ASSERT_TRUE(result.status.ok()) << result.status.message;
    ASSERT_EQ(result.times.size(), options.output_times.size());
    for (size_t i = 0; i < result.times.size(); ++i) {
      const double exact = moment / stiffness * (1 - std::cos(omega * result.times[i]));
      const double angle = result.values[0][i];
      EXPECT_NEAR(angle, exact, 1e-5) << "large " << large << " t " << result.times[i];
      if (!large) continue;
      EXPECT_NEAR(result.values[1][i], kBeamLength * std::sin(angle), 1e-5 * kBeamLength);
      EXPECT_NEAR(result.values[2][i], kBeamLength * (std::cos(angle) - 1), 1e-5 * kBeamLength);
    }
  }
}

// ---- IDA: energy of an undamped free vibration ------------------------------------------------

// A cantilever held at 50 % of its length by a tip load (the elastica at α = 2) is let go (the
// load ramps to zero in 0.1 ms) and swings undamped for 100 periods of its first mode. Its
// energy, ½·m·v² over the masses plus ½·n·f² over the compliances, stays constant but for the
// integrator's dissipation: BDF at rtol 1e-6 lost 8.0e-5 of it over the run (measured; 1.3e-5
// at rtol 1e-7), so the bound is 2e-4.
TEST(LargeKinematicsFreeVibration, KeepsItsEnergyOverAHundredPeriods) {
  Scene scene = cantilever_scene(4, kBeamLength, kBeamStiffness);
  scene.beam.kinematics = BeamKinematics::large;
  scene.beam.axial_stiffness = 1e4;
  scene.probes = {beam_probe("w", ProbeQuantity::deflection, kBeamLength)};
  Model model = build_model(scene);
  Waveform release;
  release.shape = Waveform::Shape::pwl;
  release.points = {{0.0, 2.0 * kBeamStiffness / (kBeamLength * kBeamLength)}, {1e-4, 0.0}};
  model.network.add<CurrentSource>("release", ground, model.beam.velocity.back(), release);
  // One probe per velocity with a mass and per compliance force, with the energy's weight.
  std::vector<Probe> probes = model.probes;
  std::vector<double> weights;
  auto add = [&](int index, double weight) {
    Probe probe;
    probe.name = "energy term";
    probe.terms = {{index, 1.0}};
    probes.push_back(probe);
    weights.push_back(weight);
  };
  const auto& elements = model.network.elements();
  for (size_t e = 0; e < elements.size(); ++e) {
    if (const auto* mass = dynamic_cast<const Capacitor*>(elements[e].get())) {
      add(mass->a(), 0.5 * mass->capacitance());
    } else if (const auto* spring = dynamic_cast<const Inductor*>(elements[e].get())) {
      add(model.network.branch_unknown_index(e), 0.5 * spring->inductance());
    } else if (const auto* segment = dynamic_cast<const CoRotationalSegment*>(elements[e].get())) {
      add(model.network.branch_unknown_index(e, CoRotationalSegment::transverse_force),
          0.5 * segment->transverse_compliance());
      add(model.network.branch_unknown_index(e, CoRotationalSegment::axial_force),
          0.5 * segment->axial_compliance());
    }
  }
  const System system = model.network.assemble();
  TransientOptions options;
  options.start = StartState::static_;
  options.end_time = 17.5;  // 100 periods of the first mode at this amplitude (0.175 s)
  for (int i = 0; i <= 200; ++i)
    options.output_times.push_back(1e-3 + (options.end_time - 1e-3) * i / 200);
  options.relative_tolerance = 1e-6;
  const TransientResult result = run_transient_ida(system, probes, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.times.size(), options.output_times.size());
  EXPECT_NEAR(result.values[0][0], 0.493 * kBeamLength, 0.01 * kBeamLength);  // held at 50 %
  std::vector<double> energy(result.times.size(), 0.0);
  for (size_t i = 0; i < result.times.size(); ++i)
    for (size_t k = 0; k < weights.size(); ++k)
      energy[i] += weights[k] * result.values[k + 1][i] * result.values[k + 1][i];
  for (size_t i = 0; i < energy.size(); ++i)
    EXPECT_NEAR(energy[i], energy[0], 2e-4 * energy[0]) << "t " << result.times[i];
}

// ---- what the dynamic analyses refuse ----------------------------------------------------------

// Modes, AC and transients need an axial stiffness (an inextensible beam with masses is a DAE of
// index 3); the static analysis takes an inextensible beam; the analyses not yet checked with large
// kinematics refuse the scene, naming the key.
TEST(LargeKinematicsAnalyses, EachServesOrRefusesNamingTheKey) {
  Scene scene = cantilever_scene(4);
  scene.beam.kinematics = BeamKinematics::large;
  auto refused_key = [&](LargeKinematicsUse use) {
    PrepareOptions options;
    options.large_kinematics = use;
    try {
      prepare_model(scene, options);
    } catch (const InputError& error) {
      return error.key();
    }
    return std::string();
  };
  EXPECT_EQ(refused_key(LargeKinematicsUse::static_state), "");
  EXPECT_EQ(refused_key(LargeKinematicsUse::dynamics), "beam.axial_stiffness");
  EXPECT_EQ(refused_key(LargeKinematicsUse::refused), "beam.kinematics");
  scene.beam.axial_stiffness = 1e4;
  EXPECT_EQ(refused_key(LargeKinematicsUse::dynamics), "");
}

}  // namespace
}  // namespace emnet

namespace emnet {
namespace {

// ---- identify with large kinematics --------------------------------------------------------

// identify by a resonance fits EI to the first mode about the deflected static state. Round
// trip: the tip-mass cantilever bent by α = 3 (at the true EI) has its first mode f; identify
// from EI/2 gives back the EI whose deflected state (the dead load fixed, so α moves with EI)
// has that mode, to the fit's 1e-10 in frequency, and the large model at that EI is the large
// model at the true EI (the same computation, 1e-8 in EI: f is smooth in EI). Without the load
// the large model's EI is the small model's (its linearisation at rest is the small network).
TEST(IdentifyLargeKinematics, FitsTheBendingStiffnessToTheModeAboutTheDeflectedState) {
  Scene scene = tip_mass_cantilever(16, 3.0);
  ModalOptions modal;
  modal.keep_vectors = false;
  PrepareOptions dynamics;
  dynamics.large_kinematics = LargeKinematicsUse::dynamics;
  auto first_mode = [&](const Scene& s) {
    const Model model = prepare_model(s, dynamics);
    const System system = model.network.assemble();
    return run_modes(system, solve_static(system).operating_point, modal).modes[0].frequency_hz;
  };
  const double target = first_mode(scene);
  Scene start = scene;
  set_parameter(start, "beam.bending_stiffness", kBeamStiffness / 2);
  IdentifyOptions options;
  options.target_hz = target;
  const IdentifyResult result = identify(start, options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_NEAR(result.achieved_hz, target, 1e-10 * target);
  EXPECT_NEAR(result.bending_stiffness, kBeamStiffness, 1e-8 * kBeamStiffness);
  // Unloaded: the small model's identification.
  Scene unloaded = tip_mass_cantilever(16, 0.0);
  set_parameter(unloaded, "beam.bending_stiffness", kBeamStiffness / 2);
  Scene small = unloaded;
  small.beam.kinematics = BeamKinematics::small;
  small.beam.axial_stiffness = 0.0;
  small.probes = {beam_probe("w", ProbeQuantity::deflection, kBeamLength)};
  options.target_hz = 0.9 * target;
  const IdentifyResult large_fit = identify(unloaded, options),
                       small_fit = identify(small, options);
  ASSERT_TRUE(large_fit.status.ok()) << large_fit.status.message;
  ASSERT_TRUE(small_fit.status.ok()) << small_fit.status.message;
  EXPECT_NEAR(large_fit.bending_stiffness, small_fit.bending_stiffness,
              1e-8 * small_fit.bending_stiffness);
}

}  // namespace
}  // namespace emnet
