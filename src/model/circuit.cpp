// A scene's [[circuit]] in a model's network: see include/emnet/model/circuit.hpp.
#include "emnet/model/circuit.hpp"

#include <algorithm>
#include <cmath>

#include "emnet/core/constants.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/elements/voltage_source.hpp"

namespace emnet {

namespace {

ElementPart circuit_part(CircuitKind kind) {
  switch (kind) {
    case CircuitKind::resistor:
      return ElementPart::resistor;
    case CircuitKind::capacitor:
      return ElementPart::capacitor;
    case CircuitKind::inductor:
      return ElementPart::inductor;
    case CircuitKind::voltage_source:
      return ElementPart::voltage_source;
    case CircuitKind::current_source:
      return ElementPart::current_source;
  }
  return ElementPart::resistor;
}

const char* circuit_unit(CircuitKind kind) {
  switch (kind) {
    case CircuitKind::resistor:
      return "Ohm";
    case CircuitKind::capacitor:
      return "F";
    case CircuitKind::inductor:
      return "H";
    case CircuitKind::voltage_source:
      return "V";
    case CircuitKind::current_source:
      return "A";
  }
  return "";
}

}  // namespace

Waveform circuit_waveform(const CircuitSpec& element) {
  const WaveformSpec& spec = element.waveform;
  Waveform waveform;
  switch (spec.kind) {
    case WaveformKind::dc:
      waveform = Waveform::constant(element.value);
      break;
    case WaveformKind::square: {
      waveform =
          Waveform::square(spec.low, spec.high, spec.frequency, spec.duty, spec.delay, spec.rise);
      waveform.fall = spec.fall_time();
      break;
    }
    case WaveformKind::pulse:
      waveform.shape = Waveform::Shape::pulse;
      waveform.dc = spec.low;
      waveform.pulse_high = spec.high;
      waveform.delay = spec.delay;
      waveform.rise = spec.rise;
      waveform.fall = spec.fall_time();
      waveform.width = spec.width;
      waveform.period = spec.period;
      break;
    case WaveformKind::sine:
      waveform.shape = Waveform::Shape::sine;
      waveform.dc = spec.offset;
      waveform.amplitude = spec.amplitude;
      waveform.frequency = spec.frequency;
      waveform.phase = spec.phase_degrees * kPi / 180.0;
      waveform.delay = spec.delay;
      break;
    case WaveformKind::pwl:
      waveform.shape = Waveform::Shape::pwl;
      waveform.points = spec.points;
      waveform.dc = spec.points.empty() ? 0.0 : spec.points.front().second;
      break;
  }
  waveform.ac_magnitude = element.ac;
  waveform.ac_phase = 0.0;
  return waveform;
}

bool circuit_drives_dea(const Scene& scene, const std::string& dea_name) {
  return std::any_of(scene.circuit.begin(), scene.circuit.end(), [&](const CircuitSpec& element) {
    return dea_of_node_name(element.from) == dea_name || dea_of_node_name(element.to) == dea_name;
  });
}

double waveform_largest_magnitude(const Waveform& waveform) {
  switch (waveform.shape) {
    case Waveform::Shape::dc:
      return std::abs(waveform.dc);
    case Waveform::Shape::pulse:
      return std::max(std::abs(waveform.dc), std::abs(waveform.pulse_high));
    case Waveform::Shape::sine:
      return std::abs(waveform.dc) + std::abs(waveform.amplitude);
    case Waveform::Shape::pwl: {
      double peak = std::abs(waveform.dc);
      for (const auto& point : waveform.points) peak = std::max(peak, std::abs(point.second));
      return peak;
    }
  }
  return 0.0;
}

std::vector<std::string> circuit_driven_deas(const Scene& scene) {
  std::vector<std::string> driven;
  for (const DeaSpec& dea : scene.deas)
    if (circuit_drives_dea(scene, dea.name)) driven.push_back(dea.name);
  return driven;
}

namespace {

// The circuit's elements that share, through nodes other than ground, a connected part with DEA
// `dea_name`'s terminal (those outside it are joined to it by ground only and do not move it).
std::vector<const CircuitSpec*> elements_connected_to(const Scene& scene,
                                                      const std::string& dea_name) {
  std::vector<std::string> reached{"dea." + dea_name};
  std::vector<const CircuitSpec*> connected;
  std::vector<bool> taken(scene.circuit.size(), false);
  const auto is_reached = [&](const std::string& node) {
    return !is_ground_node_name(node) &&
           std::find(reached.begin(), reached.end(), node) != reached.end();
  };
  for (bool grew = true; grew;) {
    grew = false;
    for (std::size_t k = 0; k < scene.circuit.size(); ++k) {
      const CircuitSpec& element = scene.circuit[k];
      if (taken[k] || !(is_reached(element.from) || is_reached(element.to))) continue;
      taken[k] = grew = true;
      connected.push_back(&element);
      for (const std::string& node : {element.from, element.to})
        if (!is_ground_node_name(node) && !is_reached(node)) reached.push_back(node);
    }
  }
  return connected;
}

}  // namespace

CircuitVoltageBound circuit_voltage_bound(const Scene& scene, const std::string& dea_name) {
  CircuitVoltageBound bound;
  for (const CircuitSpec* connected : elements_connected_to(scene, dea_name)) {
    const CircuitSpec& element = *connected;
    const std::string where = "circuit[" + element.name + "]";
    if (element.kind == CircuitKind::inductor || element.kind == CircuitKind::current_source) {
      bound.reason =
          where + " is a" +
          std::string(element.kind == CircuitKind::inductor ? "n inductor" : " current source") +
          ", outside the RC network the maximum principle bounds";
      return bound;
    }
    if (element.kind != CircuitKind::voltage_source) continue;
    if (!is_ground_node_name(element.from) && !is_ground_node_name(element.to)) {
      bound.reason = where + " is a voltage source with no terminal on ground";
      return bound;
    }
    const Waveform waveform = circuit_waveform(element);
    bound.peak = std::max(bound.peak, waveform_largest_magnitude(waveform));
    bound.at_start = std::max(bound.at_start, std::abs(waveform.value(0.0)));
  }
  for (const DeaSpec& dea : scene.deas)
    if (dea.back_coupling && dea.name == dea_name) {
      bound.reason = "DEA " + dea.name + "'s back-coupling (dea[].back_coupling) injects current";
      return bound;
    }
  bound.bounded = true;
  return bound;
}

std::map<std::string, NodeId> add_circuit(Network& network, ModelStructure* structure,
                                          const Scene& scene,
                                          const std::map<std::string, NodeId>& dea_terminals) {
  std::map<std::string, NodeId> nodes;
  for (std::size_t k = 0; k < scene.circuit.size(); ++k) {
    const CircuitSpec& element = scene.circuit[k];
    const std::string prefix = "circuit[" + element.name + "]";
    auto node_of = [&](const std::string& name, const char* end) -> NodeId {
      if (is_ground_node_name(name)) return ground;
      const std::string dea = dea_of_node_name(name);
      if (!dea.empty()) {
        const auto found = dea_terminals.find(dea);
        if (found == dea_terminals.end() || found->second == ground)
          throw InputError(scene.file, prefix + "." + end,
                           "'" + name + "': DEA '" + dea +
                               "' has no electrical terminal (drive.electrical_dynamics = false); "
                               "a circuit needs drive.electrical_dynamics = true");
        return found->second;
      }
      if (const auto found = nodes.find(name); found != nodes.end()) return found->second;
      const NodeId id = add_recorded_node(
          network, structure, {NodeRole::circuit, static_cast<int>(nodes.size()), ""}, name,
          Domain::electrical, "circuit node " + name + " [V]");
      nodes.emplace(name, id);
      return id;
    };
    const NodeId from = node_of(element.from, "from");
    const NodeId to = node_of(element.to, "to");
    ElementRecord record;
    record.component = Component::circuit;
    record.part = circuit_part(element.kind);
    record.index = static_cast<int>(k);
    record.meaning = std::string("circuit element ") + element.name + ", " +
                     circuit_kind_name(element.kind) + " from " + element.from + " to " +
                     element.to + " [" + circuit_unit(element.kind) + "]";
    switch (element.kind) {
      case CircuitKind::resistor:
        add_recorded<Conductance>(network, structure, std::move(record), element.name, from, to,
                                  1.0 / element.value);
        break;
      case CircuitKind::capacitor:
        add_recorded<Capacitor>(network, structure, std::move(record), element.name, from, to,
                                element.value);
        break;
      case CircuitKind::inductor:
        add_recorded<Inductor>(network, structure, std::move(record), element.name, from, to,
                               element.value, Domain::electrical);
        break;
      case CircuitKind::voltage_source:
        add_recorded<VoltageSource>(network, structure, std::move(record), element.name, from, to,
                                    circuit_waveform(element), Domain::electrical);
        break;
      case CircuitKind::current_source:
        add_recorded<CurrentSource>(network, structure, std::move(record), element.name, from, to,
                                    circuit_waveform(element));
        break;
    }
  }
  return nodes;
}

}  // namespace emnet
