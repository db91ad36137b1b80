// The keys of the [ac] table (the AC sweep's defaults) and of [model] (the band and tolerance the
// automatic choices aim at, the deflection the validity check trusts).
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

// [ac]
SceneTableKeys ac_table_keys() {
  SceneTableKeys keys = plain_table("ac", "the AC sweep's defaults");
  plain_field(keys.add(quantity("ac", "from", dim::frequency, non_negative(), false, "ac",
                                "the AC sweep's lowest frequency")),
              &Scene::ac, &AcSpec::from);
  keys.back().constraint = "> 0 on a log scale";
  plain_field(
      keys.add(quantity("ac", "to", dim::frequency, unbounded(), false,
                        "ac; the band of \"auto\" choices", "the AC sweep's highest frequency")),
      &Scene::ac, &AcSpec::to);
  keys.back().constraint = "> ac.from";
  {
    ParameterInfo& points = keys.add(key("ac", "points", ParameterKind::integer, "ac",
                                         "the number of frequencies of the AC sweep"));
    points.range = interval(Limit::inclusive, 2.0, Limit::inclusive, 1000000.0,
                            "must be between 2 and 1000000, got {}");
    points.get = [](const Scene& scene, std::size_t) -> std::optional<double> {
      return static_cast<double>(scene.ac.points);
    };
    points.set = [](Scene& scene, std::size_t, double value) {
      scene.ac.points = static_cast<int>(value);
    };
  }
  keys.add(choice("ac", "scale", {"lin", "log"}, false, "ac",
                  "the AC sweep's spacing: linear or logarithmic"))
      .text = [](const Scene& scene, std::size_t) {
    return std::string(scene.ac.log ? "log" : "lin");
  };
  return keys;
}

// [model]
SceneTableKeys model_table_keys() {
  SceneTableKeys keys =
      plain_table("model", "what the automatic choices and the validity check aim at");
  {
    ParameterInfo& band = keys.add(
        key("model", "band", ParameterKind::band, "the \"auto\" choices",
            "the frequency band the automatic choices must be accurate in: \"130 Hz\" (from "
            "0) or [from, to]"));
    band.dimension = dim::frequency;
    band.range = non_negative();
    band.constraint = "0 <= from < to";
    band.default_note =
        "unset: 0 to the larger of ac.to (with an [ac] table) and 10 x drive.frequency";
    band.text = [](const Scene& scene, std::size_t) {
      if (!scene.model.band_to) return std::string("unset");
      return "[\"" + format_quantity(scene.model.band_from.value_or(0.0), dim::frequency) +
             "\", \"" + format_quantity(*scene.model.band_to, dim::frequency) + "\"]";
    };
  }
  plain_field(keys.add(quantity("model", "tolerance", dim::none,
                                interval(Limit::exclusive, 0.0, Limit::exclusive, 0.5,
                                         "must lie in (0, 0.5) (a relative error), got {}"),
                                false, "the \"auto\" choices",
                                "the relative accuracy the automatic choices hold the band's "
                                "resonances to")),
              &Scene::model, &ModelSpec::tolerance);
  plain_field(
      keys.add(quantity("model", "deflection_limit", dim::none,
                        interval(Limit::exclusive, 0.0, Limit::inclusive, 1.0,
                                 "must be > 0 and at most 1 (a fraction of beam.length), got {}"),
                        false, "validity check",
                        "the largest |deflection| trusted to the linear beam, a fraction of "
                        "beam.length; beyond it a result is flagged")),
      &Scene::model, &ModelSpec::deflection_limit);
  return keys;
}

}  // namespace scene_keys
}  // namespace emnet
