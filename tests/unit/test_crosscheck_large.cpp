// SPICE decks and the cross-check with large kinematics (beam.kinematics = "large"): the
// co-rotational segments written as behavioural sources (src/spice/deck/corotational_segment.cpp)
// and run by ngspice, an independent solver of the same equations (its own Newton on the op,
// its own trapezoidal integration on the tran).
//
// References and tolerances are the cross-check's own (include/emnet/verification/crosscheck.hpp):
// op 1e-6 of each group's largest value (the same equations, LU in double precision on both
// sides); tran 100 × ngspice's reltol of each output's peak, against IDA at rtol 1e-10. Each case
// is one where the small network is off by far more than the tolerance, so a deck that dropped
// the geometric terms could not pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "emnet/analysis/transient.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/verification/crosscheck.hpp"
#include "fixtures.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

Model large_model(const Scene& scene, LargeKinematicsUse use) {
  return prepare_model(scene, serving_large_kinematics(use));
}

void expect_every_row_passes(const CrosscheckReport& report, std::size_t rows_at_least) {
  ASSERT_TRUE(report.status.ok()) << report.status.message;
  EXPECT_GE(report.rows.size(), rows_at_least);
  for (const CrosscheckRow& row : report.rows)
    EXPECT_TRUE(row.pass) << crosscheck_analysis_name(row.analysis) << " " << row.quantity << ": "
                          << row.largest_difference << " > " << row.tolerance << " at "
                          << row.where;
}

// The tip-mass cantilever bent by a dead tip load α = 3 (its tip 0.60·L across and 0.17·L in): the
// op deck's Newton reaches emnet's static state, every unknown (displacements, rotations, the
// chords' changes and angles, the forces) within 1e-6 of its group. The small network puts the
// tip at α/3 = 1·L, off by 70 %.
TEST(CrosscheckLargeKinematics, TheElasticasOpDeckIsEmnetsStaticState) {
  if (!testing::ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  const Model model =
      large_model(testing::tip_mass_cantilever(16, 3.0), LargeKinematicsUse::static_state);
  CrosscheckOptions options;
  options.analyses = {CrosscheckAnalysis::op};
  const CrosscheckReport report = run_crosscheck(model, options);
  expect_every_row_passes(report, 5);
  bool chords_compared = false;
  for (const CrosscheckRow& row : report.rows)
    chords_compared = chords_compared || row.quantity == "chord angles [rad]";
  EXPECT_TRUE(chords_compared);
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok()) << rest.status.message;
  EXPECT_GT(static_probe_value(system, rest, model.probes.at(1)), 0.5 * testing::kBeamLength);
}

// The cantilever (ρA = 0.3 kg/m, Kelvin–Voigt τ = 1e-4 s, EA = 1e5 N) bent by a dead tip load
// α = 3 and shaken about that state by the load's AC part: the ac deck, written in displacements
// (ngspice's operating point is the deflected state, about which it linearises the B sources
// itself), gives emnet's AC response there, every unknown and output within 1e-6 of its group
// (the same equations, LU in double precision on both sides; measured 5e-9, the operating point
// solved to reltol 1e-9 and amplified near the lightly damped mode), and its peaks are emnet's
// modes (the modal check, 8e-8). The straight beam's first mode is 5.77 Hz, the deflected one's
// 7.84 Hz: a deck that lost the geometric terms could not pass.
TEST(CrosscheckLargeKinematics, TheElasticasAcDeckIsEmnetsAcAboutTheDeflectedState) {
  if (!testing::ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  Scene scene = testing::cantilever_scene(16, testing::kBeamLength, testing::kBeamStiffness);
  scene.beam.kinematics = BeamKinematics::large;
  scene.beam.axial_stiffness = 1e5;
  scene.damping.kelvin_voigt_time = 1e-4;
  scene.loads = {
      testing::load(LoadKind::force, testing::kBeamLength,
                    3.0 * testing::kBeamStiffness / (testing::kBeamLength * testing::kBeamLength))};
  scene.probes = {testing::beam_probe("u", ProbeQuantity::axial_displacement, testing::kBeamLength),
                  testing::beam_probe("w", ProbeQuantity::deflection, testing::kBeamLength)};
  const Model model = large_model(scene, LargeKinematicsUse::dynamics);
  CrosscheckOptions options;
  options.analyses = {CrosscheckAnalysis::ac, CrosscheckAnalysis::modal};
  const CrosscheckReport report = run_crosscheck(model, options);
  expect_every_row_passes(report, 6);
  bool velocities = false, chords = false, modal = false;
  for (const CrosscheckRow& row : report.rows) {
    velocities = velocities || row.quantity.rfind("velocities", 0) == 0;
    chords = chords || row.quantity.rfind("chord angles", 0) == 0;
    modal = modal || row.analysis == CrosscheckAnalysis::modal;
  }
  EXPECT_TRUE(velocities && chords && modal);
  ModalOptions first;
  first.count = 1;
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  const ModalResult deflected = run_modes(system, rest.operating_point, first);
  Scene small = scene;
  small.beam.kinematics = BeamKinematics::small;
  small.beam.axial_stiffness = 0.0;
  small.probes.erase(small.probes.begin());  // u: large kinematics only
  const ModalResult straight = run_modes(build_model(small).network.assemble(), {}, first);
  ASSERT_FALSE(deflected.modes.empty());
  ASSERT_FALSE(straight.modes.empty());
  EXPECT_GT(std::abs(deflected.modes[0].frequency_hz / straight.modes[0].frequency_hz - 1), 0.05);
}

// The fish fin at 8 kV switched at 6.4 Hz (near its resonance), two periods from rest: the tip
// swings to 9.6 % of L, where the small network is off by about (w/L)² ≈ 1 % of the swing; the
// tran deck's integration agrees with IDA within 100 × reltol = 1e-4 (measured 6.9e-6).
TEST(CrosscheckLargeKinematics, TheFinsTranDeckFollowsIdaAtLargeSwing) {
  if (!testing::ngspice_available()) GTEST_SKIP() << "ngspice is not installed";
  const Scene scene =
      read_scene(testing::kFishfin, {"beam.kinematics=large", "beam.axial_stiffness=200 kN",
                                     "drive.voltage=8000", "drive.frequency=6.4"});
  const Model model = large_model(scene, LargeKinematicsUse::dynamics);
  CrosscheckOptions options;
  options.analyses = {CrosscheckAnalysis::tran};
  const CrosscheckReport report = run_crosscheck(model, options);
  expect_every_row_passes(report, 1);
  for (const CrosscheckRow& row : report.rows) EXPECT_EQ(row.analysis, CrosscheckAnalysis::tran);
}

// Every deck is written with large kinematics, the op and ac decks in displacements and the tran
// deck in velocities; an inextensible beam is refused naming the key (its axial force is a
// multiplier).
TEST(CrosscheckLargeKinematics, EveryDeckIsWrittenAndAnInextensibleBeamIsRefused) {
  const Scene scene =
      read_scene(testing::kFishfin, {"beam.kinematics=large", "beam.axial_stiffness=200 kN"});
  const Model model = large_model(scene, LargeKinematicsUse::dynamics);
  auto refused_key = [](const Model& m, SpiceAnalysis analysis) -> std::string {
    SpiceDeckOptions options;
    options.analysis = analysis;
    options.end_time = 0.4;
    options.output_step = 1e-3;
    try {
      write_spice_deck(m, options);
    } catch (const InputError& error) {
      return error.key();
    }
    return "";
  };
  EXPECT_EQ(refused_key(model, SpiceAnalysis::op), "");
  EXPECT_EQ(refused_key(model, SpiceAnalysis::tran), "");
  EXPECT_EQ(refused_key(model, SpiceAnalysis::ac), "");
  for (const SpiceAnalysis analysis : {SpiceAnalysis::op, SpiceAnalysis::ac, SpiceAnalysis::tran}) {
    SpiceDeckOptions options;
    options.analysis = analysis;
    options.end_time = 0.4;
    options.output_step = 1e-3;
    EXPECT_EQ(write_spice_deck(model, options).displacement_nodes, analysis != SpiceAnalysis::tran);
  }
  Scene inextensible = scene;
  inextensible.beam.axial_stiffness = 0.0;
  EXPECT_EQ(
      refused_key(large_model(inextensible, LargeKinematicsUse::static_state), SpiceAnalysis::op),
      "beam.axial_stiffness");
}

}  // namespace
}  // namespace emnet
