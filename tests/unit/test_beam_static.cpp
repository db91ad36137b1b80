// Static deflection of the N-segment beam network against Euler–Bernoulli closed forms.
//
// Reference: cantilever (clamped at 0, free at L) under
//   tip force F:   w = F·x²·(3L − x)/(6EI),  φ = F·x·(2L − x)/(2EI)
//   tip moment M:  w = M·x²/(2EI),           φ = M·x/EI
//   moment pair −T at a, +T at b (a < b): bending moment T on [a, b], zero elsewhere, so
//     w = 0 (x ≤ a), T(x − a)²/(2EI) (a ≤ x ≤ b), T(b − a)²/(2EI) + T(b − a)(x − b)/EI (x ≥ b)
// The segment network has exactly the Hermite element's flexibility (docs/model.md, The beam
// segment) and the mesher puts a node under every load (unequal segments where a load falls
// inside the uniform grid), so nodal values are exact for every N: the only error is rounding in a
// sparse LU of a well-conditioned system, hence 1e-10 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "fixtures.hpp"

namespace emnet {
namespace {

using testing::beam_probe;
using testing::cantilever_scene;
using testing::load;

struct ClosedForm {
  double w, phi;
};

void expect_nodes_match(int segments, const std::vector<LoadSpec>& loads,
                        const std::function<ClosedForm(double)>& exact) {
  Scene scene = cantilever_scene(segments);
  scene.loads = loads;
  const double length = scene.beam.length;
  for (int k = 0; k <= segments; ++k) {
    const double x = length * k / segments;
    scene.probes.push_back(beam_probe("w" + std::to_string(k), ProbeQuantity::deflection, x));
    scene.probes.push_back(beam_probe("phi" + std::to_string(k), ProbeQuantity::rotation, x));
  }
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const StaticResult result = solve_static(system);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  const ClosedForm tip = exact(length);
  for (int k = 0; k <= segments; ++k) {
    const double x = length * k / segments;
    const ClosedForm reference = exact(x);
    const double w = static_probe_value(system, result, model.probes[2 * k]);
    const double phi = static_probe_value(system, result, model.probes[2 * k + 1]);
    EXPECT_NEAR(w, reference.w, 1e-10 * std::abs(tip.w)) << "N=" << segments << " x=" << x;
    EXPECT_NEAR(phi, reference.phi, 1e-10 * std::abs(tip.phi)) << "N=" << segments << " x=" << x;
  }
}

class CantileverStatics : public ::testing::TestWithParam<int> {};

TEST_P(CantileverStatics, TipForceMatchesClosedForm) {
  const double force = 1.7, length = 0.5, ei = 2.0;
  expect_nodes_match(GetParam(), {load(LoadKind::force, length, force)}, [&](double x) {
    return ClosedForm{force * x * x * (3 * length - x) / (6 * ei),
                      force * x * (2 * length - x) / (2 * ei)};
  });
}

TEST_P(CantileverStatics, TipMomentMatchesClosedForm) {
  const double moment = -0.3, length = 0.5, ei = 2.0;
  expect_nodes_match(GetParam(), {load(LoadKind::moment, length, moment)}, [&](double x) {
    return ClosedForm{moment * x * x / (2 * ei), moment * x / ei};
  });
}

TEST_P(CantileverStatics, PartialMomentPairMatchesClosedForm) {
  // 0.13 L and 0.61 L fall inside the uniform grid's segments for every N tested: the mesher puts
  // nodes there, so the segments are unequal and the check covers that mesh too.
  const double torque = 0.25, length = 0.5, ei = 2.0, a = 0.13 * length, b = 0.61 * length;
  expect_nodes_match(
      GetParam(), {load(LoadKind::moment, a, -torque), load(LoadKind::moment, b, torque)},
      [&](double x) {
        if (x <= a) return ClosedForm{0.0, 0.0};
        if (x <= b) return ClosedForm{torque * (x - a) * (x - a) / (2 * ei), torque * (x - a) / ei};
        return ClosedForm{torque * (b - a) * (b - a) / (2 * ei) + torque * (b - a) * (x - b) / ei,
                          torque * (b - a) / ei};
      });
}

INSTANTIATE_TEST_SUITE_P(Segments, CantileverStatics, ::testing::Values(1, 2, 7, 50));

}  // namespace
}  // namespace emnet

namespace emnet {
namespace {

// Statically indeterminate and other supports, central force F at L/2 (closed forms, x ≤ L/2,
// symmetric beyond):
//   clamped–clamped: w = F·x²·(3L − 4x)/(48EI)      pinned–pinned: w = F·x·(3L² − 4x²)/(48EI)
// Exact at the nodes for every N (Hermite statics, consistent load when L/2 is inside a
// segment), so 1e-10 relative to the central deflection. N = 7 puts L/2 inside a segment.
class SupportedBeamStatics : public ::testing::TestWithParam<int> {};

void expect_central_load_matches(EndCondition end, int segments,
                                 const std::function<double(double)>& exact) {
  Scene scene = testing::cantilever_scene(segments);
  scene.beam.left = scene.beam.right = end;
  const double length = scene.beam.length;
  scene.loads = {testing::load(LoadKind::force, length / 2, 1.3)};
  for (int k = 0; k <= segments; ++k)
    scene.probes.push_back(testing::beam_probe("w" + std::to_string(k), ProbeQuantity::deflection,
                                               length * k / segments));
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const StaticResult result = solve_static(system);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  const double scale = std::abs(exact(length / 2));
  for (int k = 0; k <= segments; ++k) {
    double x = length * k / segments;
    const double reference = exact(x <= length / 2 ? x : length - x);
    EXPECT_NEAR(static_probe_value(system, result, model.probes[static_cast<size_t>(k)]), reference,
                1e-10 * scale)
        << "N=" << segments << " x=" << x;
  }
}

TEST_P(SupportedBeamStatics, ClampedClampedCentralForce) {
  const double force = 1.3, length = 0.5, ei = 2.0;
  expect_central_load_matches(EndCondition::clamped, GetParam(), [&](double x) {
    return force * x * x * (3 * length - 4 * x) / (48 * ei);
  });
}

TEST_P(SupportedBeamStatics, PinnedPinnedCentralForce) {
  const double force = 1.3, length = 0.5, ei = 2.0;
  expect_central_load_matches(EndCondition::pinned, GetParam(), [&](double x) {
    return force * x * (3 * length * length - 4 * x * x) / (48 * ei);
  });
}

INSTANTIATE_TEST_SUITE_P(Segments, SupportedBeamStatics, ::testing::Values(2, 7, 50));

// A free–free beam has no static state: the analysis says so instead of returning garbage.
TEST(BeamStatics, FreeBodyIsReportedNotSolved) {
  Scene scene = testing::cantilever_scene(5);
  scene.beam.left = scene.beam.right = EndCondition::free;
  scene.loads = {testing::load(LoadKind::force, 0.5, 1.0)};
  const System system = build_model(scene).network.assemble();
  const StaticResult result = solve_static(system);
  EXPECT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("no unique static state"), std::string::npos);
}

}  // namespace
}  // namespace emnet
