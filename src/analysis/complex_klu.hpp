// Sparse complex LU (SuiteSparse KLU) for a sweep over one pattern: the symbolic analysis once,
// a pivoting factorisation when asked, and otherwise a refactorisation that reuses the pivot
// order (no pivot search: the costly part of KLU's kernel, ~55 % of an AC sweep at N = 2000).
// The caller checks each solution's residual and asks for a pivoting factorisation when the
// reused pivots are no longer good enough. Handles are owned (RAII).
#pragma once

#include <klu.h>

#include <Eigen/Sparse>
#include <complex>
#include <stdexcept>

namespace emnet {

class ComplexKlu {
 public:
  using Matrix = Eigen::SparseMatrix<std::complex<double>, Eigen::ColMajor, int>;

  // `pattern` must be compressed; every later matrix has exactly its pattern.
  explicit ComplexKlu(const Matrix& pattern) {
    klu_defaults(&common_);
    // Partial pivoting proper (the largest entry of the column), not KLU's default threshold
    // 0.001 that prefers the diagonal: on the fish fin at N = 500 that threshold's pivots left
    // a relative residual of 3e-8 and a 1e-4 error in the response at the resonance; with
    // tol = 1 the error is 1.6e-10 (tests/unit/test_ac.cpp) at the same sweep time.
    common_.tol = 1.0;
    // No block-triangular pre-ordering: its maximum transversal took 3.3 s of the fish fin's AC
    // at N = 10 000 (60 006 unknowns: long augmenting paths through the zero diagonals of the
    // branch rows) on a network that is one block; without it the responses agree to
    // 3.6e-13 with the same residual, and partial pivoting (above) handles the zero diagonals.
    common_.btf = 0;
    symbolic_ =
        klu_analyze(static_cast<int>(pattern.rows()), const_cast<int*>(pattern.outerIndexPtr()),
                    const_cast<int*>(pattern.innerIndexPtr()), &common_);
    if (!symbolic_) throw std::runtime_error("KLU symbolic analysis failed");
  }
  ~ComplexKlu() {
    if (numeric_) klu_z_free_numeric(&numeric_, &common_);
    klu_free_symbolic(&symbolic_, &common_);
  }
  ComplexKlu(const ComplexKlu&) = delete;
  ComplexKlu& operator=(const ComplexKlu&) = delete;

  // Factorises `matrix`: with a pivot search when `pivoting` or the first time, else by
  // refactorisation with the previous pivots. False when the matrix is singular.
  bool factor(const Matrix& matrix, bool pivoting) {
    auto* values = reinterpret_cast<double*>(const_cast<std::complex<double>*>(matrix.valuePtr()));
    int* starts = const_cast<int*>(matrix.outerIndexPtr());
    int* rows = const_cast<int*>(matrix.innerIndexPtr());
    if (numeric_ && !pivoting)
      return klu_z_refactor(starts, rows, values, symbolic_, numeric_, &common_) == 1 &&
             common_.status == KLU_OK;
    if (numeric_) klu_z_free_numeric(&numeric_, &common_);
    numeric_ = klu_z_factor(starts, rows, values, symbolic_, &common_);
    return numeric_ != nullptr && common_.status == KLU_OK;
  }
  // Solves in place (one right-hand side).
  bool solve(Eigen::VectorXcd& rhs) {
    return klu_z_solve(symbolic_, numeric_, static_cast<int>(rhs.size()), 1,
                       reinterpret_cast<double*>(rhs.data()), &common_) == 1;
  }

 private:
  klu_common common_;
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
};

}  // namespace emnet
