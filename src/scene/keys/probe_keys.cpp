// The keys of a [[probe]] entry: a named output (deflection, rotation, their rates, strain, a
// support's reaction, a spring's force, or a DEA's voltage, current or force).
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

namespace {

// The names of probe_quantities(), in their order.
std::vector<std::string> probe_quantity_names() {
  std::vector<std::string> names;
  for (ProbeQuantity quantity : probe_quantities())
    names.emplace_back(probe_quantity_name(quantity));
  return names;
}

}  // namespace

// [[probe]]
SceneTableKeys probe_table_keys() {
  SceneTableKeys keys =
      entries_table("probe", scene_limits::probes, "named outputs, one [[probe]] entry each");
  keys.add(key("probe", "name", ParameterKind::name, "probes",
               "the probe's name, by which outputs and analyses ask for it"))
      .required = true;
  keys.back().constraint = kEntryNameConstraint;
  keys.back().text = [](const Scene& scene, std::size_t entry) { return scene.probes[entry].name; };
  keys
      .add(choice(
          "probe", "quantity", probe_quantity_names(), true, "probes",
          "what the probe measures: a beam quantity at probe[].at (reaction_force and "
          "reaction_moment: the support's force or moment on the beam at a held end, at = 0 "
          "or beam.length; strain: at a face, probe[].face and probe[].distance), a spring's "
          "force (probe[].spring), a DEA's voltage, current or force k_F*u^2 (probe[].dea), or "
          "with beam.kinematics = \"large\" the x displacement axial_displacement and the "
          "support's force along x axial_reaction_force"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(probe_quantity_name(scene.probes[entry].quantity));
  };
  entry_field(keys.add(quantity(
                  "probe", "at", dim::length, unbounded(), true,
                  "probes of beam quantities (deflection, velocity, rotation, "
                  "angular_velocity, strain, reaction_force, reaction_moment, axial_displacement, "
                  "axial_reaction_force)",
                  "where along the beam the probe measures")),
              &Scene::probes, &ProbeSpec::at);
  keys.back().constraint =
      "on the beam: 0 <= at <= beam.length; a reaction: at a held end, 0 or beam.length";
  keys.add(key("probe", "dea", ParameterKind::name, "probes dea_voltage, dea_current, dea_force",
               "the DEA whose voltage, current or force the probe measures"))
      .required = true;
  keys.back().constraint = "a DEA of the scene";
  keys.back().text = [](const Scene& scene, std::size_t entry) { return scene.probes[entry].dea; };
  keys.add(key("probe", "spring", ParameterKind::name, "probes spring_force",
               "the spring whose force (a rotational spring: moment) the probe measures, by its "
               "spring[].name or its index in the [[spring]] list (0, 1, ...)"))
      .required = true;
  keys.back().constraint = "a spring of the scene: its name, or its index";
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    return scene.probes[entry].spring;
  };
  keys.add(choice("probe", "face", {"top", "bottom"}, true, "probes strain",
                  "the face whose strain the probe measures (top = +w side, compressed when the "
                  "beam bends toward +w)"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(scene.probes[entry].face == Face::top ? "top" : "bottom");
  };
  entry_field(keys.add(quantity("probe", "distance", dim::length, positive(), true, "probes strain",
                                "z, the distance of the face from the beam's neutral plane: the "
                                "strain is -z*dpsi/dx on the top face, +z*dpsi/dx on the bottom")),
              &Scene::probes, &ProbeSpec::distance);
  return keys;
}

}  // namespace scene_keys
}  // namespace emnet
