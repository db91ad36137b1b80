// DEA transducer: the force law of paper Eq. 16 and its moment pair on the beam.
#include <gtest/gtest.h>

#include <cmath>

#include "emnet/elements/dea.hpp"
#include "emnet/scene_reader.hpp"
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

// C₀ = ε₀ε_r·A/d ≈ 0.85 nF for a 25 mm × 70 mm electrode (DESIGN §3, two digits given).
TEST(DeaForce, CapacitanceOfThePaperElectrode) {
  EXPECT_NEAR(dea_capacitance(2.8, 51e-6, 25e-3, 70e-3), 0.85e-9, 0.005e-9);
}

// A top-face DEA over [x0, x1] at voltage V (static, single drive at bias V) is the moment
// pair T = −z·k_F·V² (DESIGN §3), so the cantilever deflects (closed form, as in
// test_beam_static): w(L) = T(x1 − x0)²/(2EI) + T(x1 − x0)(L − x1)/EI. The span falls
// between nodes; nodal statics are exact, so the tolerance is rounding: 1e-10 relative. The
// bottom face gives the opposite sign.
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
    ASSERT_TRUE(rest.status.ok) << rest.status.message;
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
  ASSERT_TRUE(rest.status.ok) << rest.status.message;
  const ModalResult modes = run_modes(system, rest.operating_point);
  ASSERT_TRUE(modes.status.ok) << modes.status.message;
  ASSERT_FALSE(modes.modes.empty());
  EXPECT_NEAR(modes.modes[0].frequency_hz, 6.385, 0.005);
}

}  // namespace
}  // namespace emnet
