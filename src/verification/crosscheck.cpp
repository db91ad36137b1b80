// Cross-check against ngspice: include/emnet/verification/crosscheck.hpp explains what is compared
// and why each tolerance. The comparisons are in crosscheck_<analysis>.cpp, their shared state in
// crosscheck_session.hpp; this file has the public functions.
#include "emnet/verification/crosscheck.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "crosscheck_session.hpp"
#include "emnet/core/option_error.hpp"

namespace emnet {

const char* crosscheck_analysis_name(CrosscheckAnalysis analysis) {
  switch (analysis) {
    case CrosscheckAnalysis::op:
      return "op";
    case CrosscheckAnalysis::ac:
      return "ac";
    case CrosscheckAnalysis::modal:
      return "modal";
    case CrosscheckAnalysis::tran:
      return "tran";
  }
  return "?";
}

std::vector<CrosscheckAnalysis> parse_crosscheck_analyses(const std::string& text) {
  constexpr const char* field = "analyses";
  if (text == "all")
    return {CrosscheckAnalysis::op, CrosscheckAnalysis::ac, CrosscheckAnalysis::modal,
            CrosscheckAnalysis::tran};
  std::vector<CrosscheckAnalysis> analyses;
  std::istringstream in(text);
  for (std::string name; std::getline(in, name, ',');) {
    CrosscheckAnalysis analysis;
    if (name == "op")
      analysis = CrosscheckAnalysis::op;
    else if (name == "ac")
      analysis = CrosscheckAnalysis::ac;
    else if (name == "modal")
      analysis = CrosscheckAnalysis::modal;
    else if (name == "tran")
      analysis = CrosscheckAnalysis::tran;
    else
      throw OptionError(field, "unknown analysis '" + name + "' (op, ac, modal, tran, or all)");
    if (std::find(analyses.begin(), analyses.end(), analysis) == analyses.end())
      analyses.push_back(analysis);
  }
  if (analyses.empty()) throw OptionError(field, "names no analysis");
  return analyses;
}

void CrosscheckOptions::validate() const {
  if (!(same_network_tolerance > 0.0)) throw OptionError("same_network_tolerance", "must be > 0");
  if (modal_count < 1 || modal_count > 20)
    throw OptionError("modal_count", "must be between 1 and 20");
  if (!(modal_half_width > 0.0 && modal_half_width < 0.5))
    throw OptionError("modal_half_width", "must be between 0 and 0.5");
  if (modal_points < 10 || modal_points > 100000)
    throw OptionError("modal_points", "must be between 10 and 100000");
  if (!(tran_periods > 0.0 && tran_periods <= 1000.0))
    throw OptionError("tran_periods", "must be > 0 and at most 1000");
  if (tran_points_per_period < 2 || tran_points_per_period > 100000)
    throw OptionError("tran_points_per_period", "must be between 2 and 100000");
  if (!(tran_reltol > 0.0 && tran_reltol < 1.0))
    throw OptionError("tran_reltol", "must be between 0 and 1");
  if (!(tran_tolerance_per_reltol > 0.0))
    throw OptionError("tran_tolerance_per_reltol", "must be > 0");
}

bool CrosscheckReport::all_pass() const {
  if (!status.ok()) return false;
  for (const auto& row : rows)
    if (!row.pass) return false;
  return true;
}

CrosscheckReport run_crosscheck(const Model& model, const CrosscheckOptions& options) {
  return crosscheck_detail::CrosscheckSession(model, options).run();
}

LargestDifference largest_relative_difference(const std::vector<double>& a,
                                              const std::vector<double>& b, double scale) {
  if (a.size() != b.size()) throw std::invalid_argument("largest_relative_difference: sizes");
  if (!(scale > 0.0)) scale = 1.0;
  LargestDifference largest;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const double d = std::abs(a[k] - b[k]) / scale;
    if (d > largest.value || k == 0) largest = {d, k};
  }
  return largest;
}

bool parabolic_peak_frequency(const std::vector<double>& frequencies,
                              const std::vector<double>& magnitudes, double& peak_hz) {
  if (frequencies.size() != magnitudes.size() || frequencies.size() < 3) return false;
  const std::size_t top = static_cast<std::size_t>(
      std::max_element(magnitudes.begin(), magnitudes.end()) - magnitudes.begin());
  if (top == 0 || top + 1 >= magnitudes.size() || !(magnitudes[top] > 0.0)) return false;
  // y = 1/|H|² against u = f²: y = a·u² + b·u + c through the three points.
  double u[3], y[3];
  for (int k = 0; k < 3; ++k) {
    const std::size_t i = top - 1 + static_cast<std::size_t>(k);
    if (!(magnitudes[i] > 0.0)) return false;
    u[k] = frequencies[i] * frequencies[i];
    y[k] = 1.0 / (magnitudes[i] * magnitudes[i]);
  }
  // Divided differences (well conditioned for a narrow bracket).
  const double d01 = (y[1] - y[0]) / (u[1] - u[0]);
  const double d12 = (y[2] - y[1]) / (u[2] - u[1]);
  const double a = (d12 - d01) / (u[2] - u[0]);
  if (!(a > 0.0)) return false;
  // y' = d01 + a·(2u − u0 − u1) = 0
  const double u_min = 0.5 * (u[0] + u[1] - d01 / a);
  if (!(u_min > u[0] && u_min < u[2])) return false;
  peak_hz = std::sqrt(u_min);
  return std::isfinite(peak_hz);
}

}  // namespace emnet
