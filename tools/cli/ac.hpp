// The ac command's two files: ac.cpp parses its options and calls emnet::run_ac_study;
// ac_report.cpp prints the result (text table, --json, --csv, --plot). The frequency and
// reduction options it shares with other commands are in ac_options.cpp.
#pragma once

#include <string>
#include <vector>

#include "cli/common.hpp"
#include "emnet/studies/ac_study.hpp"

namespace emnet_cli {

// What the report needs besides the result: the command's options, the model and the sweep.
struct AcReportInput {
  const CommonOptions& options;
  const Prepared& prepared;                 // the model, its system and operating point
  const emnet::AcSpec& spec;                // the sweep as checked (checked_ac_spec)
  const std::vector<emnet::Probe>& probes;  // the responses, in the result's order
  const emnet::AcStudyResult& result;       // a successful run_ac_study
  std::string plot;                         // --plot path, or empty
  bool plot_script = false;                 // --plot-script: the plot's .dat and .gp too
  double total_seconds = 0.0;               // the command from its start
};

// Prints the result and writes its files; returns the exit status (0, or 5 outside validity).
int report_ac(const AcReportInput& input);

}  // namespace emnet_cli
