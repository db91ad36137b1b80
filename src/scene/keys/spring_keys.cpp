// The keys of a [[spring]] entry: a translational spring k*(w(at) - w(to)) or rotational one
// k*(phi(at) - phi(to)), with a dashpot in parallel, to ground when `to` is unset.
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

// [[spring]]
SceneTableKeys spring_table_keys() {
  SceneTableKeys keys =
      entries_table("spring", scene_limits::springs,
                    "springs and dashpots to ground or between two points, one [[spring]] each");
  keys.add(key("spring", "name", ParameterKind::name, "springs",
               "the spring's name (optional; outputs name it)"));
  keys.back().constraint = kEntryNameConstraint;
  keys.back().default_note = "none (addressed by index: spring[0])";
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    return scene.beam.springs[entry].name;
  };
  beam_entry_field(keys.add(quantity("spring", "at", dim::length, unbounded(), true, "springs",
                                     "where the spring holds the beam (a node is put there)")),
                   &BeamSpec::springs, &SpringSpec::at);
  keys.back().constraint = "on the beam: 0 <= at <= beam.length";
  keys.add(choice("spring", "kind", {"translational", "rotational", "axial"}, true, "springs",
                  "a force k*(w(at) - w(to)), a moment k*(phi(at) - phi(to)), or with "
                  "beam.kinematics = \"large\" a force along x k*(u(at) - u(to))"))
      .text = [](const Scene& scene, std::size_t entry) {
    switch (scene.beam.springs[entry].kind) {
      case SpringKind::rotational:
        return std::string("rotational");
      case SpringKind::axial:
        return std::string("axial");
      case SpringKind::translational:
        break;
    }
    return std::string("translational");
  };
  beam_entry_field(keys.add(quantity("spring", "stiffness", dim::stiffness, positive(), true,
                                     "springs", "k: N/m (translational) or N*m/rad (rotational)")),
                   &BeamSpec::springs, &SpringSpec::stiffness);
  keys.back().sensitivity = true;
  keys.back().unit_note = "N/m (translational), N*m/rad (rotational)";
  beam_entry_field(keys.add(quantity("spring", "damping", dim::damping, non_negative(), false,
                                     "springs", "the dashpot in parallel with the spring")),
                   &BeamSpec::springs, &SpringSpec::damping);
  keys.back().sensitivity = true;
  keys.back().unit_note = "N*s/m (translational), N*m*s/rad (rotational)";
  beam_entry_field(keys.add(quantity("spring", "to", dim::length, unbounded(), false, "springs",
                                     "the spring's other end on the beam; unset: ground")),
                   &BeamSpec::springs, &SpringSpec::to);
  keys.back().constraint = "on the beam: 0 <= to <= beam.length, not at";
  keys.back().default_note = "unset (to ground)";
  return keys;
}

}  // namespace scene_keys
}  // namespace emnet
