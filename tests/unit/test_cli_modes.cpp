// The modes command: probes, rigid-body motions by name, error bounds in its output.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using testing::run_emnet;

using emnet::testing::kCantilever;
using emnet::testing::kFishfin;

// --probe was accepted and ignored by modes (exit 0, no probe in the output). Now each probe's
// value in each mode, per unit of the mode's largest nodal deflection. Reference: the first mode
// of a clamped–free beam has its largest deflection at the tip (so the tip probe is exactly 1)
// and none at the clamp (P1 at x = 0: exactly 0, the node is held); P4 lies between (a positive
// fraction, the first mode has no node).
TEST(CliModes, ProbesGiveTheModeShapeThere) {
  const auto r = run_emnet("modes " + kFishfin +
                           " --count 2 --no-error-estimate --probe P1 --probe P4 "
                           "--probe deflection@122.5mm --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  const auto& probes = json["modes"][0]["probes"];
  ASSERT_EQ(probes.size(), 3u);
  EXPECT_EQ(probes[0]["value"].get<double>(), 0.0);
  EXPECT_GT(probes[1]["value"].get<double>(), 0.05);
  EXPECT_LT(probes[1]["value"].get<double>(), 0.95);
  EXPECT_NEAR(probes[2]["value"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(probes[2]["value_imag"].get<double>(), 0.0, 1e-12);
  const auto text = run_emnet("modes " + kFishfin + " --count 2 --no-error-estimate --probe P4");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("mode shape at the probes"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("P4"), std::string::npos);
  const auto bad = run_emnet("modes " + kFishfin + " --probe nowhere");
  EXPECT_EQ(bad.status, 2) << bad.out;
}

// Rigid-body motions by name, not as "real poles" with time constants of ±1e12 s. Reference:
// the kinematics of the supports.
TEST(CliModes, RigidBodyMotionsAreNamed) {
  struct Case {
    const char* left;
    const char* right;
    const char* name;
  };
  for (const Case& c : {Case{"pinned", "free", "rotation about x = 0 mm"},
                        Case{"sliding", "sliding", "translation"},
                        Case{"free", "free", "translation and rotation"}}) {
    const auto r = run_emnet("modes " + kCantilever +
                             " --segments 40 --no-error-estimate --set "
                             "beam.left=" +
                             c.left + " --set beam.right=" + c.right);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find(std::string("rigid-body motion (pole s = 0): ") + c.name),
              std::string::npos)
        << c.left << "-" << c.right << ":\n"
        << r.out;
    EXPECT_EQ(r.out.find("real (non-oscillatory) pole"), std::string::npos) << r.out;
  }
}

// Each mode's accuracy is its rounding error bound (first order, condition included) and the
// discretisation estimate; --json carries the bound per mode. Reference: the bound must cover
// the difference between two independent computations of the same pencil's poles, the dense
// method and Arnoldi (fish fin, N = 100), and be small (below 1e-9 relative there).
TEST(CliModes, ErrorBoundsCoverTheDifferenceOfTwoMethods) {
  const auto arnoldi = run_emnet("modes " + kFishfin +
                                 " --segments 100 --count 3 --no-error-estimate "
                                 "--json");
  const auto dense = run_emnet("modes " + kFishfin +
                               " --segments 100 --count 3 --no-error-estimate "
                               "--dense --json");
  ASSERT_EQ(arnoldi.status, 0) << arnoldi.err;
  ASSERT_EQ(dense.status, 0) << dense.err;
  const auto a = nlohmann::json::parse(arnoldi.out), d = nlohmann::json::parse(dense.out);
  for (size_t k = 0; k < 3; ++k) {
    ASSERT_TRUE(a["modes"][k]["error_bounded"].get<bool>());
    ASSERT_TRUE(d["modes"][k]["error_bounded"].get<bool>());
    const double fa = a["modes"][k]["frequency_hz"], fd = d["modes"][k]["frequency_hz"];
    const double ba = a["modes"][k]["frequency_error_bound_hz"],
                 bd = d["modes"][k]["frequency_error_bound_hz"];
    EXPECT_LE(std::abs(fa - fd), ba + bd) << "mode " << k + 1;
    EXPECT_LT(ba / fa, 1e-9);
  }
  const auto table = run_emnet("modes " + kFishfin + " --count 2");
  ASSERT_EQ(table.status, 0) << table.err;
  EXPECT_NE(table.out.find("rounding"), std::string::npos) << table.out;
}

}  // namespace
}  // namespace emnet
