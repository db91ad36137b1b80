// The SPICE deck's element lines: the groups (a beam segment, the node masses, a load, a DEA)
// from the model's record of its elements (Model::structure), and each element kind's lines
// (the mapping in include/emnet/spice/spice_netlist.hpp).
#include "deck_writer.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/elements/gyrator.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/elements/transformer.hpp"
#include "emnet/elements/voltage_source.hpp"
#include "emnet/model/circuit.hpp"

namespace emnet::spice_deck {

std::vector<Group> DeckWriter::groups() const {
  std::vector<Group> list;
  auto group_for = [&](const std::string& key) -> Group& {
    for (Group& g : list)
      if (g.key == key) return g;
    list.push_back({key, {}, {}});
    return list.back();
  };
  const std::vector<SectionSpec> sections = effective_sections(scene_.beam);
  const double default_tau = scene_.damping.effective_kelvin_voigt_time();
  const auto& elements = network_.elements();
  for (size_t e = 0; e < elements.size(); ++e) {
    const ElementRecord* record = model_.structure.element(e);
    std::string key = "other";
    std::vector<std::string> title;
    if (record && record->component == Component::beam_segment) {
      const size_t k = static_cast<size_t>(record->index);
      const std::string id = std::to_string(record->index);
      key = "segment " + id;
      const BeamLayout& beam = model_.beam;
      const bool known = k < beam.segment_lengths.size() && k < beam.segment_section.size();
      const SectionSpec* section =
          known ? &sections[static_cast<size_t>(beam.segment_section[k])] : nullptr;
      const double l = known ? beam.segment_lengths[k] : 0.0;
      const double ei = section ? section->bending_stiffness : 0.0;
      const double tau = section ? section->kelvin_voigt_time.value_or(default_tau) : default_tau;
      const bool sheared = known && beam.shear_parameter[k] > 0.0;
      if (known && k + 1 < model_.beam.x.size())
        title = {
            "segment " + id + ": x = " + millimetres(model_.beam.x[k]) + " .. " +
                millimetres(model_.beam.x[k + 1]) + ", l = " + number(l) +
                " m, EI = " + number(ei) + " N*m^2",
            std::string("  nR: rotational compliance n_R = l/EI [rad/(N*m)] between the "
                        "rotation nodes; nT: translational compliance n_T = l^3/(12*EI)") +
                (sheared
                     ? " + l/(kappa*G*A), kappa*G*A = " +
                           number(section->shear_stiffness.value_or(scene_.beam.shear_stiffness)) +
                           " N (Timoshenko)"
                     : std::string()) +
                " [m/N]",
            "  lever: ideal transformer, v_right - m = (l/2)*(Omega_left + Omega_right); "
            "its force F returns as torques (l/2)*F into both rotation nodes"};
      if (known && tau > 0.0 && k + 1 < model_.beam.x.size())
        title.push_back(
            "  Kelvin-Voigt damping: a resistor n/tau (a damper tau/n) across each "
            "compliance, tau = " +
            number(tau) + " s");
    } else if (record && record->component == Component::beam_node) {
      key = "nodes";
      title = {
          "lumped at the beam nodes (half of each segment's share to each end node): "
          "masses rhoA*l [kg] and rotary inertias [kg*m^2] as capacitors to ground, viscous "
          "dampers [N*s/m] as resistors to ground"};
    } else if (record && record->component == Component::load) {
      const size_t k = static_cast<size_t>(record->index);
      const std::string id = std::to_string(record->index);
      key = "load " + id;
      if (k < scene_.loads.size()) {
        const LoadSpec& load = scene_.loads[k];
        title = {"load " + id + ": " +
                 (load.kind == LoadKind::force ? "force " + number(load.value) + " N"
                                               : "moment " + number(load.value) + " N*m") +
                 " at x = " + millimetres(load.at) +
                 ", as consistent nodal loads from the Hermite shape functions"};
      }
    } else if (record && record->component == Component::point_mass) {
      const size_t k = static_cast<size_t>(record->index);
      key = "mass " + std::to_string(record->index);
      if (k < scene_.beam.masses.size()) {
        const MassSpec& mass = scene_.beam.masses[k];
        title = {"point mass " + (mass.name.empty() ? std::to_string(k) : mass.name) + ": " +
                 number(mass.mass) + " kg, rotary inertia " + number(mass.rotary_inertia) +
                 " kg*m^2 at x = " + millimetres(mass.at) + ", capacitors to ground"};
      }
    } else if (record && record->component == Component::spring) {
      const size_t k = static_cast<size_t>(record->index);
      key = "spring " + std::to_string(record->index);
      if (k < scene_.beam.springs.size()) {
        const SpringSpec& spring = scene_.beam.springs[k];
        const bool rotational = spring.kind == SpringKind::rotational;
        title = {std::string(rotational ? "rotational" : "translational") + " spring " +
                 (spring.name.empty() ? std::to_string(k) : spring.name) +
                 ": k = " + number(spring.stiffness) + (rotational ? " N*m/rad" : " N/m") +
                 ", damping " + number(spring.damping) + (rotational ? " N*m*s/rad" : " N*s/m") +
                 ", x = " + millimetres(spring.at) + " to " +
                 (spring.to ? "x = " + millimetres(*spring.to) : std::string("ground")) +
                 "; an inductor 1/k with a resistor 1/damping across it"};
      }
    } else if (record && record->component == Component::circuit) {
      const size_t k = static_cast<size_t>(record->index);
      key = "circuit";
      title = {
          "circuit ([[circuit]] entries): electrical elements between named nodes, ground "
          "(0) and the DEAs' source terminals s_X; a voltage source holds V(from) - V(to), a "
          "current source drives its current from its first node through itself into its second"};
      if (k < scene_.circuit.size()) {
        const CircuitSpec& element = scene_.circuit[k];
        title.push_back("  " + element.name + ": " + circuit_kind_name(element.kind) + " from " +
                        element.from + " to " + element.to +
                        (is_source(element.kind) ? std::string(", waveform ") +
                                                       waveform_kind_name(element.waveform.kind)
                                                 : std::string()));
      }
    } else if (record && (record->component == Component::dea ||
                          record->component == Component::drive_source)) {
      const DeaLayout* dea = model_.find_dea(record->dea);
      const std::string& n = record->dea;
      key = "dea " + n;
      const DeaSpec* spec = nullptr;
      for (const DeaSpec& s : scene_.deas)
        if (s.name == n) spec = &s;
      title.push_back("DEA " + n +
                      (spec ? std::string(": ") + (spec->face == Face::top ? "top" : "bottom") +
                                  " face, x = " + millimetres(spec->from) + " .. " +
                                  millimetres(spec->to) +
                                  ", lever arm z = " + millimetres(spec->lever_arm)
                            : std::string()));
      if (dea) {
        title.push_back("  force F = k_F*u^2, k_F = " + number(dea->force_constant) +
                        " N/V^2 (paper Eq. 16), as the moment pair -/+z*F at the span's ends");
        if (scene_.drive.electrical_dynamics && circuit_drives_dea(scene_, n))
          title.push_back("  electrical: driven by the circuit at its terminal s_" + n +
                          ", electrode resistance " + number(dea->electrode_resistance) +
                          " Ohm, capacitor C0 = " + number(dea->capacitance) +
                          " F; the force follows the capacitor voltage u = V(e_" + n + ")");
        else if (scene_.drive.electrical_dynamics)
          title.push_back("  electrical: source V_V_" + n + ", electrode resistance " +
                          number(dea->electrode_resistance) +
                          " Ohm, capacitor C0 = " + number(dea->capacitance) +
                          " F; the force follows the capacitor voltage u = V(e_" + n + ")");
        else
          title.push_back(
              "  ideal drive (drive.electrical_dynamics = false): the force "
              "k_F*V(t)^2 of the source voltage, as current sources");
      }
    }
    Group& group = group_for(key);
    if (group.title.empty())
      group.title = title;
    else if (key == "circuit" && title.size() > 1)
      group.title.push_back(title.back());  // one line per circuit element
    group.elements.push_back(elements[e].get());
  }
  for (Group& g : list)
    if (g.title.empty()) g.title = {g.key == "other" ? "other elements" : g.key};
  return list;
}

void DeckWriter::write_element(const Element& element) {
  std::ostringstream& out = body_;
  const std::string& name = element.name();
  auto branch = [&](int k, const std::string& spice_element, double sign) {
    const int index = system_.branch_index(name, k);
    deck_.unknowns.at(static_cast<size_t>(index)) = {
        spice_element.empty() ? "" : lower(spice_element) + "#branch", sign};
  };

  if (const auto* g = dynamic_cast<const Conductance*>(&element)) {
    if (op_ && (mechanical(g->a()) || mechanical(g->b()))) {
      left_out_.push_back(name);  // a damper: no force at rest
      return;
    }
    if (g->conductance() == 0.0) {
      comment(out, name + ": conductance 0 between " + node(g->a()) + " and " + node(g->b()) +
                       ": an open, no element");
      return;
    }
    out << element_name('R', name) << " " << node(g->a()) << " " << node(g->b()) << " "
        << value(1.0 / g->conductance(), name) << "\n";
    return;
  }
  if (const auto* c = dynamic_cast<const Capacitor*>(&element)) {
    if (op_ && (mechanical(c->a()) || mechanical(c->b()))) {
      left_out_.push_back(name);  // a mass or inertia: no force at rest
      return;
    }
    if (c->capacitance() == 0.0) {
      comment(out, name + ": capacitance 0: no element");
      return;
    }
    out << element_name('C', name) << " " << node(c->a()) << " " << node(c->b()) << " "
        << value(c->capacitance(), name) << "\n";
    return;
  }
  if (const auto* l = dynamic_cast<const Inductor*>(&element)) {
    if (l->inductance() == 0.0) {
      const std::string spice = element_name('V', name);
      comment(out, name + ": inductance 0: a short, written as a 0 V source");
      out << spice << " " << node(l->a()) << " " << node(l->b()) << " DC 0\n";
      branch(0, spice, 1.0);
      return;
    }
    if (op_ && (mechanical(l->a()) || mechanical(l->b()))) {
      // z_a − z_b = n·F: the compliance is a resistor n between displacement nodes (a damper
      // across it carries no force at rest).
      if (l->parallel_conductance() != 0.0) left_out_.push_back(name + " (its damper)");
      out << element_name('R', name) << " " << node(l->a()) << " " << node(l->b()) << " "
          << value(l->inductance(), name) << "\n";
      branch(0, "", 1.0);
      return;
    }
    const std::string spice = element_name('L', name);
    out << spice << " " << node(l->a()) << " " << node(l->b()) << " "
        << value(l->inductance(), name) << "\n";
    branch(0, spice, 1.0);
    // Its parallel conductance as a resistor across it (the same equations; in an op deck it
    // carries no force at rest and is left out above with the coil written as a resistor).
    if (l->parallel_conductance() != 0.0)
      out << element_name('R', name) << " " << node(l->a()) << " " << node(l->b()) << " "
          << value(1.0 / l->parallel_conductance(), name) << "\n";
    return;
  }
  if (const auto* i = dynamic_cast<const CurrentSource*>(&element)) {
    out << element_name('I', name) << " " << node(i->from()) << " " << node(i->to()) << " "
        << source(i->waveform(), name) << "\n";
    return;
  }
  if (const auto* v = dynamic_cast<const VoltageSource*>(&element)) {
    const std::string spice = element_name('V', name);
    if (op_ && (mechanical(v->plus()) || mechanical(v->minus()))) {
      if (v->waveform().value(0.0) != 0.0)
        throw InputError(where(), name,
                         "a constant velocity source (" + number(v->waveform().value(0.0)) +
                             ") has no static state: no op deck");
      out << spice << " " << node(v->plus()) << " " << node(v->minus()) << " DC 0\n";
    } else {
      out << spice << " " << node(v->plus()) << " " << node(v->minus()) << " "
          << source(v->waveform(), name) << "\n";
    }
    branch(0, spice, 1.0);
    return;
  }
  if (const auto* t = dynamic_cast<const Transformer*>(&element)) {
    const bool secondary_mechanical =
        mechanical(t->secondary_plus()) || mechanical(t->secondary_minus());
    std::vector<Transformer::Port> active;
    for (const auto& port : t->primaries()) {
      if (port.ratio == 0.0 || (port.plus == ground && port.minus == ground)) continue;
      if (op_ && (mechanical(port.plus) || mechanical(port.minus)) != secondary_mechanical)
        throw InputError(where(), name,
                         "a transformer between electrical and mechanical ports is not written "
                         "to op decks");
      active.push_back(port);
    }
    std::string relation = node(t->secondary_plus()) + " - " + node(t->secondary_minus()) + " =";
    for (size_t k = 0; k < active.size(); ++k)
      relation += (k ? " + " : " ") + number(active[k].ratio) + "*" +
                  voltage(active[k].plus, active[k].minus);
    if (active.empty()) relation += " 0";
    comment(out, name + ": ideal transformer, " + relation + "; sense source " +
                     "carries its force j, each primary gets ratio*j");
    const std::string sense = element_name('V', name);
    const NodeId secondary_node =
        t->secondary_plus() != ground ? t->secondary_plus() : t->secondary_minus();
    const std::string unit =
        secondary_node == ground ? "V" : across_unit(network_.node(secondary_node).domain);
    std::vector<std::string> chain;
    for (size_t k = 0; k < active.size(); ++k)
      chain.push_back(internal_node(
          name + "_" + std::to_string(k + 1),
          "internal node of " + name + ", in the series chain of its secondary [" +
              (op_ && secondary_mechanical ? (unit == "m/s" ? "m" : "rad") : unit) + "]"));
    chain.push_back(node(t->secondary_minus()));
    out << sense << " " << node(t->secondary_plus()) << " " << chain.front() << " DC 0\n";
    for (size_t k = 0; k < active.size(); ++k)
      out << element_name('E', name + "_" + std::to_string(k + 1)) << " " << chain[k] << " "
          << chain[k + 1] << " " << node(active[k].plus) << " " << node(active[k].minus) << " "
          << value(active[k].ratio, name) << "\n";
    for (size_t k = 0; k < active.size(); ++k)
      out << element_name('F', name + "_" + std::to_string(k + 1)) << " " << node(active[k].minus)
          << " " << node(active[k].plus) << " " << sense << " " << value(active[k].ratio, name)
          << "\n";
    branch(0, sense, 1.0);
    return;
  }
  if (const auto* y = dynamic_cast<const Gyrator*>(&element)) {
    const double k = y->gyration();
    comment(out, name + ": gyrator K = " + number(k) + ": current K*V(port 2) out of port 1, " +
                     "-K*V(port 1) out of port 2");
    if (!(op_ && (mechanical(y->c()) || mechanical(y->d()))))
      out << element_name('G', name + "_1") << " " << node(y->a()) << " " << node(y->b()) << " "
          << node(y->c()) << " " << node(y->d()) << " " << value(k, name) << "\n";
    if (!(op_ && (mechanical(y->a()) || mechanical(y->b()))))
      out << element_name('G', name + "_2") << " " << node(y->c()) << " " << node(y->d()) << " "
          << node(y->a()) << " " << node(y->b()) << " " << value(-k, name) << "\n";
    return;
  }
  if (const auto* d = dynamic_cast<const Dea*>(&element)) {
    const std::string u = voltage(d->electrode_plus(), d->electrode_minus());
    if (d->capacitance() != 0.0)
      out << element_name('C', name) << " " << node(d->electrode_plus()) << " "
          << node(d->electrode_minus()) << " " << value(d->capacitance(), name) << "\n";
    // Coupling coefficients summed per node, in order of first appearance.
    std::vector<std::pair<NodeId, double>> coupling;
    for (const Dea::Coupling& c : d->coupling()) {
      if (c.node == ground) continue;
      auto at = std::find_if(coupling.begin(), coupling.end(),
                             [&](const auto& p) { return p.first == c.node; });
      if (at == coupling.end())
        coupling.emplace_back(c.node, c.coefficient);
      else
        at->second += c.coefficient;
    }
    comment(out, name + ": force k_F*u^2 on the capacitor voltage u = " + u +
                     ", entering node k as c_k*k_F*u^2 (c_k: elongation rate per unit across)");
    for (const auto& [n, c] : coupling) {
      if (c == 0.0) continue;
      out << element_name('B', name + "_" + network_.node(n).name) << " 0 " << node(n)
          << " I = " << value(c * d->force_constant(), name) << "*" << u << "*" << u << "\n";
    }
    if (d->back_coupling() && !op_) {
      std::string rate;
      for (const auto& [n, c] : coupling) {
        if (c == 0.0) continue;
        rate += (rate.empty() ? "" : "+") + value(c, name) + "*V(" + node(n) + ")";
      }
      if (!rate.empty()) {
        comment(out, name + ": motional current u*dC/dx*dx/dt = 2*k_F*u*(elongation rate)");
        out << element_name('B', name + "_motional") << " " << node(d->electrode_plus()) << " "
            << node(d->electrode_minus()) << " I = " << value(2.0 * d->force_constant(), name)
            << "*" << u << "*(" << rate << ")\n";
      }
    } else if (d->back_coupling()) {
      comment(out, name + ": motional current left out (zero at rest)");
    }
    if (ac_ && d->ac_force() != 0.0) {
      comment(out, name + ": AC input, the force amplitude " + number(d->ac_force()) +
                       " N along the coupling (AC only, no DC part)");
      for (const auto& [n, c] : coupling) {
        const double amplitude = c * d->ac_force();
        if (amplitude == 0.0) continue;
        out << element_name('I', name + "_ac_" + network_.node(n).name) << " 0 " << node(n)
            << " DC 0 AC " << value(std::abs(amplitude), name) << " "
            << (amplitude < 0.0 ? "180" : "0") << "\n";
      }
    }
    return;
  }
  throw InputError(
      where(), name,
      std::string("element kind '") + element.kind() + "' has no SPICE equivalent in this writer");
}

}  // namespace emnet::spice_deck
