// The method a result was computed by: one vocabulary for every Result that says how it was
// computed, named in reports and JSON by method_name().
#pragma once

#include <string>

namespace emnet {

/// The method that computed a result; each Result's field says which of these it takes.
enum class Method {
  direct,        ///< AC: a sparse LU solve per frequency
  pole_residue,  ///< AC: partial fractions over the pencil's poles
  reduced,       ///< AC, switching sweep: modal reduction with static correction
  dense,         ///< modes: dense eigen-decomposition, every pole
  arnoldi,       ///< modes: shift-invert Arnoldi, the poles nearest s = 0
  ida,           ///< transient: SUNDIALS IDA on the DAE
  exact,         ///< transient, periodic state, switching sweep: exact for a linear network
  shooting,      ///< periodic state, switching sweep: Newton on one-period IDA runs
};

/// "direct", "pole-residue", "reduced", "dense", "arnoldi", "ida", "exact" or "shooting".
inline std::string method_name(Method method) {
  switch (method) {
    case Method::direct:
      return "direct";
    case Method::pole_residue:
      return "pole-residue";
    case Method::reduced:
      return "reduced";
    case Method::dense:
      return "dense";
    case Method::arnoldi:
      return "arnoldi";
    case Method::ida:
      return "ida";
    case Method::exact:
      return "exact";
    case Method::shooting:
      return "shooting";
  }
  return "unknown";
}

}  // namespace emnet
