// The keys of the [scene] table (the scene's name and title) and of [provenance] (where each value
// comes from): the document around the physics.
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

// [scene]
SceneTableKeys scene_table_keys() {
  SceneTableKeys keys = plain_table("scene", "the scene's name and title (required)");
  keys.add(key("scene", "name", ParameterKind::text, "outputs",
               "the scene's name, in every command's output and in SPICE decks; not empty"))
      .required = true;
  keys.add(key("scene", "title", ParameterKind::text, "plots, reports",
               "a title for plots and reports"));
  keys.add(key("scene", "description", ParameterKind::text, "nobody (documentation)",
               "free text about the scene; not read by any command"));
  keys.keys[0].text = [](const Scene& scene, std::size_t) { return scene.name; };
  keys.keys[1].text = [](const Scene& scene, std::size_t) { return scene.title; };
  keys.keys[2].text = [](const Scene&, std::size_t) { return std::string(); };
  return keys;
}

// [provenance]
SceneTableKeys provenance_table_keys() {
  SceneTableKeys keys = plain_table("provenance", "where each value comes from");
  keys.table.free_form = true;
  keys.add(key("provenance", "*", ParameterKind::free_form,
               "identify (only identified: and assumed: values are "
               "fitted), documentation",
               "where a value comes from: \"dotted.key\" = \"paper: ...\", \"data sheet: ...\", "
               "\"assumed: ...\" or \"identified: ...\""))
      .default_note = "none";
  keys.back().text = [](const Scene&, std::size_t) { return std::string(); };
  return keys;
}

}  // namespace scene_keys
}  // namespace emnet
