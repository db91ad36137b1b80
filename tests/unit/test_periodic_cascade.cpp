// The exact cascade (src/analysis/periodic_cascade.hpp): the periodic state of a network whose
// only nonlinearity is the DEAs' force k_F·u², against shooting and against a long settled
// transient, and its refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "emnet/analysis/periodic.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/elements/gyrator.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/elements/voltage_source.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/switching_sweep.hpp"
#include "small_cascade.hpp"

namespace emnet {
namespace {

Scene tweezer(std::vector<std::string> overrides = {}) {
  return read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/tweezer-jaw.toml", overrides);
}

// The largest difference between two sample sets of probe p, relative to `swing`.
double sample_difference(const std::vector<double>& a, const std::vector<double>& b, double swing) {
  double worst = 0.0;
  for (size_t s = 0; s < a.size(); ++s) worst = std::max(worst, std::abs(a[s] - b[s]));
  return worst / swing;
}

// The tweezer jaw (two square sources behind 4.7 MOhm, each DEA's RC loop, no back-coupling) on
// 8 segments at 8 Hz. Reference: shooting at IDA rtol 1e-11. Its samples agree to 1.4e-11 of
// the swing (measured); 1e-9 leaves room for IDA's error at that tolerance. Shooting's extremes
// come from a parabola through the largest samples: the tip's are 8.5e-7 of the swing too far
// out at 256 samples and within 1e-12 at 8192 (measured), so they are checked against the
// 8192-sample shooting at 1e-9. The DEA's force, a probe with a square, is the square of the
// cascade's own first stage.
TEST(PeriodicCascade, TweezerAgreesWithShooting) {
  const Model model = prepare_model(tweezer({"beam.segments=8"}));
  const System system = model.network.assemble();
  ASSERT_TRUE(system.is_nonlinear());
  ASSERT_TRUE(exact_periodic_applies(system).ok()) << exact_periodic_applies(system).message;
  const std::vector<Probe> outputs =
      switching_sweep_outputs(model, {"tip", "u_A", "u_B", "dea_force:A"});
  const PeriodicSolver solver(system);
  ASSERT_TRUE(solver.usable().ok()) << solver.usable().message;
  const double period = 1.0 / 8.0;
  const PeriodicResult exact = solver.solve(system, outputs, period, 256);
  ASSERT_TRUE(exact.status.ok()) << exact.status.message;
  EXPECT_EQ(exact.method, Method::exact);
  EXPECT_LT(exact.periodicity_residual, 1e-12);
  const PeriodicResult shooting = run_periodic_shooting(system, outputs, period, 1e-11, 256);
  ASSERT_TRUE(shooting.status.ok()) << shooting.status.message;
  const PeriodicResult fine = run_periodic_shooting(system, outputs, period, 1e-11, 8192);
  ASSERT_TRUE(fine.status.ok()) << fine.status.message;
  for (size_t p = 0; p < outputs.size(); ++p) {
    const double swing = shooting.maximum[p] - shooting.minimum[p];
    ASSERT_GT(swing, 0.0) << outputs[p].name;
    EXPECT_LT(sample_difference(exact.values[p], shooting.values[p], swing), 1e-9)
        << outputs[p].name;
    EXPECT_GE(exact.maximum[p], *std::max_element(exact.values[p].begin(), exact.values[p].end()));
    EXPECT_LE(exact.minimum[p], *std::min_element(exact.values[p].begin(), exact.values[p].end()));
  }
  // The tip's extremes (smooth there) against the fine parabola.
  const double swing = fine.maximum[0] - fine.minimum[0];
  EXPECT_NEAR(exact.minimum[0], fine.minimum[0], 1e-9 * swing);
  EXPECT_NEAR(exact.maximum[0], fine.maximum[0], 1e-9 * swing);
  // The voltages have a kink at each switching edge, where a parabola overshoots (by 5.4 V at
  // 8192 samples): their extremes lie between the sources' levels, 0 and 2.5 kV, to rounding
  // (an RC loop cannot leave them), and the largest reaches the top to 1e-9 (the 5.2 MOhm and
  // 0.17 nF loop's 0.87 ms fits about 70 times into the half period).
  for (size_t p = 1; p <= 2; ++p) {
    EXPECT_GE(exact.minimum[p], -1e-9 * 2500.0) << outputs[p].name;
    EXPECT_NEAR(exact.maximum[p], 2500.0, 1e-9 * 2500.0) << outputs[p].name;
  }
  // The force k_F·u² (a probe with a square, the cascade's own square of u_A): from 0 to
  // k_F·(2.5 kV)², to the same 1e-9.
  const auto* dea = dynamic_cast<const Dea*>(system.nonlinear_elements[0].get());
  ASSERT_NE(dea, nullptr);
  const double top = dea->force(2500.0);
  EXPECT_GE(exact.minimum[3], -1e-9 * top);
  EXPECT_NEAR(exact.maximum[3], top, 1e-9 * top);
}

// The same network from rest over 60 periods by IDA at rtol 1e-10, its last period against the
// periodic state. The loss factor is raised to 0.3 so that the slowest mode settles within
// them; the difference measured shrinks with the periods (it is the transient's decay and
// IDA's error), 1e-7 of the swing bounds it.
TEST(PeriodicCascade, TweezerAgreesWithASettledTransient) {
  const Model model = prepare_model(tweezer({"beam.segments=8", "damping.loss_factor=0.3"}));
  const System system = model.network.assemble();
  const std::vector<Probe> outputs = switching_sweep_outputs(model, {"tip"});
  const double period = 1.0 / 8.0;
  const int samples = 64, periods = 60;
  const PeriodicResult exact = PeriodicSolver(system).solve(system, outputs, period, samples);
  ASSERT_TRUE(exact.status.ok()) << exact.status.message;
  TransientOptions options;
  options.end_time = periods * period;
  options.relative_tolerance = 1e-10;
  for (int s = 0; s < samples; ++s)
    options.output_times.push_back((periods - 1) * period + exact.times[static_cast<size_t>(s)]);
  const TransientResult settled = run_transient_ida(system, outputs, options);
  ASSERT_TRUE(settled.status.ok()) << settled.status.message;
  const double swing = exact.maximum[0] - exact.minimum[0];
  const double difference = sample_difference(exact.values[0], settled.values[0], swing);
  std::printf("settled difference %.3e of the swing\n", difference);
  EXPECT_LT(difference, 1e-7);
}

using testing::displacement;
using testing::small_cascade;

// The small network with ramps in its source (the squares' polynomial factors): the cascade's
// 256 samples and its extremes against shooting at rtol 1e-11 and 8192 samples. The mass's
// displacement is smooth, so the parabola through 8192 samples is within ~1e-12 of its
// extremes; 1e-8 of the swing covers IDA's error at that tolerance (measured below).
TEST(PeriodicCascade, RampsAgreeWithShootingOnASmallNetwork) {
  const auto made = small_cascade(0.01, 30.0, 300.0);
  const System system = made->network.assemble();
  const std::vector<Probe> probes{displacement(made->velocity)};
  const PeriodicSolver solver(system);
  ASSERT_TRUE(solver.usable().ok()) << solver.usable().message;
  const PeriodicResult exact = solver.solve(system, probes, 0.2, 256);
  ASSERT_TRUE(exact.status.ok()) << exact.status.message;
  const PeriodicResult shooting = run_periodic_shooting(system, probes, 0.2, 1e-11, 8192);
  ASSERT_TRUE(shooting.status.ok()) << shooting.status.message;
  const double swing = shooting.maximum[0] - shooting.minimum[0];
  ASSERT_GT(swing, 0.0);
  double worst = 0.0;
  for (size_t s = 0; s < exact.values[0].size(); ++s)
    worst = std::max(worst, std::abs(exact.values[0][s] - shooting.values[0][32 * s]));
  std::printf("ramps: samples %.3e, extremes %.3e %.3e of the swing\n", worst / swing,
              std::abs(exact.minimum[0] - shooting.minimum[0]) / swing,
              std::abs(exact.maximum[0] - shooting.maximum[0]) / swing);
  EXPECT_LT(worst, 1e-8 * swing);
  EXPECT_NEAR(exact.minimum[0], shooting.minimum[0], 1e-8 * swing);
  EXPECT_NEAR(exact.maximum[0], shooting.maximum[0], 1e-8 * swing);
}

// Refusals, each with its reason: a DEA with its back-coupling (before decomposing), a gyrator
// that lets the mass's motion into the electrode's voltage (on the modes), and a mechanical pole
// on an exponent of u² (−2/τ: the square of the RC loop's e^{−t/τ}).
TEST(PeriodicCascade, RefusesWhatItCannotSolveSayingWhy) {
  const System coupled_back = small_cascade(0.01, 30.0, 300.0, true)->network.assemble();
  const Status back = exact_periodic_applies(coupled_back);
  EXPECT_FALSE(back.ok());
  EXPECT_NE(back.message.find("back_coupling"), std::string::npos) << back.message;

  auto made = small_cascade(0.01, 30.0, 300.0);
  made->network.add<Gyrator>("G", made->electrode, ground, made->velocity, ground, 1e-3);
  const System transducer = made->network.assemble();
  EXPECT_TRUE(exact_periodic_applies(transducer).ok());  // linear elements: seen on the modes
  const PeriodicSolver coupled(transducer);
  EXPECT_FALSE(coupled.usable().ok());
  EXPECT_NE(coupled.usable().message.find("depends on the beam's motion"), std::string::npos)
      << coupled.usable().message;
  const PeriodicResult refused = coupled.solve(transducer, {displacement(made->velocity)}, 0.2);
  EXPECT_FALSE(refused.status.ok());

  const auto resonant = small_cascade(0.01, 200.0, 3000.0);  // −2/τ = −200/s, a pole
  const System on_a_pole = resonant->network.assemble();
  const PeriodicSolver solver(on_a_pole);
  ASSERT_TRUE(solver.usable().ok()) << solver.usable().message;
  const PeriodicResult at_the_pole =
      solver.solve(on_a_pole, {displacement(resonant->velocity)}, 0.2);
  EXPECT_FALSE(at_the_pole.status.ok());
  EXPECT_NE(at_the_pole.status.message.find("coincides with an exponent"), std::string::npos)
      << at_the_pole.status.message;
}

}  // namespace
}  // namespace emnet
