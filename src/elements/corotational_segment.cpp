// Co-rotational segment: see include/emnet/elements/corotational_segment.hpp for the equations,
// signs and sources.
#include "emnet/elements/corotational_segment.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace emnet {

CoRotationalSegment::CoRotationalSegment(std::string name, End a, End b, double length,
                                         double transverse_compliance, double axial_compliance,
                                         double kelvin_voigt_time, EndForce end_force)
    : Element(std::move(name)),
      a_(a),
      b_(b),
      length_(length),
      transverse_compliance_(transverse_compliance),
      axial_compliance_(axial_compliance),
      kelvin_voigt_time_(kelvin_voigt_time),
      end_force_(end_force) {
  if (!(length > 0.0) || !(transverse_compliance > 0.0) || !(axial_compliance >= 0.0) ||
      !(kelvin_voigt_time >= 0.0) || !std::isfinite(length) ||
      !std::isfinite(transverse_compliance) || !std::isfinite(axial_compliance) ||
      !std::isfinite(kelvin_voigt_time))
    throw std::invalid_argument("co-rotational segment " + this->name() +
                                ": length and transverse compliance must be positive and finite, "
                                "axial compliance and Kelvin-Voigt time non-negative");
}

std::vector<Unknown> CoRotationalSegment::branch_unknowns() const {
  const std::string& id = name();
  using Kind = Unknown::Kind;
  // Each is fixed by the chord's change d through the segment's geometry or a compliance:
  // their IDA tolerances follow d's (Unknown::tolerance_per_displacement).
  const double per_force = 1.0 / transverse_compliance_;
  const double per_tension = axial_compliance_ > 0.0 ? 1.0 / axial_compliance_ : 0.0;
  std::vector<Unknown> unknowns = {
      {"dx_" + id, Kind::branch_through, Domain::translational, 1.0, true},
      {"dy_" + id, Kind::branch_through, Domain::translational, 1.0, true},
      {"th_" + id, Kind::branch_through, Domain::rotational, 1.0 / length_, true},
      {"F_" + id, Kind::branch_through, Domain::translational, per_force},
      {"N_" + id, Kind::branch_through, Domain::translational, per_tension}};
  if (kelvin_voigt_time_ > 0.0)
    unknowns.push_back({"Q_" + id, Kind::branch_through, Domain::translational, per_force});
  if (axial_branch() == total_axial_force)
    unknowns.push_back({"P_" + id, Kind::branch_through, Domain::translational, per_tension});
  if (end_force_ != EndForce::none) {
    const double per_end_force = std::max(per_force, per_tension);
    const std::string end = end_force_ == EndForce::a ? "a_" : "b_";
    unknowns.push_back(
        {"fx" + end + id, Kind::branch_through, Domain::translational, per_end_force});
    unknowns.push_back(
        {"fy" + end + id, Kind::branch_through, Domain::translational, per_end_force});
  }
  return unknowns;
}

int CoRotationalSegment::end_force_branch() const {
  if (end_force_ == EndForce::none) return -1;
  int offset = axial_force + 1;
  if (kelvin_voigt_time_ > 0.0) ++offset;
  if (axial_branch() == total_axial_force) ++offset;
  return offset;
}

void CoRotationalSegment::stamp(Stamper& s) const {
  const double l = length_;
  const int dx = s.branch(chord_x), dy = s.branch(chord_y), theta = s.branch(chord_angle);
  const int f = s.branch(transverse_force), n = s.branch(axial_force);
  const int q = s.branch(force_branch()), p = s.branch(axial_branch());
  // d' = v_b − v_a.
  s.c(dx, dx, 1.0);
  s.g(dx, b_.x, -1.0);
  s.g(dx, a_.x, 1.0);
  s.c(dy, dy, 1.0);
  s.g(dy, b_.y, -1.0);
  s.g(dy, a_.y, 1.0);
  // The chord's angle, linearised: −l·θ + d_y (the rest of −sin θ·(l + d_x) + cos θ·d_y in g).
  s.g(theta, theta, -l);
  s.g(theta, dy, 1.0);
  // −n_T·F' − l·θ' + (l/2)·(Ω_a + Ω_b) = 0, signed as an inductor's row (symmetric with KCL).
  s.c(f, f, -transverse_compliance_);
  s.c(f, theta, -l);
  s.g(f, a_.rotation, 0.5 * l);
  s.g(f, b_.rotation, 0.5 * l);
  // n_A·N − (ℓ − l) = 0, linearised: n_A·N − d_x.
  if (axial_compliance_ > 0.0) s.g(n, n, axial_compliance_);
  s.g(n, dx, -1.0);
  // Q = F + (τ/n_T)·((l/2)·(Ω_a + Ω_b) − l·θ'), linearised: l·θ' ≈ v_by − v_ay.
  if (kelvin_voigt_time_ > 0.0) {
    const double damper = kelvin_voigt_time_ / transverse_compliance_;
    s.g(q, q, 1.0);
    s.g(q, f, -1.0);
    s.g(q, a_.rotation, -0.5 * l * damper);
    s.g(q, b_.rotation, -0.5 * l * damper);
    s.g(q, b_.y, damper);
    s.g(q, a_.y, -damper);
  }
  // P = N + (τ/n_A)·e₁·(v_b − v_a), linearised: N + (τ/n_A)·(v_bx − v_ax).
  if (p != n) {
    const double damper = kelvin_voigt_time_ / axial_compliance_;
    s.g(p, p, 1.0);
    s.g(p, n, -1.0);
    s.g(p, b_.x, -damper);
    s.g(p, a_.x, damper);
  }
  // The forces at rest: ±Q along y, ∓P along x, (l/2)·Q on both rotations.
  s.g(a_.y, q, 1.0);
  s.g(b_.y, q, -1.0);
  s.g(a_.x, p, -1.0);
  s.g(b_.x, p, 1.0);
  s.g(a_.rotation, q, 0.5 * l);
  s.g(b_.rotation, q, 0.5 * l);
  // The end force's unknowns at rest: f_a = (−P, Q), f_b = −f_a.
  if (end_force_ != EndForce::none) {
    const int fx = s.branch(end_force_branch()), fy = s.branch(end_force_branch() + 1);
    const double sign = end_force_sign();
    s.g(fx, fx, 1.0);
    s.g(fx, p, sign);
    s.g(fy, fy, 1.0);
    s.g(fy, q, -sign);
  }
}

// The segment's geometry at y, and where its unknowns and its nodes' rows are.
struct CoRotationalSegment::ChordState {
  int dx, dy, theta, n, q, p;  // indices in y of d_x, d_y, θ, N, the transverse and axial forces
  double c, s;                 // cos θ, sin θ
  double chord;                // ℓ = cos θ·(l + d_x) + sin θ·d_y
  double normal;               // h = −sin θ·(l + d_x) + cos θ·d_y, zero on the chord
  double ratio;                // l/ℓ
  double ratio_theta, ratio_dx, ratio_dy;  // ∂(l/ℓ) = −(l/ℓ²)·∂ℓ, ∂ℓ/∂(θ, d_x, d_y) = (h, c, s)
  double dvx, dvy;                         // v_b − v_a
  double normal_rate;                      // e₂·(v_b − v_a)
};

// Adds g's entries (and, with a jacobian, ∂g/∂y) row by row; ground rows and columns are dropped.
struct CoRotationalSegment::NonlinearSink {
  Eigen::VectorXd& g;
  std::vector<Eigen::Triplet<double>>* jacobian;
  void value(int row, double v) const {
    if (row != ground) g[row] += v;
  }
  void derivative(int row, int column, double v) const {
    if (jacobian && row != ground && column != ground) jacobian->emplace_back(row, column, v);
  }
};

void CoRotationalSegment::add_nonlinear(const Eigen::VectorXd& y, int branch_offset,
                                        Eigen::VectorXd& g,
                                        std::vector<Eigen::Triplet<double>>* jacobian) const {
  ChordState state;
  state.dx = branch_offset + chord_x;
  state.dy = branch_offset + chord_y;
  state.theta = branch_offset + chord_angle;
  state.n = branch_offset + axial_force;
  state.q = branch_offset + force_branch();
  state.p = branch_offset + axial_branch();
  state.c = std::cos(y[state.theta]);
  state.s = std::sin(y[state.theta]);
  const double chord_x_length = length_ + y[state.dx], chord_y_length = y[state.dy];
  state.chord = state.c * chord_x_length + state.s * chord_y_length;
  state.normal = -state.s * chord_x_length + state.c * chord_y_length;
  state.ratio = length_ / state.chord;
  state.ratio_theta = -state.ratio / state.chord * state.normal;
  state.ratio_dx = -state.ratio / state.chord * state.c;
  state.ratio_dy = -state.ratio / state.chord * state.s;
  auto velocity = [&](NodeId node) { return node == ground ? 0.0 : y[node]; };
  state.dvx = velocity(b_.x) - velocity(a_.x);
  state.dvy = velocity(b_.y) - velocity(a_.y);
  state.normal_rate = -state.s * state.dvx + state.c * state.dvy;
  const NonlinearSink sink{g, jacobian};
  add_chord_rows(y, state, sink);
  add_damper_rows(state, sink);
  add_node_forces(y[state.q], y[state.p], state, sink,
                  end_force_ == EndForce::none ? -1 : branch_offset + end_force_branch());
}

void CoRotationalSegment::add_chord_rows(const Eigen::VectorXd& y, const ChordState& st,
                                         const NonlinearSink& sink) const {
  const double l = length_;
  // The chord's angle: h − (−l·θ + d_y).
  sink.value(st.theta, st.normal + l * y[st.theta] - y[st.dy]);
  sink.derivative(st.theta, st.theta, l - st.chord);
  sink.derivative(st.theta, st.dx, -st.s);
  sink.derivative(st.theta, st.dy, st.c - 1.0);
  // The axial row: −(ℓ − l) + d_x.
  sink.value(st.n, -(st.chord - l) + y[st.dx]);
  sink.derivative(st.n, st.theta, -st.normal);
  sink.derivative(st.n, st.dx, 1.0 - st.c);
  sink.derivative(st.n, st.dy, -st.s);
}

void CoRotationalSegment::add_damper_rows(const ChordState& st, const NonlinearSink& sink) const {
  // The axial damper's share of P: −(τ/n_A)·(e₁·(v_b − v_a) − (v_bx − v_ax)).
  if (st.p != st.n) {
    const double damper = kelvin_voigt_time_ / axial_compliance_;
    sink.value(st.p, -damper * (st.c * st.dvx + st.s * st.dvy - st.dvx));
    sink.derivative(st.p, b_.x, -damper * (st.c - 1.0));
    sink.derivative(st.p, a_.x, damper * (st.c - 1.0));
    sink.derivative(st.p, b_.y, -damper * st.s);
    sink.derivative(st.p, a_.y, damper * st.s);
    sink.derivative(st.p, st.theta, -damper * st.normal_rate);
  }
  // The transverse damper's share of Q: (τ/n_T)·(l·θ' − (v_by − v_ay)), with
  // l·θ' = (l/ℓ)·e₂·(v_b − v_a).
  if (kelvin_voigt_time_ > 0.0) {
    const double damper = kelvin_voigt_time_ / transverse_compliance_;
    const double ratio = st.ratio, c = st.c, s = st.s;
    sink.value(st.q, damper * (ratio * st.normal_rate - st.dvy));
    sink.derivative(st.q, b_.x, -damper * ratio * s);
    sink.derivative(st.q, a_.x, damper * ratio * s);
    sink.derivative(st.q, b_.y, damper * (ratio * c - 1.0));
    sink.derivative(st.q, a_.y, -damper * (ratio * c - 1.0));
    sink.derivative(
        st.q, st.theta,
        damper * (st.ratio_theta * st.normal_rate + ratio * (-c * st.dvx - s * st.dvy)));
    sink.derivative(st.q, st.dx, damper * st.ratio_dx * st.normal_rate);
    sink.derivative(st.q, st.dy, damper * st.ratio_dy * st.normal_rate);
  }
}

void CoRotationalSegment::add_node_forces(double force, double tension, const ChordState& st,
                                          const NonlinearSink& sink, int end_force_x) const {
  // The force on end a, f_a = Q·(l/ℓ)·e₂ − P·e₁, less its part at rest (−P, Q); end b the
  // opposite. Each component with its derivatives in (Q, P, θ, d_x, d_y).
  const double ratio = st.ratio, c = st.c, s = st.s;
  struct Component {
    double value;
    double derivative[5];
  };
  const Component x = {
      -force * ratio * s - tension * c + tension,
      {-ratio * s, 1.0 - c, -force * (st.ratio_theta * s + ratio * c) + tension * s,
       -force * s * st.ratio_dx, -force * s * st.ratio_dy}};
  const Component y = {force * ratio * c - tension * s - force,
                       {ratio * c - 1.0, -s, force * (st.ratio_theta * c - ratio * s) - tension * c,
                        force * c * st.ratio_dx, force * c * st.ratio_dy}};
  const int columns[5] = {st.q, st.p, st.theta, st.dx, st.dy};
  for (const auto& [end, sign] : {std::pair{a_, 1.0}, std::pair{b_, -1.0}})
    for (const auto& [row, component] : {std::pair{end.x, x}, std::pair{end.y, y}}) {
      if (row == ground) continue;
      sink.value(row, sign * component.value);
      for (int k = 0; k < 5; ++k) sink.derivative(row, columns[k], sign * component.derivative[k]);
    }
  // The end force's rows, f − (its part at rest + the rest): −(sign)·component.
  if (end_force_x < 0) return;
  const double sign = end_force_sign();
  for (const auto& [row, component] : {std::pair{end_force_x, x}, std::pair{end_force_x + 1, y}}) {
    sink.value(row, -sign * component.value);
    for (int k = 0; k < 5; ++k) sink.derivative(row, columns[k], -sign * component.derivative[k]);
  }
}

}  // namespace emnet
