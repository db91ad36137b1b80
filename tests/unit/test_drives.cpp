// The drives as every analysis sees them, in particular the switched drive (a 0/V square wave on
// one DEA). References: closed-form statics, and superposition in the linear network. On the
// fish fin, DEA A on the top face and B on the bottom face:
//   S1 switched on A:             moment −k·s(t)          (s = 1 while A is on, else 0)
//   S2 antagonistic A/B:          moment −k·s + k·(1 − s) = k·(1 − 2s)
//   S3 antagonistic, B on top:    moment −k·s − k·(1 − s) = −k (A's on-state, held)
// so S1 = (S2 + S3)/2 exactly, at every instant from rest and in the periodic state.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "fixtures.hpp"

namespace emnet {
namespace {

const std::vector<std::string> kSwitchedOnA = {"drive.kind=switched", "drive.deas=[\"A\"]"};
const std::vector<std::string> kBothOnTop = {"dea.B.face=top"};

Scene fin(std::vector<std::string> overrides, bool ideal = false) {
  if (ideal) overrides.push_back("drive.electrical_dynamics=false");
  return read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml", overrides);
}

// The deflection probes P2..P4 and the tip (P1 sits at the clamp).
std::vector<Probe> deflections(const Model& model) {
  std::vector<Probe> probes;
  for (const auto& probe : model.probes)
    if (probe.name != "P1") probes.push_back(probe);
  return probes;
}

// Static, switched drive: the DEA is on at t = 0, the moment pair T = −z·k_F·V² of the top face
// over [0, 70 mm] of the clamped fin: w(L) = T·x1²/(2EI) + T·x1·(L − x1)/EI (as in
// test_dea.cpp). Nodal statics are exact, so the tolerance is rounding: 1e-10 relative.
TEST(SwitchedDrive, StaticIsTheOnStateMomentPair) {
  for (bool ideal : {false, true}) {
    const Scene scene = fin(kSwitchedOnA, ideal);
    ASSERT_EQ(scene.drive.kind, DriveKind::switched);
    const Model model = build_model(scene);
    const System system = model.network.assemble();
    const StaticResult rest = solve_static(system);
    ASSERT_TRUE(rest.status.ok()) << rest.status.message;
    const double force = dea_force_constant(2.8, 51e-6, 51e-6, 25e-3) * 4000.0 * 4000.0;
    const double torque = -1.55e-3 * force, x1 = 0.070, length = 0.1225;
    const double ei = scene.beam.bending_stiffness;
    const double exact = torque * x1 * x1 / (2 * ei) + torque * x1 * (length - x1) / ei;
    const Probe& tip = model.probes.back();
    ASSERT_EQ(tip.name, "tip");
    EXPECT_NEAR(static_probe_value(system, rest, tip), exact, 1e-10 * std::abs(exact)) << ideal;
  }
}

// AC: the switched drive's input is the force's ±level k_F·V²/2 on A alone; the antagonistic
// pair's is the same on A plus its mirror on B, which bends the fin the same way. So the pair's
// response is twice the switched one at every frequency, with the RC loops in the network or
// not (neither input goes through them); and at f = 0 the switched response is the static
// response to half the on-state force, half of the static on-state deflection. References:
// linearity (rounding, 1e-12 of the peak) and the static solve (1e-10).
TEST(SwitchedDrive, AcIsHalfThePairsResponseAndHalfTheOnStateAtZero) {
  for (bool ideal : {false, true}) {
    const Model switched = build_model(fin(kSwitchedOnA, ideal));
    const Model pair = build_model(fin({}, ideal));
    const System switched_system = switched.network.assemble();
    const System pair_system = pair.network.assemble();
    const StaticResult switched_rest = solve_static(switched_system);
    const StaticResult pair_rest = solve_static(pair_system);
    ASSERT_TRUE(switched_rest.status.ok() && pair_rest.status.ok());
    const std::vector<double> grid = frequency_grid(0.0, 10.0, 201, false);
    const auto probes = deflections(switched);
    const AcResult a = run_ac(switched_system, switched_rest.operating_point, grid, probes);
    const AcResult b = run_ac(pair_system, pair_rest.operating_point, grid, deflections(pair));
    ASSERT_TRUE(a.status.ok() && b.status.ok());
    for (size_t k = 0; k < probes.size(); ++k) {
      double peak = 0.0;
      for (const auto& v : b.values[k]) peak = std::max(peak, std::abs(v));
      ASSERT_GT(peak, 0.0);
      for (size_t f = 0; f < grid.size(); ++f)
        EXPECT_LE(std::abs(2.0 * a.values[k][f] - b.values[k][f]), 1e-12 * peak)
            << probes[k].name << " at " << grid[f] << " Hz, ideal " << ideal;
      const double on_state = static_probe_value(switched_system, switched_rest, probes[k]);
      EXPECT_NEAR(std::real(a.values[k][0]), 0.5 * on_state, 1e-10 * std::abs(on_state))
          << probes[k].name;
      EXPECT_NEAR(std::imag(a.values[k][0]), 0.0, 1e-10 * std::abs(on_state)) << probes[k].name;
    }
  }
}

// Transient from rest, exact method (ideal drive, a linear network with piecewise-constant
// sources): S1(t) = (S2(t) + S3(t))/2 at every output time. All three are exact to rounding:
// 1e-9 of the peak over 4 periods.
TEST(SwitchedDrive, TransientIsHalfThePairPlusHalfTheHeldOnState) {
  std::vector<TransientResult> runs;
  for (const auto& overrides : {kSwitchedOnA, std::vector<std::string>{}, kBothOnTop}) {
    const Model model = build_model(fin(overrides, true));
    const System system = model.network.assemble();
    TransientOptions options;
    options.end_time = 4 * 0.2;
    for (int k = 0; k <= 400; ++k) options.output_times.push_back(options.end_time * k / 400);
    runs.push_back(run_transient_exact(system, deflections(model), options));
    ASSERT_TRUE(runs.back().status.ok()) << runs.back().status.message;
  }
  for (size_t k = 0; k < runs[0].values.size(); ++k) {
    double peak = 0.0;
    for (double v : runs[0].values[k]) peak = std::max(peak, std::abs(v));
    ASSERT_GT(peak, 0.0);
    for (size_t i = 0; i < runs[0].times.size(); ++i)
      EXPECT_NEAR(runs[0].values[k][i], 0.5 * (runs[1].values[k][i] + runs[2].values[k][i]),
                  1e-9 * peak)
          << "output " << k << " at t = " << runs[0].times[i];
  }
}

// Periodic steady state (sweep-switching's exact method) at 2, 5 and 6.4 Hz: S3's forcing is
// constant, so its periodic state is its static state and S1's extremes are S2's halved plus
// half of it. The extremes are global to 1e-11 of the peak: tolerance 1e-9 of the peak.
TEST(SwitchedDrive, PeriodicExtremesAreHalfThePairsPlusHalfTheHeldOnState) {
  for (double frequency : {2.0, 5.0, 6.4}) {
    const std::string at = "drive.frequency=" + std::to_string(frequency);
    std::vector<PeriodicResult> results;
    for (auto overrides : {kSwitchedOnA, std::vector<std::string>{}, kBothOnTop}) {
      overrides.push_back(at);
      const Model model = build_model(fin(overrides, true));
      const System system = model.network.assemble();
      const PeriodicSolver solver(system);
      results.push_back(solver.solve(system, deflections(model), 1.0 / frequency, 64));
      ASSERT_TRUE(results.back().status.ok()) << results.back().status.message;
    }
    for (size_t k = 0; k < results[0].minimum.size(); ++k) {
      const double held = results[2].maximum[k];
      EXPECT_NEAR(results[2].minimum[k], held, 1e-12 * std::abs(held));
      const double peak = std::max(std::abs(results[0].minimum[k]), results[0].maximum[k]);
      EXPECT_NEAR(results[0].maximum[k], 0.5 * (results[1].maximum[k] + held), 1e-9 * peak)
          << k << " at " << frequency << " Hz";
      EXPECT_NEAR(results[0].minimum[k], 0.5 * (results[1].minimum[k] + held), 1e-9 * peak)
          << k << " at " << frequency << " Hz";
    }
  }
}

// The antagonistic drive's AC input is its force level applied directly, not through the RC
// loops: the AC response is the same with the loops (drive.electrical_dynamics = true) and
// without (false), to rounding (1e-12 of the peak; no back-coupling, so the electrical side
// does not load the beam). The "auto" note, which keeps the loops for the fin's 0-50 Hz band,
// and ac's input description must say so (they used to claim nothing or the opposite), and
// the description gives the omitted factor 1/|1 + j*2*pi*f*tau| at the sweep's top, here
// 10 Hz with tau = R_e*C0 = 1 MOhm * eps0*2.8*25 mm*70 mm/51 um. Both sweeps are direct
// solves, so that the comparison is of the inputs alone: the pole–residue form's rounding
// depends on the pole set (the loops add two), and for P2, whose peak is a seventeenth of the
// tip's, reached 1.3e-12 of its own peak between the two.
TEST(AntagonisticDrive, AcInputBypassesTheRcLoopsAndTheNotesSaySo) {
  std::vector<AcResult> results;
  const std::vector<double> grid = frequency_grid(0.0, 10.0, 101, false);
  AcOptions direct;
  direct.method = AcMethod::direct;
  for (bool ideal : {false, true}) {
    const Model model = build_model(fin({}, ideal));
    const System system = model.network.assemble();
    const StaticResult rest = solve_static(system);
    ASSERT_TRUE(rest.status.ok());
    results.push_back(run_ac(system, rest.operating_point, grid, deflections(model), direct));
    ASSERT_TRUE(results.back().status.ok());
  }
  for (size_t k = 0; k < results[0].values.size(); ++k) {
    double peak = 0.0;
    for (const auto& v : results[1].values[k]) peak = std::max(peak, std::abs(v));
    for (size_t f = 0; f < grid.size(); ++f)
      EXPECT_LE(std::abs(results[0].values[k][f] - results[1].values[k][f]), 1e-12 * peak);
  }
  const Model automatic = prepare_model(fin({"drive.electrical_dynamics=auto"}));
  ASSERT_FALSE(automatic.automatic_choices.empty());
  const std::string& reason = automatic.automatic_choices.back().reason;
  EXPECT_NE(reason.find("RC dynamics kept"), std::string::npos) << reason;
  EXPECT_NE(reason.find("ac's input for this drive is the force k_F*V^2/2 applied directly, "
                        "not through the RC loops"),
            std::string::npos)
      << reason;

  const auto run = testing::run_emnet("ac " + std::string(EMNET_SOURCE_DIR) +
                                      "/netlists/fishfin.toml --points 11 --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const double tau = 1e6 * dea_capacitance(2.8, 51e-6, 25e-3, 70e-3);
  char factor[32];
  std::snprintf(factor, sizeof factor, "%.6g", 1.0 / std::hypot(1.0, 2 * M_PI * 10.0 * tau));
  EXPECT_NE(run.out.find("The DEAs' RC loops are not in this input, whatever "
                         "drive.electrical_dynamics"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find(std::string("at 10 Hz ") + factor), std::string::npos) << factor << "\n"
                                                                                << run.out;
}

}  // namespace
}  // namespace emnet
