// Shared test fixtures: scenes built in code (no file), so closed-form tests do not depend on
// the scene reader.
#pragma once

#include "emnet/analysis/analysis.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene.hpp"

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

// One mass m on a spring k and a damper c to ground, driven by a force of AC magnitude 1:
// X(s) = 1/(m·s² + c·s + k). `velocity` is the mass's node.
struct OneMass {
  Network network;
  NodeId velocity = ground;
};
inline OneMass one_mass_spring_damper(double mass, double stiffness, double damping) {
  OneMass one;
  one.velocity = one.network.add_node("v", Domain::translational, "mass velocity");
  one.network.add<Capacitor>("m", one.velocity, ground, mass);
  one.network.add<Inductor>("k", one.velocity, ground, 1.0 / stiffness, Domain::translational);
  one.network.add<Conductance>("c", one.velocity, ground, damping);
  Waveform force = Waveform::constant(0.0);
  force.ac_magnitude = 1.0;
  one.network.add<CurrentSource>("F", ground, one.velocity, force);
  return one;
}

}  // namespace emnet::testing
