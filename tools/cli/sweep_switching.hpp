// The sweep-switching command's two files: sweep_switching.cpp parses its options and calls
// emnet::run_switching_sweep; sweep_switching_report.cpp prints the result (text table, --json,
// --csv, --plot).
#pragma once

#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/shape_output.hpp"
#include "emnet/studies/switching_sweep.hpp"

namespace emnet_cli {

// What the report needs besides the result: the command's options and its notes.
struct SweepReportInput {
  const CommonOptions& options;
  const emnet::Model& model;
  const emnet::SwitchingSweepResult& result;
  const std::vector<std::string>& notes;
  std::string plot;            // --plot path, or empty
  bool plot_script = false;    // --plot-script: the plot's .dat and .gp too
  PlottedOutputs plotted;      // what --plot draws
  ShapeOptions shape;          // --shape, or an empty path
  double total_seconds = 0.0;  // the command from its start
};

// Prints the result and writes its files; returns the exit status (0, or 5 outside validity).
int report_switching_sweep(const SweepReportInput& input);

}  // namespace emnet_cli
