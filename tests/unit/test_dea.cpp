// DEA transducer: the force law of paper Eq. 16 and its moment pair on the beam.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>

#include "emnet/analysis/analysis.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "fixtures.hpp"

namespace emnet {
namespace {

// Paper Sect. 2.2: ε_r = 2.8, d = d' = 51 µm, electrode width 25 mm give 0.055 N at 3 kV and
// 0.097 N at 4 kV. The paper prints 3 decimals, so the tolerance is half a unit of the last:
// 5e-4 N.
TEST(DeaForce, PaperValuesAtThreeAndFourKilovolts) {
  const double k = dea_force_constant(2.8, 51e-6, 51e-6, 25e-3);
  EXPECT_NEAR(k * 3000.0 * 3000.0, 0.055, 5e-4);
  EXPECT_NEAR(k * 4000.0 * 4000.0, 0.097, 5e-4);
}

// C₀ = ε₀ε_r·A/d ≈ 0.85 nF for a 25 mm × 70 mm electrode (docs/model.md, The DEA transducer, two
// digits given).
TEST(DeaForce, CapacitanceOfThePaperElectrode) {
  EXPECT_NEAR(dea_capacitance(2.8, 51e-6, 25e-3, 70e-3), 0.85e-9, 0.005e-9);
}

// A top-face DEA over [x0, x1] at voltage V (static, single drive at bias V) is the moment
// pair T = −z·k_F·V² (docs/model.md, The DEA transducer), so the cantilever deflects (closed form,
// as in test_beam_static): w(L) = T(x1 − x0)²/(2EI) + T(x1 − x0)(L − x1)/EI. The span's ends fall
// inside the uniform grid; the mesher puts nodes there, and nodal statics are exact, so the
// tolerance is rounding: 1e-10 relative. The bottom face
// gives the opposite sign.
TEST(DeaForce, StaticMomentPairOnTheBeam) {
  for (Face face : {Face::top, Face::bottom}) {
    Scene scene = testing::cantilever_scene(9);
    DeaSpec dea;
    dea.name = "A";
    dea.from = 0.061;
    dea.to = 0.27;
    dea.face = face;
    dea.lever_arm = 1.5e-3;
    dea.relative_permittivity = 2.8;
    dea.dielectric_thickness = 51e-6;
    dea.force_thickness = 51e-6;
    dea.electrode_width = 25e-3;
    dea.electrode_resistance = 1e6;
    scene.deas = {dea};
    scene.drive.kind = DriveKind::single;
    scene.drive.deas = {"A"};
    scene.drive.bias = 3000.0;
    scene.drive.amplitude = 100.0;
    scene.drive.frequency = 1.0;
    scene.probes = {testing::beam_probe("tip", ProbeQuantity::deflection, 0.5)};
    const Model model = build_model(scene);
    const System system = model.network.assemble();
    const StaticResult rest = solve_static(system);
    ASSERT_TRUE(rest.status.ok()) << rest.status.message;
    const double force = dea_force_constant(2.8, 51e-6, 51e-6, 25e-3) * 3000.0 * 3000.0;
    const double torque = (face == Face::top ? -1.0 : 1.0) * 1.5e-3 * force;
    const double span = dea.to - dea.from, ei = scene.beam.bending_stiffness;
    const double exact = torque * span * span / (2 * ei) + torque * span * (0.5 - dea.to) / ei;
    EXPECT_NEAR(static_probe_value(system, rest, model.probes[0]), exact, 1e-10 * std::abs(exact));
  }
}

// The fish fin of the paper at N = 7: first resonance 6.385 Hz (the paper's network result),
// ± 0.005 Hz as the issue states (the scene's EI is identified to 7 digits, so the computed
// value is far inside this).
TEST(FishFin, FirstResonanceAtSevenSegments) {
  const Scene scene = read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml");
  ASSERT_EQ(scene.beam.segments, 7);
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok()) << rest.status.message;
  const ModalResult modes = run_modes(system, rest.operating_point);
  ASSERT_TRUE(modes.status.ok()) << modes.status.message;
  ASSERT_FALSE(modes.modes.empty());
  EXPECT_NEAR(modes.modes[0].frequency_hz, 6.385, 0.005);
}

// Back-coupling on the fish fin's first mode. Linearised at the capacitor voltage U₀ (at rest A
// is on at 4 kV, B off), the motional current K·ẋ (K = 2·k_F·U₀) pulls the electrode voltage
// by −K·ẋ/(G + s·C₀) (G = 1/R_e; the source holds the far end of R_e), which changes the force
// by K·δu: the beam sees, along each DEA's elongation ẋ, a force −ΔD(s)·ẋ with
// ΔD(s) = K²/(G + s·C₀). Reference: first-order perturbation of the first mode. Kelvin–Voigt
// damping is stiffness-proportional and, without back-coupling, the electrical side does not
// load the beam, so the mode's velocity shape v is real (after removing one phase); its modal
// equation m·s² + d·s + k = 0 (m = Σ masses·v², d = −2m·Re s) gains s·ΣΔD·ẋ(v)², so
//   Δs = −s·Σ_DEA ΔD(s)·ẋ(v)² / (2·m·j·Im s).
// Tolerance 1e-5 of |Δs|: ten times the neglected second-order term, of order |Δs| / (distance
// to the next pole, ~200/s) ~ 1e-6 relative; the poles' rounding (~1e-15·|s|) is ~3e-10 of
// |Δs|. Measured: 6e-7.
// The effect itself (stated in docs/model.md): f1 6.385000 → 6.385001 Hz, ζ1 0.020004 → 0.020007.
TEST(DeaBackCoupling, FirstModeShiftMatchesPerturbationTheory) {
  const std::string path = std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml";
  const Model plain = build_model(read_scene(path));
  const Model coupled =
      build_model(read_scene(path, {"dea.A.back_coupling=true", "dea.B.back_coupling=true"}));
  auto first_mode = [](const Model& model, Eigen::VectorXd& rest) {
    const System system = model.network.assemble();
    const StaticResult at_rest = solve_static(system);
    EXPECT_TRUE(at_rest.status.ok()) << at_rest.status.message;
    rest = at_rest.operating_point;
    const ModalResult modes = run_modes(system, rest);
    EXPECT_TRUE(modes.status.ok()) << modes.status.message;
    return modes.modes.at(0);
  };
  Eigen::VectorXd rest;
  const Mode mode = first_mode(plain, rest);
  Eigen::VectorXd coupled_rest;
  const Mode shifted = first_mode(coupled, coupled_rest);
  const System system = plain.network.assemble();

  // Real velocity shape: remove the phase of the largest translational velocity.
  const BeamLayout& beam = plain.beam;
  std::complex<double> reference = 0.0;
  for (NodeId node : beam.velocity)
    if (node != ground && std::abs(mode.vector[node]) > std::abs(reference))
      reference = mode.vector[node];
  const Eigen::VectorXcd v = mode.vector / (reference / std::abs(reference));
  double modal_mass = 0.0;
  for (const auto* nodes : {&beam.velocity, &beam.angular_velocity})
    for (NodeId node : *nodes)
      if (node != ground) modal_mass += system.C.coeff(node, node) * std::norm(v[node]);

  const std::complex<double> s = mode.pole;
  std::complex<double> modal_damping_change = 0.0;
  for (size_t d = 0; d < plain.scene.deas.size(); ++d) {
    const DeaSpec& spec = plain.scene.deas[d];
    const DeaLayout& layout = plain.deas[d];
    // ẋ = ∓z·(Ω(x1) − Ω(x0)); the sign drops out of ẋ².
    std::complex<double> elongation_rate = 0.0;
    for (const auto& [node, c] : beam.slope_terms(spec.to)) elongation_rate += c * v[node];
    for (const auto& [node, c] : beam.slope_terms(spec.from)) elongation_rate -= c * v[node];
    elongation_rate *= spec.lever_arm;
    const double voltage = rest[layout.electrode_node];
    const double gyration = 2.0 * layout.force_constant * voltage;
    const std::complex<double> added_damping =
        gyration * gyration / (1.0 / layout.electrode_resistance + s * layout.capacitance);
    modal_damping_change += added_damping * elongation_rate * elongation_rate;
  }
  const std::complex<double> predicted =
      -s * modal_damping_change / (2.0 * modal_mass * std::complex<double>(0.0, s.imag()));
  const std::complex<double> measured = shifted.pole - mode.pole;
  std::printf("[measured]   back-coupling shift of s1: %.6e%+.6ei 1/s, predicted %.6e%+.6ei\n",
              measured.real(), measured.imag(), predicted.real(), predicted.imag());
  ASSERT_GT(std::abs(predicted), 0.0);
  EXPECT_LT(std::abs(measured - predicted), 1e-5 * std::abs(predicted));
  EXPECT_LT(predicted.real(), 0.0);  // the motional current through R_e dissipates: more damping
}

}  // namespace
}  // namespace emnet
