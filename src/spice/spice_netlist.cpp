// SPICE deck writer: see include/emnet/spice/spice_netlist.hpp for the mapping of every element
// kind, the sign conventions, the op deck's static network and the safety rules. The deck's
// groups (a beam segment, the node masses, a load, a DEA) come from the model's record of its
// elements (Model::structure), its outputs from the model's output list (emnet/model/outputs.hpp).
#include "emnet/spice/spice_netlist.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "emnet/analysis/analysis.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/elements/capacitor.hpp"
#include "emnet/elements/conductance.hpp"
#include "emnet/elements/current_source.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/elements/gyrator.hpp"
#include "emnet/elements/inductor.hpp"
#include "emnet/elements/transformer.hpp"
#include "emnet/elements/voltage_source.hpp"
#include "emnet/model/outputs.hpp"

namespace emnet {

namespace {

constexpr double pi = 3.14159265358979323846;
// Leak resistor of an integrator output (1 F): time constant 1e9 s, see the header comment.
constexpr double integrator_leak_resistance = 1e9;

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool is_name_character(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

bool is_identifier(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), is_name_character);
}

// 12 significant digits: far below the 1e-6 at which decks are compared with emnet, and short.
std::string number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.12g", value);
  return buffer;
}

// Positions and lengths in comments, in millimetres.
std::string millimetres(double metres) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g mm", metres * 1e3);
  return buffer;
}

std::string file_name(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// Names unique without regard to letter case; never a ground alias.
class NameTable {
 public:
  std::string claim(const std::string& wanted) {
    std::string base = spice_identifier(wanted);
    if (lower(base) == "0" || lower(base) == "gnd") base = "n_" + base;
    std::string candidate = base;
    for (int k = 2; used_.count(lower(candidate)) != 0; ++k)
      candidate = base + "_" + std::to_string(k);
    used_.insert(lower(candidate));
    return candidate;
  }

 private:
  std::set<std::string> used_;
};

// A group of elements written under one comment: the lumped node elements, one beam segment,
// one load, one DEA, or the rest.
struct Group {
  std::string key;
  std::vector<std::string> title;
  std::vector<const Element*> elements;
};

class DeckWriter {
 public:
  DeckWriter(const Model& model, const SpiceDeckOptions& options)
      : model_(model),
        network_(model.network),
        scene_(model.scene),
        options_(options),
        op_(options.analysis == SpiceAnalysis::op),
        ac_(options.analysis == SpiceAnalysis::ac),
        tran_(options.analysis == SpiceAnalysis::tran),
        system_(model.network.assemble()) {}

  SpiceDeck write();

 private:
  std::string where() const { return scene_.file.empty() ? std::string("scene") : scene_.file; }
  bool mechanical(NodeId node) const {
    return node != ground && is_mechanical(network_.node(node).domain);
  }
  const std::string& node(NodeId id) const {
    static const std::string ground_name = "0";
    return id == ground ? ground_name : node_names_.at(static_cast<size_t>(id));
  }
  std::string voltage(NodeId plus, NodeId minus) const {
    if (minus == ground) return "V(" + node(plus) + ")";
    if (plus == ground) return "(-V(" + node(minus) + "))";
    return "(V(" + node(plus) + ")-V(" + node(minus) + "))";
  }
  std::string value(double x, const std::string& what) const {
    if (!std::isfinite(x)) throw InputError(where(), what, "value is not finite");
    return number(x);
  }
  // A comment, wrapped at 100 columns on spaces; continuation lines are indented.
  void comment(std::ostringstream& out, const std::string& text) const {
    const std::string safe = spice_comment_text(text);
    const size_t indent = safe.find_first_not_of(' ') == std::string::npos
                              ? 0
                              : std::min<size_t>(safe.find_first_not_of(' '), 8);
    std::string line;
    std::istringstream words(safe.substr(indent));
    std::string word;
    line = std::string(indent, ' ');
    bool first = true;
    while (words >> word) {
      if (!first && 2 + line.size() + 1 + word.size() > 100) {
        out << "* " << line << "\n";
        line = std::string(indent + 4, ' ');
        first = true;
      }
      line += (first ? "" : " ") + word;
      first = false;
    }
    out << "* " << line << "\n";
  }
  std::string element_name(char letter, const std::string& name) {
    return elements_.claim(std::string(1, letter) + "_" + name);
  }
  std::string internal_node(const std::string& name, const std::string& meaning) {
    const std::string spice = nodes_.claim(name);
    node_comments_.push_back(spice + ": " + meaning);
    return spice;
  }

  void check_names() const;
  void name_nodes();
  std::vector<Group> groups() const;
  void write_header(std::ostringstream& out) const;
  void write_element(const Element& element);
  void write_outputs();
  void write_analysis(std::ostringstream& out);
  std::string source(const Waveform& waveform, const std::string& what);
  std::string time_function(const Waveform& waveform, const std::string& what);
  std::string pwl(const std::vector<std::pair<double, double>>& points, const std::string& what);
  std::string node_meaning(const Node& node) const;

  const Model& model_;
  const Network& network_;
  const Scene& scene_;
  const SpiceDeckOptions& options_;
  const bool op_, ac_, tran_;
  const System system_;
  std::vector<Probe> outputs_;
  NameTable nodes_, elements_;
  std::vector<std::string> node_names_;
  std::vector<std::string> node_comments_;
  std::vector<std::string> output_comments_;
  std::ostringstream body_;
  std::vector<std::pair<std::string, double>> initial_conditions_;  // tran, static start
  std::vector<std::string> edge_notes_;
  std::vector<std::string> left_out_;  // op: masses and dampers of the current group
  SpiceDeck deck_;
};

void DeckWriter::check_names() const {
  for (size_t k = 0; k < scene_.deas.size(); ++k)
    if (!is_identifier(scene_.deas[k].name))
      throw InputError(where(), "dea[" + std::to_string(k) + "].name",
                       "must be a non-empty name of letters, digits and '_' only (it names "
                       "nodes and elements of SPICE decks), got '" +
                           spice_comment_text(scene_.deas[k].name) + "'");
}

std::string DeckWriter::node_meaning(const Node& node) const {
  std::string meaning = node.meaning;
  if (!op_ || !is_mechanical(node.domain)) return meaning;
  // The op deck's mechanical nodes hold displacements: say so in the node's own words.
  auto replace = [&](const std::string& from, const std::string& to) {
    for (auto at = meaning.find(from); at != std::string::npos; at = meaning.find(from, at))
      meaning.replace(at, from.size(), to), at += to.size();
  };
  replace("angular velocity", "rotation");
  replace("velocity", "deflection");
  replace("[m/s]", "[m]");
  replace("[rad/s]", "[rad]");
  return meaning;
}

void DeckWriter::name_nodes() {
  for (const Node& n : network_.nodes()) {
    const std::string spice = nodes_.claim(n.name);
    node_names_.push_back(spice);
    node_comments_.push_back(spice + ": " + node_meaning(n));
  }
}

std::vector<Group> DeckWriter::groups() const {
  std::vector<Group> list;
  auto group_for = [&](const std::string& key) -> Group& {
    for (Group& g : list)
      if (g.key == key) return g;
    list.push_back({key, {}, {}});
    return list.back();
  };
  const double l = model_.beam.segment_length;
  const double ei = scene_.beam.bending_stiffness;
  const double tau = scene_.damping.effective_kelvin_voigt_time();
  const auto& elements = network_.elements();
  for (size_t e = 0; e < elements.size(); ++e) {
    const ElementRecord* record = model_.structure.element(e);
    std::string key = "other";
    std::vector<std::string> title;
    if (record && record->component == Component::beam_segment) {
      const size_t k = static_cast<size_t>(record->index);
      const std::string id = std::to_string(record->index);
      key = "segment " + id;
      if (k + 1 < model_.beam.x.size())
        title = {"segment " + id + ": x = " + millimetres(model_.beam.x[k]) + " .. " +
                     millimetres(model_.beam.x[k + 1]) + ", l = " + number(l) +
                     " m, EI = " + number(ei) + " N*m^2",
                 "  nR: rotational compliance n_R = l/EI [rad/(N*m)] between the rotation "
                 "nodes; nT: translational compliance n_T = l^3/(12*EI) [m/N]",
                 "  lever: ideal transformer, v_right - m = (l/2)*(Omega_left + Omega_right); "
                 "its force F returns as torques (l/2)*F into both rotation nodes"};
      if (tau > 0.0 && k + 1 < model_.beam.x.size())
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
        if (scene_.drive.electrical_dynamics)
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
    if (group.title.empty()) group.title = title;
    group.elements.push_back(elements[e].get());
  }
  for (Group& g : list)
    if (g.title.empty()) g.title = {g.key == "other" ? "other elements" : g.key};
  return list;
}

std::string DeckWriter::pwl(const std::vector<std::pair<double, double>>& points,
                            const std::string& what) {
  std::string text = "PWL(";
  for (size_t k = 0; k < points.size(); ++k) {
    if (k > 0) text += (k % 4 == 0) ? "\n+ " : " ";
    text += value(points[k].first, what) + " " + value(points[k].second, what);
  }
  return text + ")";
}

std::string DeckWriter::time_function(const Waveform& w, const std::string& what) {
  switch (w.shape) {
    case Waveform::Shape::dc:
      return "DC " + value(w.dc, what);
    case Waveform::Shape::sine:
      if (w.frequency == 0.0 || w.amplitude == 0.0)
        return "DC " + value(w.dc + w.amplitude * std::sin(w.phase), what);
      return "SIN(" + value(w.dc, what) + " " + value(w.amplitude, what) + " " +
             value(w.frequency, what) + " " + value(w.delay, what) + " 0 " +
             value(w.phase * 180.0 / pi, what) + ")";
    case Waveform::Shape::pwl:
      if (w.points.empty()) return "DC " + value(w.dc, what);
      return pwl(w.points, what);
    case Waveform::Shape::pulse:
      break;
  }
  const double low = w.dc, high = w.pulse_high, delay = w.delay, width = w.width, period = w.period;
  if (low == high) return "DC " + value(low, what);
  if (w.rise > 0.0 && w.fall > 0.0) {
    if (period > 0.0)
      return "PULSE(" + value(low, what) + " " + value(high, what) + " " + value(delay, what) +
             " " + value(w.rise, what) + " " + value(w.fall, what) + " " + value(width, what) +
             " " + value(period, what) + ")";
    return pwl({{0.0, w.value(0.0)},
                {delay, low},
                {delay + w.rise, high},
                {delay + w.rise + width, high},
                {delay + w.rise + width + w.fall, low}},
               what);
  }
  if (w.rise != 0.0 || w.fall != 0.0)
    throw InputError(where(), what,
                     "a pulse with one zero and one non-zero edge time is not written to SPICE "
                     "decks (SPICE reads a zero edge as the output step); give both edges a "
                     "time");
  // Instant switching: centred linear edges of width ε.
  const double on_time = std::min(width, period > 0.0 ? period : width);
  const double off_time = period > 0.0 ? period - width : on_time;
  if (width <= 0.0) return "DC " + value(low, what);
  if (period > 0.0 && width >= period) {
    if (delay <= 0.0) return "DC " + value(high, what);
    const double edge = options_.edge_fraction * delay;
    edge_notes_.push_back(what + ": step at " + number(delay) + " s as an edge of " + number(edge) +
                          " s centred on it");
    return pwl({{0.0, low}, {delay - edge / 2, low}, {delay + edge / 2, high}}, what);
  }
  double edge = options_.edge_fraction * std::min(on_time, off_time);
  if (delay > 0.0) edge = std::min(edge, delay);
  edge_notes_.push_back(what + ": instant switching as linear edges of " + number(edge) +
                        " s centred on emnet's switching instants");
  if (period <= 0.0) {
    if (delay <= 0.0)
      return pwl({{0.0, high}, {width - edge / 2, high}, {width + edge / 2, low}}, what);
    return pwl({{0.0, low},
                {delay - edge / 2, low},
                {delay + edge / 2, high},
                {delay + width - edge / 2, high},
                {delay + width + edge / 2, low}},
               what);
  }
  if (delay > 0.0)
    return "PULSE(" + value(low, what) + " " + value(high, what) + " " +
           value(delay - edge / 2, what) + " " + value(edge, what) + " " + value(edge, what) + " " +
           value(width - edge, what) + " " + value(period, what) + ")";
  // On at t = 0: the PULSE runs from the high level and its first edge falls at `width`.
  return "PULSE(" + value(high, what) + " " + value(low, what) + " " +
         value(width - edge / 2, what) + " " + value(edge, what) + " " + value(edge, what) + " " +
         value(period - width - edge, what) + " " + value(period, what) + ")";
}

std::string DeckWriter::source(const Waveform& w, const std::string& what) {
  if (tran_) return time_function(w, what);
  std::string text = "DC " + value(w.value(0.0), what);
  if (ac_ && w.ac_magnitude != 0.0) {
    double phase = w.ac_phase + (w.ac_magnitude < 0.0 ? pi : 0.0);
    phase = std::remainder(phase, 2.0 * pi) * 180.0 / pi;
    text += " AC " + value(std::abs(w.ac_magnitude), what) + " " + value(phase, what);
  }
  return text;
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

void DeckWriter::write_outputs() {
  std::ostringstream& out = body_;
  Eigen::VectorXd static_state;
  const bool static_start = tran_ && options_.start == StartState::static_;
  if (static_start && !options_.static_state)
    throw std::invalid_argument(
        "write_spice_deck: a tran deck from the static state needs options.static_state "
        "(solve_static of the model's network)");
  if (static_start && !options_.static_state->status.ok)
    throw InputError(
        where(), "--start",
        "static: the network has no static state (" + options_.static_state->status.message + ")");
  if (static_start && options_.static_state->state.size() != system_.size())
    throw std::invalid_argument("write_spice_deck: options.static_state is of another network");
  const int node_count = static_cast<int>(network_.nodes().size());
  out << "*\n";
  comment(out,
          "---- outputs: one node per probe, fed by G sources with emnet's weights "
          "(Probe::terms: cubic Hermite between nodes)");
  for (const Probe& probe : outputs_) {
    if (probe.integrations > 1)
      throw InputError(where(), "probe " + probe.name, "a double integral is not written");
    const std::string out_node = nodes_.claim("out_" + probe.name);
    std::string formula;
    int written = 0;
    std::ostringstream lines;
    for (const auto& [index, c] : probe.terms) {
      if (index < 0 || index >= node_count)
        throw InputError(where(), "probe " + probe.name,
                         "a probe of a branch quantity is not written to SPICE decks");
      if (op_) {
        const int power_of_s = (mechanical(index) ? 1 : 0) - probe.integrations;
        if (power_of_s != 0) continue;  // a velocity at rest: zero
      }
      if (c == 0.0) continue;
      ++written;
      lines << element_name('G', "out_" + probe.name + "_" + std::to_string(written)) << " 0 "
            << out_node << " " << node(index) << " 0 " << value(c, probe.name) << "\n";
      formula += (formula.empty() ? "" : " + ") + number(c) + "*V(" + node(index) + ")";
    }
    if (formula.empty()) formula = "0";
    const bool integrate = probe.integrations == 1 && !op_;
    const std::string meaning = probe.description + " [" + probe.unit +
                                "] = " + (integrate ? "integral of " + formula : formula);
    node_comments_.push_back(out_node + ": " + meaning);
    comment(out, "probe " + probe.name + ": " + meaning);
    out << lines.str();
    if (integrate) {
      out << element_name('C', "out_" + probe.name) << " " << out_node << " 0 1\n";
      out << element_name('R', "out_" + probe.name) << " " << out_node << " 0 "
          << number(integrator_leak_resistance) << "\n";
      if (static_start)
        initial_conditions_.emplace_back(
            out_node, static_probe_value(system_, *options_.static_state, probe));
    } else {
      out << element_name('R', "out_" + probe.name) << " " << out_node << " 0 1\n";
    }
    deck_.outputs.push_back({probe.name, lower(out_node), probe.unit, probe.description});
  }
}

void DeckWriter::write_header(std::ostringstream& out) const {
  const std::string label =
      options_.scene_label.empty() ? file_name(scene_.file) : options_.scene_label;
  comment(out, "emnet SPICE deck: scene " + scene_.name + " (" + label + "), " +
                   spice_analysis_name(options_.analysis) + " analysis");
  if (!scene_.title.empty()) comment(out, "title: " + scene_.title);
  for (const auto& o : options_.overrides) comment(out, "override: --set " + o);
  comment(out,
          "Plain SPICE3: runs unchanged with ngspice -b FILE.cir; only elements LTspice "
          "also reads (R L C V I E F G B, PULSE SIN PWL)");
  out << "*\n";
  comment(out,
          "Firestone (mobility) analogy: across quantity = node voltage, through quantity "
          "= current; all values SI");
  if (op_) {
    comment(out,
            "  THIS (op) DECK IS THE STATIC NETWORK: mechanical node voltages are "
            "displacements [m] and rotations [rad], currents forces [N] and torques [N*m]");
    comment(out,
            "  compliance n = resistor n [m/N as Ohm]; masses and dampers carry no force "
            "at rest and are left out; levers keep their ratios");
  } else {
    comment(out, "  translational: velocity [m/s] as V, force [N] as A");
    comment(out, "  rotational: angular velocity [rad/s] as V, torque [N*m] as A");
    comment(out,
            "  mass m [kg] = capacitor to ground; compliance n = 1/k [m/N, rad/(N*m)] = "
            "inductor; viscous damper r [N*s/m] = resistor 1/r");
  }
  comment(out, "  electrical: voltage [V], current [A]");
  comment(out,
          "  lever / ideal transformer = 0 V sense source + E sources (across) + F sources "
          "(through); clamp = node 0");
  out << "*\n";
  const BeamSpec& beam = scene_.beam;
  comment(out, "beam: " + std::to_string(beam.segments) + " segments, L = " + number(beam.length) +
                   " m, EI = " + number(beam.bending_stiffness) +
                   " N*m^2, rhoA = " + number(beam.mass_per_length) +
                   " kg/m, rhoI = " + number(beam.rotary_inertia_per_length) + " kg*m, left " +
                   end_condition_name(beam.left) + ", right " + end_condition_name(beam.right));
  const double tau = scene_.damping.effective_kelvin_voigt_time();
  comment(out, "damping: viscous " + number(scene_.damping.viscous_per_length) +
                   " N*s/m^2, Kelvin-Voigt tau = " + number(tau) + " s");
  const DriveSpec& drive = scene_.drive;
  std::string deas;
  for (const auto& d : drive.deas) deas += (deas.empty() ? "" : ", ") + d;
  if (drive.kind == DriveKind::none) {
    comment(out, "drive: none (the scene's loads only)");
  } else {
    // The keys the drive kind uses (the reader refuses the others).
    const bool square_wave =
        drive.kind == DriveKind::antagonistic || drive.kind == DriveKind::switched;
    const std::string levels = square_wave ? "voltage " + number(drive.voltage) + " V"
                                           : "bias " + number(drive.bias) + " V, amplitude " +
                                                 number(drive.amplitude) + " V";
    const std::string switching =
        square_wave ? ", duty " + number(drive.duty) +
                          (drive.overlap != 0.0 ? ", overlap " + number(drive.overlap) + " s"
                                                : std::string()) +
                          ", rise time " + number(drive.rise_time) + " s"
                    : std::string();
    comment(out, std::string("drive: ") + drive_kind_name(drive.kind) +
                     (deas.empty() ? std::string() : " on DEA " + deas) + ", " + levels +
                     ", frequency " + number(drive.frequency) + " Hz" + switching +
                     ", electrical dynamics " + (drive.electrical_dynamics ? "on" : "off"));
  }
  if (ac_) {
    switch (drive.kind) {
      case DriveKind::antagonistic:
        comment(out,
                "AC input (as emnet ac): the alternating part of each DEA's force, "
                "k_F*V^2/2, the two DEAs in antiphase; its square wave's fundamental is "
                "4/pi times this; applied as the force itself, not through the RC loops");
        break;
      case DriveKind::switched:
        comment(out,
                "AC input (as emnet ac): the alternating part of the DEA's 0/k_F*V^2 square-wave "
                "force, k_F*V^2/2; its square wave's fundamental is 4/pi times this; applied as "
                "the force itself, not through the RC loop");
        break;
      case DriveKind::bias_differential:
      case DriveKind::single:
        comment(out,
                "AC input (as emnet ac): the source amplitude v about the bias V0, the "
                "network linearised at V0 (ngspice linearises the B sources at its "
                "operating point)");
        break;
      case DriveKind::none:
        comment(out,
                "AC input (as emnet ac): the scene's loads, each with its value as "
                "amplitude");
        break;
    }
  }
  if (op_)
    comment(out, "sources at their value at t = 0 (emnet static: the first half-period's drive)");
  out << "*\n";
  comment(out, "nodes (" + std::to_string(node_comments_.size()) + "):");
  for (const auto& line : node_comments_) comment(out, line);
  if (!deck_.notes.empty()) {
    out << "*\n";
    comment(out, "notes:");
    for (const auto& note : deck_.notes) comment(out, note);
  }
}

void DeckWriter::write_analysis(std::ostringstream& out) {
  out << "*\n";
  comment(out, "---- analysis");
  std::vector<std::string> vectors;
  for (const auto& o : deck_.outputs) vectors.push_back(o.vector);
  switch (options_.analysis) {
    case SpiceAnalysis::op:
      out << ".options reltol=1e-9 vntol=1e-15 abstol=1e-18\n";
      out << ".op\n";
      break;
    case SpiceAnalysis::ac: {
      const AcSpec spec = options_.ac.value_or(scene_.ac);
      if (spec.log && spec.points > 1) {  // one frequency: `.ac lin 1 f f`, no decades
        const double decades = std::log10(spec.to / spec.from);
        const int per_decade =
            std::max(1, static_cast<int>(std::lround((spec.points - 1) / decades)));
        comment(out, "emnet's log grid: " + std::to_string(spec.points) +
                         " points; SPICE's .ac dec takes points per decade: " +
                         std::to_string(per_decade) + " (the frequency vector gives each one)");
        out << ".ac dec " << per_decade << " " << number(spec.from) << " " << number(spec.to)
            << "\n";
      } else {
        out << ".ac lin " << spec.points << " " << number(spec.from) << " " << number(spec.to)
            << "\n";
      }
      break;
    }
    case SpiceAnalysis::tran: {
      const double max_step = options_.max_step > 0.0 ? options_.max_step : options_.output_step;
      comment(out, "reltol sets the accuracy; vntol and abstol far below the deck's values");
      out << ".options reltol=" << number(options_.relative_tolerance)
          << " vntol=1e-12 abstol=1e-15\n";
      if (options_.start == StartState::rest) {
        comment(out,
                "start at rest (as emnet tran --start rest): uic, every capacitor "
                "voltage and inductor current zero at t = 0");
        out << ".tran " << number(options_.output_step) << " " << number(options_.end_time) << " 0 "
            << number(max_step) << " uic\n";
      } else {
        comment(out,
                "start from the static state (as emnet tran --start static): ngspice's "
                "operating point under the sources at t = 0, the integrator outputs held "
                "at emnet's static values by .ic while it is computed");
        out << ".tran " << number(options_.output_step) << " " << number(options_.end_time) << " 0 "
            << number(max_step) << "\n";
        for (const auto& [n, v] : initial_conditions_)
          out << ".ic V(" << n << ")=" << number(v) << "\n";
      }
      break;
    }
  }
  if (options_.control) {
    std::string file = options_.control_output.empty()
                           ? scene_.name + "-" + spice_analysis_name(options_.analysis) + ".data"
                           : options_.control_output;
    // The file name is a name of [A-Za-z0-9_.-] only: nothing else reaches the control block.
    for (char& c : file)
      if (!is_name_character(c) && c != '.' && c != '-') c = '_';
    out << "*\n";
    comment(out, "ngspice only (written on request): run, then write the outputs to " + file);
    out << ".control\nrun\nset wr_singlescale\nset wr_vecnames\noption numdgt=15\nwrdata " << file;
    for (const auto& v : vectors) out << " " << v;
    out << "\n.endc\n";
  }
  out << ".end\n";
}

SpiceDeck DeckWriter::write() {
  check_names();
  if (tran_ && !(options_.end_time > 0.0 && std::isfinite(options_.end_time)))
    throw InputError("tran", "end time", "must be a positive time");
  if (tran_ && !(options_.output_step > 0.0 && options_.output_step <= options_.end_time))
    throw InputError("tran", "output step", "must be positive and at most the end time");
  if (tran_ && !(options_.relative_tolerance > 0.0 && options_.relative_tolerance < 1.0))
    throw InputError("tran", "reltol", "must be between 0 and 1");
  if (tran_ && !(options_.max_step >= 0.0 && std::isfinite(options_.max_step)))
    throw InputError("tran", "max step", "must be >= 0");
  if (tran_ && !(options_.edge_fraction > 0.0 && options_.edge_fraction < 0.5))
    throw InputError("tran", "edge fraction", "must be between 0 and 0.5");
  if (ac_) {
    const AcSpec spec = options_.ac.value_or(scene_.ac);
    const bool one_frequency = spec.points == 1 && spec.to == spec.from;
    if (!(spec.from >= 0.0) || !(one_frequency || (spec.to > spec.from && spec.points >= 2)) ||
        (spec.log && !(spec.from > 0.0)))
      throw InputError("ac", "sweep",
                       "needs 0 <= from < to and points >= 2, or points = 1 and from = to; "
                       "from > 0 when log");
  }
  deck_.analysis = options_.analysis;
  deck_.unknowns.assign(system_.unknowns.size(), {});
  outputs_ = options_.outputs.empty() ? spice_output_probes(model_) : options_.outputs;
  name_nodes();
  for (size_t k = 0; k < node_names_.size(); ++k) deck_.unknowns[k] = {lower(node_names_[k]), 1.0};

  for (const Group& group : groups()) {
    body_ << "*\n";
    for (size_t k = 0; k < group.title.size(); ++k)
      comment(body_, (k == 0 ? "---- " : "") + group.title[k]);
    left_out_.clear();
    for (const Element* element : group.elements) write_element(*element);
    if (!left_out_.empty()) {
      std::string names;
      for (const auto& n : left_out_) names += (names.empty() ? "" : " ") + n;
      comment(body_,
              "left out of the static network (masses, dampers: no force at rest): " + names);
    }
  }
  write_outputs();

  // What the model builder chose for the scene's "auto" keys ([model] band and tolerance).
  for (const auto& choice : model_.automatic_choices) {
    std::string note = choice.reason;  // plain comment text: '"auto"' as 'auto'
    note.erase(std::remove(note.begin(), note.end(), '"'), note.end());
    deck_.notes.push_back(note);
  }
  if (op_) {
    deck_.notes.push_back(
        "op: mechanical node voltages are displacements and rotations (emnet's static state "
        "z); compliances are resistors, so their forces have no branch vector here");
  }
  if (ac_)
    deck_.notes.push_back(
        "ac: an integral output (deflection) is 0 at f = 0 where emnet gives the static limit; "
        "compare from the first frequency above 0");
  if (tran_ || ac_)
    deck_.notes.push_back("integral outputs: 1 F with a 1e9 Ohm leak (time constant 1e9 s)");
  for (const auto& note : edge_notes_)
    if (std::find(deck_.notes.begin(), deck_.notes.end(), note) == deck_.notes.end())
      deck_.notes.push_back(note);
  if (!edge_notes_.empty())
    deck_.notes.push_back(
        "a linear edge centred on a switching instant differs from the instant switch by a "
        "zero-mean pulse: its effect is of second order in the edge width");

  std::ostringstream out;
  write_header(out);
  out << body_.str();
  write_analysis(out);
  deck_.text = out.str();
  return deck_;
}

}  // namespace

const char* spice_analysis_name(SpiceAnalysis analysis) {
  switch (analysis) {
    case SpiceAnalysis::op:
      return "op";
    case SpiceAnalysis::ac:
      return "ac";
    case SpiceAnalysis::tran:
      return "tran";
  }
  return "?";
}

std::string spice_comment_text(const std::string& text) {
  static const std::string allowed_punctuation = "_-+.,:;=()[]/*%@<>'!?^~|&";
  std::string safe;
  safe.reserve(text.size());
  for (char c : text) {
    const bool keep = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                      c == ' ' || allowed_punctuation.find(c) != std::string::npos;
    safe += keep ? c : '?';
  }
  return safe;
}

std::string spice_identifier(const std::string& text) {
  if (text.empty()) return "_";
  std::string safe = text;
  for (char& c : safe)
    if (!is_name_character(c)) c = '_';
  return safe;
}

std::vector<Probe> spice_output_probes(const Model& model) {
  return probes_of(deck_output_list(model));
}

SpiceDeck write_spice_deck(const Model& model, const SpiceDeckOptions& options) {
  DeckWriter writer(model, options);
  return writer.write();
}

}  // namespace emnet
