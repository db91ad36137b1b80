// SPICE lines of a CoRotationalSegment (beam.kinematics = "large"): its unknowns as nodes, its
// geometry and forces as B sources (behavioural sources: the modulated transformer of the
// chord's rotation), with the equations of corotational_segment.hpp:
//   dx, dy  the chord's change [m]: op and ac decks V(b) − V(a) of the displacement nodes; tran
//           deck integrators of v_b − v_a (1 F, 1e9 Ω leak, as the integral outputs)
//   th      the chord's angle [rad], by its constraint sin θ·(l + dx) − cos θ·dy = 0: a B source
//           drawing that current from the node (its conductance ∂/∂θ is the chord's length ℓ > 0)
//   ext     the chord's extension ℓ − l = cos θ·(l + dx) + sin θ·dy − l [m] (a node that is 0 at
//           rest, where SPICE's first iterate starts: l/ℓ is written l/(l + V(ext)))
//   F       the transverse compliance's force [N]: op and ac decks ((l/2)·(ψ_a + ψ_b) − l·θ)/n_T;
//           tran deck the integrator of F' = ((l/2)·(Ω_a + Ω_b) − (l/ℓ)·e₂·(v_b − v_a))/n_T
//   N       the axial force (ℓ − l)/n_A [N]
//   Q, P    with Kelvin–Voigt damping τ: tran deck Q = F + τ·F', P = N + (τ/n_A)·e₁·(v_b − v_a);
//           ac deck Q = F + τ·dF/dt, P = N + τ·dN/dt (rate nodes); the op deck leaves them out
// and the forces each node gives the segment, B sources from the node to ground:
//   (x, y)_a: +Q·(l/ℓ)·e₂ − P·e₁,   (x, y)_b: the opposite,   Ω_a, Ω_b: (l/2)·Q,
// a held end's force (f_x, f_y) left out (see write_node_forces),
// e₁ = (cos θ, sin θ), e₂ = (−sin θ, cos θ). Node voltages are velocities in the tran deck and
// displacements in the op and ac decks (rates are zero at rest in the op deck). The ac deck is
// the op deck with the network's dynamics (DeckWriter::displacements): its operating point is the
// deflected static state, about which ngspice linearises the B sources itself, as emnet's ac
// does (a velocity deck's integrators could not hold that state). An inextensible segment
// (n_A = 0, N a multiplier) has no B-source form here.
#include "emnet/elements/corotational_segment.hpp"

#include "spice/deck_writer.hpp"

namespace emnet::spice_deck {

namespace {

// The segment's own node names (claimed once) and the expressions its lines share.
struct Segment {
  const CoRotationalSegment& element;
  DeckWriter& deck;
  std::string name;
  // Nodes.
  std::string dx, dy, angle, extension, force, tension, total_force, total_tension;
  // Values and expressions: l, l/2; cos θ, sin θ; v_b − v_a along x and y; l/ℓ.
  std::string l, half, cos, sin, vx, vy, lever;

  Segment(const CoRotationalSegment& s, DeckWriter& writer)
      : element(s), deck(writer), name(s.name()) {
    dx = deck.internal_node(name + "_dx", name + ": the chord's change along x, d_x [m]");
    dy = deck.internal_node(name + "_dy", name + ": the chord's change along y, d_y [m]");
    angle = deck.internal_node(name + "_th", name + ": the chord's angle theta [rad]");
    extension = deck.internal_node(name + "_ext", name + ": the chord's extension [m]");
    force = deck.internal_node(name + "_F", name + ": the transverse compliance's force F [N]");
    tension = deck.internal_node(name + "_N", name + ": the axial force N [N], tension positive");
    total_force = force;
    total_tension = tension;
    l = deck.value(s.length(), name);
    half = deck.value(0.5 * s.length(), name);
    cos = "cos(V(" + angle + "))";
    sin = "sin(V(" + angle + "))";
    vx = deck.voltage(s.end_b().x, s.end_a().x);
    vy = deck.voltage(s.end_b().y, s.end_a().y);
    lever = l + "/(" + l + "+V(" + extension + "))";
  }
  // The tran deck's rates e₂·(v_b − v_a) and e₁·(v_b − v_a).
  std::string across_rate() const { return "(-" + sin + "*" + vx + "+" + cos + "*" + vy + ")"; }
  std::string along_rate() const { return "(" + cos + "*" + vx + "+" + sin + "*" + vy + ")"; }
  // A B source of `kind` ("V" or "I") from `node` to ground with `expression`.
  void source(const std::string& element_name, const std::string& node, const char* kind,
              const std::string& expression) {
    deck.body() << deck.element_name('B', element_name) << " " << node << " 0 " << kind << " = "
                << expression << "\n";
  }
};

void write_chord(Segment& g) {
  if (g.deck.displacements()) {
    g.source(g.dx, g.dx, "V", g.vx);
    g.source(g.dy, g.dy, "V", g.vy);
  } else {
    g.deck.integrator(g.dx, g.vx, g.deck.static_branch_value(g.name, CoRotationalSegment::chord_x));
    g.deck.integrator(g.dy, g.vy, g.deck.static_branch_value(g.name, CoRotationalSegment::chord_y));
  }
  const std::string dx = "V(" + g.dx + ")", dy = "V(" + g.dy + ")";
  g.source(g.angle, g.angle, "I", g.sin + "*(" + g.l + "+" + dx + ")-" + g.cos + "*" + dy);
  g.source(g.extension, g.extension, "V",
           g.cos + "*(" + g.l + "+" + dx + ")+" + g.sin + "*" + dy + "-" + g.l);
  g.deck.branch_node(g.name, CoRotationalSegment::chord_x, g.dx, 1.0);
  g.deck.branch_node(g.name, CoRotationalSegment::chord_y, g.dy, 1.0);
  g.deck.branch_node(g.name, CoRotationalSegment::chord_angle, g.angle, 1.0);
}

// F and N, and with τ in the tran deck Q and P (their nodes in `g`).
void write_forces(Segment& g) {
  const CoRotationalSegment& s = g.element;
  const std::string n_t = g.deck.value(s.transverse_compliance(), g.name);
  const std::string n_a = g.deck.value(s.axial_compliance(), g.name);
  auto node_or_zero = [&](NodeId id) {
    return id == ground ? std::string("0") : "V(" + g.deck.node(id) + ")";
  };
  const std::string sum =
      "(" + node_or_zero(s.end_a().rotation) + "+" + node_or_zero(s.end_b().rotation) + ")";
  const std::string force_rate =
      "((" + g.half + "*" + sum + "-" + g.lever + "*" + g.across_rate() + ")/" + n_t + ")";
  if (g.deck.displacements())
    g.source(g.force, g.force, "V",
             "(" + g.half + "*" + sum + "-" + g.l + "*V(" + g.angle + "))/" + n_t);
  else
    g.deck.integrator(g.force, force_rate,
                      g.deck.static_branch_value(g.name, CoRotationalSegment::transverse_force));
  g.source(g.tension, g.tension, "V", "V(" + g.extension + ")/" + n_a);
  g.deck.branch_node(g.name, CoRotationalSegment::transverse_force, g.force, 1.0);
  g.deck.branch_node(g.name, CoRotationalSegment::axial_force, g.tension, 1.0);
  const double tau = s.kelvin_voigt_time();
  if (tau <= 0.0) return;
  if (g.deck.op()) {
    g.deck.leave_out(g.name + " (its Kelvin-Voigt dampers)");
  } else if (g.deck.displacements()) {
    g.total_force =
        g.deck.internal_node(g.name + "_Q", g.name + ": the total transverse force Q [N]");
    g.total_tension = g.deck.internal_node(g.name + "_P", g.name + ": the total axial force P [N]");
    const std::string t = g.deck.value(tau, g.name);
    g.source(g.total_force, g.total_force, "V",
             "V(" + g.force + ")+" + t + "*V(" + g.deck.rate_of(g.force) + ")");
    g.source(g.total_tension, g.total_tension, "V",
             "V(" + g.tension + ")+" + t + "*V(" + g.deck.rate_of(g.tension) + ")");
  } else {
    g.total_force =
        g.deck.internal_node(g.name + "_Q", g.name + ": the total transverse force Q [N]");
    g.total_tension = g.deck.internal_node(g.name + "_P", g.name + ": the total axial force P [N]");
    g.source(g.total_force, g.total_force, "V",
             "V(" + g.force + ")+" + g.deck.value(tau, g.name) + "*" + force_rate);
    g.source(g.total_tension, g.total_tension, "V",
             "V(" + g.tension + ")+" + g.deck.value(tau / s.axial_compliance(), g.name) + "*" +
                 g.along_rate());
  }
  g.deck.branch_node(g.name, CoRotationalSegment::total_transverse_force, g.total_force, 1.0);
  g.deck.branch_node(g.name, CoRotationalSegment::total_axial_force, g.total_tension, 1.0);
}

// The forces the segment draws from its end nodes.
void write_node_forces(Segment& g) {
  const CoRotationalSegment& s = g.element;
  const std::string q = "V(" + g.total_force + ")", p = "V(" + g.total_tension + ")";
  const std::string fx = "(-" + q + "*" + g.lever + "*" + g.sin + "-" + p + "*" + g.cos + ")";
  const std::string fy = "(" + q + "*" + g.lever + "*" + g.cos + "-" + p + "*" + g.sin + ")";
  auto draw = [&](NodeId node, const std::string& what, const std::string& current) {
    if (node != ground) g.source(g.name + "_" + what, g.deck.node(node), "I", current);
  };
  draw(s.end_a().x, "ax", fx);
  draw(s.end_a().y, "ay", fy);
  draw(s.end_b().x, "bx", "-" + fx);
  draw(s.end_b().y, "by", "-" + fy);
  draw(s.end_a().rotation, "ra", g.half + "*" + q);
  draw(s.end_b().rotation, "rb", g.half + "*" + q);
  // A held end's force (f_x, f_y: the reaction probes' unknowns) is not written: a node near zero
  // (the axial reaction of a cantilever) would be held to vntol against the rounding of the large
  // forces it is the difference of, which stops ngspice's Newton; the crosscheck skips unknowns
  // without a vector.
}

}  // namespace

void write_corotational_segment(const CoRotationalSegment& s, DeckWriter& deck) {
  const std::string& name = s.name();
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
  Segment segment(s, deck);
  write_chord(segment);
  write_forces(segment);
  write_node_forces(segment);
}

}  // namespace emnet::spice_deck
