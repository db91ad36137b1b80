// Choosing the number of beam segments N for a band and a tolerance (beam.segments = "auto").
//
// Convergence model: the lumped-mass chain's modal frequencies converge to the continuum
// beam's as O(N⁻²), f_N = f∞·(1 + a/N² + …). Richardson extrapolation from N and
// 2N (N's mesh with every segment halved, BeamSpec::refinement = 2, so that a is the same
// constant on both) removes the leading term, f∞ ≈ f_2N + (f_2N − f_N)/3, and estimates the error
// of N as e_N = |f_N − f∞|/f∞; the worst e_N over the modes in the band (at least the first mode)
// is the error of N. Search: start from N₀ = 4·k segments, k the number of modes up to the band's
// top (several segments per half wavelength: mode k has about k half waves); halve while N₀ already
// meets the tolerance (down to 2·k), else double until it does; then, inside the bracket
// (largest failing N, smallest passing N), predict N from e ∝ N⁻² (up to three predictions,
// each one evaluated) and bisect the rest to one segment.
// The result is the smallest N ≥ 2·k whose estimated error meets the tolerance, assuming the
// error decreases with N (it does for the lumped-mass chain).
// The estimate is made on the bare beam chain (mass, stiffness and rotary inertia as given;
// damping, DEAs and loads do not change the discretisation of the mass and stiffness).
#pragma once

#include <string>
#include <vector>

#include "emnet/scene/scene.hpp"

namespace emnet {

/// Richardson extrapolation of an O(N⁻²) quantity from N (coarse) and 2N (fine) segments:
/// f∞ ≈ fine + (fine − coarse)/3.
double richardson_extrapolate(double coarse, double fine);
/// Richardson error estimate of the coarse value from N (coarse) and 2N (fine) segments:
/// |coarse − f∞|/f∞ with f∞ = fine + (fine − coarse)/3.
double richardson_error(double coarse, double fine);
/// Element by element, over the common length.
std::vector<double> richardson_errors(const std::vector<double>& coarse,
                                      const std::vector<double>& fine);

/// The band of interest [Hz] and where it came from: [model] band, else from 0 to the larger
/// of ac.to (an [ac] table) and 10 × drive.frequency (a square wave's harmonics up to the 9th,
/// each 1/k of the fundamental).
struct BandOfInterest {
  double from = 0.0;   ///< [Hz]
  double to = 0.0;     ///< [Hz]
  std::string source;  ///< "model.band", "ac.to", "10 x drive.frequency"
};
/// The band of interest of `scene`.
/// @param key  the "auto" key that needs the band, named in the error
/// @throws InputError naming `key` when the scene gives none
BandOfInterest band_of_interest(const Scene& scene, const std::string& key);

/// Undamped modal frequencies [Hz] of the bare beam chain `beam` (with its point masses and
/// springs) cut into `segments` (each cut again into beam.refinement), with a node at each of
/// `attachments` (the scene's DEA ends and loads, scene_attachment_points), the lowest `count`
/// (all, for a small chain).
/// @throws std::runtime_error when the modal solve fails
std::vector<double> beam_frequencies(const BeamSpec& beam, int segments, int count,
                                     const std::vector<double>& attachments = {});

/// The N chosen, its estimated error and how it was found.
struct SegmentSelection {
  int segments = 0;                           ///< N
  double estimated_error = 0.0;               ///< worst Richardson estimate over the band's modes
  int modes_in_band = 0;                      ///< modes whose error is counted
  double top_mode_hz = 0.0;                   ///< the highest of them (at 2N)
  int modal_solves = 0;                       ///< modal analyses of chains the selection ran
  double seconds = 0.0;                       ///< time spent [s]
  std::vector<std::pair<int, double>> tried;  ///< (N, estimated error) in the order tried
  std::string summary() const;                ///< "N = 38: estimated error 9.7e-4 over 3 modes…"
};

/// Smallest N whose band modes meet `tolerance` (see the top comment).
/// @param band_from,band_to  the band of interest [Hz]
/// @param tolerance  the largest estimated relative error of a band mode's frequency [-]
/// @throws std::runtime_error when the modal solve fails or N would exceed `maximum_segments`
SegmentSelection select_segments(const BeamSpec& beam, double band_from, double band_to,
                                 double tolerance, int maximum_segments = 20000,
                                 const std::vector<double>& attachments = {});

}  // namespace emnet
