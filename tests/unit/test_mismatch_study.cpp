// The mismatch study as a library call (emnet::run_mismatch, emnet/studies/mismatch.hpp): the
// nominal asymmetry, its sign and its scaling with the change.
//
// References:
// (1) Symmetry: the fish fin's pair is mirror-symmetric and the nominal square wave is odd
//     (drive(t + T/2) = −drive(t)), so the linear network's periodic state is odd too and its
//     extremes are equal and opposite: the nominal (change 0) asymmetry is zero up to the
//     extremes' accuracy (1e-11 of the peak, analysis/periodic.hpp), checked to 1e-10.
// (2) Superposition (mismatch.hpp): a force change x_F of DEA A gives asymmetry
//     a(x) = x_F·|S| / ((1 + x_F/2)·P), P the symmetric peak, S the static deflection with A on
//     alone, negative (A pulls to the left). So a wider electrode (x_F = x) gives a > 0 (larger
//     to the left) and a thicker film (x_F = (1 + x)⁻² − 1 < 0) a < 0; and expanding to second
//     order, a(x) = k·x − k·x²/2 (electrode) and k·(−2x + x²) (thickness), k = |S|/P, so
//     a(2X) − 2·a(X) = −k·X² and 2k·X², both of size |a(X)|·X: bounded by 2·|a(X)|·X (a factor 2
//     for the higher orders), while each a(X) is of size k·X ≫ k·X².
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "emnet/core/errors.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/mismatch.hpp"
#include "fixtures.hpp"

namespace {

emnet::Scene measured_fin() {
  return emnet::read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin-measured.toml");
}

const emnet::MismatchRow* row_of(const emnet::MismatchResult& result, const std::string& key,
                                 double change) {
  for (const emnet::MismatchRow& row : result.rows)
    if (row.key == key && row.change == change) return &row;
  return nullptr;
}

TEST(MismatchStudy, NoMismatchNoAsymmetryAndTheSignFollowsTheStrongerDea) {
  emnet::MismatchOptions options;
  options.change = 0.05;
  const emnet::MismatchResult result = emnet::run_mismatch(measured_fin(), options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.output, "dx4");  // the model's default deflection output
  EXPECT_EQ(result.periodic_solves, 7);
  ASSERT_EQ(result.rows.size(), 6u);
  EXPECT_NEAR(result.nominal_asymmetry, 0.0, 1e-10);
  EXPECT_NEAR(result.nominal_left, -result.nominal_right, 1e-10 * result.nominal_right);
  const auto* wider = row_of(result, "dea.A.electrode_width", 0.05);
  const auto* narrower = row_of(result, "dea.A.electrode_width", -0.05);
  const auto* thicker = row_of(result, "dea.A.dielectric_thickness", 0.05);
  const auto* thinner = row_of(result, "dea.A.dielectric_thickness", -0.05);
  ASSERT_TRUE(wider && narrower && thicker && thinner);
  EXPECT_GT(wider->asymmetry, 0.0);  // a stronger A: larger to A's (the left) side
  EXPECT_GT(std::abs(wider->left), wider->right);
  EXPECT_LT(narrower->asymmetry, 0.0);
  EXPECT_LT(thicker->asymmetry, 0.0);  // a thicker film: a weaker A
  EXPECT_GT(thinner->asymmetry, 0.0);
  for (const emnet::MismatchRow& row : result.rows)
    EXPECT_DOUBLE_EQ(row.asymmetry_per_unit_change, row.asymmetry / 0.05) << row.key;
}

TEST(MismatchStudy, SmallChangesScaleLinearly) {
  const double change = 0.01;
  emnet::MismatchOptions single, twice;
  single.change = change;
  twice.change = 2.0 * change;
  const emnet::Scene scene = measured_fin();
  const emnet::MismatchResult a = emnet::run_mismatch(scene, single);
  const emnet::MismatchResult b = emnet::run_mismatch(scene, twice);
  ASSERT_TRUE(a.status.ok() && b.status.ok()) << a.status.message << b.status.message;
  for (const std::string key : {"dea.A.electrode_width", "dea.A.dielectric_thickness"})
    for (const double sign : {-1.0, 1.0}) {
      const auto* at_x = row_of(a, key, sign * change);
      const auto* at_2x = row_of(b, key, sign * 2.0 * change);
      ASSERT_TRUE(at_x && at_2x) << key;
      EXPECT_GT(std::abs(at_x->asymmetry), 1e-4) << key;  // the linear term is there
      EXPECT_NEAR(at_2x->asymmetry, 2.0 * at_x->asymmetry, 2.0 * std::abs(at_x->asymmetry) * change)
          << key << " " << sign;
    }
}

TEST(MismatchStudy, BadInputsAreInputErrors) {
  emnet::MismatchOptions options;
  EXPECT_THROW(emnet::run_mismatch(emnet::testing::cantilever_scene(10), options),
               emnet::InputError);  // no antagonistic pair
  options.change = 0.0;
  EXPECT_THROW(emnet::run_mismatch(measured_fin(), options), emnet::InputError);
  options.change = 0.05;
  options.output = "no such output";
  EXPECT_THROW(emnet::run_mismatch(measured_fin(), options), emnet::InputError);
  options.output.clear();
  options.frequency_hz = 0.0;
  EXPECT_THROW(emnet::run_mismatch(measured_fin(), options), emnet::InputError);
}

}  // namespace
