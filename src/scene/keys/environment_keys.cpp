// The keys of the [environment] table: the fluid around the beam, whose added mass and damping
// per length (Sader's rectangular plate) load it.
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

// [environment]
SceneTableKeys environment_table_keys() {
  SceneTableKeys keys = plain_table("environment", "the fluid around the beam");
  keys.add(choice("environment", "fluid", {"none", "air", "water"}, false, "fluid loading",
                  "the fluid around the beam (added mass and damping of a plate in it)"))
      .text = [](const Scene& scene, std::size_t) {
    return std::string(fluid_name(scene.environment.fluid));
  };
  const char* fluid_users = "fluid loading (fluid air, water)";
  plain_field(keys.add(quantity("environment", "density", dim::density, positive(), false,
                                fluid_users, "rho, the fluid's density")),
              &Scene::environment, &EnvironmentSpec::density);
  keys.back().default_note = "the fluid's at 20 C: water 998.2 kg/m^3, air 1.204 kg/m^3";
  plain_field(
      keys.add(quantity("environment", "dynamic_viscosity", dim::dynamic_viscosity, positive(),
                        false, fluid_users, "eta, the fluid's dynamic viscosity")),
      &Scene::environment, &EnvironmentSpec::dynamic_viscosity);
  keys.back().default_note = "the fluid's at 20 C: water 1.002e-3 Pa*s, air 1.81e-5 Pa*s";
  plain_field(keys.add(quantity("environment", "width", dim::length, positive(), true, fluid_users,
                                "b, the plate's width across the motion")),
              &Scene::environment, &EnvironmentSpec::width);
  keys.back().default_note = "required with a fluid";
  plain_field(
      keys.add(quantity("environment", "frequency", dim::frequency, positive(), false, fluid_users,
                        "the frequency at which the hydrodynamic function is evaluated")),
      &Scene::environment, &EnvironmentSpec::frequency);
  keys.back().default_note = "unset: the loaded beam's first resonance (a fixed point)";
  return keys;
}

}  // namespace scene_keys
}  // namespace emnet
