// A scene's [[circuit]] in a model's network: its nodes, its elements and its sources' waveforms.
//
// Each [[circuit]] entry (emnet/scene/scene.hpp, CircuitSpec) becomes one element between two
// electrical nodes:
//   resistor        a Conductance 1/R [S] between `from` and `to`;
//   capacitor       a Capacitor C [F];
//   inductor        an Inductor L [H];
//   voltage_source  a VoltageSource holding V(from) − V(to) = v(t) [V];
//   current_source  a CurrentSource driving i(t) [A] out of `from`, through itself, into `to`.
// Node names: "ground" or "0" is ground; "dea.X" is DEA X's source terminal s_X (in front of its
// electrode resistance R_e; the model builder adds no drive source there, the circuit drives
// it); any other name is a node of the circuit (NodeRole::circuit), named so in the network and
// in SPICE decks.
//
// Waveforms (circuit_waveform), in the source's unit (V or A):
//   dc      v(t) = value;
//   square  a pulse train between low and high of period 1/frequency from `delay`: rise, then
//           high until duty/frequency after the period's start, fall, low (Waveform::square's
//           timing, with its own fall time): width = duty/frequency − rise;
//   pulse   SPICE PULSE(low high delay rise fall width period), period 0 a single pulse;
//   sine    offset + amplitude·sin(2π·frequency·(t − delay) + phase·π/180), offset +
//           amplitude·sin(phase) before `delay`;
//   pwl     linear between the points, constant before the first and after the last.
// Every waveform's AC phasor is circuit[].ac at phase 0. A dc, square, pulse or pwl source is
// piecewise linear, which the exact transient method integrates exactly.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "emnet/model/structure.hpp"
#include "emnet/network/network.hpp"
#include "emnet/network/waveform.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

/// A circuit source's time function and AC phasor (see the top comment).
Waveform circuit_waveform(const CircuitSpec& element);

/// The largest |value| `waveform` takes over time: its levels, a sine's crest, its points (V or A;
/// the drive's waveforms and the circuit's sources alike).
double waveform_largest_magnitude(const Waveform& waveform);

/// Whether a [[circuit]] element of `scene` ends on DEA `dea_name`'s terminal ("dea.NAME").
bool circuit_drives_dea(const Scene& scene, const std::string& dea_name);

/// The DEAs of `scene` that a [[circuit]] element ends on, in the scene's order: the one answer
/// to "which DEAs does the circuit drive" (the model's note, the validity checks).
std::vector<std::string> circuit_driven_deas(const Scene& scene);

/// What circuit-driven DEA `dea_name`'s terminal voltage is proven to stay within, from the
/// sources of the circuit's part joined to its terminal through nodes other than ground.
/// In a network of resistors and capacitors driven only by voltage sources that each have one
/// terminal on ground, started from rest, every node voltage stays within the range of the
/// sources' levels and 0 (the maximum principle of RC networks: the node equations are those of
/// an M-matrix, so no node exceeds its neighbours' extremes). `bounded` is false, with `reason`,
/// for a circuit outside that class (an inductor, a current source, a floating source) or a DEA
/// whose back-coupling injects current.
struct CircuitVoltageBound {
  bool bounded = false;   ///< whether the bound below holds
  std::string reason;     ///< why no bound is known (empty when bounded)
  double peak = 0.0;      ///< [V] the largest |level| any source takes over its waveform
  double at_start = 0.0;  ///< [V] the largest |level| at t = 0 (the static state's bound)
};
/// The CircuitVoltageBound of circuit-driven DEA `dea_name` of `scene`.
CircuitVoltageBound circuit_voltage_bound(const Scene& scene, const std::string& dea_name);

/// Adds the circuit's nodes and elements of `scene` to `network`, each with its record
/// (Component::circuit; its entry index). `dea_terminals` maps a DEA's name to its source node
/// s_X. Returns the circuit's own nodes by name.
/// @throws InputError naming the scene file and the entry's key for a node "dea.X" without a
///         terminal (a DEA without electrical dynamics)
std::map<std::string, NodeId> add_circuit(Network& network, ModelStructure* structure,
                                          const Scene& scene,
                                          const std::map<std::string, NodeId>& dea_terminals);

}  // namespace emnet
