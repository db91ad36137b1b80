// AC by the pole–residue form: see ac_pole_residue.hpp.
#include "ac_pole_residue.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>

#include "displacement_form.hpp"
#include "emnet/analysis/analysis.hpp"
#include "state_space.hpp"

namespace emnet {

namespace {
constexpr double two_pi = 6.283185307179586476925286766559;
using Complex = std::complex<double>;

// The state equation of the small signal about the operating point (of the network itself when
// it is linear), equilibrated at the sweep's top frequency (0: chosen from the pencil).
std::unique_ptr<LinearStateSpace> small_signal_space(const System& system,
                                                     const DisplacementForm& form,
                                                     const Eigen::VectorXd& operating_point,
                                                     const std::vector<double>& frequencies) {
  double top = 0.0;
  for (double f : frequencies) top = std::max(top, f);
  const double time_scale = two_pi * top;
  if (!system.is_nonlinear())
    return std::make_unique<LinearStateSpace>(form, form.a(), form.e(), time_scale);
  Eigen::SparseMatrix<double> d_u, d_up;
  const Eigen::VectorXd u = form.from_rest(operating_point);
  form.linearised(u, Eigen::VectorXd::Zero(form.size()), d_u, d_up);
  return std::make_unique<LinearStateSpace>(form, d_u, d_up, time_scale);
}

// The state equation x' = M·x + N·F with u = U·x + U_f·F, restricted where the form has
// hidden constraints.
struct RestrictedState {
  Eigen::MatrixXd state_matrix, u_of_state;
  Eigen::VectorXcd forcing;
};

// With hidden constraints (levers, Hc·x = 0 on every consistent state), the state is
// restricted to their null space, x = Q·z: Hc·M = 0 and Hc·N = 0 (their derivatives are
// rows of the form), so M maps into that space and the restricted M_r = Qᵀ·M·Q has the
// network's poles without the constraints' spurious ones at 0 (which would divide rounding
// by jω). False with the reason in `why_not` where that does not hold.
bool restrict_to_constraints(const LinearStateSpace& space, const Eigen::VectorXcd& full_forcing,
                             RestrictedState& state, std::string& why_not) {
  state.state_matrix = space.m();
  state.u_of_state = space.u_of_state();
  state.forcing = full_forcing;
  const Eigen::MatrixXd constraints = space.hidden_constraints_on_state();
  if (constraints.rows() == 0) return true;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(constraints.transpose());
  const Eigen::Index k = constraints.rows(), n = constraints.cols();
  if (qr.rank() != k) {
    why_not = "the levers' constraints are dependent";
    return false;
  }
  const Eigen::MatrixXd q = qr.householderQ();
  const Eigen::MatrixXd restriction = q.rightCols(n - k);
  const double scale = constraints.norm();
  if ((constraints * state.state_matrix).norm() > 1e-9 * scale * state.state_matrix.norm() ||
      (constraints * full_forcing).norm() > 1e-9 * scale * full_forcing.norm()) {
    why_not = "the state equation does not keep the levers' constraints";
    return false;
  }
  state.state_matrix = restriction.transpose() * state.state_matrix * restriction;
  state.u_of_state = state.u_of_state * restriction;
  state.forcing = restriction.transpose().cast<Complex>() * full_forcing;
  return true;
}

// A probe's residues, split into real and imaginary arrays so that the frequency loop
// vectorises.
struct ProbeTerms {
  std::vector<double> a_real, a_imag, b_real, b_imag;
  Complex direct_a, direct_b;  // (α + s·β)·U_f·F = direct_a + s·direct_b
};

// Each probe's residues on the poles of `basis` and its direct part.
std::vector<ProbeTerms> probe_terms(const DisplacementForm& form, const LinearStateSpace& space,
                                    const RestrictedState& state,
                                    const LinearStateSpace::ModalBasis& basis,
                                    const Eigen::VectorXd& f_real, const Eigen::VectorXd& f_imag,
                                    const std::vector<Probe>& probes) {
  // U_f·F by real and imaginary part.
  const Eigen::VectorXd no_state = Eigen::VectorXd::Zero(space.state_size());
  Eigen::VectorXd u_real, u_imag, unused;
  space.full_state(no_state, f_real, u_real, unused);
  space.full_state(no_state, f_imag, u_imag, unused);
  const Eigen::VectorXcd u_forced =
      u_real.cast<Complex>() + Complex(0.0, 1.0) * u_imag.cast<Complex>();
  const Eigen::VectorXcd r = basis.vectors_lu.solve(state.forcing);
  const Eigen::MatrixXcd modal_u = state.u_of_state.cast<Complex>() * basis.vectors;
  std::vector<ProbeTerms> terms(probes.size());
  Eigen::RowVectorXd on_u, on_up;
  for (size_t p = 0; p < probes.size(); ++p) {
    form.probe_rows(probes[p], on_u, on_up);
    const Eigen::RowVectorXcd a = (on_u.cast<Complex>() * modal_u).cwiseProduct(r.transpose());
    const Eigen::RowVectorXcd b = (on_up.cast<Complex>() * modal_u).cwiseProduct(r.transpose());
    ProbeTerms& t = terms[p];
    for (Eigen::Index k = 0; k < basis.values.size(); ++k) {
      t.a_real.push_back(a[k].real());
      t.a_imag.push_back(a[k].imag());
      t.b_real.push_back(b[k].real());
      t.b_imag.push_back(b[k].imag());
    }
    t.direct_a = on_u.cast<Complex>().dot(u_forced);
    t.direct_b = on_up.cast<Complex>().dot(u_forced);
  }
  return terms;
}

// p(jω) = Σ_k (a_k + jω·b_k)/(jω − λ_k) + its direct part at every frequency, into
// sweep.values.
void evaluate_sweep(const std::vector<ProbeTerms>& terms, const Eigen::VectorXcd& poles,
                    const std::vector<double>& frequencies, PoleResidueSweep& sweep) {
  const size_t count = static_cast<size_t>(poles.size());
  std::vector<double> pole_real(count), pole_imag(count);
  for (size_t k = 0; k < count; ++k) {
    pole_real[k] = poles[static_cast<Eigen::Index>(k)].real();
    pole_imag[k] = poles[static_cast<Eigen::Index>(k)].imag();
  }
  sweep.values.assign(terms.size(), std::vector<Complex>(frequencies.size()));
  std::vector<double> inverse_real(count), inverse_imag(count);
  for (size_t step = 0; step < frequencies.size(); ++step) {
    const double omega = two_pi * frequencies[step];
    // 1/(jω − λ) = (−Re λ − j(ω − Im λ)) / ((Re λ)² + (ω − Im λ)²).
    for (size_t k = 0; k < count; ++k) {
      const double x = -pole_real[k], y = omega - pole_imag[k];
      const double scale = 1.0 / (x * x + y * y);
      inverse_real[k] = x * scale;
      inverse_imag[k] = -y * scale;
    }
    for (size_t p = 0; p < terms.size(); ++p) {
      const ProbeTerms& t = terms[p];
      double a_re = 0.0, a_im = 0.0, b_re = 0.0, b_im = 0.0;
      for (size_t k = 0; k < count; ++k) {
        a_re += t.a_real[k] * inverse_real[k] - t.a_imag[k] * inverse_imag[k];
        a_im += t.a_real[k] * inverse_imag[k] + t.a_imag[k] * inverse_real[k];
        b_re += t.b_real[k] * inverse_real[k] - t.b_imag[k] * inverse_imag[k];
        b_im += t.b_real[k] * inverse_imag[k] + t.b_imag[k] * inverse_real[k];
      }
      const Complex s(0.0, omega);
      sweep.values[p][step] =
          Complex(a_re, a_im) + t.direct_a + s * (Complex(b_re, b_im) + t.direct_b);
    }
  }
}

}  // namespace

PoleResidueSweep pole_residue_sweep(const System& system, const Eigen::VectorXd& operating_point,
                                    const Eigen::SparseMatrix<double>& linearised_g_matrix,
                                    const std::vector<double>& frequencies,
                                    const std::vector<Probe>& probes) {
  PoleResidueSweep sweep;
  const Eigen::VectorXcd b_ac = system.b_ac();
  // A phasor on a row without an s⁰ part (a velocity source) has no displacement form.
  const RowClassification rows = classify_rows(system, linearised_g_matrix);
  for (Eigen::Index k = 0; k < b_ac.size(); ++k)
    if (rows.divided[static_cast<size_t>(k)] && b_ac[k] != 0.0) {
      sweep.why_not = "an AC source drives a velocity";
      return sweep;
    }
  try {
    const DisplacementForm form(system);
    const std::unique_ptr<LinearStateSpace> space =
        small_signal_space(system, form, operating_point, frequencies);
    // F = [b_ac; 0] in the displacement form's rows, by real and imaginary part.
    Eigen::VectorXd f_real = Eigen::VectorXd::Zero(form.size());
    Eigen::VectorXd f_imag = Eigen::VectorXd::Zero(form.size());
    f_real.head(system.size()) = b_ac.real();
    f_imag.head(system.size()) = b_ac.imag();
    const Eigen::VectorXcd full_forcing =
        space->forcing(f_real).cast<Complex>() +
        Complex(0.0, 1.0) * space->forcing(f_imag).cast<Complex>();
    RestrictedState state;
    if (!restrict_to_constraints(*space, full_forcing, state, sweep.why_not)) return sweep;
    LinearStateSpace::ModalBasis basis;
    const bool well_conditioned = LinearStateSpace::ModalBasis::of(state.state_matrix, basis);
    sweep.basis_condition = basis.condition;
    if (!well_conditioned) {
      sweep.why_not = "the state matrix's eigenvectors are ill-conditioned (κ > 1e6)";
      return sweep;
    }
    sweep.poles.assign(basis.values.data(), basis.values.data() + basis.values.size());
    evaluate_sweep(probe_terms(form, *space, state, basis, f_real, f_imag, probes), basis.values,
                   frequencies, sweep);
    for (const auto& series : sweep.values)
      for (const auto& v : series)
        if (!std::isfinite(v.real()) || !std::isfinite(v.imag())) {
          sweep.why_not = "a pole lies on the frequency grid";
          sweep.values.clear();
          return sweep;
        }
    sweep.applies = true;
  } catch (const std::exception& e) {
    sweep.why_not = e.what();
  }
  return sweep;
}

std::vector<size_t> pole_residue_check_points(const PoleResidueSweep& sweep,
                                              const std::vector<double>& frequencies,
                                              size_t pole_limit) {
  std::vector<size_t> points;
  if (frequencies.empty()) return points;
  points.push_back(0);
  points.push_back(frequencies.size() - 1);
  for (const auto& series : sweep.values) {
    // |z|² orders the values as |z| does, without a square root (or hypot) per value.
    size_t largest = 0;
    for (size_t k = 1; k < series.size(); ++k)
      if (std::norm(series[k]) > std::norm(series[largest])) largest = k;
    points.push_back(largest);
  }
  // The least damped oscillatory poles whose frequency lies in the grid's range.
  const auto [low, high] = std::minmax_element(frequencies.begin(), frequencies.end());
  std::vector<std::complex<double>> in_band;
  for (const auto& pole : sweep.poles) {
    const double f = pole.imag() / two_pi;
    if (pole.imag() > 0.0 && f >= *low && f <= *high) in_band.push_back(pole);
  }
  std::sort(in_band.begin(), in_band.end(), [](const auto& x, const auto& y) {
    return -x.real() / std::abs(x) < -y.real() / std::abs(y);
  });
  if (in_band.size() > pole_limit) in_band.resize(pole_limit);
  for (const auto& pole : in_band) {
    const double f = pole.imag() / two_pi;
    size_t nearest = 0;
    for (size_t k = 1; k < frequencies.size(); ++k)
      if (std::abs(frequencies[k] - f) < std::abs(frequencies[nearest] - f)) nearest = k;
    points.push_back(nearest);
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

}  // namespace emnet
