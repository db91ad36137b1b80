// The switching sweep's method and swept model: see switching_sweep_method.hpp.
#include "switching_sweep_method.hpp"

#include <algorithm>
#include <memory>
#include <utility>

#include "emnet/analysis/periodic.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/drive.hpp"
#include "emnet/model/outputs.hpp"

namespace emnet {

PrepareOptions served_by_the_sweep(const Scene& scene, PrepareOptions given,
                                   SwitchingSweepMethod method) {
  const bool asked = scene.beam.kinematics == BeamKinematics::large || scene.beam.kinematics_auto;
  if (asked && method != SwitchingSweepMethod::exact)
    given.large_kinematics = LargeKinematicsUse::dynamics;
  return given;
}

namespace {

// Whether the exact method serves the nonlinear `system` as a cascade (periodic.hpp
// exact_periodic_applies), within the dense limit; its solver made and kept in options.solver
// when it does (the sweep's decomposition, its time added to `decomposition_seconds`), else why
// not.
Status exact_cascade_serves(const System& system, SwitchingSweepOptions& options,
                            double& decomposition_seconds) {
  if (system.size() > options.dense_limit)
    return Status::failure("its " + std::to_string(system.size()) +
                           " unknowns are more than the dense limit of " +
                           std::to_string(options.dense_limit));
  if (Status applies = exact_periodic_applies(system); !applies.ok()) return applies;
  const Stopwatch stopwatch;
  auto solver = options.solver ? options.solver : std::make_shared<const PeriodicSolver>(system);
  const Status usable = solver->usable();
  decomposition_seconds += stopwatch.seconds();
  if (!usable.ok()) return usable;
  options.solver = std::move(solver);
  return Status::success();
}

// An automatic reduction's band (the sweep's highest frequency) and tolerance (model.tolerance),
// unless given.
void set_reduction_band(const Model& model, SwitchingSweepOptions& options) {
  if (options.reduction.band > 0.0) return;
  const std::vector<double> frequencies = switching_frequencies(options);
  options.reduction.band = *std::max_element(frequencies.begin(), frequencies.end());
  options.reduction.tolerance = model.scene.model.tolerance;
}

}  // namespace

SwitchingSweepOptions resolve_sweep_method(const Model& model, const SwitchingSweepOptions& given,
                                           std::vector<std::string>& notes,
                                           double& decomposition_seconds) {
  SwitchingSweepOptions options = given;
  if (options.method != SwitchingSweepMethod::automatic) return options;
  const System system = model.network.assemble();
  const bool large = model.scene.beam.kinematics == BeamKinematics::large;
  if (large && options.reduce)
    throw InputError(model.scene.file, "beam.kinematics",
                     "is \"large\": a nonlinear network, which the reduced (modal) periodic "
                     "method cannot solve; the shooting method (the automatic choice) can");
  if (system.is_nonlinear() && !options.reduce) {
    const std::string why = large                         ? "large kinematics"
                            : model.scene.circuit.empty() ? "the DEAs' RC loops"
                                                          : "DEAs driven through the [[circuit]]";
    const Status cascade = exact_cascade_serves(system, options, decomposition_seconds);
    if (cascade.ok()) {
      options.method = SwitchingSweepMethod::exact;
      notes.push_back(
          "method: exact cascade, since the network's only nonlinearity is the DEAs' "
          "force k_F·u² (" +
          why +
          "): the circuit's periodic state, its squared DEA voltages and the beam's "
          "response to them, each in closed form");
      return options;
    }
    if (!large && system.size() > options.dense_limit && exact_periodic_applies(system).ok()) {
      options.method = SwitchingSweepMethod::exact;
      options.reduce = true;
      set_reduction_band(model, options);
      notes.push_back(
          "method: reduced cascade, since the network's only nonlinearity is the "
          "DEAs' force k_F·u² (" +
          why + ") and its " + std::to_string(system.size()) + " unknowns are more than the " +
          std::to_string(options.dense_limit) +
          " up to which the exact cascade decomposes it densely; the modes below f_c, "
          "the beam's truncated part exact at the squared voltages' exponents but for "
          "its transients after each edge, checked below");
      return options;
    }
    options.method = SwitchingSweepMethod::shooting;
    notes.push_back("method: shooting, since the network is nonlinear (" + why +
                    (large ? "); the exact method needs a linear one, or a cascade"
                           : ") and the exact cascade does not serve it: " + cascade.message));
    return options;
  }
  options.method = SwitchingSweepMethod::exact;
  if (options.reduce || system.size() <= options.dense_limit) return options;
  options.reduce = true;
  set_reduction_band(model, options);
  notes.push_back(
      "method: reduced, since the network's " + std::to_string(system.size()) +
      " unknowns are more than the " + std::to_string(options.dense_limit) +
      " up to which the dense exact method is chosen (its time grows as the cube: it would " +
      "need about " + format_number("%.3g", periodic_memory_bytes(system.size()) / 1e9) +
      " GB); modes below f_c with a static correction, checked below");
  return options;
}

namespace {

// beam.kinematics = "auto" is chosen once, by the swept model: a model prepared per frequency
// (switched circuit sources) takes the same kinematics.
SweptModel with_kinematics_chosen(SweptModel swept) {
  swept.scene.beam.kinematics = swept.model.scene.beam.kinematics;
  swept.scene.beam.kinematics_auto = false;
  return swept;
}

}  // namespace

SweptModel prepare_swept_model(const Scene& scene, SwitchingSweepMethod method,
                               const std::vector<std::string>& probe_texts,
                               const PrepareOptions& prepare, double highest_hz) {
  // Large kinematics make the network nonlinear: shooting serves it, the exact method cannot.
  const bool large = scene.beam.kinematics == BeamKinematics::large;
  if (large && method == SwitchingSweepMethod::exact)
    throw InputError(scene.file, "beam.kinematics",
                     "is \"large\": a nonlinear network, which the exact periodic method cannot "
                     "solve; the shooting method (the automatic choice) can");
  SweptModel swept{prepare_model(scene, served_by_the_sweep(scene, prepare, method)), scene, {}};
  check_swept_drive(swept.model.scene);
  const bool built_large = swept.model.scene.beam.kinematics == BeamKinematics::large;
  if (method == SwitchingSweepMethod::shooting || built_large)
    return with_kinematics_chosen(std::move(swept));
  const bool automatic = method == SwitchingSweepMethod::automatic;
  // The network as built: the exact method serves it as a cascade where the DEAs' force is its
  // only nonlinearity (run_switching_sweep), keeping the RC loops and the circuit.
  const System built = swept.model.network.assemble();
  const bool nonlinear = built.is_nonlinear();
  const Status cascade = nonlinear ? exact_periodic_applies(built) : Status::success();
  const bool as_built = automatic || (nonlinear && cascade.ok());
  for (const auto& text : probe_texts)
    if (asks_for_dea_electrics(text)) {
      if (as_built)  // the RC loop is asked for: the exact cascade or shooting
        return with_kinematics_chosen(std::move(swept));
      throw OptionError("probe",
                        "the exact periodic method takes the DEAs' RC loop, whose voltage and "
                        "current this probe asks for, only as an exact cascade, which this "
                        "network is not (" +
                            cascade.message + "); use the shooting method",
                        text);
    }
  if (nonlinear && !swept.model.scene.circuit.empty() && as_built)
    return with_kinematics_chosen(std::move(swept));
  if (nonlinear && !swept.model.scene.circuit.empty())
    throw InputError(swept.model.scene.file, "circuit",
                     "the exact periodic method serves DEAs driven through a [[circuit]] as a "
                     "cascade only, which this network is not (" +
                         cascade.message + "); use the shooting method");
  if (nonlinear) {
    double tau = 0.0;
    for (const auto& dea : swept.model.deas)
      tau = std::max(tau, dea.electrode_resistance * dea.capacitance);
    swept.notes.push_back(
        "exact method: DEAs as ideal voltage-driven forces, the electrical model the scene "
        "gives them (drive.electrical_dynamics) set aside (their RC time constant " +
        format_with_unit(tau, "s") + " is " + format_number("%.2g", tau * highest_hz) +
        " of the shortest period); the shooting method integrates the full "
        "model");
    set_electrical_dynamics(swept.scene, false);
    swept.model = prepare_model(swept.scene, prepare);
    // The rebuilt model's own note would say the scene set it false; the note above says why.
    auto& notes = swept.model.notes;
    notes.erase(std::remove_if(notes.begin(), notes.end(),
                               [](const std::string& note) {
                                 return note.rfind("DEA electrical dynamics left out", 0) == 0;
                               }),
                notes.end());
  }
  return with_kinematics_chosen(std::move(swept));
}

}  // namespace emnet
