// RAII owners of SUNDIALS handles (SUNDIALS 6.x: every object lives in a SUNContext).
#pragma once

#include <ida/ida.h>
#include <ida/ida_ls.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace emnet::sundials {

// What a failed IDA call returned, named: "IDASetId: IDA_ILL_INPUT (-22)". IDA's own calls
// return IDA_* flags; the linear-solver interface (IDASetLinearSolver, IDASetJacFn) returns
// IDALS_* flags, named by IDAGetLinReturnFlagName. Both name functions return malloc'd text.
inline std::string describe_flag(const char* call, int flag, bool linear_solver_interface) {
  char* name = linear_solver_interface ? IDAGetLinReturnFlagName(flag) : IDAGetReturnFlagName(flag);
  std::string text =
      std::string(call) + ": " + (name ? name : "unknown flag") + " (" + std::to_string(flag) + ")";
  std::free(name);
  return text;
}

// Compiled kernels of the serial vector operations that IDA calls, installed in each Vector's
// operation table (IDA's own vectors are clones and share it). Debian's SUNDIALS 6.4.1 is
// built without optimisation: each element of its N_VLinearSum or N_VWrmsNorm makes a round
// trip through the stack (8 ns), and its kernels took 45 % of the 1000-segment fin's run.
// Each kernel does the same floating-point operations in the same order as SUNDIALS's own
// (special cases included), so results are bit-for-bit the same.
namespace kernels {

inline sunindextype length(N_Vector v) {
  return NV_LENGTH_S(v);
}
inline realtype* data(N_Vector v) {
  return NV_DATA_S(v);
}

// y += a·x, as SUNDIALS's axpy.
inline void add_scaled(realtype a, N_Vector x, N_Vector y) {
  const sunindextype n = length(x);
  const realtype* xd = data(x);
  realtype* yd = data(y);
  if (a == 1.0) {
    for (sunindextype i = 0; i < n; ++i) yd[i] += xd[i];
  } else if (a == -1.0) {
    for (sunindextype i = 0; i < n; ++i) yd[i] -= xd[i];
  } else {
    for (sunindextype i = 0; i < n; ++i) yd[i] += a * xd[i];
  }
}

// z = a·x + b·y with SUNDIALS's case analysis (e.g. a = b: z = a·(x + y)).
inline void linear_sum(realtype a, N_Vector x, realtype b, N_Vector y, N_Vector z) {
  if (b == 1.0 && z == y) return add_scaled(a, x, y);
  if (a == 1.0 && z == x) return add_scaled(b, y, x);
  const sunindextype n = length(x);
  const realtype *xd = data(x), *yd = data(y);
  realtype* zd = data(z);
  if (a == 1.0 && b == 1.0) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] + yd[i];
  } else if ((a == 1.0 && b == -1.0) || (a == -1.0 && b == 1.0)) {
    const realtype* minuend = a == 1.0 ? xd : yd;
    const realtype* subtrahend = a == 1.0 ? yd : xd;
    for (sunindextype i = 0; i < n; ++i) zd[i] = minuend[i] - subtrahend[i];
  } else if (a == 1.0 || b == 1.0) {
    const realtype c = a == 1.0 ? b : a;
    const realtype* scaled = a == 1.0 ? yd : xd;
    const realtype* added = a == 1.0 ? xd : yd;
    for (sunindextype i = 0; i < n; ++i) zd[i] = c * scaled[i] + added[i];
  } else if (a == -1.0 || b == -1.0) {
    const realtype c = a == -1.0 ? b : a;
    const realtype* scaled = a == -1.0 ? yd : xd;
    const realtype* subtracted = a == -1.0 ? xd : yd;
    for (sunindextype i = 0; i < n; ++i) zd[i] = c * scaled[i] - subtracted[i];
  } else if (a == b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] + yd[i]);
  } else if (a == -b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] - yd[i]);
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
  }
}

inline void constant(realtype c, N_Vector z) {
  const sunindextype n = length(z);
  realtype* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c;
}

inline void product(N_Vector x, N_Vector y, N_Vector z) {
  const sunindextype n = length(x);
  const realtype *xd = data(x), *yd = data(y);
  realtype* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] * yd[i];
}

inline void quotient(N_Vector x, N_Vector y, N_Vector z) {
  const sunindextype n = length(x);
  const realtype *xd = data(x), *yd = data(y);
  realtype* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] / yd[i];
}

inline void scale(realtype c, N_Vector x, N_Vector z) {
  const sunindextype n = length(x);
  const realtype* xd = data(x);
  realtype* zd = data(z);
  if (c == 1.0) {
    if (z != x)
      for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i];
  } else if (c == -1.0) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = -xd[i];
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = c * xd[i];
  }
}

inline void absolute(N_Vector x, N_Vector z) {
  const sunindextype n = length(x);
  const realtype* xd = data(x);
  realtype* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = std::abs(xd[i]);
}

inline void inverse(N_Vector x, N_Vector z) {
  const sunindextype n = length(x);
  const realtype* xd = data(x);
  realtype* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = 1.0 / xd[i];
}

inline void add_constant(N_Vector x, realtype b, N_Vector z) {
  const sunindextype n = length(x);
  const realtype* xd = data(x);
  realtype* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] + b;
}

inline realtype dot_product(N_Vector x, N_Vector y) {
  const sunindextype n = length(x);
  const realtype *xd = data(x), *yd = data(y);
  realtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) sum += xd[i] * yd[i];
  return sum;
}

inline realtype max_norm(N_Vector x) {
  const sunindextype n = length(x);
  const realtype* xd = data(x);
  realtype largest = 0.0;
  for (sunindextype i = 0; i < n; ++i)
    if (std::abs(xd[i]) > largest) largest = std::abs(xd[i]);
  return largest;
}

inline realtype weighted_square_sum(N_Vector x, N_Vector w) {
  const sunindextype n = length(x);
  const realtype *xd = data(x), *wd = data(w);
  realtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) {
    const realtype product = xd[i] * wd[i];
    sum += product * product;
  }
  return sum;
}

inline realtype weighted_square_sum_masked(N_Vector x, N_Vector w, N_Vector id) {
  const sunindextype n = length(x);
  const realtype *xd = data(x), *wd = data(w), *idd = data(id);
  realtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i)
    if (idd[i] > 0.0) {
      const realtype product = xd[i] * wd[i];
      sum += product * product;
    }
  return sum;
}

inline realtype root_of_positive(realtype x) {
  return x <= 0.0 ? 0.0 : std::sqrt(x);
}

inline realtype wrms_norm(N_Vector x, N_Vector w) {
  return root_of_positive(weighted_square_sum(x, w) / static_cast<realtype>(length(x)));
}

inline realtype wrms_norm_masked(N_Vector x, N_Vector w, N_Vector id) {
  return root_of_positive(weighted_square_sum_masked(x, w, id) / static_cast<realtype>(length(x)));
}

inline realtype minimum(N_Vector x) {
  const sunindextype n = length(x);
  const realtype* xd = data(x);
  realtype smallest = xd[0];
  for (sunindextype i = 1; i < n; ++i)
    if (xd[i] < smallest) smallest = xd[i];
  return smallest;
}

inline void compare(realtype c, N_Vector x, N_Vector z) {
  const sunindextype n = length(x);
  const realtype* xd = data(x);
  realtype* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = std::abs(xd[i]) >= c ? 1.0 : 0.0;
}

}  // namespace kernels

// Installs the kernels above in a serial vector's operation table; the fused and vector-array
// operations are left to SUNDIALS's generic loops over them.
inline void install_compiled_kernels(N_Vector vector) {
  N_Vector_Ops ops = vector->ops;
  ops->nvlinearsum = kernels::linear_sum;
  ops->nvconst = kernels::constant;
  ops->nvprod = kernels::product;
  ops->nvdiv = kernels::quotient;
  ops->nvscale = kernels::scale;
  ops->nvabs = kernels::absolute;
  ops->nvinv = kernels::inverse;
  ops->nvaddconst = kernels::add_constant;
  ops->nvdotprod = kernels::dot_product;
  ops->nvdotprodlocal = kernels::dot_product;
  ops->nvmaxnorm = kernels::max_norm;
  ops->nvmaxnormlocal = kernels::max_norm;
  ops->nvwrmsnorm = kernels::wrms_norm;
  ops->nvwrmsnormmask = kernels::wrms_norm_masked;
  ops->nvwsqrsumlocal = kernels::weighted_square_sum;
  ops->nvwsqrsummasklocal = kernels::weighted_square_sum_masked;
  ops->nvmin = kernels::minimum;
  ops->nvminlocal = kernels::minimum;
  ops->nvcompare = kernels::compare;
}

class Context {
 public:
  Context() {
    if (SUNContext_Create(nullptr, &context_) != 0) throw std::runtime_error("SUNContext_Create");
  }
  ~Context() { SUNContext_Free(&context_); }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  operator SUNContext() const { return context_; }

 private:
  SUNContext context_ = nullptr;
};

class Vector {
 public:
  Vector(sunindextype length, SUNContext context) : vector_(N_VNew_Serial(length, context)) {
    if (!vector_) throw std::runtime_error("N_VNew_Serial");
    install_compiled_kernels(vector_);
  }
  ~Vector() { N_VDestroy(vector_); }
  Vector(const Vector&) = delete;
  Vector& operator=(const Vector&) = delete;
  operator N_Vector() const { return vector_; }
  double* data() const { return N_VGetArrayPointer(vector_); }

 private:
  N_Vector vector_;
};

class Matrix {
 public:
  explicit Matrix(SUNMatrix matrix) : matrix_(matrix) {
    if (!matrix_) throw std::runtime_error("SUNMatrix creation");
  }
  ~Matrix() { SUNMatDestroy(matrix_); }
  Matrix(const Matrix&) = delete;
  Matrix& operator=(const Matrix&) = delete;
  operator SUNMatrix() const { return matrix_; }

 private:
  SUNMatrix matrix_;
};

class LinearSolver {
 public:
  explicit LinearSolver(SUNLinearSolver solver) : solver_(solver) {
    if (!solver_) throw std::runtime_error("SUNLinearSolver creation");
  }
  ~LinearSolver() { SUNLinSolFree(solver_); }
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;
  operator SUNLinearSolver() const { return solver_; }

 private:
  SUNLinearSolver solver_;
};

class Ida {
 public:
  explicit Ida(SUNContext context) : memory_(IDACreate(context)) {
    if (!memory_) throw std::runtime_error("IDACreate");
  }
  ~Ida() { IDAFree(&memory_); }
  Ida(const Ida&) = delete;
  Ida& operator=(const Ida&) = delete;
  void* get() const { return memory_; }

 private:
  void* memory_;
};

}  // namespace emnet::sundials
