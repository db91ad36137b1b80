// beam.segments = "auto": the smallest N whose band modes meet the tolerance (see the header).
#include "emnet/studies/segment_selection.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "emnet/analysis/analysis.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/model.hpp"

namespace emnet {

namespace {

// Two segments per mode index: below that the chain cannot carry the mode shape's half waves
// and the O(N⁻²) asymptotics, on which the estimate rests, has not begun.
constexpr int kMinimumSegmentsPerMode = 2;
// The search starts at four segments per mode index.
constexpr int kStartSegmentsPerMode = 4;
// Chain used first to count the modes up to the band's top.
constexpr int kCountingSegments = 32;
// Steps refined by the N⁻² prediction before bisection takes over.
constexpr int kPredictedSteps = 3;

}  // namespace

double richardson_extrapolate(double coarse, double fine) {
  return fine + (fine - coarse) / 3.0;
}

double richardson_error(double coarse, double fine) {
  const double extrapolated = richardson_extrapolate(coarse, fine);
  return std::abs(coarse - extrapolated) / std::abs(extrapolated);
}

std::vector<double> richardson_errors(const std::vector<double>& coarse,
                                      const std::vector<double>& fine) {
  std::vector<double> errors;
  for (size_t k = 0; k < coarse.size() && k < fine.size(); ++k)
    errors.push_back(richardson_error(coarse[k], fine[k]));
  return errors;
}

BandOfInterest band_of_interest(const Scene& scene, const std::string& key) {
  BandOfInterest band;
  if (scene.model.band_to) {
    band.from = scene.model.band_from.value_or(0.0);
    band.to = *scene.model.band_to;
    band.source = "model.band";
    return band;
  }
  if (scene.ac.given) {
    band.to = scene.ac.to;
    band.source = "ac.to";
  }
  if (scene.drive.kind != DriveKind::none && 10.0 * scene.drive.frequency > band.to) {
    band.to = 10.0 * scene.drive.frequency;
    band.source = "10 x drive.frequency";
  }
  if (!(band.to > 0.0))
    throw InputError(scene.file, key,
                     "\"auto\" needs a frequency band to be accurate in: give [model] band, an "
                     "[ac] table or a periodic drive");
  return band;
}

std::vector<double> beam_frequencies(const BeamSpec& beam, int segments, int count,
                                     const std::vector<double>& attachments) {
  BeamSpec spec = beam;
  spec.segments = segments;
  spec.auto_segments = false;
  Network network;
  add_beam(network, spec, DampingSpec{}, attachments);
  const System system = network.assemble();
  ModalOptions options;
  options.count = count;
  options.keep_vectors = false;
  // A few modes of a chain of more than ~100 unknowns: shift-invert Arnoldi is cheaper than the
  // dense pencil (its cost grows as n³; at N = 52, 318 unknowns, 30 ms against 2 ms).
  if (count > 0) options.dense_limit = std::max(100, 10 * count);
  const ModalResult result = run_modes(system, Eigen::VectorXd::Zero(system.size()), options);
  if (!result.status.ok())
    throw std::runtime_error("segment selection: modes at N = " + std::to_string(segments) + ": " +
                             result.status.message);
  std::vector<double> frequencies;
  for (const Mode& mode : result.modes) frequencies.push_back(mode.frequency_hz);
  return frequencies;
}

std::string SegmentSelection::summary() const {
  return "N = " + std::to_string(segments) + ": estimated discretisation error " +
         format_number("%.2g", estimated_error) + " over " + std::to_string(modes_in_band) +
         " mode(s) up to " + format_number("%.5g", top_mode_hz) + " Hz (Richardson from N and " +
         "2N); chosen in " + std::to_string(tried.size()) + " step(s), " +
         std::to_string(modal_solves) + " modal solves, " + format_number("%.3g", seconds * 1e3) +
         " ms";
}

SegmentSelection select_segments(const BeamSpec& beam, double band_from, double band_to,
                                 double tolerance, int maximum_segments,
                                 const std::vector<double>& attachments) {
  const auto start = std::chrono::steady_clock::now();
  SegmentSelection selection;
  // By (N, refinement): the 2N of an estimate is N's mesh with every segment halved.
  std::map<std::pair<int, int>, std::vector<double>> cache;
  int wanted = 0;  // modes requested from large (Arnoldi) solves
  auto frequencies = [&](int segments, int refinement = 1) -> const std::vector<double>& {
    auto found = cache.find({segments, refinement});
    if (found != cache.end()) return found->second;
    ++selection.modal_solves;
    BeamSpec refined = beam;
    refined.refinement = refinement;
    return cache
        .emplace(std::make_pair(segments, refinement),
                 beam_frequencies(refined, segments, wanted, attachments))
        .first->second;
  };

  // How many modes lie up to the band's top: count on a chain fine enough to have a mode
  // above it (lumped-mass frequencies sit close below the continuum's).
  int counting = kCountingSegments;
  int modes_up_to_top = 0;
  for (;;) {
    wanted = counting;
    const std::vector<double>& f = frequencies(counting);
    modes_up_to_top = static_cast<int>(
        std::count_if(f.begin(), f.end(), [&](double value) { return value <= band_to; }));
    if (modes_up_to_top < static_cast<int>(f.size()) || counting > maximum_segments) break;
    counting *= 2;
  }
  const int k = std::max(1, modes_up_to_top);
  wanted = k + 2;

  // Worst Richardson error over the band's modes (classified at 2N); infinite when N has
  // fewer modes than the band needs.
  auto error_of = [&](int segments) {
    if (2 * segments > 2 * maximum_segments)
      throw std::runtime_error("segment selection: the tolerance " +
                               format_number("%.3g", tolerance) + " needs more than " +
                               std::to_string(maximum_segments) + " segments");
    const std::vector<double> fine = frequencies(segments, 2);
    const std::vector<double> coarse = frequencies(segments);
    std::vector<size_t> band;
    for (size_t i = 0; i < fine.size(); ++i)
      if (fine[i] >= band_from && fine[i] <= band_to) band.push_back(i);
    if (band.empty()) {  // no mode in the band: the one nearest above it, else the last
      size_t i = 0;
      while (i + 1 < fine.size() && fine[i] < band_from) ++i;
      band.push_back(i);
    }
    double worst = 0.0;
    for (size_t i : band)
      worst = std::max(worst, i < coarse.size() ? richardson_error(coarse[i], fine[i])
                                                : std::numeric_limits<double>::infinity());
    selection.tried.emplace_back(segments, worst);
    return std::make_pair(worst, std::make_pair(static_cast<int>(band.size()),
                                                fine.empty() ? 0.0 : fine[band.back()]));
  };

  const int floor_segments = kMinimumSegmentsPerMode * k;
  int passing = 0, failing = 0;  // smallest N known to pass, largest known to fail
  double failing_error = 0.0;
  int n = kStartSegmentsPerMode * k;
  if (error_of(n).first <= tolerance) {
    passing = n;
    while (passing / 2 >= floor_segments) {
      const int lower = passing / 2;
      const double e = error_of(lower).first;
      if (e <= tolerance) {
        passing = lower;
      } else {
        failing = lower;
        failing_error = e;
        break;
      }
    }
    if (failing == 0) failing = floor_segments - 1;
  } else {
    failing = n;
    failing_error = selection.tried.back().second;
    for (;;) {
      n *= 2;
      const double e = error_of(n).first;
      if (e <= tolerance) {
        passing = n;
        break;
      }
      failing = n;
      failing_error = e;
    }
  }
  // Refine inside (failing, passing]: predict N from the largest failing N's error by the N⁻²
  // law (when it holds, the prediction passes and the next one, N − 1, fails: two steps), at
  // most kPredictedSteps times, then bisect.
  int predictions = 0;
  while (passing - failing > 1) {
    int probe = (failing + passing) / 2;
    if (predictions < kPredictedSteps && std::isfinite(failing_error) && failing_error > 0.0) {
      ++predictions;
      probe = static_cast<int>(std::ceil(failing * std::sqrt(failing_error / tolerance)));
      probe = std::clamp(probe, failing + 1, passing - 1);
    }
    const double e = error_of(probe).first;
    if (e <= tolerance) {
      passing = probe;
    } else {
      failing = probe;
      failing_error = e;
    }
  }
  const auto [error, band] = error_of(passing);
  selection.tried.pop_back();  // re-evaluated from the cache, not a new step
  selection.segments = passing;
  selection.estimated_error = error;
  selection.modes_in_band = band.first;
  selection.top_mode_hz = band.second;
  selection.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return selection;
}

}  // namespace emnet
