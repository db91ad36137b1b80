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

/// A scene's model, its assembled System and its operating point.
struct PreparedModel {
  Status status;      ///< the operating point's failure ("static operating point: …")
  Model model;        ///< prepare_model of the scene: every "auto" key resolved, then built
  System system;      ///< model.network.assemble()
  StaticResult rest;  ///< the operating point (OperatingPoint::rest)
};

/// The PreparedModel of `scene`; the operating point's numerical failure is the Status.
/// @throws InputError from prepare_model
PreparedModel prepare_at_rest(const Scene& scene, const PrepareOptions& options = {},
                              const OperatingPointOptions& point_options = {});

}  // namespace emnet
