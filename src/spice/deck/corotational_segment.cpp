// SPICE lines of a CoRotationalSegment (beam.kinematics = "large"): its unknowns as nodes, its
// geometry and forces as B sources (behavioural sources: the modulated transformer of the
// chord's rotation), with the equations of corotational_segment.hpp:
//   dx, dy  the chord's change [m]: op deck V(b) − V(a) of the displacement nodes; tran deck
//           integrators of v_b − v_a (1 F, 1e9 Ω leak, as the integral outputs)
//   th      the chord's angle [rad], by its constraint sin θ·(l + dx) − cos θ·dy = 0: a B source
//           drawing that current from the node (its conductance ∂/∂θ is the chord's length ℓ > 0)
//   ext     the chord's extension ℓ − l = cos θ·(l + dx) + sin θ·dy − l [m] (a node that is 0 at
//           rest, where SPICE's first iterate starts: l/ℓ is written l/(l + V(ext)))
//   F       the transverse compliance's force [N]: op deck ((l/2)·(ψ_a + ψ_b) − l·θ)/n_T; tran deck
//           the integrator of F' = ((l/2)·(Ω_a + Ω_b) − (l/ℓ)·e₂·(v_b − v_a))/n_T
//   N       the axial force (ℓ − l)/n_A [N]
//   Q, P    with Kelvin–Voigt damping τ (tran deck): Q = F + τ·F', P = N + (τ/n_A)·e₁·(v_b − v_a)
// and the forces each node gives the segment, B sources from the node to ground:
//   (x, y)_a: +Q·(l/ℓ)·e₂ − P·e₁,   (x, y)_b: the opposite,   Ω_a, Ω_b: (l/2)·Q,
// a held end's force (f_x, f_y) left out (see write_node_forces),
// e₁ = (cos θ, sin θ), e₂ = (−sin θ, cos θ). Node voltages are velocities in the tran deck and
// displacements in the op deck (rates are zero at rest there). The ac deck is refused: ngspice
// linearises about its own operating point of the velocity deck, at which the integrators cannot
// hold the deflected state (emnet's ac linearises about it), and an inextensible segment
// (n_A = 0, N a multiplier) has no B-source form here.
#include "emnet/elements/corotational_segment.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

namespace {

// The segment's own node names, claimed once.
struct SegmentNodes {
  std::string dx, dy, angle, extension, force, tension, total_force, total_tension;
};

SegmentNodes claim_nodes(const CoRotationalSegment& s, DeckWriter& deck) {
  const std::string& name = s.name();
  SegmentNodes n;
  n.dx = deck.internal_node(name + "_dx", name + ": the chord's change along x, d_x [m]");
  n.dy = deck.internal_node(name + "_dy", name + ": the chord's change along y, d_y [m]");
  n.angle = deck.internal_node(name + "_th", name + ": the chord's angle theta [rad]");
  n.extension = deck.internal_node(name + "_ext", name + ": the chord's extension [m]");
  n.force = deck.internal_node(name + "_F", name + ": the transverse compliance's force F [N]");
  n.tension = deck.internal_node(name + "_N", name + ": the axial force N [N], tension positive");
  n.total_force = n.force;
  n.total_tension = n.tension;
  return n;
}

// The rates in the tran deck: e₂·(v_b − v_a) and e₁·(v_b − v_a).
struct ChordRates {
  std::string across, along;
};

ChordRates chord_rates(const CoRotationalSegment& s, const SegmentNodes& n, DeckWriter& deck) {
  const std::string vx = deck.voltage(s.end_b().x, s.end_a().x);
  const std::string vy = deck.voltage(s.end_b().y, s.end_a().y);
  const std::string c = "cos(V(" + n.angle + "))", si = "sin(V(" + n.angle + "))";
  return {"(-" + si + "*" + vx + "+" + c + "*" + vy + ")",
          "(" + c + "*" + vx + "+" + si + "*" + vy + ")"};
}

void write_chord(const CoRotationalSegment& s, const SegmentNodes& n, DeckWriter& deck) {
  const std::string& name = s.name();
  const std::string l = deck.value(s.length(), name);
  std::ostringstream& out = deck.body();
  const std::string vx = deck.voltage(s.end_b().x, s.end_a().x);
  const std::string vy = deck.voltage(s.end_b().y, s.end_a().y);
  if (deck.op()) {
    out << deck.element_name('B', n.dx) << " " << n.dx << " 0 V = " << vx << "\n";
    out << deck.element_name('B', n.dy) << " " << n.dy << " 0 V = " << vy << "\n";
  } else {
    deck.integrator(n.dx, vx, deck.static_branch_value(name, CoRotationalSegment::chord_x));
    deck.integrator(n.dy, vy, deck.static_branch_value(name, CoRotationalSegment::chord_y));
  }
  const std::string c = "cos(V(" + n.angle + "))", si = "sin(V(" + n.angle + "))";
  const std::string dx = "V(" + n.dx + ")", dy = "V(" + n.dy + ")";
  out << deck.element_name('B', n.angle) << " " << n.angle << " 0 I = " << si << "*(" << l << "+"
      << dx << ")-" << c << "*" << dy << "\n";
  out << deck.element_name('B', n.extension) << " " << n.extension << " 0 V = " << c << "*(" << l
      << "+" << dx << ")+" << si << "*" << dy << "-" << l << "\n";
  deck.branch_node(name, CoRotationalSegment::chord_x, n.dx, 1.0);
  deck.branch_node(name, CoRotationalSegment::chord_y, n.dy, 1.0);
  deck.branch_node(name, CoRotationalSegment::chord_angle, n.angle, 1.0);
}

// F and N, and with τ in the tran deck Q and P (their nodes in `n`).
void write_forces(const CoRotationalSegment& s, SegmentNodes& n, DeckWriter& deck) {
  const std::string& name = s.name();
  const std::string l = deck.value(s.length(), name);
  const std::string half = deck.value(0.5 * s.length(), name);
  const std::string n_t = deck.value(s.transverse_compliance(), name);
  const std::string n_a = deck.value(s.axial_compliance(), name);
  std::ostringstream& out = deck.body();
  auto node_or_zero = [&](NodeId id) {
    return id == ground ? std::string("0") : "V(" + deck.node(id) + ")";
  };
  const std::string sum =
      "(" + node_or_zero(s.end_a().rotation) + "+" + node_or_zero(s.end_b().rotation) + ")";
  const ChordRates rates = chord_rates(s, n, deck);
  const std::string force_rate = "((" + half + "*" + sum + "-" + l + "/(" + l + "+V(" +
                                 n.extension + "))*" + rates.across + ")/" + n_t + ")";
  if (deck.op())
    out << deck.element_name('B', n.force) << " " << n.force << " 0 V = (" << half << "*" << sum
        << "-" << l << "*V(" << n.angle << "))/" << n_t << "\n";
  else
    deck.integrator(n.force, force_rate,
                    deck.static_branch_value(name, CoRotationalSegment::transverse_force));
  out << deck.element_name('B', n.tension) << " " << n.tension << " 0 V = V(" << n.extension << ")/"
      << n_a << "\n";
  deck.branch_node(name, CoRotationalSegment::transverse_force, n.force, 1.0);
  deck.branch_node(name, CoRotationalSegment::axial_force, n.tension, 1.0);
  const double tau = s.kelvin_voigt_time();
  if (tau <= 0.0) return;
  if (deck.op()) {
    deck.leave_out(name + " (its Kelvin-Voigt dampers)");
    deck.branch_node(name, CoRotationalSegment::total_transverse_force, n.force, 1.0);
    deck.branch_node(name, CoRotationalSegment::total_axial_force, n.tension, 1.0);
    return;
  }
  n.total_force = deck.internal_node(name + "_Q", name + ": the total transverse force Q [N]");
  n.total_tension = deck.internal_node(name + "_P", name + ": the total axial force P [N]");
  const std::string t = deck.value(tau, name);
  out << deck.element_name('B', n.total_force) << " " << n.total_force << " 0 V = V(" << n.force
      << ")+" << t << "*" << force_rate << "\n";
  out << deck.element_name('B', n.total_tension) << " " << n.total_tension << " 0 V = V("
      << n.tension << ")+" << deck.value(tau / s.axial_compliance(), name) << "*" << rates.along
      << "\n";
  deck.branch_node(name, CoRotationalSegment::total_transverse_force, n.total_force, 1.0);
  deck.branch_node(name, CoRotationalSegment::total_axial_force, n.total_tension, 1.0);
}

// The forces the segment draws from its end nodes.
void write_node_forces(const CoRotationalSegment& s, const SegmentNodes& n, DeckWriter& deck) {
  const std::string& name = s.name();
  const std::string l = deck.value(s.length(), name);
  const std::string half = deck.value(0.5 * s.length(), name);
  const std::string c = "cos(V(" + n.angle + "))", si = "sin(V(" + n.angle + "))";
  const std::string q = "V(" + n.total_force + ")", p = "V(" + n.total_tension + ")";
  const std::string lever = l + "/(" + l + "+V(" + n.extension + "))";
  const std::string fx = "(-" + q + "*" + lever + "*" + si + "-" + p + "*" + c + ")";
  const std::string fy = "(" + q + "*" + lever + "*" + c + "-" + p + "*" + si + ")";
  std::ostringstream& out = deck.body();
  auto draw = [&](NodeId node, const std::string& what, const std::string& current) {
    if (node == ground) return;
    out << deck.element_name('B', name + "_" + what) << " " << deck.node(node)
        << " 0 I = " << current << "\n";
  };
  draw(s.end_a().x, "ax", fx);
  draw(s.end_a().y, "ay", fy);
  draw(s.end_b().x, "bx", "-" + fx);
  draw(s.end_b().y, "by", "-" + fy);
  draw(s.end_a().rotation, "ra", half + "*" + q);
  draw(s.end_b().rotation, "rb", half + "*" + q);
  // A held end's force (f_x, f_y: the reaction probes' unknowns) is not written: a node near zero
  // (the axial reaction of a cantilever) would be held to vntol against the rounding of the large
  // forces it is the difference of, which stops ngspice's Newton; the crosscheck skips unknowns
  // without a vector.
}

}  // namespace

void write_corotational_segment(const CoRotationalSegment& s, DeckWriter& deck) {
  const std::string& name = s.name();
  if (deck.ac())
    throw InputError(deck.where(), "beam.kinematics",
                     "is \"large\": an ac deck is not written, because ngspice linearises about "
                     "its own operating point of the velocity deck, where the integrators of the "
                     "chords cannot hold the deflected state (emnet ac linearises about it); op "
                     "and tran decks are written");
  if (s.axial_compliance() == 0.0)
    throw InputError(deck.where(), "beam.axial_stiffness",
                     "is needed for a SPICE deck with beam.kinematics = \"large\": an "
                     "inextensible segment's axial force is a multiplier, which no B source "
                     "writes; give the axial stiffness EA");
  deck.comment(
      name + ": co-rotational segment, l = " + number(s.length()) + " m, n_T = " +
      number(s.transverse_compliance()) + " m/N, n_A = " + number(s.axial_compliance()) + " m/N" +
      (s.kelvin_voigt_time() > 0.0 ? ", Kelvin-Voigt tau = " + number(s.kelvin_voigt_time()) + " s"
                                   : std::string()));
  SegmentNodes nodes = claim_nodes(s, deck);
  write_chord(s, nodes, deck);
  write_forces(s, nodes, deck);
  write_node_forces(s, nodes, deck);
}

}  // namespace emnet::spice_deck
