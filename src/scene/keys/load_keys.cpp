// The keys of a [[load]] entry: a point force or moment on the beam at x = at, its static
// value and its AC amplitude.
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

// [[load]]
SceneTableKeys load_table_keys() {
  SceneTableKeys keys =
      entries_table("load", scene_limits::loads, "point loads, one [[load]] entry each");
  keys.add(choice("load", "kind", {"force", "moment"}, true, "loads",
                  "a point force or a point moment on the beam"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(scene.loads[entry].kind == LoadKind::force ? "force" : "moment");
  };
  entry_field(keys.add(quantity("load", "at", dim::length, unbounded(), true, "loads",
                                "where the load acts along the beam")),
              &Scene::loads, &LoadSpec::at);
  keys.back().constraint = "on the beam: 0 <= at <= beam.length";
  entry_field(keys.add(quantity("load", "value", dim::force, unbounded(), true, "loads",
                                "the load's value (its static value and its AC amplitude)")),
              &Scene::loads, &LoadSpec::value);
  keys.back().unit_note = "N (a force), N*m (a moment)";
  return keys;
}

}  // namespace scene_keys
}  // namespace emnet
