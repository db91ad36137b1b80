// The eigenpairs of the modal analysis' shift-invert operator T = (I − Π)·(Â + σ̂Ê)⁻¹·Ê on the
// equilibrated displacement-form pencil (analysis.hpp, modal; Π the rigid-body projector): every
// one by a dense decomposition for small pencils (modal.cpp), the ones nearest σ̂ by implicitly
// restarted Arnoldi (Spectra) for large ones (modal_arnoldi.cpp). An eigenvalue μ of T is the
// pole ŝ = σ̂ − 1/μ.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/core/errors.hpp"
#include "rigid_body_space.hpp"

namespace emnet {

// The sparse LU of Â + σ̂·Ê that T applies.
using ShiftInvertLu = Eigen::SparseLU<Eigen::SparseMatrix<double>>;

struct Eigenpairs {
  std::vector<std::complex<double>> values;  // μ
  std::vector<Eigen::VectorXcd> vectors;
};

// The eigenpairs of T nearest σ̂ (the right ones) and, with options.error_bounds, those of the
// transposed operator (the left vectors), by Arnoldi: the request starts at the conjugate pairs
// of the wanted modes (options.count, 0: 10) and grows while real poles and overdamped pairs
// take converged places (at most two more attempts). Adds the restarts to result.iterations and
// a shortfall of converged poles to result.note. `lu` factorises Â + σ̂·Ê (its transpose() is
// not const); `rigid` is empty without rigid-body motions. Reports through options.progress;
// cancelled: cancelled_status(). A request that converges to no pole is a failed Status.
Status arnoldi_eigenpairs(ShiftInvertLu& lu, const Eigen::SparseMatrix<double>& e_hat,
                          const RigidBodySpace& rigid, double sigma_hat,
                          const ModalOptions& options, Eigenpairs& right, Eigenpairs& left,
                          ModalResult& result);

}  // namespace emnet
