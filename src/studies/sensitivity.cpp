// Eigenvalue sensitivities to scene parameters; see include/emnet/studies/sensitivity.hpp.
#include "emnet/studies/sensitivity.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "analysis/left_eigenvector.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/studies/resolve.hpp"

namespace emnet {

namespace {

constexpr double two_pi = 6.283185307179586476925286766559;

// ---- parameters by key ----------------------------------------------------------------

// Every numeric parameter of `scene` that enters the linearised network, zero or not: the
// parameter table's sensitivity keys that the scene uses (emnet/scene/parameters.hpp), in the
// table's order, DEA by DEA.
std::vector<SceneParameterAddress> network_parameters(const Scene& scene) {
  std::vector<SceneParameterAddress> addresses;
  for (SceneParameterAddress& address : scene_numeric_parameters(scene))
    if (address.info->sensitivity) addresses.push_back(std::move(address));
  return addresses;
}

double value_of(const Scene& scene, const SceneParameterAddress& address) {
  return address.info->get(scene, address.entry).value_or(0.0);
}

SceneParameter parameter_of(const Scene& scene, const SceneParameterAddress& address) {
  return {address.key, parameter_unit(*address.info, scene, address.entry),
          value_of(scene, address)};
}

// The parameter `key` names ("dea.A.x", "dea[A].x", "dea.0.x", "dea[0].x" or a plain key).
SceneParameterAddress find_network_parameter(const Scene& scene, const std::string& key) {
  const std::vector<SceneParameterAddress> parameters = network_parameters(scene);
  try {
    const SceneParameterAddress named = find_scene_parameter_address(scene, key, "parameters");
    for (const SceneParameterAddress& parameter : parameters)
      if (parameter.key == named.key) return parameter;
  } catch (const InputError&) {
    // Not a key of this scene: said below with the keys it has.
  }
  std::string known;
  for (const SceneParameterAddress& parameter : parameters)
    if (value_of(scene, parameter) != 0.0) known += (known.empty() ? "" : ", ") + parameter.key;
  throw OptionError("parameters",
                    "not a numeric parameter of scene '" + scene.name + "'; known: " + known, key);
}

// ---- the linearised network of a scene --------------------------------------------------

struct Linearised {
  Status status;
  System system;  // shares its elements with the model it was assembled from
  Eigen::VectorXd operating_point;
  Eigen::SparseMatrix<double> g_matrix;  // G + J_g at the operating point
};

// As the program's modes: a linear network without a static state (a free body) is analysed
// about zero; a nonlinear one needs its operating point (with large kinematics the deflected
// static state, as the modes study).
Linearised linearise(const Scene& scene) {
  Linearised result;
  result.system = prepare_model(scene, serving_large_kinematics(LargeKinematicsUse::dynamics))
                      .network.assemble();
  const OperatingPoint point = operating_point(result.system);
  if (!point.status.ok()) {
    result.status = point.status;
    return result;
  }
  result.operating_point = point.rest.operating_point;
  result.g_matrix = linearised_g(result.system, result.operating_point);
  return result;
}

ModalResult modes_of(const Linearised& network, int count, bool keep_vectors) {
  ModalOptions options;
  options.keep_vectors = keep_vectors;
  if (network.system.size() > options.dense_limit) options.count = count + 2;
  return run_modes(network.system, network.operating_point, options);
}

void fill_frequencies(ModeSensitivity& sensitivity, std::complex<double> pole, double value) {
  const std::complex<double> ds = sensitivity.pole_derivative;
  sensitivity.frequency_derivative = ds.imag() / two_pi;
  sensitivity.natural_frequency_derivative =
      (std::conj(pole) * ds).real() / (two_pi * std::abs(pole));
  sensitivity.normalised = value * ds.imag() / pole.imag();
  sensitivity.normalised_natural = value * (std::conj(pole) * ds).real() / std::norm(pole);
}

}  // namespace

std::vector<SceneParameter> scene_parameters(const Scene& scene) {
  std::vector<SceneParameter> parameters;
  for (const SceneParameterAddress& address : network_parameters(scene))
    if (value_of(scene, address) != 0.0) parameters.push_back(parameter_of(scene, address));
  return parameters;
}

SceneParameter find_scene_parameter(const Scene& scene, const std::string& key) {
  const SceneParameterAddress address = find_network_parameter(scene, key);
  if (value_of(scene, address) == 0.0)
    throw OptionError("parameters",
                      "is 0 in scene '" + scene.name + "': a relative step is undefined", key);
  return parameter_of(scene, address);
}

Scene with_parameter(const Scene& scene, const std::string& key, double value) {
  Scene copy = scene;
  const SceneParameterAddress address = find_network_parameter(scene, key);
  if (address.key == "beam.length" && scene.beam.length > 0.0) {
    // Positions along the beam scale with it: a probe at the free end stays at the end.
    const double stretch = value / scene.beam.length;
    for (auto& dea : copy.deas) {
      dea.from *= stretch;
      dea.to *= stretch;
    }
    for (auto& probe : copy.probes) probe.at *= stretch;
    for (auto& load : copy.loads) load.at *= stretch;
    for (auto& section : copy.beam.sections) section.length *= stretch;
    for (auto& mass : copy.beam.masses) mass.at *= stretch;
    for (auto& spring : copy.beam.springs) {
      spring.at *= stretch;
      if (spring.to) *spring.to *= stretch;
    }
  }
  address.info->set(copy, address.entry, value);
  return copy;
}

void SensitivityOptions::validate() const {
  if (modes < 1) throw OptionError("modes", "must be >= 1");
  if (!(matrix_relative_step > 0.0 && matrix_relative_step < 1.0))
    throw OptionError("matrix_relative_step", "must be a relative step in (0, 1)");
  if (!(check_relative_step > 0.0 && check_relative_step < 1.0))
    throw OptionError("check_relative_step", "must be a relative step in (0, 1)");
}

namespace {

std::vector<SceneParameter> parameters_to_differentiate(const Scene& scene,
                                                        const std::vector<std::string>& keys) {
  if (keys.empty()) return scene_parameters(scene);
  std::vector<SceneParameter> parameters;
  for (const auto& key : keys) parameters.push_back(find_scene_parameter(scene, key));
  return parameters;
}

// Per mode, its left eigenvector y and the denominator yᴴ·C·x of the pole's derivative.
struct LeftEigenvectors {
  std::vector<Eigen::VectorXcd> vectors;
  std::vector<std::complex<double>> denominators;
};

// Once per mode; their largest residual into result.left_vector_residual.
Status find_left_eigenvectors(const Linearised& nominal, SensitivityResult& result,
                              LeftEigenvectors& lefts) {
  const Eigen::SparseMatrix<std::complex<double>> c_complex =
      nominal.system.C.cast<std::complex<double>>();
  LeftEigenSolver solver(nominal.g_matrix, nominal.system.C,
                         equilibrate_pencil(nominal.g_matrix, nominal.system.C));
  for (const Mode& mode : result.modes) {
    Eigen::MatrixXcd space;
    double residual = 0.0;
    std::string why;
    if (!solver.space(mode.pole, 1, space, residual, why)) return Status::failure(why);
    Eigen::VectorXcd left = space.col(0);
    result.left_vector_residual = std::max(result.left_vector_residual, residual);
    const std::complex<double> denominator = left.dot(c_complex * mode.vector);  // yᴴ·C·x
    if (!(std::abs(denominator) > 0.0) || !std::isfinite(std::abs(denominator)))
      return Status::failure("yᴴ·C·x vanishes: the pole is not simple");
    lefts.vectors.push_back(std::move(left));
    lefts.denominators.push_back(denominator);
  }
  return check_residual(result.left_vector_residual, "left eigenvector");
}

// ds/dp = -yᴴ·(dG/dp + s·dC/dp)·x / (yᴴ·C·x), with dG/dp and dC/dp by central differences of
// the assembled matrices at the relative step matrix_relative_step.
Status differentiate_the_poles(const Scene& scene, const Linearised& nominal,
                               const std::vector<Mode>& modes, const LeftEigenvectors& lefts,
                               const SensitivityOptions& options, ParameterSensitivity& entry) {
  const SceneParameter& parameter = entry.parameter;
  const double p = parameter.value;
  const double h = options.matrix_relative_step * std::abs(p);
  const Linearised up = linearise(with_parameter(scene, parameter.key, p + h));
  const Linearised down = linearise(with_parameter(scene, parameter.key, p - h));
  if (!up.status.ok() || !down.status.ok())
    return Status::failure(parameter.key +
                           " ± step: " + (up.status.ok() ? down.status : up.status).message);
  if (up.system.size() != nominal.system.size() || down.system.size() != nominal.system.size())
    return Status::failure(parameter.key + " changes the network's unknowns");
  const Eigen::SparseMatrix<std::complex<double>> dg =
      ((up.g_matrix - down.g_matrix) / (2.0 * h)).cast<std::complex<double>>();
  const Eigen::SparseMatrix<std::complex<double>> dc =
      ((up.system.C - down.system.C) / (2.0 * h)).cast<std::complex<double>>();
  for (size_t k = 0; k < modes.size(); ++k) {
    const Mode& mode = modes[k];
    ModeSensitivity sensitivity;
    const Eigen::VectorXcd perturbation = dg * mode.vector + mode.pole * (dc * mode.vector);
    sensitivity.pole_derivative = -lefts.vectors[k].dot(perturbation) / lefts.denominators[k];
    fill_frequencies(sensitivity, mode.pole, p);
    entry.modes.push_back(sensitivity);
  }
  return Status::success();
}

// Central differences of the poles at steps h and 2h (derivatives[0] and [1], per mode).
Status pole_differences(const Scene& scene, const SceneParameter& parameter, int wanted,
                        size_t mode_count, const SensitivityOptions& options,
                        std::vector<std::vector<std::complex<double>>>& derivatives) {
  const double p = parameter.value;
  for (double factor : {1.0, 2.0}) {
    const double step = factor * options.check_relative_step * std::abs(p);
    std::vector<std::vector<Mode>> sides;
    for (double sign : {+1.0, -1.0}) {
      const Linearised side = linearise(with_parameter(scene, parameter.key, p + sign * step));
      if (!side.status.ok()) return side.status;
      const ModalResult side_modes = modes_of(side, wanted, false);
      if (!side_modes.status.ok() || side_modes.modes.size() < mode_count)
        return Status::failure(parameter.key + " check: modes not found");
      sides.push_back(side_modes.modes);
    }
    std::vector<std::complex<double>> d;
    for (size_t k = 0; k < mode_count; ++k)
      d.push_back((sides[0][k].pole - sides[1][k].pole) / (2.0 * step));
    derivatives.push_back(d);
  }
  return Status::success();
}

// The derivatives against the poles' central differences, with an estimate of the error of
// those differences.
Status check_by_finite_differences(const Scene& scene, const std::vector<Mode>& modes, int wanted,
                                   const SensitivityOptions& options, ParameterSensitivity& entry) {
  const double p = entry.parameter.value;
  std::vector<std::vector<std::complex<double>>> derivatives;
  if (Status found =
          pole_differences(scene, entry.parameter, wanted, modes.size(), options, derivatives);
      !found.ok())
    return found;
  for (size_t k = 0; k < modes.size(); ++k) {
    ModeSensitivity& sensitivity = entry.modes[k];
    const double pole_size = std::abs(modes[k].pole);
    const double to_normalised = std::abs(p) / pole_size;
    sensitivity.finite_difference_pole_derivative = derivatives[0][k];
    sensitivity.check_difference =
        std::abs(sensitivity.pole_derivative - derivatives[0][k]) * to_normalised;
    // Truncation (Richardson) plus rounding: poles accurate to ~100ε relative (dense
    // eigen-decomposition), divided by the step 2h.
    const double truncation = std::abs(derivatives[1][k] - derivatives[0][k]) / 3.0;
    const double rounding = 100.0 * std::numeric_limits<double>::epsilon() * pole_size /
                            (2.0 * options.check_relative_step * std::abs(p));
    sensitivity.check_error_estimate = (truncation + rounding) * to_normalised;
  }
  return Status::success();
}

double seconds_since(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

SensitivityResult run_sensitivity(const Scene& given, const std::vector<std::string>& keys,
                                  const SensitivityOptions& options) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  SensitivityResult result;
  // One kinematics for the nominal scene and every step of it.
  const Scene scene = resolve_kinematics(given, LargeKinematicsUse::dynamics, &result.notes);
  auto finish = [&](Status status) {
    result.status = std::move(status);
    result.seconds = seconds_since(start);
    return result;
  };
  const std::vector<SceneParameter> parameters = parameters_to_differentiate(scene, keys);

  const Linearised nominal = linearise(scene);
  if (!nominal.status.ok()) return finish(nominal.status);
  const int wanted = std::max(options.modes, 1);
  const ModalResult modal = modes_of(nominal, wanted, true);
  if (!modal.status.ok()) return finish(modal.status.with_context("modes: "));
  if (modal.modes.empty()) return finish(Status::failure("the network has no oscillatory mode"));
  result.modes.assign(modal.modes.begin(),
                      modal.modes.begin() + std::min<size_t>(modal.modes.size(), wanted));
  LeftEigenvectors lefts;
  if (Status found = find_left_eigenvectors(nominal, result, lefts); !found.ok())
    return finish(found);

  double check_seconds = 0.0;
  for (const SceneParameter& parameter : parameters) {
    if (!keep_going(options.progress, static_cast<long>(result.parameters.size()),
                    static_cast<long>(parameters.size()), "parameters"))
      return finish(cancelled_status());
    ParameterSensitivity entry{parameter, {}};
    if (Status done = differentiate_the_poles(scene, nominal, result.modes, lefts, options, entry);
        !done.ok())
      return finish(done);
    if (options.check) {
      const auto check_start = std::chrono::steady_clock::now();
      if (Status checked = check_by_finite_differences(scene, result.modes, wanted, options, entry);
          !checked.ok())
        return finish(checked);
      check_seconds += seconds_since(check_start);
    }
    result.parameters.push_back(std::move(entry));
  }
  result.check_seconds = check_seconds;
  return finish(Status::success());
}

}  // namespace emnet
