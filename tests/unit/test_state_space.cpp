// The state equation of the displacement form (analysis/state_space.hpp) by its two splits of
// E: the QR that every shipped scene takes and the SVD that rank-deficient pencils take.
// References: the direct sparse solve of (jω·E + A)·u = f at a frequency (the same pencil, no
// reduction), and the SVD split's poles. Tolerances: both are backward-stable orthogonal
// reductions of pencils with κ(Ê) ≤ 700 after equilibration, so rounding stays near κ·ε ≈ 1e-13
// times the pencil's own conditioning. Measured worst: responses 1.9e-12, poles 1.6e-11 (both on
// the tweezer jaw); 1e-10 leaves that room without letting a wrong block, sign or scaling through
// (each is O(1)).
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <complex>
#include <string>
#include <vector>

#include "analysis/displacement_form.hpp"
#include "analysis/state_space.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using Complex = std::complex<double>;

struct SmallSignalPencil {
  Model model;
  System system;
  Eigen::SparseMatrix<double> a, e;
  Eigen::VectorXd f;  // the AC input in the form's rows
};

// The scene's small-signal pencil about its operating point (the network's own for a linear
// one) and its AC input, as the pole–residue AC sweep forms them.
SmallSignalPencil small_signal_pencil(const std::string& scene, const std::vector<std::string>& overrides) {
  SmallSignalPencil p{prepare_model(read_scene(testing::shipped_scene(scene), overrides)), {}, {}, {}, {}};
  p.system = p.model.network.assemble();
  const DisplacementForm form(p.system);
  const StaticResult rest = solve_static(p.system);
  form.linearised(form.from_rest(rest.operating_point), Eigen::VectorXd::Zero(form.size()), p.a,
                  p.e);
  p.f = Eigen::VectorXd::Zero(form.size());
  p.f.head(p.system.size()) = p.system.b_ac().real();
  return p;
}

// u at s = jω from the state equation: x = (jω·I − M)⁻¹·N·f, then u from x and f.
Eigen::VectorXcd response_by_state(const LinearStateSpace& space, const Eigen::VectorXd& f,
                                   double omega) {
  const Eigen::Index n = space.state_size();
  const Eigen::MatrixXcd shifted =
      Complex(0.0, omega) * Eigen::MatrixXcd::Identity(n, n) - space.m().cast<Complex>();
  const Eigen::VectorXcd x = shifted.partialPivLu().solve(space.forcing(f).cast<Complex>());
  Eigen::VectorXd u_real, u_imag, up;
  space.full_state(x.real(), f, u_real, up);
  space.full_state(x.imag(), Eigen::VectorXd::Zero(f.size()), u_imag, up);
  return u_real.cast<Complex>() + Complex(0.0, 1.0) * u_imag.cast<Complex>();
}

Eigen::VectorXcd response_by_direct_solve(const SmallSignalPencil& p, double omega) {
  const Eigen::SparseMatrix<Complex> pencil =
      p.a.cast<Complex>() + Complex(0.0, omega) * p.e.cast<Complex>();
  Eigen::SparseLU<Eigen::SparseMatrix<Complex>> lu(pencil);
  return lu.solve(p.f.cast<Complex>());
}

// The largest distance of a pole of `m` from the nearest of `reference`, relative to the pole's
// size or to 1e-6 of the largest pole, whichever is larger. Below that floor sit the zero poles
// of rigid-body motions and hidden constraints: Jordan chains at s = 0 that rounding spreads
// over (ε·‖M‖)^(1/k) (on the tweezer jaw 1e-9 1/s, against poles up to 1e5 1/s), differently in
// each basis.
double largest_pole_mismatch(const Eigen::MatrixXd& m, const Eigen::MatrixXd& reference) {
  const Eigen::VectorXcd poles = m.eigenvalues(), expected = reference.eigenvalues();
  const double floor = 1e-6 * expected.cwiseAbs().maxCoeff();
  double worst = 0.0;
  for (const Complex& pole : poles) {
    double nearest = INFINITY;
    for (const Complex& other : expected) nearest = std::min(nearest, std::abs(pole - other));
    worst = std::max(worst, nearest / std::max(std::abs(pole), floor));
  }
  return worst;
}

struct SplitScene {
  std::string file;
  std::vector<std::string> overrides;
  double frequency;  // [Hz] near the first mode
};

class StateSpaceSplit : public ::testing::TestWithParam<SplitScene> {};

TEST_P(StateSpaceSplit, QrAndSvdGiveTheDirectSolvesResponseAndTheSamePoles) {
  const SplitScene& c = GetParam();
  const SmallSignalPencil p = small_signal_pencil(c.file, c.overrides);
  const DisplacementForm form(p.system);
  const double omega = 2.0 * M_PI * c.frequency;
  const LinearStateSpace by_qr(form, p.a, p.e, omega);
  const LinearStateSpace by_svd(form, p.a, p.e, omega, LinearStateSpace::Split::singular_values);
  ASSERT_EQ(by_qr.state_size(), by_svd.state_size());
  const Eigen::VectorXcd reference = response_by_direct_solve(p, omega);
  for (const LinearStateSpace* space : {&by_qr, &by_svd}) {
    const Eigen::VectorXcd u = response_by_state(*space, p.f, omega);
    EXPECT_LT((u - reference).norm(), 1e-10 * reference.norm());
  }
  EXPECT_LT(largest_pole_mismatch(by_qr.m(), by_svd.m()), 1e-10);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, StateSpaceSplit,
    ::testing::Values(SplitScene{"fishfin.toml", {"drive.electrical_dynamics=false"}, 6.0},
                      SplitScene{"fishfin-shear.toml", {"drive.electrical_dynamics=false"}, 6.0},
                      SplitScene{"cantilever.toml", {}, 10.0},
                      SplitScene{"tweezer-jaw.toml", {}, 16.5}),
    [](const auto& info) {
      std::string name = info.param.file.substr(0, info.param.file.find('.'));
      for (char& ch : name)
        if (ch == '-') ch = '_';
      return name;
    });

}  // namespace
}  // namespace emnet
