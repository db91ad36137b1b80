// --shape: the beam's deformed shape as a CSV table, a picture (.png, .svg) or an animated GIF,
// for the commands that compute one (sweep-switching: at the sweep peak).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "cli/common.hpp"
#include "emnet/model/deformed_shape.hpp"
#include "emnet/model/model.hpp"

namespace emnet_cli {

struct ShapeOptions {
  std::string path;  // --shape: .csv, .png, .svg or .gif
  int instants = 0;  // --shape-instants; 0: 36 for a GIF, 8 otherwise
};

// Adds --shape and --shape-instants to `command`; `what` says where the shape is taken.
void add_shape_options(CLI::App* command, ShapeOptions& shape, const std::string& what);

// The instants to compute: 0 without --shape.
// @throws InputError naming --shape for an unknown extension, --shape-instants without --shape
int shape_instants(const ShapeOptions& shape);

// With --shape, writes `result` to shape.path (CSV: one row per instant and node; otherwise the
// picture or animation, emnet/report/shape_plot.hpp, titled with the scene, `what` and the
// kinematics of `model`) and, when `say`, prints "shape written to PATH (8 instants over one
// period at 6.4 Hz)". Nothing without --shape or without a result.
// @param what  the state drawn, e.g. "periodic state"
// @throws FileError when it cannot be written
void write_shape(const ShapeOptions& shape, const std::optional<emnet::DeformedShape>& result,
                 const emnet::Model& model, const std::string& what, const CommonOptions& options,
                 bool say);

}  // namespace emnet_cli
