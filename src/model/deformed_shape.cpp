// The beam's deformed shape (emnet/model/deformed_shape.hpp).
#include "emnet/model/deformed_shape.hpp"

#include <cmath>
#include <stdexcept>

namespace emnet {

ShapeProbes shape_probes(const Model& model) {
  ShapeProbes shape;
  shape.positions = model.beam.x;
  shape.axial = model.beam.kinematics == BeamKinematics::large;
  for (const ProbeQuantity quantity :
       {ProbeQuantity::deflection, ProbeQuantity::axial_displacement}) {
    if (quantity == ProbeQuantity::axial_displacement && !shape.axial) break;
    for (size_t k = 0; k < shape.positions.size(); ++k) {
      ProbeSpec spec;
      spec.name =
          std::string(quantity == ProbeQuantity::deflection ? "y" : "x") + std::to_string(k);
      spec.quantity = quantity;
      spec.at = shape.positions[k];
      shape.probes.push_back(model.make_probe(spec));
    }
  }
  return shape;
}

RotationProbes rotation_probes(const Model& model, size_t most) {
  RotationProbes rotations;
  if (model.beam.kinematics == BeamKinematics::large || most == 0) return rotations;
  const size_t nodes = model.beam.x.size();
  const size_t stride = (nodes + most - 1) / most;
  for (size_t k = 0; k < nodes; k += stride) rotations.positions.push_back(model.beam.x[k]);
  if (nodes > 0 && rotations.positions.back() != model.beam.x.back())
    rotations.positions.back() = model.beam.x.back();
  for (size_t k = 0; k < rotations.positions.size(); ++k) {
    ProbeSpec spec;
    spec.name = "psi" + std::to_string(k);
    spec.quantity = ProbeQuantity::rotation;
    spec.at = rotations.positions[k];
    rotations.probes.push_back(model.make_probe(spec));
  }
  return rotations;
}

std::optional<RotationPeak> largest_rotation(const RotationProbes& probes,
                                             const std::vector<double>& peaks) {
  if (peaks.size() != probes.probes.size())
    throw std::invalid_argument("largest_rotation: one peak per rotation probe expected");
  std::optional<size_t> largest;  // a non-finite peak (a failed solve's) is not taken
  for (size_t k = 0; k < peaks.size(); ++k)
    if (std::isfinite(peaks[k]) && (!largest || std::abs(peaks[k]) > std::abs(peaks[*largest])))
      largest = k;
  if (!largest) return std::nullopt;
  return rotation_peak_at(probes.positions[*largest], peaks[*largest]);
}

DeformedShape deformed_shape(const ShapeProbes& probes, const std::vector<double>& times,
                             const std::vector<std::vector<double>>& values) {
  const size_t nodes = probes.positions.size();
  if (values.size() != probes.probes.size() || values.size() != nodes * (probes.axial ? 2 : 1))
    throw std::invalid_argument("deformed_shape: one series per shape probe expected");
  for (const auto& series : values)
    if (series.size() != times.size())
      throw std::invalid_argument("deformed_shape: one value per instant expected");
  DeformedShape shape;
  shape.reference_x = probes.positions;
  shape.times = times;
  shape.x.assign(times.size(), probes.positions);
  shape.y.assign(times.size(), std::vector<double>(nodes, 0.0));
  for (size_t t = 0; t < times.size(); ++t)
    for (size_t k = 0; k < nodes; ++k) {
      shape.y[t][k] = values[k][t];
      if (probes.axial) shape.x[t][k] += values[nodes + k][t];
    }
  return shape;
}

}  // namespace emnet
