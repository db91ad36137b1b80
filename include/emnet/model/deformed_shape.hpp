// The beam's deformed shape in the plane, for pictures and animations of a periodic state or a
// transient: at each node k of the beam, the undeformed position x_k along the beam plus the
// fixed-frame x displacement (large kinematics; with small kinematics the beam has no axial
// motion, so x = x_k) and the y deflection w_k. Lengths in metres.
#pragma once

#include <optional>
#include <vector>

#include "emnet/model/model.hpp"
#include "emnet/model/validity.hpp"
#include "emnet/network/output.hpp"

namespace emnet {

/// The probes a deformed shape reads: every node's deflection, then (large kinematics) every
/// node's x displacement, in the order of `positions`.
struct ShapeProbes {
  std::vector<double> positions;  ///< x_k of the beam's nodes [m]
  std::vector<Probe> probes;      ///< deflection at each node, then x displacement (large)
  bool axial = false;             ///< whether the x displacements are among `probes`
};

/// The shape's probes of `model`'s beam.
ShapeProbes shape_probes(const Model& model);

/// The section rotation at the beam's nodes, where a small-kinematics result reads its largest
/// rotation for its geometric error (emnet/model/validity.hpp).
struct RotationProbes {
  std::vector<double> positions;  ///< x_k [m] of the nodes probed
  std::vector<Probe> probes;      ///< rotation at each
};

/// Rotation probes at `model`'s beam nodes: every node up to `most`, else `most` of them evenly
/// spread with the last one; none with large kinematics (its results have no geometric error).
RotationProbes rotation_probes(const Model& model, size_t most = 64);

/// The largest of `peaks` (|rotation| [rad] per probe of `probes`, as a result computed them);
/// none when `probes` is empty or no peak is finite.
/// @throws std::invalid_argument when `peaks` does not match `probes`
std::optional<RotationPeak> largest_rotation(const RotationProbes& probes,
                                             const std::vector<double>& peaks);

/// The beam's curve at several instants.
struct DeformedShape {
  std::vector<double> reference_x;  ///< the undeformed beam: x_k [m], at y = 0
  std::vector<double> times;        ///< the instants [s]
  /// The switching frequency [Hz] whose period the instants are phases of; 0: they are not (a
  /// picture colours them by t over the last instant).
  double frequency = 0.0;
  std::vector<std::vector<double>> x, y;  ///< [instant][node], the fixed frame's [m]
  /// The period 1/frequency [s]; 0 without a frequency.
  double period() const { return frequency > 0.0 ? 1.0 / frequency : 0.0; }
};

/// The shape at `times` from the values of shape_probes' probes there.
/// @param values  [probe][instant], as a transient or a periodic result holds them
/// @throws std::invalid_argument when `values` does not match `probes` and `times`
DeformedShape deformed_shape(const ShapeProbes& probes, const std::vector<double>& times,
                             const std::vector<std::vector<double>>& values);

}  // namespace emnet
