// The fish fin on one mesh for either kinematics, shared by the large-deflection tests that
// compare the two.
#pragma once

#include <string>
#include <vector>

#include "emnet/scene/scene_reader.hpp"
#include "shipped_scenes.hpp"

namespace emnet::testing {

/// The fish fin with the ideal drive (the DEAs as voltage-driven forces), `kinematics` "small"
/// or "large" (with the assumed 200 kN axial stiffness of its carbon tape), and `overrides`.
/// With 21 segments every probe (P1..P4 at thirds of 70 mm, the tip) is on a node, so both
/// kinematics have the same mesh (large kinematics puts a node at each probe; at 7 segments that
/// moves the first mode by 0.12 %, a discretisation difference, not a geometric one).
inline Scene one_mesh_fin(const std::string& kinematics, std::vector<std::string> overrides = {}) {
  overrides.push_back("drive.electrical_dynamics=false");
  overrides.push_back("beam.segments=21");
  overrides.push_back("beam.kinematics=" + kinematics);
  if (kinematics == "large") overrides.push_back("beam.axial_stiffness=200 kN");
  return read_scene(kFishfin, overrides);
}

}  // namespace emnet::testing
