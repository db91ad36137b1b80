// The keys of a [[mass]] entry: a point mass m (and rotary inertia J) on the beam at x = at, a
// capacitor to ground on the node there.
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

// [[mass]]
SceneTableKeys mass_table_keys() {
  SceneTableKeys keys =
      entries_table("mass", scene_limits::masses, "point masses on the beam, one [[mass]] each");
  keys.add(key("mass", "name", ParameterKind::name, "point masses",
               "the mass's name (optional; outputs name it)"));
  keys.back().constraint = kEntryNameConstraint;
  keys.back().default_note = "none (addressed by index: mass[0])";
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    return scene.beam.masses[entry].name;
  };
  beam_entry_field(keys.add(quantity("mass", "at", dim::length, unbounded(), true, "point masses",
                                     "where the mass sits along the beam (a node is put there)")),
                   &BeamSpec::masses, &MassSpec::at);
  keys.back().constraint = "on the beam: 0 <= at <= beam.length";
  beam_entry_field(
      keys.add(quantity("mass", "mass", dim::mass, non_negative(), true, "point masses",
                        "the point mass (a sensor, a clamp's moving part)")),
      &BeamSpec::masses, &MassSpec::mass);
  keys.back().sensitivity = true;
  beam_entry_field(
      keys.add(quantity("mass", "rotary_inertia", dim::rotary_inertia, non_negative(), false,
                        "point masses", "its rotary inertia about the beam's axis of bending")),
      &BeamSpec::masses, &MassSpec::rotary_inertia);
  keys.back().sensitivity = true;
  return keys;
}

}  // namespace scene_keys
}  // namespace emnet
