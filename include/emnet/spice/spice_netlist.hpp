// SPICE export: a writer over the assembled network's element ports and parameters (after
// gnucap's lang_spice), not a method of each element. It writes a plain SPICE3 deck that
// ngspice runs unchanged (`ngspice -b deck.cir`) and that uses only what LTspice also reads:
// R, L, C, V, I, E, F, G, B, PULSE/SIN/PWL sources, .op/.ac/.tran, .options, .ic. An
// ngspice-only `.control` block (run, then wrdata of the outputs) is written only on request.
//
// Conventions (Firestone analogy): across = node voltage, through = current.
//   translational: velocity v [m/s] = V,  force F [N] = A
//   rotational:    angular velocity Ω [rad/s] = V,  torque M [N·m] = A
//   electrical:    potential u [V],  current i [A]
// Every value is SI; a deck's "V" on a velocity node is metres per second, its "A" newtons.
// Ground (a clamp, or the electrical reference) is node 0.
//
// Element kinds, in the ac and tran decks (the velocity network as emnet assembles it):
//   Conductance g   resistor R = 1/g between a and b; g = 0 writes no element (an open).
//   Capacitor C     capacitor C (a mass or inertia to ground, or an electrical capacitor).
//   Inductor n      inductor L = n (a compliance carries the spring force as its current);
//                   emnet's branch unknown j (a → b) is the vector "l_NAME#branch", same sign.
//   CurrentSource   I from → to (SPICE current flows from its first node through the source
//                   into its second, so it is injected into `to`, as in emnet).
//   VoltageSource   V plus minus; emnet's j (from plus through the source to minus) is the
//                   SPICE branch current "v_NAME#branch", same sign.
//   Transformer     (a lever with one or more primaries) y_s+ − y_s− = Σ a_k·(y_pk+ − y_pk−):
//                   a 0 V sense source V_NAME from s+ to an internal node, then one E source
//                   per primary in series (gain a_k on that primary's across) down to s−; the
//                   sense current j = I(V_NAME) is emnet's branch unknown (same sign) and each
//                   primary receives a_k·j through an F source (into pk+, out of pk−).
//   Gyrator K       two G sources: K·(y_c − y_d) out of a into b, −K·(y_a − y_b) out of c into d.
//   Dea             its capacitor C₀ (e+, e−), and per coupling node k a B source injecting
//                   c_k·k_F·u² with u = V(e+) − V(e−) (the force follows the capacitor
//                   voltage); with back-coupling a B source drawing 2·k_F·u·ẋ from e+ to e−,
//                   ẋ = Σ c_k·V(k). Its direct AC force (antagonistic drive) is an AC-only
//                   current source c_k·ac_force into each coupling node (ac deck only).
//   CoRotationalSegment (beam.kinematics = "large") its unknowns as nodes and its geometry and
//                   forces as B sources (deck/corotational_segment.cpp): the chord's change
//                   (op, ac: V(b) − V(a) of the displacement nodes; tran: an integrator of v_b −
//                   v_a, 1 F ‖ 1 GΩ as the outputs), its angle θ by its constraint sin θ·(l + d_x)
//                   − cos θ·d_y = 0, the extension ℓ − l, the forces F (tran: an integrator of F'),
//                   N = (ℓ − l)/n_A, with τ Q and P, and the forces on the end nodes. An
//                   inextensible segment is refused naming beam.axial_stiffness.
// The ac deck of a large-kinematics beam is written in displacements, as the op deck (below), with
// the network's dynamics added, so that ngspice's operating point is the deflected static state
// and its ac linearises the B sources there, as emnet's ac does (a velocity deck's integrators
// cannot hold that state): a mass m draws m·d²V/dt² (an F source of the current a capacitor m
// takes from the node's rate), a damper r is a capacitor r, a compliance a resistor n, the
// segments' Kelvin–Voigt totals and the DEAs' motional currents take rate nodes. A rate node
// d/dt V(x) is an E copy of x charging 1 F through a 0 V sense source, whose current an H source
// makes a voltage. Outputs are the probes' values themselves (no integrators); emnet's
// mechanical unknowns (velocities) map to the nodes' rates.
// Independent sources: op and ac decks hold their value at t = 0 (what emnet's static and its
// AC operating point use, System::b(0)) and, in the ac deck, their AC phasor (System::b_ac);
// tran decks hold the time function: DC, SIN, PULSE or PWL. A pulse with zero rise and fall
// time (emnet switches instantly) gets linear edges of a stated tiny width ε centred on the
// switching instants (so the error against the instant switch is of second order in ε); a
// pulse that is on at t = 0 starts on (SPICE's PULSE then runs from its high level).
//
// The op deck is the static network in displacements, built like emnet's static analysis
// (src/analysis/static.cpp): every mechanical across unknown is s·(displacement) and the
// network is taken at s = 0. Mechanical node voltages are then displacements [m] and rotations
// [rad]; a compliance n becomes a resistor R = n (z_a − z_b = n·F); masses and mechanical
// dampers carry no static force and are left out; levers keep their ratios (displacements
// obey the same relation as velocities); electrical elements stay as they are; a DEA keeps its
// force and drops its motional current (zero at rest). A non-zero velocity source has no
// static state and is refused. The op deck therefore has no branch vector for compliances.
//
// Outputs: every probe becomes an output node "out_NAME" fed by one G source per term of its
// linear functional (the same Hermite weights emnet uses, Probe::terms). A probe that is a
// time integral (a deflection from velocities) feeds a 1 F capacitor in parallel with a
// 1 GΩ resistor: V(out) = ∫Σc·V dt with a leak time constant of 1e9 s (1e-8 relative over
// 10 s; |1/(jωRC)| = 1.6e-9 relative at 0.1 Hz); the resistor gives the op point a DC path.
// Its initial value is the start state of `emnet tran`: zero at rest (`.tran … uic`), or the
// static value under the drive at t = 0 (written with `.ic`; ngspice holds the node there while
// it computes the operating point, which gives the rest of the static state). The writer runs
// no analysis: that static state is the caller's (SpiceDeckOptions::static_state), which has
// usually solved it already and can report its failure in its own terms. A probe that is
// not an integral feeds a 1 Ω resistor: V(out) = Σc·V. In the op deck a probe's term stays when
// emnet's static_probe_value keeps it (displacement of a deflection, voltage of a DEA), through
// a 1 Ω resistor. In the ac deck (in velocities) an integral output at f = 0 is 0, where emnet
// gives the static limit: compare from the first frequency above 0.
//
// Safety: no text from a scene reaches a deck unchecked. Comment text keeps only printable
// ASCII letters, digits, spaces and `_-+.,:;=()[]/*%@<>'!?^~|&` (anything else, newlines and
// carriage returns included, becomes '?'), and every comment line starts with "* ". Node and
// element names keep only [A-Za-z0-9_] (anything else becomes '_'), are unique without regard
// to letter case (a suffix _2, _3, … otherwise) and never alias ground ("0", "gnd"). A DEA
// name that is not a name of letters, digits and '_' is refused with an InputError naming
// the key (dea[k].name): it names nodes and elements and must stay recognisable.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

/// The analysis a deck runs: .op, .ac or .tran.
enum class SpiceAnalysis { op, ac, tran };
/// "op", "ac" or "tran".
const char* spice_analysis_name(SpiceAnalysis analysis);

/// What write_spice_deck writes.
struct SpiceDeckOptions {
  SpiceAnalysis analysis = SpiceAnalysis::op;  ///< the deck's analysis
  /// Outputs; empty: spice_output_probes(model).
  std::vector<Probe> outputs;
  /// ac: the sweep; unset: the scene's [ac] table (what `emnet ac` uses without options).
  std::optional<AcSpec> ac;
  /// tran: `.tran output_step end_time 0 max_step [uic]`.
  double end_time = 0.0;     ///< [s], > 0
  double output_step = 0.0;  ///< [s], > 0
  double max_step = 0.0;     ///< [s]; 0: output_step
  /// tran: `.options reltol=`; vntol and abstol are set far below the deck's values (1e-12 V,
  /// 1e-15 A) so that reltol is what limits the error.
  double relative_tolerance = 1e-6;
  /// tran: ε of instantly switching pulses = this fraction of the pulse's shorter level time.
  double edge_fraction = 1e-5;
  StartState start = StartState::rest;  ///< tran: the start state, at rest or static
  /// tran with start = static: the static state of the model's network (solve_static of
  /// model.network.assemble()), whose integral outputs' values the deck's .ic lines hold.
  /// Required then: std::invalid_argument without it; a failed one is an OptionError naming the
  /// field "start" ("the network has no static state").
  std::optional<StaticResult> static_state;
  /// Append an ngspice `.control` block (run, then wrdata of the outputs to `control_output`).
  bool control = false;
  std::string control_output;  ///< empty: "<scene name>-<analysis>.data"
  /// How the header names the scene file; empty: the file name of Scene::file (no directory,
  /// so that a deck does not depend on where the repository is).
  std::string scene_label;
  std::vector<std::string> overrides;  ///< --set overrides, listed in the header
};

/// Where ngspice holds one of emnet's quantities: emnet value = sign × vector.
struct SpiceVector {
  std::string vector;  ///< ngspice vector name, lower case ("v3", "l_nt0#branch"); empty: none
  double sign = 1.0;   ///< the factor from the vector to emnet's value
};

/// One output of a deck: the probe it is and the vector that holds it.
struct SpiceOutput {
  std::string probe;   ///< emnet probe name
  std::string vector;  ///< ngspice vector of its output node, lower case ("out_p4")
  std::string unit;    ///< the probe's unit (m, rad, V, …)
  std::string description;
};

/// A written deck and where its vectors hold emnet's unknowns and outputs.
struct SpiceDeck {
  std::string text;  ///< the deck, lines ending in '\n', first line a comment, last ".end"
  SpiceAnalysis analysis = SpiceAnalysis::op;  ///< the analysis it runs
  /// One entry per unknown of network.assemble() (System::unknowns order). Node entries hold
  /// the node's voltage vector (op: the displacement z, or the voltage, of emnet's
  /// StaticResult::state; ac/tran: the velocity / voltage, in the ac deck in displacements the
  /// mechanical node's rate node); branch entries the branch current.
  std::vector<SpiceVector> unknowns;
  /// Whether mechanical node voltages are displacements: the op deck, and the ac deck of a
  /// large-kinematics beam (outputs then are the probes' values themselves, no integrators).
  bool displacement_nodes = false;
  std::vector<SpiceOutput> outputs;  ///< one per output probe, in order
  std::vector<std::string> notes;    ///< what the deck approximates, in words
};

/// The deck for `options.analysis` over `model` (its network, beam layout and DEAs).
/// @throws InputError for a model that cannot be written safely or options out of range (an
///         OptionError naming "start" when options.static_state is a failed one)
/// @throws std::invalid_argument for a tran deck from the static state without
///         options.static_state, or with one of another network
SpiceDeck write_spice_deck(const Model& model, const SpiceDeckOptions& options);

/// A deck's default outputs: the model's deck_output_list (emnet/model/outputs.hpp): the scene's
/// probes as they are (P1 included), dx_k = P_k − P1 when a probe P1 exists (paper Eqs. 20–22),
/// and each DEA's capacitor voltage u_X and current i_X when it has an electrical model.
std::vector<Probe> spice_output_probes(const Model& model);

/// Text made safe for a SPICE comment (see the header comment).
std::string spice_comment_text(const std::string& text);
/// A name made of [A-Za-z0-9_] only (an empty text gives "_").
std::string spice_identifier(const std::string& text);

}  // namespace emnet
