// What a sweep changes, apart from what it does not (emnet/network/network.hpp, Excitation;
// emnet/model/drive.hpp, drive_excitation), and a System that owns its elements.
// Reference: a full rebuild, the model built from the scene with drive.frequency = f and
// assembled. The excitation-only rebuild must give the same b(t) and b_ac bit for bit (exact
// equality, no tolerance: the same waveforms from the same function, the same stamps), for the
// fish fin with its RC loops and with the ideal drive (with an overlap, whose on-time depends on
// the frequency), and for a sine drive, each at two frequencies.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "emnet/model/drive.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using emnet::testing::kFishfin;

bool same_matrix(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && Eigen::MatrixXd(a) == Eigen::MatrixXd(b);
}

// b(t) at 400 instants over two periods and at every breakpoint (both sides of each edge), and
// b_ac, of `swept` against `full`.
void expect_same_excitation(const System& swept, const System& full, double frequency) {
  const double span = 2.0 / frequency;
  std::vector<double> times;
  for (int k = 0; k <= 400; ++k) times.push_back(span * k / 400);
  for (double t : full.breakpoints(0.0, span)) {
    times.push_back(t);
    times.push_back(t * (1 + 1e-12));
    times.push_back(t * (1 - 1e-12));
  }
  EXPECT_EQ(swept.breakpoints(0.0, span), full.breakpoints(0.0, span));
  for (double t : times) EXPECT_TRUE(swept.b(t) == full.b(t)) << "b(t) at t = " << t;
  EXPECT_TRUE(swept.b_ac() == full.b_ac());
  ASSERT_EQ(swept.excitation().waveforms.size(), full.excitation().waveforms.size());
  ASSERT_EQ(swept.excitation().source_terms.size(), full.excitation().source_terms.size());
}

void expect_excitation_rebuild_exact(const Scene& scene, const std::vector<double>& frequencies) {
  const Model base = build_model(scene);
  const System system = base.network.assemble();
  for (double f : frequencies) {
    SCOPED_TRACE("f = " + std::to_string(f) + " Hz");
    Scene at = scene;
    at.drive.frequency = f;
    const System full = build_model(at).network.assemble();
    // What stays: G and C do not depend on the drive's frequency.
    EXPECT_TRUE(same_matrix(system.G, full.G));
    EXPECT_TRUE(same_matrix(system.C, full.C));
    EXPECT_EQ(system.is_nonlinear(), full.is_nonlinear());
    const System swept = system.with_excitation(drive_excitation(base, system.excitation(), f));
    expect_same_excitation(swept, full, f);
    // And from the excitation alone, without G and C.
    const System again =
        system.with_excitation(drive_excitation(base, base.network.assemble_excitation(), f));
    expect_same_excitation(again, full, f);
  }
}

TEST(DriveExcitation, FishFinWithItsRcLoopsAtTwoFrequencies) {
  const Scene scene = read_scene(kFishfin);
  ASSERT_TRUE(scene.drive.electrical_dynamics);
  expect_excitation_rebuild_exact(scene, {2.0, 6.4});
}

TEST(DriveExcitation, FishFinIdealDriveWithOverlapAtTwoFrequencies) {
  const Scene scene =
      read_scene(kFishfin, {"drive.electrical_dynamics=false", "drive.overlap=\"2 ms\""});
  expect_excitation_rebuild_exact(scene, {2.0, 6.4});
}

TEST(DriveExcitation, SineDriveAtTwoFrequencies) {
  Scene scene = read_scene(kFishfin, {"drive.electrical_dynamics=false"});
  scene.drive.kind = DriveKind::bias_differential;
  scene.drive.bias = 2000.0;
  scene.drive.amplitude = 1000.0;
  expect_excitation_rebuild_exact(scene, {2.0, 6.4});
}

TEST(DriveExcitation, RefusesAnExcitationOfAnotherNetwork) {
  const Model fin = build_model(read_scene(kFishfin));
  const Model ideal = build_model(read_scene(kFishfin, {"drive.electrical_dynamics=false"}));
  EXPECT_THROW(drive_excitation(fin, ideal.network.assemble_excitation(), 3.0), std::logic_error);
  System system = fin.network.assemble();
  Excitation wrong = system.excitation();
  wrong.ac = Eigen::VectorXcd::Zero(system.size() + 1);
  EXPECT_THROW(system.set_excitation(wrong), std::invalid_argument);
}

// The System is the last owner of its nonlinear elements once the model is gone: g(y) is the
// same as while the model lived (the reference), and no other owner is left.
TEST(SystemOwnership, SystemOutlivesItsModel) {
  System system;
  Eigen::VectorXd alive;
  Eigen::VectorXd y;
  {
    const Model model = build_model(read_scene(kFishfin));
    system = model.network.assemble();
    ASSERT_TRUE(system.is_nonlinear());
    y = Eigen::VectorXd::LinSpaced(system.size(), 1.0, 400.0);
    system.nonlinear(y, alive, nullptr);
  }
  for (const auto& element : system.nonlinear_elements) EXPECT_EQ(element.use_count(), 1);
  Eigen::VectorXd after;
  Eigen::SparseMatrix<double> jacobian;
  system.nonlinear(y, after, &jacobian);
  EXPECT_TRUE(after == alive);
  EXPECT_GT(jacobian.nonZeros(), 0);
}

}  // namespace
}  // namespace emnet
