// The static study's values (emnet/studies/static_study.hpp).
#include "emnet/studies/static_study.hpp"

#include <algorithm>
#include <cmath>

#include "emnet/model/drive.hpp"

namespace emnet {

std::vector<std::string> static_node_columns(const Model& model) {
  std::vector<std::string> columns = {"x_m", "deflection_m", "rotation_rad"};
  if (model.beam.kinematics == BeamKinematics::large) columns.push_back("axial_displacement_m");
  return columns;
}

std::string static_discretisation(const Model& model) {
  return model.beam.kinematics == BeamKinematics::large
             ? "large kinematics: chords of constant length between the nodes, an error of order "
               "N^-2 in the deflected shape"
             : "exact at the nodes for any N (Hermite statics)";
}

StaticStudyValues static_study_values(const Model& model, const System& system,
                                      const StaticResult& rest, const std::vector<Probe>& probes) {
  StaticStudyValues values;
  const auto& beam = model.beam;
  for (size_t k = 0; k < beam.x.size(); ++k) {
    ProbeSpec w;
    w.name = "w";
    w.quantity = ProbeQuantity::deflection;
    w.at = beam.x[k];
    ProbeSpec phi = w;
    phi.name = "phi";
    phi.quantity = ProbeQuantity::rotation;
    values.nodes.push_back({beam.x[k], static_probe_value(system, rest, model.make_probe(w)),
                            static_probe_value(system, rest, model.make_probe(phi))});
    if (beam.kinematics == BeamKinematics::large) {
      ProbeSpec u = w;
      u.name = "u";
      u.quantity = ProbeQuantity::axial_displacement;
      values.nodes.back().push_back(static_probe_value(system, rest, model.make_probe(u)));
    }
  }
  for (const auto& probe : probes)
    values.probe_values.push_back(static_probe_value(system, rest, probe));
  std::vector<DeflectionPeak> peaks{{"the beam's nodes", 0.0}};
  for (const auto& row : values.nodes) peaks[0].peak = std::max(peaks[0].peak, std::abs(row[1]));
  for (size_t k = 0; k < probes.size(); ++k)
    if (probes[k].quantity == ProbeQuantity::deflection)
      peaks.push_back({probes[k].name, std::abs(values.probe_values[k])});
  // The largest rotation at the nodes (all of them, computed above) for the geometric error.
  std::optional<RotationPeak> rotation;
  if (model.beam.kinematics == BeamKinematics::small)
    for (const auto& row : values.nodes)
      rotation = larger_rotation(rotation, rotation_peak_at(row[0], row[2]));
  values.validity =
      check_validity(model.scene, peaks, drive_voltages_at_start(model.scene), rotation);
  return values;
}

}  // namespace emnet
