// Sensitivity of the resonance frequencies to the scene's parameters (issue 6, point 4).
//
// The poles s of the linearised network are the eigenvalues of the pencil
//     (G + J_g + s·C)·x = 0,        yᴴ·(G + J_g + s·C) = 0,
// with x the right and y the left eigenvector (analysis.hpp; J_g = ∂g/∂y at the operating
// point). A parameter p moves the matrices; first-order eigenvalue perturbation of a simple
// eigenvalue gives (J. H. Wilkinson, The Algebraic Eigenvalue Problem, 1965, §2.8–2.10;
// P. Lancaster, "On eigenvalues of matrices dependent on a parameter", Numer. Math. 6, 1964):
//
//     ds/dp = − yᴴ·(∂(G + J_g)/∂p + s·∂C/∂p)·x / (yᴴ·C·x)          [1/s per unit of p]
//
// x comes from run_modes; y from inverse iteration on the adjoint pencil at the known pole,
// (Ĝ + ŝĈ)ᴴ·ŷ = b, two steps with one sparse LU, on the equilibrated pencil
// (equilibration.hpp: y = diag(r)·ŷ). ∂G/∂p and ∂C/∂p are central differences of the network's
// matrices assembled from the scene at p·(1 ± δ), δ = 1e-6, each at its own operating point.
// Entries that are linear in p (ρA in the masses, lever arm in the coupling, 1/R) make this exact
// up to rounding, about ε/δ ≈ 1e-10 relative; entries that are not (l³/EI with l = L/N, the
// Kelvin–Voigt dampers τ/n) add a truncation error O(δ²) ≈ 1e-12.
//
// Frequencies (sign convention of Mode: Im s ≥ 0, Re s ≤ 0 for a damped mode):
//     damped  f_d = Im s / 2π:   df_d/dp = Im(ds/dp) / 2π
//     natural f_n = |s| / 2π:    df_n/dp = Re(s̄·ds/dp) / (2π·|s|)
//     normalised (dimensionless): S = (p/f)·df/dp, the % change of f per % change of p.
// Closed-form check: an undamped uniform beam has f ∝ √(EI/ρA)/L², and so has its lumped
// network for any N (stiffnesses ∝ EI/l³, masses ∝ ρA·l): S = +½ for EI, −½ for ρA, −2 for L.
//
// Reference check (`check`): the poles themselves re-computed at p·(1 ± h) and differenced
// centrally, with h = 1e-4 and 2h; Richardson's estimate |D(2h) − D(h)|/3 bounds the truncation
// error of D(h), and ε·|s|/h its rounding.
//
// With beam.kinematics = "large" the network is linearised about its deflected static state,
// found again at every step: ∂(G + J_g)/∂p then includes the state's own change (the
// geometric stiffness of a pre-bent beam moves with EI under dead loads), and the static
// state's Newton residual enters the difference as residual/δ.
//
// Parameters are the keys the parameter table marks `sensitivity` (emnet/scene/parameters.hpp:
// continuous parameters of the linearised network's matrices) that the scene uses, named as
// `--set` names them: "beam.bending_stiffness", "damping.loss_factor", "dea[A].lever_arm" (also
// "dea.A.lever_arm", or by index "dea.0.…").
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "emnet/analysis/analysis.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/core/progress.hpp"
#include "emnet/scene/scene.hpp"

namespace emnet {

struct SceneParameter {
  std::string key;   // canonical: "beam.length", "dea[A].lever_arm"
  std::string unit;  // SI unit of the value ("" for dimensionless)
  double value = 0.0;
};

// Every numeric parameter of the scene that enters the linearised network and is non-zero (a
// relative step of zero is none): beam, damping, DEA geometry and material, drive levels; the
// parameter table's sensitivity keys the scene uses, in the table's order.
std::vector<SceneParameter> scene_parameters(const Scene& scene);
// One parameter by key; throws OptionError (the field "parameters" of run_sensitivity, naming
// the key and listing the known ones) when the scene has no such parameter or its value is zero.
SceneParameter find_scene_parameter(const Scene& scene, const std::string& key);
// The scene with one parameter set to `value` (no validation: meant for small steps). A new
// beam.length stretches every position along the beam with it (DEA extents, probes, loads), so
// that a probe at the free end stays there: the derivative is that of a uniformly longer beam.
Scene with_parameter(const Scene& scene, const std::string& key, double value);

struct SensitivityOptions {
  int modes = 3;                       // the lowest oscillatory modes analysed
  double matrix_relative_step = 1e-6;  // δ of the matrices' central difference
  bool check = false;                  // also difference the poles themselves
  double check_relative_step = 1e-4;   // h of that check (and 2h for its error estimate)
  Progress* progress = nullptr;        // one report per parameter; cancelled: Status "cancelled"

  /// The checks of the options alone, as run_sensitivity makes them first.
  /// @throws OptionError naming "modes" (< 1) or a relative step outside (0, 1)
  void validate() const;
};

struct ModeSensitivity {
  std::complex<double> pole_derivative;       // ds/dp [1/s per unit of p]
  double frequency_derivative = 0.0;          // df_d/dp [Hz per unit of p]
  double natural_frequency_derivative = 0.0;  // df_n/dp [Hz per unit of p]
  double normalised = 0.0;                    // (p/f_d)·df_d/dp [-]
  double normalised_natural = 0.0;            // (p/f_n)·df_n/dp [-]
  // With `check`: the pole's central difference at h, and |ds/dp − ds/dp(FD)|·p/|s| (the
  // difference of the normalised pole sensitivities: dimensionless, defined for a zero one)
  // against the FD reference's estimated error in the same measure.
  std::complex<double> finite_difference_pole_derivative;
  double check_difference = 0.0;
  double check_error_estimate = 0.0;
};

struct ParameterSensitivity {
  SceneParameter parameter;
  std::vector<ModeSensitivity> modes;
};

struct SensitivityResult {
  Status status;
  std::vector<Mode> modes;  // the nominal modes analysed
  std::vector<ParameterSensitivity> parameters;
  // Largest ‖(Ĝ + ŝĈ)ᴴ·ŷ‖ / ((‖Ĝ‖ + |ŝ|·‖Ĉ‖)·‖ŷ‖) of the left eigenvectors (unit-free).
  double left_vector_residual = 0.0;
  double seconds = 0.0;            // everything
  double check_seconds = 0.0;      // of which the finite-difference check
  std::vector<std::string> notes;  // beam.kinematics = "auto": the choice, made once
};

// Sensitivities of the first options.modes oscillatory poles to the named parameters (all of
// scene_parameters() when `keys` is empty). Unknown keys throw InputError; numerical failure
// (no operating point of a nonlinear network, no modes, a failed factorisation) is a status.
SensitivityResult run_sensitivity(const Scene& scene, const std::vector<std::string>& keys,
                                  const SensitivityOptions& options = {});

}  // namespace emnet
