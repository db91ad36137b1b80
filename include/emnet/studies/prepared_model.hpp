// A scene made ready for the analyses that linearise: its model (prepare_model: every "auto"
// key resolved, then built), the assembled System and its operating point
// (emnet/analysis/operating_point.hpp: the static state, else zero for a linear network without
// one, whose note is then added to the model's notes). What the command line's analyses and the
// Python module start from.
#pragma once

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/model/model.hpp"
#include "emnet/studies/resolve.hpp"

namespace emnet {

struct PreparedModel {
  Status status;  // the operating point's failure ("static operating point: …")
  Model model;
  System system;
  StaticResult rest;  // the operating point (OperatingPoint::rest)
};

// InputError from prepare_model; the operating point's numerical failure is the Status.
PreparedModel prepare_at_rest(const Scene& scene, const PrepareOptions& options = {},
                              const OperatingPointOptions& point_options = {});

}  // namespace emnet
