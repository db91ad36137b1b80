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
  // The linear chain: its modes at rest are the same with either kinematics (the mass lumping
  // is), without the axial modes of the large network.
  spec.kinematics = BeamKinematics::small;
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

namespace {

// The worst Richardson error over the band's modes at N, and the modes it was taken over.
struct BandError {
  double worst = 0.0;
  int modes_in_band = 0;
  double top_mode_hz = 0.0;
};

// The state of select_segments' search: its inputs, the frequencies of every chain it has solved
// (by (N, refinement): the 2N of an estimate is N's mesh with every segment halved), and the
// selection whose steps and solves it counts.
struct SegmentSearch {
  const BeamSpec& beam;
  double band_from;
  double band_to;
  double tolerance;
  int maximum_segments;
  const std::vector<double>& attachments;
  SegmentSelection& selection;
  std::map<std::pair<int, int>, std::vector<double>> cache;
  int wanted = 0;  // modes requested from large (Arnoldi) solves

  const std::vector<double>& frequencies(int segments, int refinement = 1) {
    auto found = cache.find({segments, refinement});
    if (found != cache.end()) return found->second;
    ++selection.modal_solves;
    BeamSpec refined = beam;
    refined.refinement = refinement;
    return cache
        .emplace(std::make_pair(segments, refinement),
                 beam_frequencies(refined, segments, wanted, attachments))
        .first->second;
  }

  // How many modes lie up to the band's top: counted on a chain fine enough to have a mode
  // above it (lumped-mass frequencies sit close below the continuum's).
  int modes_up_to_top() {
    int counting = kCountingSegments;
    int modes = 0;
    for (;;) {
      wanted = counting;
      const std::vector<double>& f = frequencies(counting);
      modes = static_cast<int>(
          std::count_if(f.begin(), f.end(), [&](double value) { return value <= band_to; }));
      if (modes < static_cast<int>(f.size()) || counting > maximum_segments) break;
      counting *= 2;
    }
    return modes;
  }

  // Worst Richardson error over the band's modes (classified at 2N); infinite when N has
  // fewer modes than the band needs. Each call is a step of selection.tried.
  BandError error_of(int segments) {
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
    return {worst, static_cast<int>(band.size()), fine.empty() ? 0.0 : fine[band.back()]};
  }
};

// The smallest N known to pass the tolerance and the largest known to fail it, with its error.
struct Bracket {
  int passing = 0;
  int failing = 0;
  double failing_error = 0.0;
};

// A bracket around the smallest passing N for `modes` modes up to the band's top: from four
// segments per mode, halved while it passes (not below two per mode), doubled while it fails.
Bracket bracket_segments(SegmentSearch& search, int modes) {
  const int floor_segments = kMinimumSegmentsPerMode * modes;
  Bracket bracket;
  int n = kStartSegmentsPerMode * modes;
  if (search.error_of(n).worst <= search.tolerance) {
    bracket.passing = n;
    while (bracket.passing / 2 >= floor_segments) {
      const int lower = bracket.passing / 2;
      const double e = search.error_of(lower).worst;
      if (e <= search.tolerance) {
        bracket.passing = lower;
      } else {
        bracket.failing = lower;
        bracket.failing_error = e;
        break;
      }
    }
    if (bracket.failing == 0) bracket.failing = floor_segments - 1;
  } else {
    bracket.failing = n;
    bracket.failing_error = search.selection.tried.back().second;
    for (;;) {
      n *= 2;
      const double e = search.error_of(n).worst;
      if (e <= search.tolerance) {
        bracket.passing = n;
        break;
      }
      bracket.failing = n;
      bracket.failing_error = e;
    }
  }
  return bracket;
}

// Refines inside (failing, passing]: predicts N from the largest failing N's error by the N⁻²
// law (when it holds, the prediction passes and the next one, N − 1, fails: two steps), at most
// kPredictedSteps times, then bisects. Returns the smallest passing N.
int narrow_bracket(SegmentSearch& search, Bracket bracket) {
  int predictions = 0;
  while (bracket.passing - bracket.failing > 1) {
    int probe = (bracket.failing + bracket.passing) / 2;
    if (predictions < kPredictedSteps && std::isfinite(bracket.failing_error) &&
        bracket.failing_error > 0.0) {
      ++predictions;
      probe = static_cast<int>(
          std::ceil(bracket.failing * std::sqrt(bracket.failing_error / search.tolerance)));
      probe = std::clamp(probe, bracket.failing + 1, bracket.passing - 1);
    }
    const double e = search.error_of(probe).worst;
    if (e <= search.tolerance) {
      bracket.passing = probe;
    } else {
      bracket.failing = probe;
      bracket.failing_error = e;
    }
  }
  return bracket.passing;
}

}  // namespace

SegmentSelection select_segments(const BeamSpec& beam, double band_from, double band_to,
                                 double tolerance, int maximum_segments,
                                 const std::vector<double>& attachments) {
  const auto start = std::chrono::steady_clock::now();
  SegmentSelection selection;
  SegmentSearch search{beam,        band_from, band_to, tolerance, maximum_segments,
                       attachments, selection, {},      0};
  const int modes = std::max(1, search.modes_up_to_top());
  search.wanted = modes + 2;
  const int passing = narrow_bracket(search, bracket_segments(search, modes));
  const BandError error = search.error_of(passing);
  selection.tried.pop_back();  // re-evaluated from the cache, not a new step
  selection.segments = passing;
  selection.estimated_error = error.worst;
  selection.modes_in_band = error.modes_in_band;
  selection.top_mode_hz = error.top_mode_hz;
  selection.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return selection;
}

}  // namespace emnet
