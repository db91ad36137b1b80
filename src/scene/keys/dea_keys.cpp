// The keys of a [[dea]] entry: a dielectric elastomer actuator on a beam face between `from` and
// `to`, its film (permittivity, thicknesses), electrodes (width, resistance) and lever arm z.
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

// [[dea]]
SceneTableKeys dea_table_keys() {
  SceneTableKeys keys =
      entries_table("dea", scene_limits::deas, "the DEAs, one [[dea]] entry each");
  keys.add(key("dea", "name", ParameterKind::name, "DEA",
               "the DEA's name (drive.deas, probes and outputs name it)"))
      .required = true;
  keys.back().constraint = kEntryNameConstraint;
  keys.back().text = [](const Scene& scene, std::size_t entry) { return scene.deas[entry].name; };
  entry_field(keys.add(quantity("dea", "from", dim::length, unbounded(), true, "DEA",
                                "x0, where the DEA's electrode starts along the beam")),
              &Scene::deas, &DeaSpec::from);
  keys.back().constraint = "on the beam: 0 <= from < to";
  entry_field(keys.add(quantity("dea", "to", dim::length, unbounded(), true, "DEA",
                                "x1, where the DEA's electrode ends along the beam")),
              &Scene::deas, &DeaSpec::to);
  keys.back().constraint = "on the beam: from < to <= beam.length";
  keys.add(choice("dea", "face", {"top", "bottom"}, true, "DEA",
                  "the beam face the DEA is on (top = +w side: energised, it bends toward -w)"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(scene.deas[entry].face == Face::top ? "top" : "bottom");
  };
  entry_field(keys.add(quantity("dea", "lever_arm", dim::length, positive(), true, "DEA",
                                "z, the distance of the DEA's film from the beam's neutral plane")),
              &Scene::deas, &DeaSpec::lever_arm);
  keys.back().sensitivity = true;
  entry_field(keys.add(quantity("dea", "relative_permittivity", dim::none, positive(), true, "DEA",
                                "epsilon_r, the film's relative permittivity")),
              &Scene::deas, &DeaSpec::relative_permittivity);
  keys.back().sensitivity = true;
  entry_field(keys.add(quantity("dea", "dielectric_thickness", dim::length, positive(), true, "DEA",
                                "d, the film's thickness in its capacitance (and the validity "
                                "check's field V/d)")),
              &Scene::deas, &DeaSpec::dielectric_thickness);
  keys.back().sensitivity = true;
  entry_field(keys.add(quantity("dea", "force_thickness", dim::length, positive(), true, "DEA",
                                "d', the film's thickness in the electrostatic force (the paper's "
                                "Eq. 16)")),
              &Scene::deas, &DeaSpec::force_thickness);
  keys.back().sensitivity = true;
  entry_field(keys.add(quantity("dea", "electrode_width", dim::length, positive(), true, "DEA",
                                "the electrode's width across the beam")),
              &Scene::deas, &DeaSpec::electrode_width);
  keys.back().sensitivity = true;
  entry_field(
      keys.add(quantity("dea", "electrode_resistance", dim::resistance, positive(), true, "DEA",
                        "the electrodes' series resistance (the RC loop with the film)")),
      &Scene::deas, &DeaSpec::electrode_resistance);
  keys.back().sensitivity = true;
  keys.add(key("dea", "back_coupling", ParameterKind::boolean, "DEA",
               "true: the film's current has the motional part V*dC/dt (the beam loads the "
               "electrical side)"))
      .text = [](const Scene& scene, std::size_t entry) {
    return bool_text(scene.deas[entry].back_coupling);
  };
  entry_field(
      keys.add(quantity("dea", "breakdown_field", dim::electric_field, positive(), false,
                        "validity check",
                        "the film's breakdown field: a larger V/d is flagged as outside the "
                        "model (default: ELASTOSIL Film 2030's data sheet)")),
      &Scene::deas, &DeaSpec::breakdown_field);
  return keys;
}

}  // namespace scene_keys
}  // namespace emnet
