// Energy balance of the transient analyses: for a passive network started at rest, the work
// W(t) put in by the sources equals the stored energy E(t) plus the energy dissipated; for an
// undamped (lossless) network W(t) = E(t) at every instant (energy conservation of a lossless
// network: masses, compliances and ideal levers store or pass on power, none is lost).
//
//   E(t) = Σ_masses ½·m·v² + Σ_inertias ½·J·Ω² + Σ_compliances ½·n·F²
//   W(t) = ∫ Σ_sources F_source·v_node dt
//
// Every probe is read back from the solver's output (velocities and spring forces with
// integrations = 0, source-node displacements with integrations = 1), so the check covers the
// displacement form, the solvers and the probe readout together, without a reference solution.
//
// The sources are piecewise constant (zero rise time), so W needs no quadrature: over an
// interval of constant F it is F·(x(t₂) − x(t₁)), x the displacement of the driven node. Every
// switching edge is an output time. At an edge the solvers report the state just before it
// (the output at t = 0 is the state just after the sources switch on). A force on a node
// without mass (a DEA moment on a rotation node of the fish fin) moves that node by a jump
// Δx at the edge: the node follows its equilibrium, so the jump is the zero-rise-time limit of
// a quasi-static ramp, and its work is exactly ½·(F⁻ + F⁺)·Δx (F and x both linear along the
// ramp). The state after the edge is taken from an extra output at t_edge + δ, extrapolated
// back with the node's velocity (x⁺ = x(t + δ) − δ·ẋ(t + δ); error O(δ²)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "emnet/analysis/transient.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/elements/transformer.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "fixtures.hpp"

namespace emnet {
namespace {

// Probes for the energy balance of a network, and the bookkeeping to evaluate it.
struct EnergyProbes {
  std::vector<Probe> probes;
  struct Store {
    size_t probe;
    double half_value;  // E += half_value · probe²  (½·m, ½·J or ½·n)
  };
  std::vector<Store> stores;
  struct Drive {
    const CurrentSource* source;
    size_t displacement;  // probe: x_to − x_from
    size_t velocity;      // probe: v_to − v_from
  };
  std::vector<Drive> drives;
  int dissipators = 0;  // conductances and dampers across springs
};

LinearTerms across_terms(NodeId plus, NodeId minus) {
  LinearTerms terms;
  if (plus != ground) terms.emplace_back(plus, 1.0);
  if (minus != ground) terms.emplace_back(minus, -1.0);
  return terms;
}

// Every element of the network must be a storage (capacitor, inductor), a lossless coupling
// (transformer), a through source (whose work is counted) or a damper; anything else would
// leave power unaccounted for, so the helper refuses it.
EnergyProbes energy_probes(const Network& network, const System& system) {
  EnergyProbes out;
  auto add_probe = [&](const std::string& name, LinearTerms terms, int integrations) {
    Probe probe;
    probe.name = name;
    probe.terms = std::move(terms);
    probe.integrations = integrations;
    out.probes.push_back(probe);
    return out.probes.size() - 1;
  };
  for (const auto& element : network.elements()) {
    if (const auto* c = dynamic_cast<const Capacitor*>(element.get())) {
      out.stores.push_back(
          {add_probe("v_" + c->name(), across_terms(c->a(), c->b()), 0), 0.5 * c->capacitance()});
    } else if (const auto* l = dynamic_cast<const Inductor*>(element.get())) {
      out.stores.push_back({add_probe("F_" + l->name(), {{system.branch_index(l->name()), 1.0}}, 0),
                            0.5 * l->inductance()});
      if (l->parallel_conductance() != 0.0) ++out.dissipators;  // a damper across the spring
    } else if (const auto* s = dynamic_cast<const CurrentSource*>(element.get())) {
      const LinearTerms terms = across_terms(s->to(), s->from());
      const size_t x = add_probe("x_" + s->name(), terms, 1);
      const size_t v = add_probe("v_" + s->name(), terms, 0);
      out.drives.push_back({s, x, v});
    } else if (dynamic_cast<const Conductance*>(element.get())) {
      ++out.dissipators;
    } else if (!dynamic_cast<const Transformer*>(element.get())) {
      throw std::logic_error(std::string("energy balance: unexpected element kind ") +
                             element->kind() + " (" + element->name() + ")");
    }
  }
  return out;
}

// Output times: every switching edge (exactly the solvers' breakpoints), `per_interval` − 1
// uniform times inside each constant interval, and t_edge + δ after each interior edge.
struct Schedule {
  std::vector<double> times;
  std::vector<bool> after_edge;  // times[i] = edge + δ, times[i − 1] = edge
  double delta = 0.0;
};

Schedule make_schedule(const System& system, double end_time, int per_interval) {
  std::vector<double> edges = system.breakpoints(0.0, end_time);
  if (edges.empty() || edges.back() < end_time) edges.push_back(end_time);
  double shortest = edges.front();
  for (size_t k = 1; k < edges.size(); ++k) shortest = std::min(shortest, edges[k] - edges[k - 1]);
  Schedule schedule;
  schedule.delta = 1e-9 * shortest;
  double begin = 0.0;
  schedule.times.push_back(0.0);
  schedule.after_edge.push_back(false);
  for (double edge : edges) {
    if (begin > 0.0) {
      schedule.times.push_back(begin + schedule.delta);
      schedule.after_edge.push_back(true);
    }
    for (int j = 1; j < per_interval; ++j) {
      schedule.times.push_back(begin + (edge - begin) * j / per_interval);
      schedule.after_edge.push_back(false);
    }
    schedule.times.push_back(edge);
    schedule.after_edge.push_back(false);
    begin = edge;
  }
  return schedule;
}

struct Balance {
  std::vector<double> work, energy;
  double max_energy = 0.0;
  double worst = 0.0;      // max |W − E|
  double final_gap = 0.0;  // W − E at the end
};

// W and E at every output time of `result` (run from rest on `schedule`).
Balance energy_balance(const EnergyProbes& energy, const Schedule& schedule,
                       const TransientResult& result) {
  const auto& t = result.times;
  const auto& y = result.values;
  Balance balance;
  balance.work.assign(t.size(), 0.0);
  balance.energy.assign(t.size(), 0.0);
  for (size_t i = 0; i < t.size(); ++i)
    for (const auto& store : energy.stores)
      balance.energy[i] += store.half_value * y[store.probe][i] * y[store.probe][i];
  // t = 0: the sources switch on from rest (F⁻ = 0, x⁻ = 0); the output is the state after.
  double work = 0.0;
  for (const auto& drive : energy.drives)
    work += 0.5 * drive.source->waveform().value(0.5 * t[1]) * y[drive.displacement][0];
  balance.work[0] = work;
  for (size_t i = 1; i < t.size(); ++i) {
    for (const auto& drive : energy.drives) {
      const Waveform& w = drive.source->waveform();
      const auto& x = y[drive.displacement];
      if (schedule.after_edge[i]) {
        // Edge at t[i − 1]: x[i − 1] is x⁻; x⁺ extrapolated back from t[i] = edge + δ.
        const double f_before = w.value(t[i - 1] - 0.5 * (t[i - 1] - t[i - 2]));
        const double f_after = w.value(0.5 * (t[i - 1] + t[i]));
        const double x_after = x[i] - (t[i] - t[i - 1]) * y[drive.velocity][i];
        work += 0.5 * (f_before + f_after) * (x_after - x[i - 1]) + f_after * (x[i] - x_after);
      } else {
        work += w.value(0.5 * (t[i - 1] + t[i])) * (x[i] - x[i - 1]);
      }
    }
    balance.work[i] = work;
  }
  for (size_t i = 0; i < t.size(); ++i) {
    balance.max_energy = std::max(balance.max_energy, balance.energy[i]);
    balance.worst = std::max(balance.worst, std::abs(balance.work[i] - balance.energy[i]));
  }
  balance.final_gap = balance.work.back() - balance.energy.back();
  return balance;
}

// The fixtures' cantilever (N = 7) with a square-wave tip force 0/F at `frequency` (high for
// the first half period): the scene's beam plus a force source on the tip's velocity node.
struct Driven {
  Model model;
  System system;
};

Driven square_driven_cantilever(double viscous_per_length, double force, double frequency) {
  Scene scene = testing::cantilever_scene(7);
  scene.damping.viscous_per_length = viscous_per_length;
  Driven driven{build_model(scene), {}};
  const NodeId tip = driven.model.beam.velocity.back();
  driven.model.network.add<CurrentSource>("F_tip", ground, tip,
                                          Waveform::square(0.0, force, frequency, 0.5, 0.0, 0.0));
  driven.system = driven.model.network.assemble();
  return driven;
}

// Bounds on |W − E| / max E for the two undamped runs below (20 edges, 10 drive periods).
// Exact method: no truncation error, but the rounding in Φ = e^{M·h} is not at 1e-16: the beam
// chain is stiff (its highest modes lie far above the first, ‖M·h‖ ≫ 1 for a half period h),
// and the error of the scaling-and-squaring exponential grows with ‖M·h‖. The cached
// Φ(half period) is applied again at every edge, so its small energy error adds up edge by
// edge: measured a few 1e-11·max E per edge on the fish fin, 6.8e-10 after 20 edges (cantilever
// 1.1e-10); the error grows ~6× per 10× longer interval and ~7× from N = 7 to N = 14, as
// rounding in e^{M·h} does. Bound 5e-9: 7× the larger measurement.
constexpr double exact_bound = 5e-9;
// IDA at rtol 1e-8: BDF is not energy-conserving; its numerical damping makes W − E grow
// linearly with the run, ≈ 3–4·rtol·max E per half period (measured at the end: 6.2e-7
// cantilever, 8.5e-7 fish fin, both W > E). Bound 3e-6: 3.5× the larger measurement, i.e.
// ~15·rtol per half period over the 20 half periods.
constexpr double ida_bound = 3e-6;
constexpr double ida_rtol = 1e-8;

TransientResult run(const std::string& method, const System& system,
                    const std::vector<Probe>& probes, const Schedule& schedule, double end_time) {
  TransientOptions options;
  options.end_time = end_time;
  options.output_times = schedule.times;
  options.relative_tolerance = ida_rtol;
  return method == "exact" ? run_transient_exact(system, probes, options)
                           : run_transient_ida(system, probes, options);
}

void report(const std::string& what, const Balance& balance) {
  std::printf("[energy] %-20s max E = %.6e J, max |W - E| = %.3e J = %.3e max E\n", what.c_str(),
              balance.max_energy, balance.worst, balance.worst / balance.max_energy);
}

// (a) Undamped cantilever, N = 7 (first resonance ≈ 5.8 Hz), square-wave tip force 0/1 N at
// 1.6 Hz for 10 periods from rest. Reference: energy conservation of a lossless network,
// W(t) = E(t) at every output time. The tip node carries a mass, so nothing jumps at the
// edges. Tolerances: exact_bound, ida_bound above (measured 1.1e-10 and 6.2e-7).
// 1.6 Hz: the edges k·0.3125 s are exact binary fractions, so the last edge is end_time itself.
TEST(Energy, UndampedCantileverWorkEqualsStoredEnergy) {
  const double frequency = 1.6, end_time = 10 / frequency;
  const Driven driven = square_driven_cantilever(0.0, 1.0, frequency);
  const EnergyProbes energy = energy_probes(driven.model.network, driven.system);
  ASSERT_EQ(energy.dissipators, 0);
  ASSERT_EQ(energy.drives.size(), 1u);
  const std::vector<double> edges = driven.system.breakpoints(0.0, end_time);
  ASSERT_EQ(edges.size(), 20u);  // both edges of 10 periods
  ASSERT_EQ(edges.back(), end_time);
  const Schedule schedule = make_schedule(driven.system, end_time, 40);
  struct Case {
    const char* method;
    double bound;
  };
  for (const Case& c : {Case{"exact", exact_bound}, Case{"ida", ida_bound}}) {
    const TransientResult result = run(c.method, driven.system, energy.probes, schedule, end_time);
    ASSERT_TRUE(result.status.ok()) << c.method << ": " << result.status.message;
    ASSERT_EQ(result.times.size(), schedule.times.size()) << c.method;
    const Balance balance = energy_balance(energy, schedule, result);
    report(std::string("cantilever, ") + c.method, balance);
    EXPECT_GT(balance.max_energy, 0.0);
    for (size_t i = 0; i < result.times.size(); ++i)
      ASSERT_NEAR(balance.work[i], balance.energy[i], c.bound * balance.max_energy)
          << c.method << " at t = " << result.times[i];
  }
}

// (b) The fish fin of netlists/fishfin.toml, undamped (loss factor 0), the DEAs as ideal
// voltage-driven forces: antagonistic 4 kV square wave at 5 Hz, 10 periods from rest. The DEA
// forces are moment sources on the massless rotation node at 70 mm, which jumps at every
// edge; the work of the jump is ½·(F⁻ + F⁺)·Δx (file header). Reference: energy conservation
// of a lossless network. Tolerances: exact_bound, ida_bound above (measured 6.8e-10, 8.5e-7).
TEST(Energy, UndampedFishFinWorkEqualsStoredEnergy) {
  const Scene scene = read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml",
                                 {"damping.loss_factor=0", "drive.electrical_dynamics=false"});
  const Model model = build_model(scene);
  const System system = model.network.assemble();
  const EnergyProbes energy = energy_probes(model.network, system);
  ASSERT_EQ(energy.dissipators, 0);
  ASSERT_GE(energy.drives.size(), 2u);
  const double end_time = 10 / scene.drive.frequency;
  const std::vector<double> edges = system.breakpoints(0.0, end_time);
  ASSERT_EQ(edges.size(), 20u);
  ASSERT_EQ(edges.back(), end_time);
  const Schedule schedule = make_schedule(system, end_time, 40);
  struct Case {
    const char* method;
    double bound;
  };
  for (const Case& c : {Case{"exact", exact_bound}, Case{"ida", ida_bound}}) {
    const TransientResult result = run(c.method, system, energy.probes, schedule, end_time);
    ASSERT_TRUE(result.status.ok()) << c.method << ": " << result.status.message;
    ASSERT_EQ(result.times.size(), schedule.times.size()) << c.method;
    const Balance balance = energy_balance(energy, schedule, result);
    report(std::string("fish fin, ") + c.method, balance);
    EXPECT_GT(balance.max_energy, 0.0);
    for (size_t i = 0; i < result.times.size(); ++i)
      ASSERT_NEAR(balance.work[i], balance.energy[i], c.bound * balance.max_energy)
          << c.method << " at t = " << result.times[i];
  }
}

// The check can fail: the cantilever of (a) with viscous damping to ground (0.2 N·s/m², a
// damping ratio of about 1 % in mode 1). Reference: a passive network dissipates, so
// W(t) − E(t) = ∫ Σ c·v² dt is positive and never decreases. Exact method, tolerance
// exact_bound as for (a): the gap at the end must exceed it by far (measured 0.55·max E),
// and W − E may not decrease between outputs by more than it.
TEST(Energy, DampedCantileverDissipatesWork) {
  const double frequency = 1.6, end_time = 10 / frequency;
  const Driven driven = square_driven_cantilever(0.2, 1.0, frequency);
  const EnergyProbes energy = energy_probes(driven.model.network, driven.system);
  ASSERT_GT(energy.dissipators, 0);
  const Schedule schedule = make_schedule(driven.system, end_time, 40);
  const TransientResult result = run("exact", driven.system, energy.probes, schedule, end_time);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  const Balance balance = energy_balance(energy, schedule, result);
  std::printf("[energy] damped cantilever: W - E at the end = %.3e J = %.3e max E\n",
              balance.final_gap, balance.final_gap / balance.max_energy);
  const double tolerance = exact_bound * balance.max_energy;
  EXPECT_GT(balance.final_gap, 1e3 * tolerance);
  for (size_t i = 1; i < result.times.size(); ++i)
    EXPECT_GE(balance.work[i] - balance.energy[i],
              balance.work[i - 1] - balance.energy[i - 1] - tolerance)
        << "t = " << result.times[i];
}

}  // namespace
}  // namespace emnet
