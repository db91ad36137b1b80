// Identification of a scene parameter from a resonance, and of the loss factor from a peak
// (emnet/studies/identify.hpp).
#include "emnet/studies/identify.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/studies/periodic_peak.hpp"
#include "emnet/studies/resolve.hpp"
#include "option_parameter.hpp"

namespace emnet {
namespace {

// A failure that ends the fit: its Status becomes the result's.
struct FitStopped {
  Status status;
};

[[noreturn]] void stop(std::string why) {
  throw FitStopped{Status::failure(std::move(why))};
}

constexpr const char* kBendingStiffness = "beam.bending_stiffness";

struct ResonanceFit {
  double value = 0.0, frequency = 0.0;
  int iterations = 0;  // modal solves
};

// One trial of the root find: u = log(value), f the mode's frequency there, g = f/f_target − 1.
struct Trial {
  double u = 0.0, frequency = 0.0, residual = 0.0;
};

class Identification {
 public:
  Identification(const IdentifyOptions& options, IdentifyResult& result,
                 SceneParameterAddress parameter, std::string unit)
      : options_(options),
        result_(result),
        parameter_(std::move(parameter)),
        unit_(std::move(unit)) {}

  // The scene's value of the parameter moved until mode mode_number is at the target.
  // EI by its fixed point (f ∝ √EI of a linear beam: one update is nearly exact); with large
  // kinematics the deflected state moves with EI under dead loads, so f is not ∝ √EI and the
  // fixed point converges slowly (30 iterations to 2e-6 on an elastica at α = 3): Brent's
  // method on the root instead.
  ResonanceFit fit_resonance(const Scene& scene) {
    const bool fixed_point =
        parameter_.key == kBendingStiffness && scene.beam.kinematics != BeamKinematics::large;
    return fixed_point ? fit_bending_stiffness(scene) : fit_by_root(scene);
  }

  // `scene` with the parameter at `value`; a value the scene refuses (a position off the beam,
  // sections that no longer add up) ends the fit.
  void set_value(Scene& scene, double value) const {
    try {
      set_parameter(scene, parameter_.key, value);
    } catch (const InputError& refused) {
      stop("identify: " + parameter_.key + " = " + with_unit(value) +
           " is refused: " + refused.what());
    }
  }

  std::string with_unit(double value) const {
    return format_number("%.6g", value) + (unit_.empty() ? "" : " " + unit_);
  }

 private:
  // EI ← EI·(target/f)² from the scene's EI until f is at the target.
  ResonanceFit fit_bending_stiffness(Scene scene) {
    const int limit = options_.stiffness_iterations;
    double stiffness = get_parameter(scene, kBendingStiffness);
    double frequency = 0.0;
    for (int iteration = 1; iteration <= limit; ++iteration) {
      if (!keep_going(
              options_.progress, iteration - 1, limit,
              "bending stiffness: fixed-point iterations (" + std::to_string(limit) + " at most)"))
        throw FitStopped{cancelled_status()};
      set_parameter(scene, kBendingStiffness, stiffness);
      frequency = mode_frequency(scene);
      if (at_target(frequency)) return {stiffness, frequency, iteration};
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

  bool at_target(double frequency) const {
    return std::abs(frequency - options_.target_hz) <=
           options_.frequency_tolerance * options_.target_hz;
  }

  std::string mode_text() const { return "mode " + std::to_string(options_.mode_number); }

  // A root of g(u) = f(e^u)/f_target − 1: a bracket by expanding steps in u, then Brent's method.
  ResonanceFit fit_by_root(Scene scene) {
    const std::string& key = parameter_.key;
    const long budget = 2 + 8 + options_.root_iterations;  // rough, for the progress bar
    int solves = 0;
    auto evaluate = [&](double u) {
      if (!keep_going(options_.progress, solves, budget,
                      key + ": bracket and root find (" + std::to_string(budget) + " trials)"))
        throw FitStopped{cancelled_status()};
      ++solves;
      set_value(scene, std::exp(u));
      Trial trial;
      trial.u = u;
      trial.frequency = mode_frequency(scene);
      trial.residual = trial.frequency / options_.target_hz - 1.0;
      return trial;
    };
    auto done = [&](const Trial& trial) {
      return ResonanceFit{std::exp(trial.u), trial.frequency, solves};
    };
    const double ln10 = std::log(10.0);
    const double u_start = std::log(get_parameter(scene, key));

    // 1. The bracket: f at the start and at twice the start value give the direction of f in
    // the parameter; then steps of growing length toward the target until g changes sign.
    Trial low = evaluate(u_start);
    if (at_target(low.frequency)) return done(low);
    Trial high = evaluate(u_start + std::log(2.0));
    if (at_target(high.frequency)) return done(high);
    if (high.frequency == low.frequency)
      stop("identify: " + mode_text() + " stays at " + format_number("%.10g", low.frequency) +
           " Hz when " + key + " doubles from " + with_unit(std::exp(u_start)) +
           ": it does not depend on " + key);
    if ((low.residual > 0.0) != (high.residual > 0.0)) return brent(low, high, evaluate, done);
    const bool rising = high.frequency > low.frequency;  // f grows with the parameter
    const double direction = (low.residual < 0.0) == rising ? 1.0 : -1.0;  // toward the target
    Trial last = direction > 0.0 ? high : low;
    double step = std::log(4.0);
    double previous_change = std::abs(high.frequency - low.frequency);
    // The target out of reach: f levels off at `limit` as the parameter → ∞ (or → 0).
    auto out_of_reach = [&](const Trial& limit, const Trial* before) {
      const bool above = options_.target_hz > limit.frequency;
      stop("identify: the target " + format_with_unit(options_.target_hz, "Hz") + " lies " +
           (above ? "above" : "below") + " what any " + key + " reaches (" +
           format_number("%.6g", limit.frequency) + " Hz at " + key +
           (direction > 0.0 ? " → ∞" : " → 0") + ": " + mode_text() + " levels off, " +
           format_number("%.10g", limit.frequency) + " Hz at " + with_unit(std::exp(limit.u)) +
           (before == nullptr ? std::string()
                              : " after " + format_number("%.10g", before->frequency) + " Hz at " +
                                    with_unit(std::exp(before->u))) +
           ")");
    };
    bool series_short = false;  // the steps to come cannot reach the target (below)
    for (;;) {
      const double u = last.u + direction * step;
      if (std::abs(u - u_start) > options_.bracket_span * ln10) {
        if (series_short) out_of_reach(last, nullptr);
        stop("identify: no value of " + key + " within a factor 1e" +
             format_number("%g", options_.bracket_span) + " of the scene's " +
             with_unit(std::exp(u_start)) + " puts " + mode_text() + " at " +
             format_with_unit(options_.target_hz, "Hz") + " (" +
             format_number("%.10g", last.frequency) + " Hz at " + with_unit(std::exp(last.u)) +
             ")");
      }
      const Trial next = evaluate(u);
      if (at_target(next.frequency)) return done(next);
      if ((next.residual > 0.0) != (last.residual > 0.0))
        return direction > 0.0 ? brent(last, next, evaluate, done)
                               : brent(next, last, evaluate, done);
      if (std::abs(next.residual) > std::abs(last.residual))
        stop("identify: " + mode_text() + " moved away from the target " +
             format_with_unit(options_.target_hz, "Hz") + " (" +
             format_number("%.10g", last.frequency) + " Hz at " + with_unit(std::exp(last.u)) +
             ", " + format_number("%.10g", next.frequency) + " Hz at " +
             with_unit(std::exp(next.u)) + "): the frequency is not monotone in " + key);
      // Levelled off short of the target: the limit value → ∞ (or → 0) does not reach it. Two
      // signs: a change below saturation_tolerance; or changes that shrink at least 10-fold per
      // step (as C/k does when k grows 1e4-fold), so that all the steps to come, a geometric
      // series, move f by at most change/(ratio − 1), less than a tenth of the gap left. The
      // second is followed until a step changes f by at most limit_tolerance, so that the
      // frequency given as the limit is one.
      const double change = std::abs(next.frequency - last.frequency);
      const double ratio = previous_change / change;
      const double gap = std::abs(options_.target_hz - next.frequency);
      series_short = series_short || (ratio >= 10.0 && 10.0 * change / (ratio - 1.0) < gap);
      if (change <= options_.saturation_tolerance * next.frequency ||
          (series_short && change <= options_.limit_tolerance * next.frequency))
        out_of_reach(next, &last);
      previous_change = change;
      last = next;
      step = std::min(2.0 * step, std::log(1e4));
    }
  }

  // Brent's zero finder (Brent 1973, ch. 4, as zeroin) on the bracket [a, b] in u, whose
  // residuals have opposite signs; ends when |f − f_target| ≤ frequency_tolerance·f_target.
  template <typename Evaluate, typename Done>
  ResonanceFit brent(Trial a, Trial b, Evaluate& evaluate, Done& done) {
    const double epsilon = std::numeric_limits<double>::epsilon();
    Trial c = b;
    double d = b.u - a.u, e = d;
    for (int iteration = 0; iteration < options_.root_iterations; ++iteration) {
      if ((b.residual > 0.0) == (c.residual > 0.0)) {
        c = a;
        d = e = b.u - a.u;
      }
      if (std::abs(c.residual) < std::abs(b.residual)) {
        a = b;
        b = c;
        c = a;
      }
      const double tolerance = 2.0 * epsilon * std::abs(b.u) + 1e-15;
      const double half = 0.5 * (c.u - b.u);
      if (std::abs(half) <= tolerance)
        stop("identify: " + mode_text() + " jumps across the target " +
             format_with_unit(options_.target_hz, "Hz") + " at " + parameter_.key + " = " +
             with_unit(std::exp(b.u)) + " (from " + format_number("%.10g", b.frequency) + " to " +
             format_number("%.10g", c.frequency) + " Hz): another mode takes its place");
      if (std::abs(e) >= tolerance && std::abs(a.residual) > std::abs(b.residual)) {
        // Inverse quadratic interpolation (secant when a = c).
        const double s = b.residual / a.residual;
        double p, q;
        if (a.u == c.u) {
          p = 2.0 * half * s;
          q = 1.0 - s;
        } else {
          const double qa = a.residual / c.residual, r = b.residual / c.residual;
          p = s * (2.0 * half * qa * (qa - r) - (b.u - a.u) * (r - 1.0));
          q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
        }
        if (p > 0.0) q = -q;
        p = std::abs(p);
        if (2.0 * p < std::min(3.0 * half * q - std::abs(tolerance * q), std::abs(e * q))) {
          e = d;
          d = p / q;
        } else {  // bisection
          d = half;
          e = d;
        }
      } else {
        d = half;
        e = d;
      }
      a = b;
      b = evaluate(b.u + (std::abs(d) > tolerance ? d : std::copysign(tolerance, half)));
      if (at_target(b.frequency)) return done(b);
    }
    stop("identify: " + mode_text() + " at " + format_number("%.10g", b.frequency) + " Hz after " +
         std::to_string(options_.root_iterations) + " root-finding steps on " + parameter_.key +
         ", target " + format_with_unit(options_.target_hz, "Hz"));
  }

 public:
  // The periodic peak of the peak target's output at the target frequency; with `rotation`
  // also the largest rotation at the beam's nodes there (for the validity check).
  double periodic_peak(const Scene& scene, std::optional<RotationPeak>* rotation = nullptr) {
    PeriodicExtremesOptions extremes_options;
    extremes_options.frequency_hz = options_.target_hz;
    extremes_options.output = options_.peak->output;
    extremes_options.field = "peak";
    extremes_options.largest_rotation = rotation != nullptr;
    const PeriodicExtremesResult extremes = periodic_extremes(scene, extremes_options);
    ++result_.periodic_solves;
    if (!extremes.status.ok()) throw FitStopped{extremes.status};
    if (rotation) *rotation = extremes.rotation;
    return extremes.peak;
  }

 private:
  // The damped frequency of mode mode_number about the scene's operating point (with large
  // kinematics the deflected static state, as the modes study).
  double mode_frequency(const Scene& scene) {
    const Model model =
        prepare_model(scene, serving_large_kinematics(LargeKinematicsUse::dynamics));
    const System system = model.network.assemble();
    const OperatingPoint point = operating_point(system);
    if (!point.status.ok()) throw FitStopped{point.status};
    if (point.about_zero && !noted_about_zero_) {
      result_.notes.push_back(point.note);
      noted_about_zero_ = true;
    }
    ModalOptions modal_options;
    modal_options.keep_vectors = false;
    if (system.size() > modal_options.dense_limit) modal_options.count = options_.mode_number + 5;
    const ModalResult modes = run_modes(system, point.rest.operating_point, modal_options);
    ++result_.modal_solves;
    if (!modes.status.ok() || static_cast<int>(modes.modes.size()) < options_.mode_number)
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
  const SceneParameterAddress parameter_;
  const std::string unit_;
  bool noted_about_zero_ = false;
};

// The key options.parameter names in `scene`, checked for a quantity the scene uses with a
// positive value (the root find works on its logarithm).
SceneParameterAddress fitted_parameter(const Scene& scene, const IdentifyOptions& options) {
  constexpr const char* field = "parameter";
  const SceneParameterAddress address = find_option_parameter(scene, options.parameter, field);
  const ParameterInfo& info = *address.info;
  const std::string& key = address.key;
  if (!info.numeric())
    throw OptionError(field,
                      std::string("is not a number but a ") + parameter_kind_name(info.kind) +
                          " key; identify fits a numeric key",
                      key);
  if (info.kind != ParameterKind::quantity)
    throw OptionError(field,
                      "is an integer key; identify fits a continuous quantity (a stiffness, a "
                      "mass, a length, ...)",
                      key);
  if (const std::string unused = parameter_unused_reason(info, scene, address.entry);
      !unused.empty())
    throw OptionError(field, "is not used by scene '" + scene.name + "': " + unused, key);
  const std::optional<double> value = info.get(scene, address.entry);
  if (!value)
    throw OptionError(field,
                      "is not set in scene '" + scene.name +
                          "': the fit starts from the scene's value (give one with {overrides})",
                      key);
  if (!(*value > 0.0))
    throw OptionError(
        field,
        "is " + format_number("%.6g", *value) + " in scene '" + scene.name +
            "': the fit searches log(value) from the scene's value, which must be > 0",
        key);
  if (options.peak && key == "damping.loss_factor")
    throw OptionError(field,
                      "{peak} fits damping.loss_factor to the peak; fit another key to the "
                      "resonance",
                      key);
  return address;
}

// Throws when `key` (canonical) has a [provenance] entry (in any form --set takes) that makes
// it a given: "paper: ..." or "data sheet: ...".
void refuse_given(const Scene& scene, const std::string& key) {
  // A table-wide entry ("mass.mass": every [[mass]]'s mass) covers each entry's key.
  const std::string table_wide =
      key.substr(0, key.find_first_of(".[")) + "." + key.substr(key.find_last_of(".]") + 1);
  for (const auto& [entry_key, origin] : scene.provenance) {
    std::string canonical;
    if (entry_key == table_wide) {
      canonical = key;
    } else {
      try {
        canonical = find_scene_parameter_address(scene, entry_key, "provenance").key;
      } catch (const InputError&) {
        continue;  // names no entry of this scene (the reader checked its key)
      }
    }
    if (canonical != key) continue;
    if (origin.rfind("paper", 0) == 0 || origin.rfind("data sheet", 0) == 0)
      throw InputError(scene.file, "provenance." + entry_key,
                       "identify would fit " + key + ", which the scene takes as given (\"" +
                           origin.substr(0, origin.find(':')) +
                           "\"); only 'identified:' or 'assumed:' values are fitted");
  }
}

SceneParameterAddress check_inputs(const Scene& scene, const IdentifyOptions& options) {
  options.validate();
  const SceneParameterAddress parameter = fitted_parameter(scene, options);
  refuse_given(scene, parameter.key);
  if (options.peak) refuse_given(scene, "damping.loss_factor");
  if (options.peak && !scene.damping.loss_factor)
    throw OptionError::in_file("peak", scene.file, "damping.loss_factor",
                               "{peak} fits damping.loss_factor, which the scene does not set");
  return parameter;
}

}  // namespace

void IdentifyOptions::validate() const {
  if (!(target_hz > 0.0) || !std::isfinite(target_hz))
    throw OptionError("target_hz", "must be a positive frequency in Hz (> 0)");
  if (mode_number < 1) throw OptionError("mode_number", "must be >= 1");
  if (peak) {
    if (!(peak->value > 0.0) || !std::isfinite(peak->value))
      throw OptionError("peak", "the peak must be > 0");
    if (!(peak->voltage >= 0.0) || !std::isfinite(peak->voltage))
      throw OptionError("peak", "the voltage must be > 0");
  }
}

namespace {

// The options a fit of `scene` holds itself to: with large kinematics a peak target's periodic
// state is shot, to about 1e-7 of the peak (shooting_residual_limit: 1e-6 of the state), and near
// the resonance the peak goes as 1/η: bisecting η below kShotPeakRatio, or asking the rounds for
// less than kShotRoundTolerance, would chase IDA's noise.
constexpr double kShotPeakRatio = 1e-6;
constexpr double kShotRoundTolerance = 1e-5;

IdentifyOptions options_for(const Scene& scene, const IdentifyOptions& given,
                            std::vector<std::string>& notes) {
  IdentifyOptions options = given;
  if (!options.peak || scene.beam.kinematics != BeamKinematics::large) return options;
  options.bisection_ratio = std::max(options.bisection_ratio, kShotPeakRatio);
  options.round_tolerance = std::max(options.round_tolerance, kShotRoundTolerance);
  notes.push_back(
      "identify by the peak with large kinematics: each periodic peak is shot (IDA "
      "rtol " +
      format_number("%.3g", kPeriodicPeakShootingRtol) +
      ", about 1e-7 of the peak), so the loss factor is bisected to " +
      short_number(options.bisection_ratio) + " and the rounds end at " +
      short_number(options.round_tolerance) + " (relative)");
  return options;
}

// Narrows [low, high] to a bracket of the loss factor around `start`: each end moved from it by
// `factor`, squared after each step, until the peak there is on its side of `target` or the
// options' end is reached. Whether it brackets the target.
template <class PeakAt>
bool bracket_from(double start, double factor, double target, PeakAt& peak_at, double& low,
                  double& high) {
  const double lowest = low, highest = high;
  double step = factor;
  low = std::clamp(start / step, lowest, highest);
  bool low_found = peak_at(low) >= target;
  while (!low_found && low > lowest) {
    step *= step;
    low = std::max(lowest, start / step);
    low_found = peak_at(low) >= target;
  }
  step = factor;
  high = std::clamp(start * step, lowest, highest);
  bool high_found = peak_at(high) <= target;
  while (!high_found && high < highest) {
    step *= step;
    high = std::min(highest, start * step);
    high_found = peak_at(high) <= target;
  }
  return low_found && high_found;
}

}  // namespace

IdentifyResult identify(const Scene& given_scene, const IdentifyOptions& given_options) {
  const Stopwatch stopwatch;
  IdentifyResult result;
  // One kinematics for every trial of the fit.
  const Scene scene = resolve_kinematics(given_scene, LargeKinematicsUse::dynamics, &result.notes);
  const IdentifyOptions options = options_for(scene, given_options, result.notes);
  const SceneParameterAddress parameter = check_inputs(scene, options);
  result.parameter = {parameter.key, parameter_unit(*parameter.info, scene, parameter.entry),
                      get_parameter(scene, parameter.key)};
  Identification identification(options, result, parameter, result.parameter.unit);
  try {
    // 1. The parameter to the resonance.
    ResonanceFit fit = identification.fit_resonance(scene);
    // 2. With a peak target, the loss factor to the peak at the resonance, then the parameter
    // again, until both hold.
    if (options.peak) {
      const PeakTarget& peak = *options.peak;
      Scene measured = scene;  // at the measurement's voltage
      if (peak.voltage > 0.0) set_parameter(measured, "drive.voltage", peak.voltage);
      auto with = [&](double eta, double value) {
        Scene trial = measured;
        set_parameter(trial, "damping.loss_factor", eta);
        identification.set_value(trial, value);
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
          return identification.periodic_peak(with(eta, fit.value));
        };
        // The peak falls monotonically with the loss factor: bisection in log η, over the
        // options' bracket, or with large kinematics over one grown from the last η (at the
        // bracket's far ends a shot beam would swing around its clamp or barely move).
        const bool bracketed = scene.beam.kinematics == BeamKinematics::large
                                   ? bracket_from(loss_factor, round == 1 ? 4.0 : 1.001, peak.value,
                                                  peak_at, low, high)
                                   : !(peak_at(low) < peak.value || peak_at(high) > peak.value);
        if (!bracketed)
          stop("identify by the peak: no loss factor in [" + short_number(low, 6) + ", " +
               short_number(high, 6) + "] gives the peak " + format_with_unit(peak.value, "m") +
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
        const double previous_value = fit.value;
        fit = identification.fit_resonance(trial);
        result.achieved_peak = identification.periodic_peak(with(loss_factor, fit.value));
        if (std::abs(loss_factor - previous) <= options.round_tolerance * loss_factor &&
            std::abs(fit.value - previous_value) <= options.round_tolerance * fit.value) {
          converged = true;
          break;
        }
      }
      result.peak_rounds = converged ? round : options.peak_rounds;
      if (!converged)
        result.notes.push_back("identify by the peak: the loss factor and " + parameter.key +
                               " still changed by more than " +
                               format_number("%.3g", options.round_tolerance) +
                               " (relative) after " + std::to_string(options.peak_rounds) +
                               " rounds; the last round's values are given");
      result.loss_factor = loss_factor;
      result.peak_residual = (result.achieved_peak - peak.value) / peak.value;
      std::optional<RotationPeak> rotation;  // at the values found: one more periodic solve
      identification.periodic_peak(with(loss_factor, fit.value), &rotation);
      result.validity = check_validity(measured, {{peak.output, result.achieved_peak}},
                                       drive_peak_voltages(measured), rotation);
    }
    result.parameter.value = fit.value;
    result.bending_stiffness =
        parameter.key == kBendingStiffness ? fit.value : scene.beam.bending_stiffness;
    result.achieved_hz = fit.frequency;
    result.stiffness_iterations = fit.iterations;
    result.frequency_residual = (fit.frequency - options.target_hz) / options.target_hz;
    result.fitted.push_back(result.parameter);
    if (options.peak) result.fitted.push_back({"damping.loss_factor", "", result.loss_factor});
  } catch (const FitStopped& stopped) {
    result.status = stopped.status;
  }
  result.seconds = stopwatch.seconds();
  return result;
}

}  // namespace emnet
