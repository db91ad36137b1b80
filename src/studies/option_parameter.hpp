// A scene key that an option of a study names (identify's parameter, sensitivity's parameters, a
// design study's variations): found as find_scene_parameter_address finds it, its errors an
// OptionError naming the option's field and the key.
#pragma once

#include <string>

#include "emnet/core/option_error.hpp"
#include "emnet/scene/parameters.hpp"

namespace emnet {

inline SceneParameterAddress find_option_parameter(const Scene& scene, const std::string& key,
                                                   const std::string& field) {
  try {
    return find_scene_parameter_address(scene, key, field);
  } catch (const OptionError&) {
    throw;
  } catch (const InputError& error) {
    throw OptionError(field, input_error_reason(error), error.key());
  }
}

}  // namespace emnet
