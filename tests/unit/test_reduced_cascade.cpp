// The reduced cascade (ReducedPeriodicSolver on a network whose only nonlinearity is the DEAs'
// force k_F·u², include/emnet/analysis/modal_reduction.hpp) against the exact cascade
// (PeriodicSolver), which is exact to rounding (tests/unit/test_periodic_cascade.cpp checks it
// against shooting and a settled transient).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/design_study.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/switching_sweep.hpp"
#include "small_cascade.hpp"

namespace emnet {
namespace {

// The tweezer jaw (35 segments, 222 unknowns: two DEAs behind 4.7 MOhm, a Kelvin–Voigt cluster of
// about 65 real poles at −1/τ = −4712 1/s). Arnoldi stops at the cluster and keeps 5 modes and
// the two RC poles; the beam's truncated part is exact but for its transients after each edge.
// The tip and body-end extremes sit where those have decayed (e^{−4712·h}, h ≥ 10 ms), so they
// agree with the exact cascade to the two decompositions' rounding (extremes_difference, relative
// to each probe's largest |value|: measured 5e-12; 1e-9 leaves room for it). The samples differ
// right after the edges by the transients left out: the stated estimate (their start) covers the
// measured difference within a factor 2 (the cluster's transient decays monotonically from its
// start; the factor is for the fast poles').
TEST(ReducedCascade, TweezerJawExtremesAgreeWithTheExactCascade) {
  for (const char* hz : {"8 Hz", "5.5 Hz", "1 Hz"}) {
    const std::string at(hz);
    const Model model = prepare_model(
        read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/tweezer-jaw.toml",
                   {"circuit.src_A.frequency=" + at, "circuit.src_B.frequency=" + at}));
    const System system = model.network.assemble();
    const std::vector<Probe> outputs = switching_sweep_outputs(model, {"tip", "body_end"});
    ReductionOptions options;
    options.band = 8.0;
    options.dense_limit = 200;  // Arnoldi on the 222 unknowns
    const ReducedPeriodicSolver reduced(system, options);
    ASSERT_TRUE(reduced.reduction().status.ok()) << reduced.reduction().status.message;
    EXPECT_LT(reduced.reduction().kept.size(), 20u);
    EXPECT_FALSE(reduced.reduction().all_found);  // stopped at the cluster
    const double period = 1.0 / std::stod(at);
    const PeriodicResult exact = PeriodicSolver(system).solve(system, outputs, period, 64);
    const PeriodicResult solved = reduced.solve(system, outputs, period, 64);
    ASSERT_TRUE(exact.status.ok()) << exact.status.message;
    ASSERT_TRUE(solved.status.ok()) << solved.status.message;
    EXPECT_EQ(solved.method, Method::reduced);
    EXPECT_LT(solved.periodicity_residual, 1e-12);
    const double extremes = extremes_difference(solved, exact);
    const double samples = periodic_difference(solved, exact);
    std::printf("%s: extremes %.3e, samples %.3e, estimate %.3e\n", hz, extremes, samples,
                solved.truncation_estimate);
    EXPECT_LT(extremes, 1e-9) << hz;
    EXPECT_GT(solved.truncation_estimate, 0.0);
    EXPECT_LE(samples, 2.0 * solved.truncation_estimate) << hz;
  }
}

using testing::displacement;
using testing::small_cascade;

Scene tweezer_jaw() {
  return read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/tweezer-jaw.toml", {});
}

// The jaw's pole search: the request for 4 modes finds the 12 poles below the Kelvin–Voigt
// cluster, the request for 8 runs into the cluster and finds none more (useful_request 4). With
// last_request 4 (a design study's variants) the search stops there and keeps the same poles,
// from the request for 4 where the full search keeps the request for 8's: two Arnoldi runs, whose
// poles agree to 1e-9 (checked), so the periodic states agree to that order too (measured
// 3e-12 of each probe's largest value; the tolerance is the poles' own).
TEST(ReducedCascade, ALastRequestKeepsThePolesWithoutTheClusterRun) {
  const Model model = prepare_model(tweezer_jaw());
  const System system = model.network.assemble();
  const std::vector<Probe> outputs = switching_sweep_outputs(model, {"tip", "body_end"});
  ReductionOptions options;
  options.band = 8.0;
  options.dense_limit = 200;
  const ReducedPeriodicSolver searched(system, options);
  ASSERT_TRUE(searched.reduction().status.ok()) << searched.reduction().status.message;
  EXPECT_FALSE(searched.reduction().all_found);
  EXPECT_EQ(searched.reduction().useful_request, 4);
  options.last_request = searched.reduction().useful_request;
  const ReducedPeriodicSolver stopped(system, options);
  ASSERT_TRUE(stopped.reduction().status.ok()) << stopped.reduction().status.message;
  EXPECT_FALSE(stopped.reduction().all_found);
  EXPECT_NE(stopped.reduction().note.find("no request beyond 4 modes"), std::string::npos)
      << stopped.reduction().note;
  ASSERT_EQ(stopped.reduction().kept.size(), searched.reduction().kept.size());
  for (size_t k = 0; k < stopped.reduction().kept.size(); ++k)
    EXPECT_LT(std::abs(stopped.reduction().kept[k].pole - searched.reduction().kept[k].pole),
              1e-9 * std::abs(searched.reduction().kept[k].pole));
  const PeriodicResult a = searched.solve(system, outputs, 1.0 / 8.0, 64);
  const PeriodicResult b = stopped.solve(system, outputs, 1.0 / 8.0, 64);
  ASSERT_TRUE(a.status.ok() && b.status.ok());
  EXPECT_LT(periodic_difference(b, a), 1e-9);
  // The request for 4 modes grew its Arnoldi run from 6 poles (the real poles took places);
  // started at the size it grew to, the run is the same computation without the outgrown one:
  // the same poles bit for bit.
  const int grown = stopped.reduction().useful_arnoldi_request;
  EXPECT_GT(grown, 6);
  options.arnoldi_request = grown;
  const ReducedPeriodicSolver started(system, options);
  ASSERT_TRUE(started.reduction().status.ok()) << started.reduction().status.message;
  ASSERT_EQ(started.reduction().kept.size(), stopped.reduction().kept.size());
  for (size_t k = 0; k < started.reduction().kept.size(); ++k)
    EXPECT_EQ(started.reduction().kept[k].pole, stopped.reduction().kept[k].pole);
  for (auto field : {&ReductionOptions::last_request, &ReductionOptions::arnoldi_request}) {
    ReductionOptions bad;
    bad.band = 1.0;
    bad.*field = -1;
    EXPECT_THROW(validate(bad), OptionError);
  }
  for (auto field :
       {&ModalOptions::count, &ModalOptions::dense_limit, &ModalOptions::first_request}) {
    ModalOptions bad;
    bad.*field = -1;
    EXPECT_THROW(validate(bad), OptionError);
  }
}

// The small cascade against the exact cascade, with the −300 1/s pole truncated (the cut-off
// between the circuit's poles and it) and with every pole kept. Truncated, its particular state
// is exact (the feed-through at the squares' exponents), its transient after each edge left out:
// one real exponential decaying from its start, so the stated estimate (the start) bounds the
// difference at every sample; 1e-12 of the largest value is rounding. With every pole kept the
// reduced cascade is the exact one to rounding (1e-10). `inductance` 0: the RC pole −100 1/s
// (real exponents 0, −100, −200); 1e5 H: the RLC pair −50 ± 86.6j 1/s (complex exponents, the
// complex factorisation).
void check_the_small_cascade(double inductance, double cutoff_hz, size_t kept) {
  const auto made = small_cascade(0.01, 30.0, 300.0, false, inductance);
  const System system = made->network.assemble();
  const std::vector<Probe> probes{displacement(made->velocity)};
  const PeriodicResult exact = PeriodicSolver(system).solve(system, probes, 0.2, 256);
  ASSERT_TRUE(exact.status.ok()) << exact.status.message;

  ReductionOptions truncating;
  truncating.band = 5.0;
  truncating.cutoff_hz = cutoff_hz;
  const ReducedPeriodicSolver reduced(system, truncating);
  ASSERT_TRUE(reduced.reduction().status.ok()) << reduced.reduction().status.message;
  EXPECT_EQ(reduced.reduction().kept.size(), kept);
  const PeriodicResult solved = reduced.solve(system, probes, 0.2, 256);
  ASSERT_TRUE(solved.status.ok()) << solved.status.message;
  const double samples = periodic_difference(solved, exact);
  std::printf("L = %g H, one pole truncated: samples %.3e, estimate %.3e, extremes %.3e\n",
              inductance, samples, solved.truncation_estimate, extremes_difference(solved, exact));
  EXPECT_GT(samples, 1e-9);  // the transient is there to be left out
  EXPECT_LE(samples, solved.truncation_estimate + 1e-12);

  ReductionOptions all;
  all.band = 5.0;
  all.cutoff_hz = 1e6;
  const ReducedPeriodicSolver whole(system, all);
  ASSERT_TRUE(whole.reduction().status.ok()) << whole.reduction().status.message;
  const PeriodicResult complete = whole.solve(system, probes, 0.2, 256);
  ASSERT_TRUE(complete.status.ok()) << complete.status.message;
  EXPECT_LT(periodic_difference(complete, exact), 1e-10);
  EXPECT_LT(complete.truncation_estimate, 1e-10);
}

TEST(ReducedCascade, ATruncatedPoleLeavesOnlyItsTransientWithRamps) {
  // Cut-off 200/2π Hz: keeps −30 and the RC pole −100.
  check_the_small_cascade(0.0, 200.0 / (2.0 * M_PI), 2);
}

TEST(ReducedCascade, ComplexCircuitPolesGiveComplexExponents) {
  // Cut-off 200/2π Hz: keeps −30 and the pair −50 ± 86.6j (|s| = 100), as one kept pole.
  check_the_small_cascade(1e5, 200.0 / (2.0 * M_PI), 2);
}

// A cut-off below every pole keeps none: the reduced cascade needs the circuit's poles, and says
// so rather than solving on the static correction alone.
TEST(ReducedCascade, RefusesACutOffBelowEveryPole) {
  const auto made = small_cascade(0.01, 30.0, 300.0);
  const System system = made->network.assemble();
  ReductionOptions options;
  options.band = 5.0;
  options.cutoff_hz = 1.0;  // 6.3 1/s, below −30
  const ReducedPeriodicSolver reduced(system, options);
  EXPECT_FALSE(reduced.reduction().status.ok());
  EXPECT_NE(reduced.reduction().status.message.find("keeps no pole"), std::string::npos)
      << reduced.reduction().status.message;
  EXPECT_FALSE(reduced.solve(system, {displacement(made->velocity)}, 0.2).status.ok());
}

// A DEA with its back-coupling is not a cascade: the reduction says so and every solve fails.
TEST(ReducedCascade, RefusesABackCoupledDea) {
  const auto made = small_cascade(0.01, 30.0, 300.0, true);
  const System system = made->network.assemble();
  ReductionOptions options;
  options.band = 5.0;
  const ReducedPeriodicSolver reduced(system, options);
  EXPECT_FALSE(reduced.reduction().status.ok());
  EXPECT_NE(reduced.reduction().status.message.find("back-coupling"), std::string::npos)
      << reduced.reduction().status.message;
  EXPECT_FALSE(reduced.solve(system, {displacement(made->velocity)}, 0.2).status.ok());
}

// A sweep of the scene's outputs at `frequencies`, without the first mode and the rotation.
SwitchingSweepOptions sweep_at(const Model& model, const std::vector<double>& frequencies) {
  SwitchingSweepOptions options;
  options.frequencies = frequencies;
  options.outputs = switching_sweep_outputs(model, {});
  options.first_mode = false;
  options.largest_rotation = false;
  return options;
}

// The jaw's sweep by the exact cascade at a few frequencies: the reference of the sweeps below.
SwitchingSweepResult exact_sweep(const Model& model, const std::vector<double>& frequencies) {
  SwitchingSweepOptions options = sweep_at(model, frequencies);
  options.method = SwitchingSweepMethod::exact;
  return run_switching_sweep(model, model.scene, options);
}

// `sweep-switching --reduce` on the jaw: its check against the full exact cascade states the
// error of the peaks it prints (to rounding: 1e-9, as above) apart from the samples' (the
// transients after the edges, above 1e-4), and judges the tolerance on the peaks.
TEST(ReducedCascade, TheSweepsCheckStatesTheErrorOfThePeaksItPrints) {
  const Model model = prepare_model(tweezer_jaw());
  const std::vector<double> frequencies{1.0, 3.0, 5.5, 7.0};
  SwitchingSweepOptions options = sweep_at(model, frequencies);
  options.reduce = true;
  options.reduction.band = 7.0;
  const SwitchingSweepResult reduced = run_switching_sweep(model, model.scene, options);
  ASSERT_TRUE(reduced.status.ok()) << reduced.status.message;
  EXPECT_EQ(reduced.method, Method::reduced);
  ASSERT_TRUE(reduced.reduction.has_value());
  const SwitchingSweepReductionCheck& check = *reduced.reduction;
  EXPECT_TRUE(check.cascade);
  EXPECT_TRUE(check.against_full);
  EXPECT_LT(check.measured_extremes_error, 1e-9);
  EXPECT_GT(check.measured_error, 1e-4);
  EXPECT_TRUE(check.tolerance_met);
  const SwitchingSweepResult exact = exact_sweep(model, frequencies);
  ASSERT_TRUE(exact.status.ok()) << exact.status.message;
  EXPECT_LT(extremes_difference(reduced, exact), 1e-9);
}

// Above the dense limit (lowered to 100 unknowns for the jaw's 222) the automatic method takes
// the reduced cascade, not shooting, and says so; its check against a wider reduction (which
// stops at the same cluster) states at least the truncated transients' estimate, which is above
// the peaks' actual error against the exact cascade.
TEST(ReducedCascade, AutomaticAboveTheDenseLimitStatesItsEstimate) {
  const Model model = prepare_model(tweezer_jaw());
  const std::vector<double> frequencies{2.0, 6.0};
  SwitchingSweepOptions options = sweep_at(model, frequencies);
  options.dense_limit = 100;
  const SwitchingSweepResult reduced = run_switching_sweep(model, model.scene, options);
  ASSERT_TRUE(reduced.status.ok()) << reduced.status.message;
  EXPECT_EQ(reduced.method, Method::reduced);
  bool said = false;
  for (const std::string& note : reduced.notes)
    said |= note.find("method: reduced cascade") != std::string::npos;
  EXPECT_TRUE(said);
  ASSERT_TRUE(reduced.reduction.has_value());
  EXPECT_FALSE(reduced.reduction->against_full);
  EXPECT_TRUE(reduced.reduction->cascade);
  const SwitchingSweepResult exact = exact_sweep(model, frequencies);
  ASSERT_TRUE(exact.status.ok()) << exact.status.message;
  const double actual = extremes_difference(reduced, exact);
  EXPECT_LT(actual, 1e-9);
  EXPECT_GT(reduced.reduction->stated_error(), 1e-4);  // the transients' start
  EXPECT_GE(reduced.reduction->stated_error(), actual);
}

// A design study of the jaw (a cascade above 150 unknowns) sweeps every variant by the reduced
// cascade after checking it on the nominal scene, and says so; each variant's columns are its
// exact cascade's to 1e-9 of the largest peak (rounding, as above).
TEST(ReducedCascade, ADesignStudyOfTheJawReducesEachVariantsSweep) {
  const Scene jaw = tweezer_jaw();
  VariantTable table;
  table.keys = {"circuit.R_A.value"};
  table.rows = {{4.0e6}, {5.5e6}};
  DesignStudyOptions options;
  options.analyses = {StudyAnalysis::switching_sweep};
  options.sweep_frequencies = {2.0, 4.0, 6.0};
  options.report_frequencies = {4.0};
  options.threads = 1;
  const DesignStudyResult study = run_design_study(jaw, table, options);
  ASSERT_TRUE(study.status.ok()) << study.status.message;
  bool said = false;
  for (const std::string& note : study.notes)
    said |= note.find("the reduced cascade for every variant") != std::string::npos;
  EXPECT_TRUE(said);
  for (size_t v = 0; v < table.rows.size(); ++v) {
    ASSERT_TRUE(study.rows[v].status.ok()) << study.rows[v].status.message;
    const Model model =
        prepare_model(read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/tweezer-jaw.toml",
                                 {"circuit.R_A.value=" + std::to_string(table.rows[v][0])}));
    const SwitchingSweepResult exact = exact_sweep(model, {4.0});
    ASSERT_TRUE(exact.status.ok()) << exact.status.message;
    // Columns: sweep.peak_hz, then each output's min and max at 4 Hz.
    const std::vector<double>& values = study.rows[v].values;
    ASSERT_EQ(values.size(), 1 + 2 * exact.outputs.size());
    for (size_t p = 0; p < exact.outputs.size(); ++p) {
      const double scale =
          std::max(std::abs(exact.outputs[p].left[0]), std::abs(exact.outputs[p].right[0]));
      EXPECT_NEAR(values[1 + 2 * p], exact.outputs[p].left[0], 1e-9 * scale);
      EXPECT_NEAR(values[2 + 2 * p], exact.outputs[p].right[0], 1e-9 * scale);
    }
  }
}

}  // namespace
}  // namespace emnet
