// Shared test fixtures: scenes built in code (no file), so closed-form tests do not depend on
// the scene reader.
#pragma once

#include "emnet/analysis.hpp"
#include "emnet/model.hpp"
#include "emnet/scene.hpp"

namespace emnet::testing {

// Uniform clamped–free beam, SI values of netlists/cantilever.toml.
inline Scene cantilever_scene(int segments, double length = 0.5, double bending_stiffness = 2.0,
                              double mass_per_length = 0.3) {
  Scene scene;
  scene.name = "cantilever";
  scene.beam.length = length;
  scene.beam.segments = segments;
  scene.beam.bending_stiffness = bending_stiffness;
  scene.beam.mass_per_length = mass_per_length;
  scene.beam.left = EndCondition::clamped;
  scene.beam.right = EndCondition::free;
  return scene;
}

inline ProbeSpec beam_probe(const std::string& name, ProbeQuantity quantity, double at) {
  ProbeSpec spec;
  spec.name = name;
  spec.quantity = quantity;
  spec.at = at;
  return spec;
}

inline LoadSpec load(LoadKind kind, double at, double value) {
  LoadSpec spec;
  spec.kind = kind;
  spec.at = at;
  spec.value = value;
  return spec;
}

}  // namespace emnet::testing
