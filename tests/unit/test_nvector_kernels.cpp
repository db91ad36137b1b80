// The compiled N_Vector kernels that IDA's vectors use (src/analysis/sundials_handles.hpp)
// against SUNDIALS's own serial kernels, and the IDA calls' flags checked.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "../../src/analysis/sundials_handles.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/network/network.hpp"

namespace emnet {
namespace {

// Two families of serial vectors of one length: `reference` keeps SUNDIALS's operation table,
// `compiled` has the project's kernels installed. Slot k of both starts with the same values.
class VectorPairs {
 public:
  VectorPairs(sunindextype length, int count) : length_(length) {
    for (int k = 0; k < count; ++k) {
      reference_.push_back(N_VNew_Serial(length, context_));
      compiled_.push_back(N_VNew_Serial(length, context_));
      sundials::install_compiled_kernels(compiled_.back());
    }
  }
  ~VectorPairs() {
    for (N_Vector v : reference_) N_VDestroy(v);
    for (N_Vector v : compiled_) N_VDestroy(v);
  }
  VectorPairs(const VectorPairs&) = delete;
  VectorPairs& operator=(const VectorPairs&) = delete;

  // Random values with signs, exact ±1 and 0 entries, and spread magnitudes (1e-8 … 1e8), so
  // that the kernels' special cases and rounding are exercised.
  void fill_randomly(std::mt19937_64& random) {
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-8, 8), kind(0, 9);
    for (size_t k = 0; k < reference_.size(); ++k)
      for (sunindextype i = 0; i < length_; ++i) {
        const int which = kind(random);
        const double value = which == 0   ? 0.0
                             : which == 1 ? 1.0
                             : which == 2 ? -1.0
                                          : mantissa(random) * std::pow(10.0, exponent(random));
        NV_Ith_S(reference_[k], i) = value;
        NV_Ith_S(compiled_[k], i) = value;
      }
  }
  N_Vector reference(int k) const { return reference_[static_cast<size_t>(k)]; }
  N_Vector compiled(int k) const { return compiled_[static_cast<size_t>(k)]; }
  // Bit-for-bit equality of slot k in both families (memcmp: NaN and −0 count).
  bool same_bits(int k) const {
    return std::memcmp(NV_DATA_S(reference(k)), NV_DATA_S(compiled(k)),
                       static_cast<size_t>(length_) * sizeof(realtype)) == 0;
  }

 private:
  sunindextype length_;
  sundials::Context context_;
  std::vector<N_Vector> reference_, compiled_;
};

bool same_bits(realtype a, realtype b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Reference: SUNDIALS 6's serial N_Vector (the operations the kernels replace), on random
// vectors of several lengths including 1. Tolerance: none — the kernels promise the same
// floating-point operations in the same order, so every result must match bit for bit.
TEST(NvectorKernels, EveryInstalledOperationMatchesSundialsBitForBit) {
  std::mt19937_64 random(20261204);
  const double coefficients[] = {1.0, -1.0, 2.5, -2.5, 0.0, 1e-7};
  for (sunindextype length : {1, 2, 7, 64, 1001}) {
    VectorPairs v(length, 4);
    for (int trial = 0; trial < 5; ++trial) {
      auto vector_op = [&](const char* name, auto&& op, int output) {
        v.fill_randomly(random);
        op(v.reference(0), v.reference(1), v.reference(2), v.reference(3));
        op(v.compiled(0), v.compiled(1), v.compiled(2), v.compiled(3));
        for (int k = 0; k < 4; ++k)
          EXPECT_TRUE(v.same_bits(k)) << name << ", slot " << k << ", length " << length
                                      << (k == output ? " (output)" : " (input changed)");
      };
      auto scalar_op = [&](const char* name, auto&& op) {
        v.fill_randomly(random);
        const realtype expected = op(v.reference(0), v.reference(1), v.reference(2));
        const realtype got = op(v.compiled(0), v.compiled(1), v.compiled(2));
        EXPECT_TRUE(same_bits(expected, got))
            << name << ", length " << length << ": " << expected << " vs " << got;
      };
      for (double a : coefficients)
        for (double b : coefficients) {
          // z distinct, z aliasing y, z aliasing x: the kernels' axpy shortcuts.
          vector_op(
              "linearsum",
              [&](N_Vector x, N_Vector y, N_Vector z, N_Vector) {
                x->ops->nvlinearsum(a, x, b, y, z);
              },
              2);
          vector_op(
              "linearsum z = y",
              [&](N_Vector x, N_Vector y, N_Vector, N_Vector) {
                x->ops->nvlinearsum(a, x, b, y, y);
              },
              1);
          vector_op(
              "linearsum z = x",
              [&](N_Vector x, N_Vector y, N_Vector, N_Vector) {
                x->ops->nvlinearsum(a, x, b, y, x);
              },
              0);
        }
      for (double c : coefficients) {
        vector_op(
            "const", [&](N_Vector, N_Vector, N_Vector z, N_Vector) { z->ops->nvconst(c, z); }, 2);
        vector_op(
            "scale", [&](N_Vector x, N_Vector, N_Vector z, N_Vector) { x->ops->nvscale(c, x, z); },
            2);
        vector_op(
            "scale in place",
            [&](N_Vector x, N_Vector, N_Vector, N_Vector) { x->ops->nvscale(c, x, x); }, 0);
        vector_op(
            "addconst",
            [&](N_Vector x, N_Vector, N_Vector z, N_Vector) { x->ops->nvaddconst(x, c, z); }, 2);
        vector_op(
            "compare",
            [&](N_Vector x, N_Vector, N_Vector z, N_Vector) {
              x->ops->nvcompare(std::abs(c), x, z);
            },
            2);
      }
      vector_op(
          "prod", [](N_Vector x, N_Vector y, N_Vector z, N_Vector) { x->ops->nvprod(x, y, z); }, 2);
      vector_op(
          "div", [](N_Vector x, N_Vector y, N_Vector z, N_Vector) { x->ops->nvdiv(x, y, z); }, 2);
      vector_op(
          "abs", [](N_Vector x, N_Vector, N_Vector z, N_Vector) { x->ops->nvabs(x, z); }, 2);
      vector_op(
          "inv", [](N_Vector x, N_Vector, N_Vector z, N_Vector) { x->ops->nvinv(x, z); }, 2);
      scalar_op("dotprod",
                [](N_Vector x, N_Vector y, N_Vector) { return x->ops->nvdotprod(x, y); });
      scalar_op("dotprodlocal",
                [](N_Vector x, N_Vector y, N_Vector) { return x->ops->nvdotprodlocal(x, y); });
      scalar_op("maxnorm", [](N_Vector x, N_Vector, N_Vector) { return x->ops->nvmaxnorm(x); });
      scalar_op("maxnormlocal",
                [](N_Vector x, N_Vector, N_Vector) { return x->ops->nvmaxnormlocal(x); });
      scalar_op("wrmsnorm",
                [](N_Vector x, N_Vector w, N_Vector) { return x->ops->nvwrmsnorm(x, w); });
      scalar_op("wrmsnormmask", [](N_Vector x, N_Vector w, N_Vector id) {
        return x->ops->nvwrmsnormmask(x, w, id);
      });
      scalar_op("wsqrsumlocal",
                [](N_Vector x, N_Vector w, N_Vector) { return x->ops->nvwsqrsumlocal(x, w); });
      scalar_op("wsqrsummasklocal", [](N_Vector x, N_Vector w, N_Vector id) {
        return x->ops->nvwsqrsummasklocal(x, w, id);
      });
      scalar_op("min", [](N_Vector x, N_Vector, N_Vector) { return x->ops->nvmin(x); });
      scalar_op("minlocal", [](N_Vector x, N_Vector, N_Vector) { return x->ops->nvminlocal(x); });
    }
  }
}

// A call IDA refuses is a failed Status naming the call and its flag, not a failure further on
// under another name. Reference: IDASVtolerances returns IDA_ILL_INPUT for rtol < 0 (SUNDIALS
// 6 ida.c); the run must stop at that call.
TEST(SundialsFlags, RefusedToleranceNamesTheCallAndItsFlag) {
  Network network;
  const NodeId v = network.add_node("v", Domain::translational, "mass velocity");
  network.add<Capacitor>("m", v, ground, 0.2);
  network.add<Inductor>("k", v, ground, 1.0 / 50.0, Domain::translational);
  network.add<Conductance>("c", v, ground, 0.3);
  network.add<CurrentSource>("F", ground, v, Waveform::constant(2.0));
  const System system = network.assemble();
  Probe x;
  x.name = "x";
  x.terms = {{v, 1.0}};
  x.integrations = 1;
  TransientOptions options;
  options.end_time = 1.0;
  options.output_times = {0.0, 0.5, 1.0};
  options.relative_tolerance = -1.0;
  options.absolute_tolerance = 1e-9;
  const TransientResult result = run_transient_ida(system, {x}, options);
  ASSERT_FALSE(result.status.ok());
  EXPECT_NE(result.status.message.find("IDASVtolerances: IDA_ILL_INPUT (-22)"), std::string::npos)
      << result.status.message;
}

}  // namespace
}  // namespace emnet
