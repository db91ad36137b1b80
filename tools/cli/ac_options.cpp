// The frequency and modal-reduction options of several commands (declared in common.hpp): a
// frequency option ("6.4", "6.4 Hz", "2 kHz", "5 mHz"); the AC sweep of the scene's [ac] table
// with --from, --to, --points and --scale applied (ac, netlist --analysis ac); --tolerance and
// --band of a modal reduction (ac, sweep-switching); the warning when its tolerance is not met.
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "cli/common.hpp"
#include "cli/option_names.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/report/json.hpp"

namespace emnet_cli {

using emnet::InputError;

double parse_frequency(const std::string& text, const std::string& option) {
  try {
    size_t used = 0;
    const double value = std::stod(text, &used);
    std::string rest = text.substr(used);
    rest.erase(0, rest.find_first_not_of(' '));
    double factor = 1.0;
    if (rest == "kHz")
      factor = 1e3;
    else if (rest == "mHz")
      factor = 1e-3;
    else if (!rest.empty() && rest != "Hz")
      throw std::invalid_argument("unit");
    if (!std::isfinite(value)) throw std::invalid_argument("finite");
    return value * factor;
  } catch (const std::exception&) {
    throw InputError(option, option, "expected a frequency in Hz, got '" + text + "'");
  }
}

// Frequencies an AC sweep (or deck) may have: 1 to 1000000, inclusive.
constexpr int kMaximumAcPoints = 1000000;

// The AC sweep of the scene's [ac] table with --from, --to, --points and --scale applied
// (ac and netlist --analysis ac): one frequency (--points 1, --to equal to --from or not
// given) or an increasing range.
emnet::AcSpec checked_ac_spec(emnet::AcSpec spec, const std::string& from_text,
                              const std::string& to_text, std::optional<int> points,
                              const std::string& scale) {
  if (!from_text.empty()) spec.from = parse_frequency(from_text, "--from");
  if (!to_text.empty()) spec.to = parse_frequency(to_text, "--to");
  if (points) spec.points = *points;
  if (!scale.empty()) spec.log = scale == "log";
  if (spec.points < 1 || spec.points > kMaximumAcPoints)
    throw InputError("--points", "--points",
                     "must be from 1 to " + std::to_string(kMaximumAcPoints) +
                         " (inclusive), got " + std::to_string(spec.points));
  if (spec.from < 0.0) throw InputError("--from", "--from", "must be >= 0 Hz");
  if (spec.points == 1) {
    if (to_text.empty()) spec.to = spec.from;
    if (spec.to != spec.from)
      throw InputError("--to", "--to",
                       "one frequency (--points 1) needs --to equal to --from, or no --to");
  } else if (!(spec.to > spec.from)) {
    throw InputError("--to", "--to",
                     "must be > --from for a sweep of --points >= 2 (equal to it with --points 1)");
  }
  if (spec.log && !(spec.from > 0.0))
    throw InputError("--from", "--from", "a log sweep needs --from > 0 Hz");
  return spec;
}

// --tolerance and --band of a modal reduction (ac, sweep-switching); band defaults to
// `default_band` [Hz], tolerance to the scene's model.tolerance. Bad values are input errors
// naming the option.
emnet::ReductionOptions reduction_options(const std::string& tolerance, const std::string& band,
                                          double default_band, double default_tolerance) {
  emnet::ReductionOptions reduction;
  reduction.tolerance = default_tolerance;
  if (!tolerance.empty()) {
    try {
      size_t used = 0;
      reduction.tolerance = std::stod(tolerance, &used);
      if (used != tolerance.size()) throw std::invalid_argument("trailing text");
    } catch (const std::exception&) {
      throw InputError("--tolerance", "tolerance",
                       "expected a relative error in (0, 1), got '" + tolerance + "'");
    }
  }
  reduction.band = band.empty() ? default_band : parse_frequency(band, "--band");
  emnet::validate(reduction);
  return reduction;
}

// The reduction's modes, cut-off and measured error, said loudly when the tolerance is not met.
std::string tolerance_warning(double measured, double tolerance) {
  return "WARNING: modal reduction: the requested tolerance is NOT MET: measured error " +
         format("%.3g", measured) + " > " + format("%.3g", tolerance) +
         " against the full model. Raise --band (a higher cut-off keeps more modes) unless the "
         "note says poles below the cut-off were not found, or run without --reduce.";
}

void add_reduction_tolerance_and_band(CLI::App* command, std::string& tolerance,
                                      std::string& band) {
  sets_fields(command->add_option("--tolerance", tolerance,
                                  "modal reduction (--reduce, or --method auto where it "
                                  "reduces): relative error wanted, in (0, 1) (default: the "
                                  "scene's model.tolerance, 1e-3)"),
              {"tolerance", "reduction.tolerance"});
  sets_fields(command->add_option("--band", band,
                                  "modal reduction: highest frequency of interest [Hz] "
                                  "(default: --to)"),
              {"band", "reduction.band"});
}

}  // namespace emnet_cli
