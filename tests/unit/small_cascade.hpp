// A small exact cascade built by hand, shared by the exact and the reduced cascade's tests: one
// DEA (1 nF) behind a resistor R = τ/C (with `inductance` > 0 also an inductor, the voltage's
// poles then a complex pair), pushing a 1 kg mass on a spring and a damper with real poles −a and
// −b (c = a + b, k = a·b), so either can be placed on an exponent of u²; a 0/1 kV square source
// at 5 Hz with ramps (rise and fall 4 ms, 1/50 of the period: the squares' polynomial factors).
#pragma once

#include <memory>
#include <vector>

#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/elements/voltage_source.hpp"
#include "emnet/network/network.hpp"
#include "emnet/network/output.hpp"

namespace emnet::testing {

struct SmallCascade {
  Network network;
  NodeId electrode = ground, velocity = ground;
};

inline std::unique_ptr<SmallCascade> small_cascade(double tau, double a, double b,
                                                   bool back_coupling = false,
                                                   double inductance = 0.0) {
  auto made = std::make_unique<SmallCascade>();
  Network& network = made->network;
  const double capacitance = 1e-9;
  const NodeId in = network.add_node("in", Domain::electrical, "source");
  made->electrode = network.add_node("e", Domain::electrical, "electrode");
  made->velocity = network.add_node("v", Domain::translational, "mass velocity");
  network.add<VoltageSource>("V", in, ground, Waveform::square(0.0, 1000.0, 5.0, 0.5, 0.0, 0.004),
                             Domain::electrical);
  if (inductance > 0.0) {
    const NodeId middle = network.add_node("m", Domain::electrical, "between R and L");
    network.add<Conductance>("R", in, middle, capacitance / tau);
    network.add<Inductor>("L", middle, made->electrode, inductance, Domain::electrical);
  } else {
    network.add<Conductance>("R", in, made->electrode, capacitance / tau);
  }
  network.add<Dea>("D", made->electrode, ground, capacitance, 1e-6,
                   std::vector<Dea::Coupling>{{made->velocity, 1.0}}, back_coupling);
  network.add<Capacitor>("m", made->velocity, ground, 1.0);
  network.add<Conductance>("c", made->velocity, ground, a + b);
  network.add<Inductor>("k", made->velocity, ground, 1.0 / (a * b), Domain::translational);
  return made;
}

// The displacement of the mass (its velocity integrated once).
inline Probe displacement(NodeId velocity) {
  Probe probe;
  probe.name = "x";
  probe.unit = "m";
  probe.terms = {{velocity, 1.0}};
  probe.integrations = 1;
  return probe;
}

}  // namespace emnet::testing
