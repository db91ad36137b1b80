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

// ---- the tip-mass elastica (large kinematics) ----------------------------------------------

inline constexpr double kBeamLength = 0.5, kBeamStiffness = 2.0, kTipMass = 0.01;

// A nearly massless cantilever (ρA = 1e-10 kg/m: its mass moves the first frequency by ~1e-9 of
// the tip mass's 0.01 kg) with a tip mass and a nearly rigid axis (EA = 1e11 N: the axial
// compliance adds L/EA = 5e-12 m/N to the tip's compliance, against the N = 64 discretisation
// error of 2e-8 m/N), with large kinematics, under the dead tip load α·EI/L².
inline Scene tip_mass_cantilever(int segments, double alpha) {
  Scene scene = cantilever_scene(segments, kBeamLength, kBeamStiffness, 1e-10);
  scene.beam.kinematics = BeamKinematics::large;
  scene.beam.axial_stiffness = 1e11;
  MassSpec mass;
  mass.at = kBeamLength;
  mass.mass = kTipMass;
  scene.beam.masses = {mass};
  scene.loads = {
      load(LoadKind::force, kBeamLength, alpha * kBeamStiffness / (kBeamLength * kBeamLength))};
  scene.probes = {beam_probe("u", ProbeQuantity::axial_displacement, kBeamLength),
                  beam_probe("w", ProbeQuantity::deflection, kBeamLength)};
  return scene;
}

// A force of AC magnitude 1 and no time function: the default drive of one_mass_spring_damper.
inline Waveform unit_ac_force() {
  Waveform force = Waveform::constant(0.0);
  force.ac_magnitude = 1.0;
  return force;
}

// One mass m on a spring k and a damper c to ground, driven by `force` (by default of AC
// magnitude 1: X(s) = 1/(m·s² + c·s + k)). `velocity` is the mass's node; displacement() the
// probe of its displacement x (the velocity integrated once).
struct OneMass {
  Network network;
  NodeId velocity = ground;
  Probe displacement() const {
    Probe x;
    x.name = "x";
    x.terms = {{velocity, 1.0}};
    x.integrations = 1;
    return x;
  }
};
inline OneMass one_mass_spring_damper(double mass, double stiffness, double damping,
                                      const Waveform& force = unit_ac_force()) {
  OneMass one;
  one.velocity = one.network.add_node("v", Domain::translational, "mass velocity");
  one.network.add<Capacitor>("m", one.velocity, ground, mass);
  one.network.add<Inductor>("k", one.velocity, ground, 1.0 / stiffness, Domain::translational);
  one.network.add<Conductance>("c", one.velocity, ground, damping);
  one.network.add<CurrentSource>("F", ground, one.velocity, force);
  return one;
}

}  // namespace emnet::testing
