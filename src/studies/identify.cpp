// Identification of bending stiffness and loss factor (emnet/studies/identify.hpp).
#include "emnet/studies/identify.hpp"

#include <cmath>
#include <utility>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/studies/periodic_peak.hpp"
#include "emnet/studies/resolve.hpp"

namespace emnet {
namespace {

// A failure that ends the fit: its Status becomes the result's.
struct FitStopped {
  Status status;
};

[[noreturn]] void stop(std::string why) {
  throw FitStopped{Status::failure(std::move(why))};
}

// "%.6g" without the exponent's leading zero: 1e-5, not 1e-05.
std::string short_number(double value) {
  std::string text = format_number("%.6g", value);
  for (const char* exponent : {"e-0", "e+0"})
    if (const size_t at = text.find(exponent); at != std::string::npos) text.erase(at + 2, 1);
  return text;
}

struct StiffnessFit {
  double stiffness = 0.0, frequency = 0.0;
  int iterations = 0;
};

class Identification {
 public:
  Identification(const IdentifyOptions& options, IdentifyResult& result)
      : options_(options), result_(result) {}

  // EI ← EI·(target/f)² from the scene's EI until f is at the target.
  StiffnessFit fit_stiffness(Scene scene) {
    const int limit = options_.stiffness_iterations;
    double stiffness = get_parameter(scene, "beam.bending_stiffness");
    double frequency = 0.0;
    for (int iteration = 1; iteration <= limit; ++iteration) {
      if (!keep_going(
              options_.progress, iteration - 1, limit,
              "bending stiffness: fixed-point iterations (" + std::to_string(limit) + " at most)"))
        throw FitStopped{cancelled_status()};
      set_parameter(scene, "beam.bending_stiffness", stiffness);
      frequency = mode_frequency(scene);
      if (std::abs(frequency - options_.target_hz) <=
          options_.frequency_tolerance * options_.target_hz)
        return {stiffness, frequency, iteration};
      stiffness *= (options_.target_hz / frequency) * (options_.target_hz / frequency);
      if (!std::isfinite(stiffness) || !(stiffness > 0.0))
        stop("identify: the bending stiffness update left the positive numbers (" +
             format_number("%.6g", stiffness) + " N*m^2) at mode " +
             std::to_string(options_.mode_number) + " = " + format_with_unit(frequency, "Hz"));
    }
    stop("identify: mode " + std::to_string(options_.mode_number) + " at " +
         format_number("%.10g", frequency) + " Hz after " + std::to_string(limit) +
         " fixed-point iterations of beam.bending_stiffness, target " +
         format_with_unit(options_.target_hz, "Hz") + " (relative residual " +
         format_number("%.3g", (frequency - options_.target_hz) / options_.target_hz) +
         "): the target is out of reach of the stiffness");
  }

  // The periodic peak of the peak target's output at the target frequency.
  double periodic_peak(const Scene& scene) {
    PeriodicExtremesOptions extremes_options;
    extremes_options.frequency_hz = options_.target_hz;
    extremes_options.output = options_.peak->output;
    extremes_options.where = "--peak";
    const PeriodicExtremesResult extremes = periodic_extremes(scene, extremes_options);
    ++result_.periodic_solves;
    if (!extremes.status.ok) throw FitStopped{extremes.status};
    return extremes.peak;
  }

 private:
  // The damped frequency of mode mode_number about the scene's operating point.
  double mode_frequency(const Scene& scene) {
    const Model model = prepare_model(scene);
    const System system = model.network.assemble();
    const OperatingPoint point = operating_point(system);
    if (!point.status.ok) throw FitStopped{point.status};
    if (point.about_zero && !noted_about_zero_) {
      result_.notes.push_back(point.note);
      noted_about_zero_ = true;
    }
    ModalOptions modal_options;
    modal_options.keep_vectors = false;
    if (system.size() > modal_options.dense_limit) modal_options.count = options_.mode_number + 5;
    const ModalResult modes = run_modes(system, point.rest.operating_point, modal_options);
    ++result_.modal_solves;
    if (!modes.status.ok || static_cast<int>(modes.modes.size()) < options_.mode_number)
      stop("identify: mode " + std::to_string(options_.mode_number) + " not found");
    const double frequency =
        modes.modes[static_cast<size_t>(options_.mode_number - 1)].frequency_hz;
    if (!std::isfinite(frequency) || !(frequency > 0.0))
      stop("identify: mode " + std::to_string(options_.mode_number) + " has the frequency " +
           format_number("%.6g", frequency) + " Hz");
    return frequency;
  }

  const IdentifyOptions& options_;
  IdentifyResult& result_;
  bool noted_about_zero_ = false;
};

void check_inputs(const Scene& scene, const IdentifyOptions& options) {
  if (!(options.target_hz > 0.0) || !std::isfinite(options.target_hz))
    throw InputError("--resonance", "--resonance", "must be a positive frequency in Hz (> 0)");
  if (options.mode_number < 1) throw InputError("--mode", "--mode", "must be >= 1");
  if (options.peak) {
    if (!(options.peak->value > 0.0) || !std::isfinite(options.peak->value))
      throw InputError("--peak", "--peak", "the peak must be > 0");
    if (!(options.peak->voltage >= 0.0) || !std::isfinite(options.peak->voltage))
      throw InputError("--peak", "--peak", "the voltage must be > 0");
  }
  std::vector<std::string> fitted_keys{"beam.bending_stiffness"};
  if (options.peak) fitted_keys.push_back("damping.loss_factor");
  for (const std::string& key : fitted_keys) {
    const auto entry = scene.provenance.find(key);
    if (entry == scene.provenance.end()) continue;
    const std::string& origin = entry->second;
    if (origin.rfind("paper", 0) == 0 || origin.rfind("data sheet", 0) == 0)
      throw InputError(scene.file, "provenance." + key,
                       "identify would fit " + key + ", which the scene takes as given (\"" +
                           origin.substr(0, origin.find(':')) +
                           "\"); only 'identified:' or 'assumed:' values are fitted");
  }
  if (options.peak && !scene.damping.loss_factor)
    throw InputError(scene.file, "damping.loss_factor",
                     "--peak fits damping.loss_factor, which the scene does not set");
}

}  // namespace

IdentifyResult identify(const Scene& scene, const IdentifyOptions& options) {
  const Stopwatch stopwatch;
  check_inputs(scene, options);
  IdentifyResult result;
  Identification identification(options, result);
  try {
    // 1. Bending stiffness to the resonance.
    StiffnessFit fit = identification.fit_stiffness(scene);
    // 2. With a peak target, the loss factor to the peak at the resonance, then the stiffness
    // again, until both hold.
    if (options.peak) {
      const PeakTarget& peak = *options.peak;
      Scene measured = scene;  // at the measurement's voltage
      if (peak.voltage > 0.0) set_parameter(measured, "drive.voltage", peak.voltage);
      auto with = [&](double eta, double stiffness) {
        Scene trial = measured;
        set_parameter(trial, "damping.loss_factor", eta);
        set_parameter(trial, "beam.bending_stiffness", stiffness);
        return trial;
      };
      double loss_factor = *scene.damping.loss_factor;
      bool converged = false;
      const long steps = options.bisection_steps + 2;  // the bracket's two ends, then bisection
      int round = 1;
      for (; round <= options.peak_rounds; ++round) {
        double low = options.loss_factor_low, high = options.loss_factor_high;
        long step = 0;
        auto peak_at = [&](double eta) {
          if (!keep_going(options.progress, step++, steps,
                          "loss factor: round " + std::to_string(round) + " (" +
                              std::to_string(options.peak_rounds) + " at most), bisection steps (" +
                              std::to_string(steps) + " at most)"))
            throw FitStopped{cancelled_status()};
          return identification.periodic_peak(with(eta, fit.stiffness));
        };
        // The peak falls monotonically with the loss factor: bisection in log η.
        if (peak_at(low) < peak.value || peak_at(high) > peak.value)
          stop("identify --peak: no loss factor in [" + short_number(low) + ", " +
               short_number(high) + "] gives the peak " + format_with_unit(peak.value, "m") +
               " at " + format_with_unit(options.target_hz, "Hz"));
        for (int k = 0; k < options.bisection_steps && high / low > 1 + options.bisection_ratio;
             ++k) {
          const double middle = std::sqrt(low * high);
          (peak_at(middle) > peak.value ? low : high) = middle;
        }
        const double previous = loss_factor;
        loss_factor = std::sqrt(low * high);
        Scene trial = measured;
        set_parameter(trial, "damping.loss_factor", loss_factor);
        const double previous_stiffness = fit.stiffness;
        fit = identification.fit_stiffness(trial);
        result.achieved_peak = identification.periodic_peak(with(loss_factor, fit.stiffness));
        if (std::abs(loss_factor - previous) <= options.round_tolerance * loss_factor &&
            std::abs(fit.stiffness - previous_stiffness) <=
                options.round_tolerance * fit.stiffness) {
          converged = true;
          break;
        }
      }
      result.peak_rounds = converged ? round : options.peak_rounds;
      if (!converged)
        result.notes.push_back(
            "identify --peak: the loss factor and the stiffness still changed by more than " +
            format_number("%.3g", options.round_tolerance) + " (relative) after " +
            std::to_string(options.peak_rounds) + " rounds; the last round's values are given");
      result.loss_factor = loss_factor;
      result.peak_residual = (result.achieved_peak - peak.value) / peak.value;
      result.validity = check_validity(measured, {{peak.output, result.achieved_peak}},
                                       drive_peak_voltages(measured));
    }
    result.bending_stiffness = fit.stiffness;
    result.achieved_hz = fit.frequency;
    result.stiffness_iterations = fit.iterations;
    result.frequency_residual = (fit.frequency - options.target_hz) / options.target_hz;
    result.fitted.push_back({"beam.bending_stiffness", "N*m^2", result.bending_stiffness});
    if (options.peak) result.fitted.push_back({"damping.loss_factor", "", result.loss_factor});
  } catch (const FitStopped& stopped) {
    result.status = stopped.status;
  }
  result.seconds = stopwatch.seconds();
  return result;
}

}  // namespace emnet
