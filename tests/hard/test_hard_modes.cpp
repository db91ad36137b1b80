// Hard cases of the modal analysis: beams at the segment limit (100 000 segments, 400 000 and
// more unknowns) with a statically indeterminate support and with a rigid-body motion.
//
// Reference (closed form): the uniform Euler–Bernoulli beam of netlists/cantilever.toml,
// f1 = (βL)²/(2πL²)·√(EI/ρA) with βL = 4.730041 (clamped–clamped) and 3.926602 (pinned–free,
// besides its rigid rotation about the pin). The lumping error is O(N⁻²), below 1e-9 here, so
// the tolerance 1e-7 is set by the rounding bound each mode carries (measured 4e-9 and 1.5e-8
// relative for the first modes), which must itself hold.
#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.hpp"

namespace emnet {
namespace {

TEST(HardModes, SegmentLimitWithoutAFreeEndAndWithARigidRotation) {
  struct Case {
    EndCondition left, right;
    double beta_l;
    size_t rigid;
  };
  for (const Case& c : {Case{EndCondition::clamped, EndCondition::clamped, 4.730040744862704, 0},
                        Case{EndCondition::pinned, EndCondition::free, 3.926602312047919, 1}}) {
    Scene scene = testing::cantilever_scene(100000);
    scene.beam.left = c.left;
    scene.beam.right = c.right;
    const Model model = build_model(scene);
    const System system = model.network.assemble();
    ModalOptions options;
    options.count = 1;
    const ModalResult modes = run_modes(system, Eigen::VectorXd::Zero(system.size()), options);
    ASSERT_TRUE(modes.status.ok()) << modes.status.message;
    EXPECT_EQ(modes.rigid_body_modes.size(), c.rigid);
    EXPECT_TRUE(modes.real_poles.empty()) << modes.real_poles.size();
    ASSERT_FALSE(modes.modes.empty());
    const double exact = c.beta_l * c.beta_l / (2 * M_PI * 0.25) * std::sqrt(2.0 / 0.3);
    const Mode& first = modes.modes[0];
    std::printf("[measured] %s-%s: f1 = %.12g Hz, closed form %.12g Hz, bound %.2g\n",
                end_condition_name(c.left), end_condition_name(c.right), first.frequency_hz, exact,
                first.pole_error / std::abs(first.pole));
    ASSERT_TRUE(first.error_bounded) << first.unbounded_reason;
    EXPECT_LT(first.pole_error / std::abs(first.pole), 1e-7);
    EXPECT_NEAR(first.frequency_hz / exact, 1.0, 1e-7);
  }
}

}  // namespace
}  // namespace emnet
