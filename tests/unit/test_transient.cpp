// Transient analysis: the exact method against closed forms, IDA against the exact method.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "emnet/analysis/transient.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "fixtures.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

// The fish fin with its DEAs as ideal voltage-driven forces: a linear network under
// piecewise-constant forces, which the exact method solves.
Scene ideal_drive_fishfin_scene() {
  return read_scene(testing::kFishfin, {"drive.electrical_dynamics=false"});
}

std::vector<double> uniform_times(double end, int count) {
  std::vector<double> times;
  for (int k = 0; k <= count; ++k) times.push_back(end * k / count);
  return times;
}

// One mass m on a spring k and damper c, a force step F at t = 0 from rest:
//   x(t) = F/k·[1 − e^{−ζω t}·(cos ω_d t + ζω/ω_d·sin ω_d t)].
// Reference: closed form. The exact method's only error is rounding in a 2×2 matrix
// exponential: 1e-12 of F/k. IDA at rtol 1e-9 stays within 1e-6 of F/k (its global error
// is a small multiple of rtol over these 20 periods).
TEST(Transient, StepResponseOfOneMassMatchesClosedForm) {
  const double m = 0.2, k = 50.0, c = 0.3, force = 2.0;
  const testing::OneMass one = testing::one_mass_spring_damper(m, k, c, Waveform::constant(force));
  const System system = one.network.assemble();
  const Probe x = one.displacement();
  const double omega = std::sqrt(k / m), zeta = c / (2 * std::sqrt(k * m));
  const double omega_d = omega * std::sqrt(1 - zeta * zeta);
  TransientOptions options;
  options.end_time = 20 * 2 * M_PI / omega;
  options.output_times = uniform_times(options.end_time, 400);
  options.relative_tolerance = 1e-9;
  const TransientResult exact = run_transient_exact(system, {x}, options);
  const TransientResult ida = run_transient_ida(system, {x}, options);
  ASSERT_TRUE(exact.status.ok()) << exact.status.message;
  ASSERT_TRUE(ida.status.ok()) << ida.status.message;
  ASSERT_EQ(exact.times.size(), options.output_times.size());
  ASSERT_EQ(ida.times.size(), options.output_times.size());
  for (size_t i = 0; i < exact.times.size(); ++i) {
    const double t = exact.times[i];
    const double reference =
        force / k *
        (1 - std::exp(-zeta * omega * t) *
                 (std::cos(omega_d * t) + zeta * omega / omega_d * std::sin(omega_d * t)));
    EXPECT_NEAR(exact.values[0][i], reference, 1e-12 * force / k) << t;
    EXPECT_NEAR(ida.values[0][i], reference, 1e-6 * force / k) << t;
  }
}

// The same mass critically damped (c = 2·√(k·m)): a double pole at −ω, whose computed
// eigenvectors are nearly parallel, so the exact method leaves the modal form for matrix
// exponentials (the only test of that path: one ramp interval, one constant one; without a
// lever there is nothing to project). The force ramps from 0 to F over T, then holds (pwl):
// with r(t) = (t − 2/ω + (t + 2/ω)·e^{−ωt})/k the response to a unit ramp of force (partial
// fractions of 1/(m·s²·(s + ω)²)),
//   x(t) = F/T·(r(t) − r(t − T)),  r = 0 before 0.
// Reference: closed form. Tolerance 1e-13 of F/k: rounding in the 2×2 state's block
// exponentials (Van Loan's, 4×4 and 6×6) over two intervals, a few ε of their norm each
// (measured 2.4e-15); a wrong block, slope term or interval would be O(1).
TEST(Transient, CriticallyDampedMassUnderARampTakesTheExponentialsAndMatchesClosedForm) {
  const double m = 0.2, k = 50.0, c = 2.0 * std::sqrt(k * m), force = 2.0;
  const double omega = std::sqrt(k / m), ramp = 0.3;
  Waveform pwl;
  pwl.shape = Waveform::Shape::pwl;
  pwl.points = {{0.0, 0.0}, {ramp, force}};
  const testing::OneMass one = testing::one_mass_spring_damper(m, k, c, pwl);
  const System system = one.network.assemble();
  const Probe x = one.displacement();
  TransientOptions options;
  options.end_time = 2.0;
  options.output_times = uniform_times(options.end_time, 200);
  const TransientResult exact = run_transient_exact(system, {x}, options);
  ASSERT_TRUE(exact.status.ok()) << exact.status.message;
  ASSERT_EQ(exact.times.size(), options.output_times.size());
  const auto unit_ramp = [&](double t) {
    return t <= 0.0 ? 0.0 : (t - 2.0 / omega + (t + 2.0 / omega) * std::exp(-omega * t)) / k;
  };
  for (size_t i = 0; i < exact.times.size(); ++i) {
    const double t = exact.times[i];
    const double reference = force / ramp * (unit_ramp(t) - unit_ramp(t - ramp));
    EXPECT_NEAR(exact.values[0][i], reference, 1e-13 * force / k) << t;
  }
}

// IDA's counters, each read from its own getter: every step takes at least one Newton
// iteration, and every iteration one residual evaluation, so residual evaluations ≥ Newton
// iterations ≥ steps > 0; a Jacobian is evaluated at least once and at most once an iteration;
// failed error tests are retried steps, fewer than the steps. (Reference: the counting of
// IDA's statistics. A counter shifted onto its neighbour, as when the arguments reading them
// were evaluated in the wrong order, breaks the chain: steps 0.)
TEST(Transient, IdaStatisticsAreEachTheirOwnCounter) {
  const Scene scene = ideal_drive_fishfin_scene();
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  TransientOptions options;
  options.end_time = 2 / scene.drive.frequency;
  options.output_times = uniform_times(options.end_time, 200);
  const TransientResult ida = run_transient_ida(system, model.probes, options);
  ASSERT_TRUE(ida.status.ok()) << ida.status.message;
  const IntegratorStatistics& statistics = ida.statistics;
  EXPECT_GT(statistics.steps, 0);
  EXPECT_GE(statistics.newton_iterations, statistics.steps);
  EXPECT_GE(statistics.residual_evaluations, statistics.newton_iterations);
  EXPECT_GE(statistics.jacobian_evaluations, 1);
  EXPECT_LE(statistics.jacobian_evaluations, statistics.newton_iterations);
  EXPECT_LT(statistics.error_test_failures, statistics.steps);
}

// The paper's experiment in simulation: the fish fin switched at 5 Hz for 50 periods, with
// the DEAs as ideal voltage-driven forces (a linear network under piecewise-constant forces).
// Reference: the exact method. IDA at rtol 1e-8 must stay within 1e-6 of the peak deflection
// at P2..P4 and the tip over the whole run (its error is a few rtol of the peak: BDF global
// error grows with the number of periods, 50 here).
TEST(Transient, IdaMatchesExactOnTheFishFinOverFiftyPeriods) {
  const Scene scene = ideal_drive_fishfin_scene();
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  TransientOptions options;
  options.end_time = 50 / scene.drive.frequency;
  options.output_times = uniform_times(options.end_time, 50 * 100);
  options.relative_tolerance = 1e-8;
  const TransientResult exact = run_transient_exact(system, model.probes, options);
  const TransientResult ida = run_transient_ida(system, model.probes, options);
  ASSERT_TRUE(exact.status.ok()) << exact.status.message;
  ASSERT_TRUE(ida.status.ok()) << ida.status.message;
  ASSERT_EQ(exact.times.size(), ida.times.size());
  for (size_t p = 0; p < model.probes.size(); ++p) {
    if (model.probes[p].name == "P1") continue;  // at the clamp: zero by construction
    double peak = 0.0, worst = 0.0;
    for (size_t i = 0; i < exact.times.size(); ++i) {
      peak = std::max(peak, std::abs(exact.values[p][i]));
      worst = std::max(worst, std::abs(ida.values[p][i] - exact.values[p][i]));
    }
    EXPECT_GT(peak, 0.0);
    EXPECT_LT(worst, 1e-6 * peak) << model.probes[p].name;
  }
}

// Outputs stepped from one to the next by the addition theorem (ModalClock) against each
// output time alone, where the increments come straight from one exponential of the whole
// offset into its interval: the fish fin over 10 periods with 997 irregularly spaced output
// times (a uniform grid, a geometric cluster after every edge and random times). Reference:
// the single-output runs. Tolerance 1e-12 of each output's peak: each step adds one rounding
// of the size of the terms, and an interval holds at most ~120 outputs here (1e-14 per step).
TEST(Transient, ExactOutputsSteppedMatchOutputsTakenAlone) {
  const Scene scene = ideal_drive_fishfin_scene();
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const double period = 1.0 / scene.drive.frequency;
  TransientOptions options;
  options.end_time = 10 * period;
  std::vector<double> times = uniform_times(options.end_time, 500);
  for (int edge = 0; edge < 20; ++edge)
    for (int k = 0; k < 12; ++k) times.push_back(edge * 0.5 * period + 1e-6 * std::pow(2.0, k));
  unsigned state = 12345;
  while (times.size() < 997) {
    state = state * 1103515245u + 12345u;
    times.push_back(options.end_time * ((state >> 8) & 0xFFFF) / 65536.0);
  }
  std::sort(times.begin(), times.end());
  options.output_times = times;
  const TransientResult all = run_transient_exact(system, model.probes, options);
  ASSERT_TRUE(all.status.ok()) << all.status.message;
  ASSERT_EQ(all.times.size(), times.size());
  std::vector<double> peak(model.probes.size(), 0.0);
  for (size_t p = 0; p < model.probes.size(); ++p)
    for (double v : all.values[p]) peak[p] = std::max(peak[p], std::abs(v));
  for (size_t i = 0; i < times.size(); i += 7) {  // every 7th alone: 143 runs
    TransientOptions alone = options;
    alone.output_times = {times[i]};
    const TransientResult one = run_transient_exact(system, model.probes, alone);
    ASSERT_TRUE(one.status.ok()) << one.status.message;
    for (size_t p = 0; p < model.probes.size(); ++p)
      EXPECT_NEAR(all.values[p][i], one.values[p][0], 1e-12 * std::max(peak[p], 1e-300))
          << model.probes[p].name << " at t = " << times[i];
  }
}

// A drive of 0 V throughout: the network stays exactly at rest (no source, no motion; both
// methods must return exact zeros, not rounding noise).
TEST(Transient, ZeroDriveStaysExactlyAtRest) {
  const Scene scene = read_scene(testing::kFishfin, {"drive.voltage=0"});
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  TransientOptions options;
  options.end_time = 5 / scene.drive.frequency;
  options.output_times = uniform_times(options.end_time, 100);
  const TransientResult ida = run_transient_ida(system, model.probes, options);
  ASSERT_TRUE(ida.status.ok()) << ida.status.message;
  for (const auto& series : ida.values)
    for (double v : series) EXPECT_EQ(v, 0.0);
}

}  // namespace
}  // namespace emnet
