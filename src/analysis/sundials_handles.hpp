// RAII owners of SUNDIALS handles (SUNDIALS 6.x: every object lives in a SUNContext).
#pragma once

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <stdexcept>

namespace emnet::sundials {

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
