// The tran command's two files: tran.cpp parses its options, checks them and calls the
// transient analysis (emnet/analysis/transient.hpp); tran_report.cpp prints the result (text
// table, --json, --csv, --plot).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/shape_output.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/validity.hpp"

namespace emnet_cli {

struct TranOptions {
  std::optional<double> switching;  // Hz; default: the scene's drive.frequency
  double periods = 10.0;
  double rtol = 1e-6;
  double max_step = 0.0;
  double atol = 0.0;
  std::string method = "ida";
  std::string start = "rest";
  int points_per_period = 100;
  std::string plot;
  bool plot_script = false;  // --plot-script: the plot's .dat and .gp too
  ShapeOptions shape;        // --shape: the last period's
};

// What the report needs: the command's options, the model, the outputs and the result.
struct TranReportInput {
  const CommonOptions& options;
  const TranOptions& tran;
  const emnet::Model& model;
  const emnet::System& system;
  const std::vector<emnet::Probe>& probes;  // the outputs shown (table, --csv, --json)
  // The outputs --plot may draw: `probes`, then the plot-only ones (the DEA voltages beside
  // --probe); `plotted` indexes these.
  const std::vector<emnet::Probe>& plot_probes;
  const PlottedOutputs& plotted;
  const emnet::TransientResult& result;              // of `probes`
  const std::optional<emnet::DeformedShape>& shape;  // with --shape
  // The values of the plot-only outputs, [plot-only output][time].
  const std::vector<std::vector<double>>& plot_only_values;
  const emnet::Validity& validity;
  std::string start_text;      // the start state in words
  double end_time = 0.0;       // [s]
  double total_seconds = 0.0;  // the command from its start
};

// Prints the result and writes its files; returns the exit status (0, or 5 outside validity).
int report_tran(const TranReportInput& input);

}  // namespace emnet_cli
