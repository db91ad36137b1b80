// Uses the installed emnet library as another project would: a mass m on a spring of
// compliance n (Firestone analogy: the mass a capacitor, the spring an inductor, both
// translational) has one undamped mode at f = 1/(2π·√(m·n)). Reference: that closed form;
// tolerance 1e-10 relative (rounding of a dense 2×2 eigen-decomposition). Exits 0 when the
// library gives it, 1 otherwise.
#include <cmath>
#include <cstdio>

#include "emnet/analysis/analysis.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/network/network.hpp"

int main() {
  const double mass = 0.02, compliance = 1e-3;  // [kg], [m/N]
  emnet::Network network;
  const emnet::NodeId velocity =
      network.add_node("v", emnet::Domain::translational, "velocity of the mass");
  network.add<emnet::Capacitor>("mass", velocity, emnet::ground, mass);
  network.add<emnet::Inductor>("spring", velocity, emnet::ground, compliance,
                               emnet::Domain::translational);
  const emnet::System system = network.assemble();
  const emnet::ModalResult modes = emnet::run_modes(system, Eigen::VectorXd::Zero(system.size()));
  const double exact = 1.0 / (2.0 * M_PI * std::sqrt(mass * compliance));
  if (!modes.status.ok() || modes.modes.size() != 1) {
    std::fprintf(stderr, "consumer: modes failed: %s\n", modes.status.message.c_str());
    return 1;
  }
  const double frequency = modes.modes[0].frequency_hz;
  std::printf("mass on a spring: f = %.12g Hz (closed form %.12g Hz)\n", frequency, exact);
  return std::abs(frequency - exact) <= 1e-10 * exact ? 0 : 1;
}
