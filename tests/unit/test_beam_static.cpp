// Static deflection of the N-segment beam network against Euler–Bernoulli closed forms.
//
// Reference: cantilever (clamped at 0, free at L) under
//   tip force F:   w = F·x²·(3L − x)/(6EI),  φ = F·x·(2L − x)/(2EI)
//   tip moment M:  w = M·x²/(2EI),           φ = M·x/EI
//   moment pair −T at a, +T at b (a < b): bending moment T on [a, b], zero elsewhere, so
//     w = 0 (x ≤ a), T(x − a)²/(2EI) (a ≤ x ≤ b), T(b − a)²/(2EI) + T(b − a)(x − b)/EI (x ≥ b)
// The segment network has exactly the Hermite element's flexibility (DESIGN §2) and loads
// between nodes enter as consistent nodal loads, so nodal values are exact for every N: the
// only error is rounding in a sparse LU of a well-conditioned system, hence 1e-10 relative.
#include <gtest/gtest.h>

#include <cmath>

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
  ASSERT_TRUE(result.status.ok) << result.status.message;
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
  // Pair between nodes for every N tested (0.13 L and 0.61 L fall inside segments).
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
