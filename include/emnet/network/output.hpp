// An output of a network: a linear functional of its unknowns y, or the time integral of one.
//
// Analyses evaluate outputs (static value, AC phasor, time course, mode shape) without knowing
// what built them; the model layer makes them from a scene's probes (deflection at x, DEA
// voltage, …), tests make them directly.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "emnet/core/quantity.hpp"

namespace emnet {

// A linear functional Σ coefficient·y[index] over the unknowns.
using LinearTerms = std::vector<std::pair<int, double>>;

// An output: a linear functional of y. For `integrations` = 1 the quantity is the time
// integral of the functional (a deflection from velocities: W = V/(jω) in AC).
struct Probe {
  std::string name;
  ProbeQuantity quantity = ProbeQuantity::deflection;
  std::string unit;
  LinearTerms terms;
  int integrations = 0;
  std::string description;  // "deflection at x = 70.0 mm"
};

}  // namespace emnet
