// The keys of the [drive] table: what drives the DEAs (square waves, sines, or nothing) and
// whether each DEA is its RC loop or an ideal voltage-driven force.
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

// [drive]
SceneTableKeys drive_table_keys() {
  SceneTableKeys keys = plain_table("drive", "what drives the DEAs");
  const std::vector<std::string> kinds = {"none", "antagonistic", "switched", "bias_differential",
                                          "single"};
  keys.add(choice("drive", "kind", kinds, false, "every drive kind",
                  "what drives the DEAs: none (loads only), antagonistic or switched square waves, "
                  "bias_differential or single sines"))
      .text = [](const Scene& scene, std::size_t) {
    return std::string(drive_kind_name(scene.drive.kind));
  };
  {
    ParameterInfo& deas =
        keys.add(used_by_kinds(key("drive", "deas", ParameterKind::name_list, "",
                                   "the driven DEAs by name: [A, B] or [A]"),
                               {DriveKind::antagonistic, DriveKind::switched,
                                DriveKind::bias_differential, DriveKind::single}));
    deas.required = true;
    deas.constraint = "two names (antagonistic, bias_differential) or one (switched, single)";
    deas.text = [](const Scene& scene, std::size_t) {
      std::string list;
      for (const std::string& name : scene.drive.deas)
        list += (list.empty() ? "" : ", ") + ("\"" + name + "\"");
      return "[" + list + "]";
    };
  }
  plain_field(
      keys.add(used_by_kinds(quantity("drive", "voltage", dim::voltage, non_negative(), true, "",
                                      "V, the square wave's switched level (0/V)"),
                             {DriveKind::antagonistic, DriveKind::switched})),
      &Scene::drive, &DriveSpec::voltage);
  keys.back().sensitivity = true;
  plain_field(keys.add(used_by_kinds(quantity("drive", "bias", dim::voltage, non_negative(), true,
                                              "", "V0, the sine drive's constant part"),
                                     {DriveKind::bias_differential, DriveKind::single})),
              &Scene::drive, &DriveSpec::bias);
  keys.back().sensitivity = true;
  plain_field(
      keys.add(used_by_kinds(quantity("drive", "amplitude", dim::voltage, non_negative(), true, "",
                                      "v, the sine drive's amplitude: V0 + v*sin(2*pi*f*t)"),
                             {DriveKind::bias_differential, DriveKind::single})),
      &Scene::drive, &DriveSpec::amplitude);
  plain_field(
      keys.add(used_by_kinds(quantity("drive", "frequency", dim::frequency, positive(), true, "",
                                      "the switching or sine frequency (drive kind none: only "
                                      "the period a transient's length in periods counts)"),
                             {DriveKind::none, DriveKind::antagonistic, DriveKind::switched,
                              DriveKind::bias_differential, DriveKind::single})),
      &Scene::drive, &DriveSpec::frequency);
  keys.back().used_by = "every drive kind";
  keys.back().default_note = "required (optional with drive kind none)";
  plain_field(keys.add(used_by_kinds(
                  quantity("drive", "duty", dim::none,
                           interval(Limit::exclusive, 0.0, Limit::exclusive, 1.0,
                                    "must be between 0 and 1 (exclusive), got {}"),
                           false, "", "the fraction of each period DEA A (or the DEA) is on"),
                  {DriveKind::antagonistic, DriveKind::switched})),
              &Scene::drive, &DriveSpec::duty);
  plain_field(
      keys.add(used_by_kinds(quantity("drive", "rise_time", dim::time, non_negative(), false, "",
                                      "the time each edge of the square wave takes"),
                             {DriveKind::antagonistic, DriveKind::switched})),
      &Scene::drive, &DriveSpec::rise_time);
  keys.back().constraint = "shorter than half a period";
  plain_field(
      keys.add(used_by_kinds(quantity("drive", "overlap", dim::time, unbounded(), false, "",
                                      "how long A stays on after B has switched on (negative: "
                                      "a dead time between them)"),
                             {DriveKind::antagonistic})),
      &Scene::drive, &DriveSpec::overlap);
  keys.back().constraint = "DEA A's on-time duty*T + overlap inside the period, clear of the edges";
  keys.add(key("drive", "electrical_dynamics", ParameterKind::boolean, "every drive kind",
               "true: each DEA is its capacitor behind its electrode resistance; false: an ideal "
               "voltage-driven force; \"auto\": chosen for [model]'s band"))
      .text = [](const Scene& scene, std::size_t) {
    return scene.drive.electrical_dynamics_auto ? std::string("auto")
                                                : bool_text(scene.drive.electrical_dynamics);
  };
  keys.back().constraint = "or \"auto\"";
  return keys;
}

}  // namespace scene_keys
}  // namespace emnet
