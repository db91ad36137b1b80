// beam.kinematics = "auto" (resolve_scene): large where the small beam's geometric error,
// estimated from the largest deflection the scene's loads and drive give it, exceeds
// model.tolerance; small otherwise (emnet/studies/resolve.hpp).
#pragma once

#include "emnet/scene/scene.hpp"
#include "emnet/studies/resolve.hpp"

namespace emnet {

/// The choice for `scene` (its other "auto" keys resolved), served as `use` allows.
AutomaticChoice choose_kinematics(const Scene& scene, LargeKinematicsUse use);

}  // namespace emnet
