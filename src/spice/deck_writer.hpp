// The SPICE deck writer's inner parts, shared by its sources: spice_netlist.cpp (the deck, its
// header, outputs and analysis), deck_groups.cpp (the groups of elements and their titles, by
// the component each element realises), deck/<element>.cpp (each element kind's lines, found
// through the table of deck/element_writers.cpp) and deck_sources.cpp (the sources' time
// functions). The mapping itself is described in include/emnet/spice/spice_netlist.hpp.
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "emnet/core/errors.hpp"
#include "emnet/spice/spice_netlist.hpp"

namespace emnet::spice_deck {

inline constexpr double pi = 3.14159265358979323846;
// Leak resistor of an integrator output (1 F): time constant 1e9 s, see the header comment.
inline constexpr double integrator_leak_resistance = 1e9;

inline std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

inline bool is_name_character(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

inline bool is_identifier(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), is_name_character);
}

// 12 significant digits: far below the 1e-6 at which decks are compared with emnet, and short.
inline std::string number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.12g", value);
  return buffer;
}

// Positions and lengths in comments, in millimetres.
inline std::string millimetres(double metres) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g mm", metres * 1e3);
  return buffer;
}

inline std::string file_name(const std::string& path) {
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

// A group's title as one element's component gives it (deck_groups.cpp): the group's key, its
// title lines, and a line of its own for each element (the circuit's entries), if any.
struct GroupTitle {
  std::string key = "other";
  std::vector<std::string> lines;
  std::string element_line;
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
        displacements_(op_ || (ac_ && model.beam.kinematics == BeamKinematics::large)),
        system_(model.network.assemble()) {}

  SpiceDeck write();

  // ---- What an element's writer (deck/<element>.cpp) uses to write its lines.
  bool op() const { return op_; }
  bool ac() const { return ac_; }
  // Whether mechanical node voltages are displacements and rotations: the op deck, and the ac
  // deck of a large-kinematics beam (ngspice then linearises it about the deflected static state,
  // its own operating point, as emnet's ac does); velocities otherwise.
  bool displacements() const { return displacements_; }
  // A node whose voltage is d/dt V(spice_node): a copy of the node (an E source) charges 1 F
  // through a 0 V sense source, whose current an H source makes the node's voltage. 0 at rest,
  // jω·V in ac; written once per node ("0" for ground).
  std::string rate_of(const std::string& spice_node);
  // rate_of the network node `id`.
  std::string rate(NodeId id) { return id == ground ? std::string("0") : rate_of(node(id)); }
  const Network& network() const { return network_; }
  std::string where() const { return scene_.file.empty() ? std::string("scene") : scene_.file; }
  bool mechanical(NodeId node) const {
    return node != ground && is_mechanical(network_.node(node).domain);
  }
  // Whether a port between `a` and `b` is mechanical (either node is).
  bool mechanical(NodeId a, NodeId b) const { return mechanical(a) || mechanical(b); }
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
  // The deck's element lines, in order.
  std::ostringstream& body() { return body_; }
  // A comment line (wrapped) among the element lines.
  void comment(const std::string& text) { comment(body_, text); }
  std::string element_name(char letter, const std::string& name) {
    return elements_.claim(std::string(1, letter) + "_" + name);
  }
  std::string internal_node(const std::string& name, const std::string& meaning) {
    const std::string spice = nodes_.claim(name);
    node_comments_.push_back(spice + ": " + meaning);
    return spice;
  }
  // Where ngspice holds the k-th branch unknown of element `element`: the branch vector of
  // `spice_element` (none if empty), times `sign`.
  void branch(const std::string& element, int k, const std::string& spice_element, double sign) {
    const int index = system_.branch_index(element, k);
    deck_.unknowns.at(static_cast<size_t>(index)) = {
        spice_element.empty() ? "" : lower(spice_element) + "#branch", sign};
  }
  // Where ngspice holds the k-th branch unknown of element `element`: the voltage of the deck's
  // node `spice_node`, times `sign`.
  void branch_node(const std::string& element, int k, const std::string& spice_node, double sign) {
    const int index = system_.branch_index(element, k);
    deck_.unknowns.at(static_cast<size_t>(index)) = {lower(spice_node), sign};
  }
  // An integrator node of a tran deck: V(node) = ∫ rate dt, a B source of current `rate` into
  // 1 F with the outputs' 1e9 Ω leak; from the static state, held at `static_value` by .ic.
  void integrator(const std::string& spice_node, const std::string& rate, double static_value) {
    body_ << element_name('B', spice_node) << " 0 " << spice_node << " I = " << rate << "\n";
    integrating_capacitor(body_, spice_node, spice_node, static_value);
  }
  // The static operating point's value of the k-th branch unknown of `element` (y at rest:
  // what a tran deck from the static state starts from); 0 without a static state.
  double static_branch_value(const std::string& element, int k) const {
    if (!options_.static_state || !options_.static_state->status.ok()) return 0.0;
    return options_.static_state->operating_point[system_.branch_index(element, k)];
  }
  // The scene's file or name, for errors naming a key.
  const Scene& scene() const { return scene_; }
  // An element (or part) the op deck leaves out of the current group: no force at rest.
  void leave_out(const std::string& name) { left_out_.push_back(name); }
  // A source's SPICE value: its time function (tran), or its value at t = 0 and AC phasor.
  std::string source(const Waveform& waveform, const std::string& what);

 private:
  // A section's heading comment: the title after a rule of four dashes.
  void section_comment(std::ostringstream& out, const std::string& title) const {
    comment(out, std::string(4, '-') + ' ' + title);
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

  // The 1 F ‖ 1e9 Ω that makes `node` the integral of the current fed into it (element names from
  // `basis`); from the static state, held at `static_value` by .ic.
  void integrating_capacitor(std::ostringstream& out, const std::string& basis,
                             const std::string& node, double static_value) {
    out << element_name('C', basis) << " " << node << " 0 1\n";
    out << element_name('R', basis) << " " << node << " 0 " << number(integrator_leak_resistance)
        << "\n";
    if (tran_ && options_.start == StartState::static_)
      initial_conditions_.emplace_back(node, static_value);
  }

  void check_names() const;
  void check_options() const;
  void name_nodes();
  std::vector<Group> groups() const;
  GroupTitle group_title(const ElementRecord* record) const;
  void write_groups();
  void write_element(const Element& element);
  void add_notes();
  void write_header(std::ostringstream& out) const;
  void write_conventions(std::ostringstream& out) const;
  void write_beam(std::ostringstream& out) const;
  void write_drive(std::ostringstream& out) const;
  void write_ac_input(std::ostringstream& out) const;
  void write_outputs();
  void write_analysis(std::ostringstream& out);
  std::string time_function(const Waveform& waveform, const std::string& what);
  std::string pwl(const std::vector<std::pair<double, double>>& points, const std::string& what);
  std::string node_meaning(const Node& node) const;

  const Model& model_;
  const Network& network_;
  const Scene& scene_;
  const SpiceDeckOptions& options_;
  const bool op_, ac_, tran_, displacements_;
  const System system_;
  std::vector<Probe> outputs_;
  NameTable nodes_, elements_;
  std::vector<std::string> node_names_;
  std::vector<std::string> node_comments_;
  std::vector<std::string> output_comments_;
  std::ostringstream body_;
  std::vector<std::pair<std::string, double>> initial_conditions_;  // tran, static start
  std::vector<std::string> edge_notes_;
  std::vector<std::string> left_out_;         // op: masses and dampers of the current group
  std::map<std::string, std::string> rates_;  // rate_of's nodes, by the node they differentiate
  SpiceDeck deck_;
};

}  // namespace emnet::spice_deck
