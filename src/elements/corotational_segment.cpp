// Co-rotational segment: see include/emnet/elements/corotational_segment.hpp for the equations,
// signs and sources.
#include "emnet/elements/corotational_segment.hpp"

#include <cmath>
#include <stdexcept>

namespace emnet {

CoRotationalSegment::CoRotationalSegment(std::string name, End a, End b, double length,
                                         double transverse_compliance, double axial_compliance,
                                         double kelvin_voigt_time)
    : Element(std::move(name)),
      a_(a),
      b_(b),
      length_(length),
      transverse_compliance_(transverse_compliance),
      axial_compliance_(axial_compliance),
      kelvin_voigt_time_(kelvin_voigt_time) {
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
  std::vector<Unknown> unknowns = {
      {"dx_" + id, Unknown::Kind::branch_through, Domain::translational},
      {"dy_" + id, Unknown::Kind::branch_through, Domain::translational},
      {"th_" + id, Unknown::Kind::branch_through, Domain::rotational},
      {"F_" + id, Unknown::Kind::branch_through, Domain::translational},
      {"N_" + id, Unknown::Kind::branch_through, Domain::translational}};
  if (kelvin_voigt_time_ > 0.0)
    unknowns.push_back({"Q_" + id, Unknown::Kind::branch_through, Domain::translational});
  if (axial_branch() == total_axial_force)
    unknowns.push_back({"P_" + id, Unknown::Kind::branch_through, Domain::translational});
  return unknowns;
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
}

void CoRotationalSegment::add_nonlinear(const Eigen::VectorXd& y, int branch_offset,
                                        Eigen::VectorXd& g,
                                        std::vector<Eigen::Triplet<double>>* jacobian) const {
  const double l = length_;
  const int dx = branch_offset + chord_x, dy = branch_offset + chord_y;
  const int theta = branch_offset + chord_angle, n = branch_offset + axial_force;
  const int q = branch_offset + force_branch(), p = branch_offset + axial_branch();
  const double c = std::cos(y[theta]), s = std::sin(y[theta]);
  const double chord_x_length = l + y[dx], chord_y_length = y[dy];
  const double chord = c * chord_x_length + s * chord_y_length;    // ℓ
  const double normal = -s * chord_x_length + c * chord_y_length;  // h, zero on the chord
  const double force = y[q], tension = y[p];
  const double ratio = l / chord;  // l/ℓ
  // ∂ℓ/∂(θ, d_x, d_y) = (h, cos θ, sin θ); ∂(l/ℓ) = −(l/ℓ²)·∂ℓ.
  const double ratio_theta = -ratio / chord * normal, ratio_dx = -ratio / chord * c,
               ratio_dy = -ratio / chord * s;
  auto add = [&](int row, int column, double value) {
    if (jacobian && row != ground && column != ground) jacobian->emplace_back(row, column, value);
  };
  // The chord's angle: h − (−l·θ + d_y).
  g[theta] += normal + l * y[theta] - y[dy];
  add(theta, theta, l - chord);
  add(theta, dx, -s);
  add(theta, dy, c - 1.0);
  // The axial row: −(ℓ − l) + d_x.
  g[n] += -(chord - l) + y[dx];
  add(n, theta, -normal);
  add(n, dx, 1.0 - c);
  add(n, dy, -s);
  auto velocity = [&](NodeId node) { return node == ground ? 0.0 : y[node]; };
  const double dvx = velocity(b_.x) - velocity(a_.x), dvy = velocity(b_.y) - velocity(a_.y);
  const double normal_rate = -s * dvx + c * dvy;  // e₂·(v_b − v_a)
  // The axial damper's share of P: −(τ/n_A)·(e₁·(v_b − v_a) − (v_bx − v_ax)).
  if (p != n) {
    const double damper = kelvin_voigt_time_ / axial_compliance_;
    g[p] += -damper * (c * dvx + s * dvy - dvx);
    add(p, b_.x, -damper * (c - 1.0));
    add(p, a_.x, damper * (c - 1.0));
    add(p, b_.y, -damper * s);
    add(p, a_.y, damper * s);
    add(p, theta, -damper * normal_rate);
  }
  // The transverse damper's share of Q: (τ/n_T)·(l·θ' − (v_by − v_ay)), l·θ' = (l/ℓ)·e₂·(v_b −
  // v_a).
  if (kelvin_voigt_time_ > 0.0) {
    const double damper = kelvin_voigt_time_ / transverse_compliance_;
    g[q] += damper * (ratio * normal_rate - dvy);
    add(q, b_.x, -damper * ratio * s);
    add(q, a_.x, damper * ratio * s);
    add(q, b_.y, damper * (ratio * c - 1.0));
    add(q, a_.y, -damper * (ratio * c - 1.0));
    add(q, theta, damper * (ratio_theta * normal_rate + ratio * (-c * dvx - s * dvy)));
    add(q, dx, damper * ratio_dx * normal_rate);
    add(q, dy, damper * ratio_dy * normal_rate);
  }
  // The force on end a, f_a = Q·(l/ℓ)·e₂ − P·e₁, less its part at rest (−P, Q); end b the opposite.
  const double fx = -force * ratio * s - tension * c + tension;
  const double fy = force * ratio * c - tension * s - force;
  const double fx_q = -ratio * s, fx_n = 1.0 - c;
  const double fx_theta = -force * (ratio_theta * s + ratio * c) + tension * s;
  const double fx_dx = -force * s * ratio_dx, fx_dy = -force * s * ratio_dy;
  const double fy_q = ratio * c - 1.0, fy_n = -s;
  const double fy_theta = force * (ratio_theta * c - ratio * s) - tension * c;
  const double fy_dx = force * c * ratio_dx, fy_dy = force * c * ratio_dy;
  for (const auto& [end, sign] : {std::pair{a_, 1.0}, std::pair{b_, -1.0}}) {
    if (end.x != ground) {
      g[end.x] += sign * fx;
      add(end.x, q, sign * fx_q);
      add(end.x, p, sign * fx_n);
      add(end.x, theta, sign * fx_theta);
      add(end.x, dx, sign * fx_dx);
      add(end.x, dy, sign * fx_dy);
    }
    if (end.y != ground) {
      g[end.y] += sign * fy;
      add(end.y, q, sign * fy_q);
      add(end.y, p, sign * fy_n);
      add(end.y, theta, sign * fy_theta);
      add(end.y, dx, sign * fy_dx);
      add(end.y, dy, sign * fy_dy);
    }
  }
}

}  // namespace emnet
