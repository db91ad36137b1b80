// SPICE deck writer: see include/emnet/spice/spice_netlist.hpp for the mapping of every element
// kind, the sign conventions, the op deck's static network and the safety rules. This file
// writes the deck's header, outputs and analysis; the element lines are deck/<element>.cpp's
// (grouped by the model's record of its elements in deck_groups.cpp), the sources' time
// functions deck_sources.cpp's; the outputs come from the model's output list
// (emnet/model/outputs.hpp).
#include "emnet/spice/spice_netlist.hpp"

#include "deck_writer.hpp"
#include "emnet/analysis/analysis.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/model/outputs.hpp"

namespace emnet {

namespace spice_deck {

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
  if (!displacements_ || !is_mechanical(node.domain)) return meaning;
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

void DeckWriter::write_outputs() {
  std::ostringstream& out = body_;
  Eigen::VectorXd static_state;
  const bool static_start = tran_ && options_.start == StartState::static_;
  if (static_start && !options_.static_state)
    throw std::invalid_argument(
        "write_spice_deck: a tran deck from the static state needs options.static_state "
        "(solve_static of the model's network)");
  if (static_start && !options_.static_state->status.ok())
    throw OptionError::in_file(
        "start", where(), "",
        "static: the network has no static state (" + options_.static_state->status.message + ")");
  if (static_start && options_.static_state->state.size() != system_.size())
    throw std::invalid_argument("write_spice_deck: options.static_state is of another network");
  const int node_count = static_cast<int>(network_.nodes().size());
  out << "*\n";
  section_comment(out,
                  "outputs: one node per probe, fed by G sources with emnet's weights "
                  "(Probe::terms: cubic Hermite between nodes)");
  for (const std::string& note : deck_left_out_notes(model_)) comment(out, note);
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
      // In displacement form a term is the node's voltage times s^power: a velocity is the rate
      // of a displacement (at rest zero), an integral of an electrical voltage is not written.
      const int power_of_s = displacements_ ? (mechanical(index) ? 1 : 0) - probe.integrations : 0;
      if (c == 0.0 || (op_ && power_of_s != 0)) continue;
      if (power_of_s < 0)
        throw InputError(where(), "probe " + probe.name,
                         "an integral of an electrical quantity is not written to this deck");
      const std::string term = power_of_s == 1 ? rate_of(node(index)) : node(index);
      ++written;
      lines << element_name('G', "out_" + probe.name + "_" + std::to_string(written)) << " 0 "
            << out_node << " " << term << " 0 " << value(c, probe.name) << "\n";
      formula += (formula.empty() ? "" : " + ") + number(c) + "*V(" + term + ")";
    }
    if (formula.empty()) formula = "0";
    const bool integrate = probe.integrations == 1 && !displacements_;
    const std::string meaning = probe.description + " [" + probe.unit +
                                "] = " + (integrate ? "integral of " + formula : formula);
    node_comments_.push_back(out_node + ": " + meaning);
    comment(out, "probe " + probe.name + ": " + meaning);
    out << lines.str();
    if (integrate) {
      integrating_capacitor(
          out, "out_" + probe.name, out_node,
          static_start ? static_probe_value(system_, *options_.static_state, probe) : 0.0);
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
  for (const auto& o : options_.overrides) comment(out, "override: " + o);
  comment(out,
          "Plain SPICE3: runs unchanged with ngspice -b FILE.cir; only elements LTspice "
          "also reads (R L C V I E F G B, PULSE SIN PWL)");
  out << "*\n";
  write_conventions(out);
  out << "*\n";
  write_beam(out);
  write_drive(out);
  if (ac_) write_ac_input(out);
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

// The analogy: what a node voltage and a current are in each domain, and each element kind.
void DeckWriter::write_conventions(std::ostringstream& out) const {
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
  } else if (displacements_) {
    comment(out,
            "  THIS ac DECK IS IN DISPLACEMENTS (large kinematics): mechanical node voltages are "
            "displacements [m] and rotations [rad], currents forces [N] and torques [N*m]; "
            "ngspice linearises it about its operating point, the deflected static state");
    comment(out,
            "  compliance n = resistor n; viscous damper r = capacitor r; mass m = the current "
            "m*d2V/dt2 (an F source of a capacitor m on the node's rate); a velocity is a rate "
            "node d/dt V (E copy, 1 F, 0 V sense, H source)");
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
}

// The beam: its segments and sections, and its damping.
void DeckWriter::write_beam(std::ostringstream& out) const {
  const BeamSpec& beam = scene_.beam;
  if (beam.sections.empty()) {
    comment(out, "beam: " + std::to_string(beam.segments) + " segments, L = " +
                     number(beam.length) + " m, EI = " + number(beam.bending_stiffness) +
                     " N*m^2, rhoA = " + number(beam.mass_per_length) +
                     " kg/m, rhoI = " + number(beam.rotary_inertia_per_length) + " kg*m, left " +
                     end_condition_name(beam.left) + ", right " + end_condition_name(beam.right) +
                     (beam.theory == BeamTheory::timoshenko ? ", timoshenko" : ""));
  } else {
    comment(out, "beam: " + std::to_string(model_.beam.x.size() - 1) + " segments, L = " +
                     number(beam.length) + " m in " + std::to_string(beam.sections.size()) +
                     " sections, left " + end_condition_name(beam.left) + ", right " +
                     end_condition_name(beam.right) + ", " + beam_theory_name(beam.theory));
    for (size_t s = 0; s < beam.sections.size(); ++s) {
      const SectionSpec& section = beam.sections[s];
      comment(out, "  section " + std::to_string(s) + ": l = " + number(section.length) +
                       " m, EI = " + number(section.bending_stiffness) +
                       " N*m^2, rhoA = " + number(section.mass_per_length) +
                       " kg/m, rhoI = " + number(section.rotary_inertia_per_length) + " kg*m");
    }
  }
  const double tau = scene_.damping.effective_kelvin_voigt_time();
  comment(out, "damping: viscous " + number(scene_.damping.viscous_per_length) +
                   " N*s/m^2, Kelvin-Voigt tau = " + number(tau) + " s");
}

// The drive: its kind, DEAs, levels and switching, with the keys its kind uses.
void DeckWriter::write_drive(std::ostringstream& out) const {
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
}

// What the ac deck's input is, as emnet ac takes it for the drive kind.
void DeckWriter::write_ac_input(std::ostringstream& out) const {
  switch (scene_.drive.kind) {
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

void DeckWriter::write_analysis(std::ostringstream& out) {
  out << "*\n";
  section_comment(out, "analysis");
  std::vector<std::string> vectors;
  for (const auto& o : deck_.outputs) vectors.push_back(o.vector);
  switch (options_.analysis) {
    case SpiceAnalysis::op:
      out << ".options reltol=1e-9 vntol=1e-15 abstol=1e-18\n";
      out << ".op\n";
      break;
    case SpiceAnalysis::ac: {
      if (displacements_) {  // the operating point is the deflected state: solved as the op deck
        comment(out, "the operating point (the deflected state) as tightly as the op deck's");
        out << ".options reltol=1e-9 vntol=1e-15 abstol=1e-18\n";
      }
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
                "start at rest (as emnet's transient from rest): uic, every capacitor "
                "voltage and inductor current zero at t = 0");
        out << ".tran " << number(options_.output_step) << " " << number(options_.end_time) << " 0 "
            << number(max_step) << " uic\n";
      } else {
        comment(out,
                "start from the static state (as emnet's transient from it): ngspice's "
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

void DeckWriter::check_options() const {
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
}

// Each group under its title, then its elements' lines (and, in the op deck, what it left out).
void DeckWriter::write_groups() {
  for (const Group& group : groups()) {
    body_ << "*\n";
    for (size_t k = 0; k < group.title.size(); ++k) {
      if (k == 0)
        section_comment(body_, group.title[k]);
      else
        comment(body_, group.title[k]);
    }
    left_out_.clear();
    for (const Element* element : group.elements) write_element(*element);
    if (!left_out_.empty()) {
      std::string names;
      for (const auto& n : left_out_) names += (names.empty() ? "" : " ") + n;
      comment(body_,
              "left out of the static network (masses, dampers: no force at rest): " + names);
    }
  }
}

// The notes of the header: the resolve step's choices, what the analysis changes, the edges.
void DeckWriter::add_notes() {
  // What the resolve step chose for the scene's "auto" keys ([model] band and tolerance).
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
  if (ac_ && displacements_)
    deck_.notes.push_back(
        "ac: about the deflected static state (displacement nodes, B sources linearised by "
        "ngspice at its operating point); mechanical unknowns are compared as their rate nodes");
  if (ac_ && !displacements_)
    deck_.notes.push_back(
        "ac: an integral output (deflection) is 0 at f = 0 where emnet gives the static limit; "
        "compare from the first frequency above 0");
  if (tran_ || (ac_ && !displacements_))
    deck_.notes.push_back("integral outputs: 1 F with a 1e9 Ohm leak (time constant 1e9 s)");
  for (const auto& note : edge_notes_)
    if (std::find(deck_.notes.begin(), deck_.notes.end(), note) == deck_.notes.end())
      deck_.notes.push_back(note);
  if (!edge_notes_.empty())
    deck_.notes.push_back(
        "a linear edge centred on a switching instant differs from the instant switch by a "
        "zero-mean pulse: its effect is of second order in the edge width");
}

std::string DeckWriter::rate_of(const std::string& spice_node) {
  if (spice_node == "0") return spice_node;
  if (const auto found = rates_.find(spice_node); found != rates_.end()) return found->second;
  const std::string rate = internal_node(spice_node + "_rate", "d/dt V(" + spice_node + ")");
  const std::string copy = internal_node(spice_node + "_copy", "V(" + spice_node + ") again");
  const std::string sense = internal_node(spice_node + "_sense", "0 V: the rate's sense source");
  const std::string source = element_name('V', spice_node + "_rate");
  body_ << element_name('E', spice_node + "_copy") << " " << copy << " 0 " << spice_node
        << " 0 1\n";
  body_ << element_name('C', spice_node + "_rate") << " " << copy << " " << sense << " 1\n";
  body_ << source << " " << sense << " 0 DC 0\n";
  body_ << element_name('H', spice_node + "_rate") << " " << rate << " 0 " << source << " 1\n";
  rates_.emplace(spice_node, rate);
  return rate;
}

SpiceDeck DeckWriter::write() {
  check_names();
  check_options();
  deck_.analysis = options_.analysis;
  deck_.displacement_nodes = displacements_;
  deck_.unknowns.assign(system_.unknowns.size(), {});
  outputs_ = options_.outputs.empty() ? spice_output_probes(model_) : options_.outputs;
  name_nodes();
  for (size_t k = 0; k < node_names_.size(); ++k) deck_.unknowns[k] = {lower(node_names_[k]), 1.0};
  write_groups();
  write_outputs();
  if (displacements_ && !op_)  // emnet's mechanical unknowns are velocities: the nodes' rates
    for (size_t k = 0; k < node_names_.size(); ++k)
      if (is_mechanical(network_.nodes()[k].domain))
        deck_.unknowns[k] = {lower(rate_of(node_names_[k])), 1.0};
  add_notes();
  std::ostringstream out;
  write_header(out);
  out << body_.str();
  write_analysis(out);
  deck_.text = out.str();
  return deck_;
}

}  // namespace spice_deck

using spice_deck::is_name_character;

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
  spice_deck::DeckWriter writer(model, options);
  return writer.write();
}

}  // namespace emnet
