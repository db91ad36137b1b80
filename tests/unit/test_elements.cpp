// Elements and builder rules against closed forms: gyrator, damping rules, DEA electrical loop,
// rotary inertia.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/gyrator.hpp"
#include "fixtures.hpp"

namespace emnet {
namespace {

using Complex = std::complex<double>;

// Gyrator (K) between an electrical node with C1 to ground and a mass m: the mass appears on
// the electrical side as an inductor L = m/K². With a unit AC current into the electrical node:
//   u1 = 1/(jωC1 + K²/(jωm)),   resonance at ω0 = K/√(m·C1), undamped.
// Reference: closed form; tolerance 1e-12 relative (rounding of a 3×3 solve) away from ω0,
// and the modal pole to 1e-10 (dense eigen-decomposition of a 2×2 pencil).
TEST(Gyrator, MassBehindGyratorIsAnInductor) {
  const double c1 = 2e-6, m = 0.05, k = 0.3;
  Network network;
  const NodeId u = network.add_node("u", Domain::electrical, "electrical port");
  const NodeId v = network.add_node("v", Domain::translational, "mass velocity");
  network.add<Capacitor>("C1", u, ground, c1);
  network.add<Capacitor>("m", v, ground, m);
  network.add<Gyrator>("K", u, ground, v, ground, k);
  Waveform source = Waveform::constant(0.0);
  source.ac_magnitude = 1.0;
  network.add<CurrentSource>("I", ground, u, source);
  const System system = network.assemble();
  Probe probe;
  probe.terms = {{u, 1.0}};
  const auto grid = frequency_grid(10.0, 1000.0, 50, true);
  const AcResult ac = run_ac(system, Eigen::VectorXd::Zero(system.size()), grid, {probe});
  ASSERT_TRUE(ac.status.ok()) << ac.status.message;
  for (size_t i = 0; i < grid.size(); ++i) {
    const Complex jw(0.0, 2 * M_PI * grid[i]);
    const Complex exact = 1.0 / (jw * c1 + k * k / (jw * m));
    EXPECT_LT(std::abs(ac.values[0][i] - exact), 1e-12 * std::abs(exact));
  }
  const ModalResult modes = run_modes(system, Eigen::VectorXd::Zero(system.size()));
  ASSERT_TRUE(modes.status.ok()) << modes.status.message;
  ASSERT_EQ(modes.modes.size(), 1u);
  EXPECT_NEAR(modes.modes[0].frequency_hz, k / std::sqrt(m * c1) / (2 * M_PI),
              1e-10 * modes.modes[0].frequency_hz);
}

ModalResult cantilever_modes(const Scene& scene) {
  const System system = build_model(scene).network.assemble();
  const StaticResult rest = solve_static(system);
  EXPECT_TRUE(rest.status.ok());
  return run_modes(system, rest.operating_point);
}

// Kelvin–Voigt damping τ is the damping matrix τ·K exactly (a damper τ/n across every
// compliance), so every mode has ζ_n = τ·ω_n/2 with ω_n the undamped natural frequency; a loss
// factor η at f is τ = η/(2πf). Reference: that identity on the same network; tolerance 1e-9
// (rounding of the dense eigen-decomposition).
TEST(Damping, KelvinVoigtGivesStiffnessProportionalDamping) {
  Scene scene = testing::cantilever_scene(10);
  const double tau = 1e-4;
  scene.damping.loss_factor = tau * 2 * M_PI * 50.0;
  scene.damping.loss_factor_frequency = 50.0;
  const ModalResult damped = cantilever_modes(scene);
  const ModalResult undamped = cantilever_modes(testing::cantilever_scene(10));
  ASSERT_GE(damped.modes.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    const double omega = 2 * M_PI * undamped.modes[k].frequency_hz;
    EXPECT_NEAR(damped.modes[k].damping_ratio, tau * omega / 2, 1e-9) << "mode " << k + 1;
    EXPECT_NEAR(damped.modes[k].natural_frequency_hz / undamped.modes[k].frequency_hz, 1.0, 1e-9);
  }
}

// Viscous damping to ground c per length, lumped like the mass, is C = (c/ρA)·M, so
// ζ_n = c/(2·ρA·ω_n). Same reference and tolerance as above.
TEST(Damping, ViscousDampingIsMassProportional) {
  Scene scene = testing::cantilever_scene(10);
  scene.damping.viscous_per_length = 0.05;
  const ModalResult damped = cantilever_modes(scene);
  const ModalResult undamped = cantilever_modes(testing::cantilever_scene(10));
  for (size_t k = 0; k < 3; ++k) {
    const double omega = 2 * M_PI * undamped.modes[k].frequency_hz;
    EXPECT_NEAR(damped.modes[k].damping_ratio, 0.05 / (2 * 0.3 * omega), 1e-9) << k + 1;
  }
}

// Rotary inertia ρI adds rotational kinetic energy and no stiffness, so by Rayleigh's quotient
// every frequency drops (reference: that energy argument; the test checks the sign only).
TEST(Beam, RotaryInertiaLowersFrequencies) {
  Scene scene = testing::cantilever_scene(10);
  scene.beam.rotary_inertia_per_length = 0.3 * 0.01 * 0.01;
  const ModalResult with = cantilever_modes(scene);
  const ModalResult without = cantilever_modes(testing::cantilever_scene(10));
  for (size_t k = 0; k < 3; ++k)
    EXPECT_LT(with.modes[k].frequency_hz, without.modes[k].frequency_hz);
}

// The DEA's electrical loop: source → R → C₀. With a bias-differential drive the capacitor
// voltage is v/(1 + jωRC₀) and the current jωC₀·v/(1 + jωRC₀) (no back-coupling: the
// mechanics does not load the circuit). Reference: closed form; tolerance 1e-9 relative (the
// circuit sits in a system whose other rows are scaled 1e9 apart: rounding of 1e-16·1e7).
TEST(Dea, ElectricalLoopIsAnRcLowPass) {
  Scene scene = testing::cantilever_scene(7);
  for (const char* name : {"A", "B"}) {
    DeaSpec dea;
    dea.name = name;
    dea.from = 0.0;
    dea.to = 0.2;
    dea.face = name[0] == 'A' ? Face::top : Face::bottom;
    dea.lever_arm = 1.5e-3;
    dea.relative_permittivity = 2.8;
    dea.dielectric_thickness = 51e-6;
    dea.force_thickness = 51e-6;
    dea.electrode_width = 25e-3;
    dea.electrode_resistance = 1e6;
    scene.deas.push_back(dea);
  }
  scene.drive.kind = DriveKind::bias_differential;
  scene.drive.deas = {"A", "B"};
  scene.drive.bias = 2000.0;
  scene.drive.amplitude = 10.0;
  scene.drive.frequency = 5.0;
  ProbeSpec voltage{"uA", ProbeQuantity::dea_voltage, 0.0, "A"};
  ProbeSpec current{"iA", ProbeQuantity::dea_current, 0.0, "A"};
  scene.probes = {voltage, current};
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok());
  const double c0 = model.deas[0].capacitance, r = 1e6;
  const auto grid = frequency_grid(1.0, 1e5, 30, true);
  const AcResult ac = run_ac(system, rest.operating_point, grid, model.probes);
  ASSERT_TRUE(ac.status.ok());
  for (size_t i = 0; i < grid.size(); ++i) {
    const Complex jw(0.0, 2 * M_PI * grid[i]);
    const Complex u = 10.0 / (1.0 + jw * r * c0), current_exact = jw * c0 * u;
    EXPECT_LT(std::abs(ac.values[0][i] - u), 1e-9 * std::abs(u)) << grid[i];
    EXPECT_LT(std::abs(ac.values[1][i] - current_exact), 1e-9 * std::abs(current_exact)) << grid[i];
  }
}

}  // namespace
}  // namespace emnet
