// Design studies (emnet/studies/design_study.hpp): the analyses of each variant and their columns,
// run on a pool of threads, one row per variant (the variant table: design_study_variants.cpp).
#include "emnet/studies/design_study.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <thread>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/modal_reduction.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/deformed_shape.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/switching_sweep.hpp"
#include "option_parameter.hpp"

namespace emnet {

namespace {

std::string unit_suffix(const std::string& unit) {
  return unit.empty() ? std::string() : "_" + unit;
}

std::string frequency_label(double hz) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", hz);
  return text;
}

// The row's values for the analyses: filled per analysis in column order.
struct ColumnLayout {
  std::vector<std::string> columns, units;
  std::vector<Probe> static_probes;
  std::vector<Probe> sweep_outputs;
  std::vector<double> sweep_frequencies;
  std::vector<std::size_t> report_indices;  // into sweep_frequencies
  // The sweep by the reduced cascade, checked on the nominal scene (choose_the_sweep_method).
  bool sweep_reduced = false;
  double sweep_tolerance = 0.0;   // model.tolerance of the nominal scene
  int sweep_last_request = 0;     // the nominal reduction's useful request, where it hit a cluster
  int sweep_arnoldi_request = 0;  // and the Arnoldi run's own request there
};

// A cascade (the DEAs driven through a [[circuit]]) with more unknowns than this has its sweep
// reduced in a study where the reduction's extremes meet the tolerance on the nominal scene: the
// exact cascade's dense decomposition is O(n³) per variant (about 50 ms of the tweezer jaw's 72 ms
// at 222 unknowns), the reduction O(n) (about 10 ms).
constexpr int kStudyReducedCascadeUnknowns = 150;

// The reduction of a variant's sweep: the band up to the sweep's highest frequency, at the
// nominal scene's tolerance.
ReductionOptions study_sweep_reduction(const ColumnLayout& layout) {
  ReductionOptions reduction;
  reduction.band = layout.sweep_frequencies.back();
  reduction.tolerance = layout.sweep_tolerance;
  reduction.last_request = layout.sweep_last_request;
  reduction.arnoldi_request = layout.sweep_arnoldi_request;
  return reduction;
}

bool has(const std::vector<StudyAnalysis>& analyses, StudyAnalysis analysis) {
  return std::find(analyses.begin(), analyses.end(), analysis) != analyses.end();
}

// What the study's analyses do with large kinematics: the static state alone takes any beam;
// modes (about the deflected state) and the sweep (by shooting) need the dynamics' EA.
PrepareOptions study_prepare_options(const DesignStudyOptions& options) {
  const bool dynamics = has(options.analyses, StudyAnalysis::modes) ||
                        has(options.analyses, StudyAnalysis::switching_sweep);
  return serving_large_kinematics(dynamics ? LargeKinematicsUse::dynamics
                                           : LargeKinematicsUse::static_state);
}

// One variant's network and what its analyses append to: `values` in the layout's order, the
// deflections the validity check judges.
struct VariantRun {
  const Model& model;
  const System& system;
  const OperatingPoint& op;
  const ColumnLayout& layout;
  const DesignStudyOptions& options;
  const PrepareOptions& prepare;
  std::vector<double>& values;
  std::vector<DeflectionPeak> deflections;
  std::optional<RotationPeak> rotation;  // the largest the analyses computed
};

// f<k>_hz, zeta<k>, f<k>_error_hz of the lowest mode_count modes.
Status append_modes(VariantRun& run) {
  ModalOptions modal;
  modal.count = run.options.mode_count;
  modal.keep_vectors = false;
  const ModalResult result = run_modes(run.system, run.op.rest.operating_point, modal);
  if (!result.status.ok()) return result.status.with_context("modes: ");
  if (result.modes.size() < static_cast<std::size_t>(run.options.mode_count))
    return Status::failure("modes: " + std::to_string(result.modes.size()) +
                           " oscillatory mode(s) found, " + std::to_string(run.options.mode_count) +
                           " asked");
  for (int k = 0; k < run.options.mode_count; ++k) {
    const Mode& mode = result.modes[static_cast<std::size_t>(k)];
    if (!mode.error_bounded)
      return Status::failure("modes: the rounding error of mode " + std::to_string(k + 1) +
                             " cannot be bounded: " + mode.unbounded_reason);
    run.values.push_back(mode.frequency_hz);
    run.values.push_back(mode.damping_ratio);
    run.values.push_back(mode.pole_error / (2.0 * M_PI));
  }
  return Status::success();
}

// static.<probe> of every probe.
void append_static(VariantRun& run) {
  for (const Probe& probe : run.layout.static_probes) {
    run.values.push_back(static_probe_value(run.system, run.op.rest, probe));
    if (probe.quantity == ProbeQuantity::deflection)
      run.deflections.push_back({probe.name + " (static)", std::abs(run.values.back())});
  }
  const RotationProbes rotations = rotation_probes(run.model);
  std::vector<double> peaks;
  for (const Probe& probe : rotations.probes)
    peaks.push_back(std::abs(static_probe_value(run.system, run.op.rest, probe)));
  run.rotation = larger_rotation(run.rotation, largest_rotation(rotations, peaks));
}

// sweep.peak_hz, then each output's extremes at the reported frequencies. As `emnet
// sweep-switching` chooses (SwitchingSweepMethod::automatic): the exact method's model, the DEAs
// as ideal voltage-driven forces, where the scene has their electrical model through [drive];
// the model as it is where a [[circuit]] drives them (the nominal scene passed
// prepare_swept_model's checks in column_layout): the exact cascade, or shooting where it does
// not serve (back-coupling), and shooting with large kinematics.
Status append_sweep(VariantRun& run) {
  const Model& model = run.model;
  const ColumnLayout& layout = run.layout;
  std::optional<Model> ideal;
  if (run.system.is_nonlinear() && model.scene.circuit.empty() &&
      model.scene.beam.kinematics != BeamKinematics::large) {
    Scene ideal_scene = model.scene;
    set_electrical_dynamics(ideal_scene, false);
    ideal = prepare_model(ideal_scene, run.prepare);
  }
  const Model& swept = ideal ? *ideal : model;
  // The sweep peak needs the last output at every frequency; the other outputs are columns at
  // the reported frequencies only: two runs, each solving what its columns need.
  SwitchingSweepOptions sweep;
  sweep.frequencies = layout.sweep_frequencies;
  sweep.samples = run.options.sweep_samples;
  sweep.extremes_only = true;  // the columns are extremes (left, right) and the peak
  sweep.outputs = {layout.sweep_outputs.back()};
  sweep.first_mode = false;
  if (layout.sweep_reduced && !ideal) {  // checked on the nominal scene
    sweep.reduce = true;
    sweep.reduction = study_sweep_reduction(layout);
    sweep.check_reduction = false;
  }
  const SwitchingSweepResult peak = run_switching_sweep(swept, swept.scene, sweep);
  if (!peak.status.ok()) return peak.status.with_context("sweep-switching: ");
  run.values.push_back(peak.peak_frequency);
  if (layout.sweep_outputs.back().quantity == ProbeQuantity::deflection) {
    double largest = 0.0;  // over every frequency of the sweep
    for (std::size_t k = 0; k < peak.frequencies.size(); ++k)
      largest = std::max(
          {largest, std::abs(peak.outputs[0].left[k]), std::abs(peak.outputs[0].right[k])});
    run.deflections.push_back({layout.sweep_outputs.back().name + " (sweep)", largest});
  }
  if (peak.validity.largest_rotation > 0.0)  // at the sweep's peak (switching_sweep.cpp)
    run.rotation = larger_rotation(run.rotation,
                                   RotationPeak{"the sweep peak", peak.validity.largest_rotation});
  if (layout.report_indices.empty()) return Status::success();
  sweep.frequencies.clear();
  for (std::size_t index : layout.report_indices)
    sweep.frequencies.push_back(layout.sweep_frequencies[index]);
  sweep.outputs = layout.sweep_outputs;
  sweep.solver = peak.solver;  // one decomposition (or reduction) per variant
  sweep.reduced_solver = peak.reduced_solver;
  sweep.largest_rotation = false;  // taken from the first run's validity above
  const SwitchingSweepResult at = run_switching_sweep(swept, swept.scene, sweep);
  if (!at.status.ok()) return at.status.with_context("sweep-switching: ");
  for (const SwitchingSweepOutput& output : at.outputs)
    for (std::size_t k = 0; k < layout.report_indices.size(); ++k) {
      run.values.push_back(output.left[k]);
      run.values.push_back(output.right[k]);
      if (output.probe.quantity == ProbeQuantity::deflection)
        run.deflections.push_back({output.probe.name + " (sweep)",
                                   std::max(std::abs(output.left[k]), std::abs(output.right[k]))});
    }
  return Status::success();
}

// The analyses of one variant, appending to `values` in the layout's order.
Status run_analyses(const Scene& scene, const ColumnLayout& layout,
                    const DesignStudyOptions& options, std::vector<double>& values,
                    Validity& validity, VariantCost& cost) {
  Stopwatch stopwatch;
  const PrepareOptions prepare = study_prepare_options(options);
  const Model model = prepare_model(scene, prepare);
  const System system = model.network.assemble();
  cost.build += stopwatch.seconds();
  stopwatch.restart();
  OperatingPointOptions op_options;
  op_options.require_static = has(options.analyses, StudyAnalysis::static_state);
  const OperatingPoint op = operating_point(system, op_options);
  cost.operating_point += stopwatch.seconds();
  if (!op.status.ok()) return op.status;
  VariantRun run{model, system, op, layout, options, prepare, values, {}, {}};
  for (StudyAnalysis analysis : options.analyses) {
    stopwatch.restart();
    if (analysis == StudyAnalysis::modes) {
      const Status done = append_modes(run);
      cost.modes += stopwatch.seconds();
      if (!done.ok()) return done;
    } else if (analysis == StudyAnalysis::static_state) {
      append_static(run);
      cost.static_state += stopwatch.seconds();
    } else {
      if (const Status done = append_sweep(run); !done.ok()) return done;
      cost.sweep += stopwatch.seconds();
    }
  }
  for (double value : values)
    if (!std::isfinite(value)) return Status::failure("a result is not finite");
  validity =
      check_validity(model.scene, run.deflections, drive_peak_voltages(model.scene), run.rotation);
  return Status::success();
}

ColumnLayout column_layout(const Model& model, const DesignStudyOptions& options,
                           const PrepareOptions& prepare) {
  ColumnLayout layout;
  for (StudyAnalysis analysis : options.analyses) {
    if (analysis == StudyAnalysis::modes) {
      for (int k = 1; k <= options.mode_count; ++k) {
        const std::string n = std::to_string(k);
        layout.columns.insert(layout.columns.end(),
                              {"f" + n + "_hz", "zeta" + n, "f" + n + "_error_hz"});
        layout.units.insert(layout.units.end(), {"Hz", "", "Hz"});
      }
    } else if (analysis == StudyAnalysis::static_state) {
      layout.static_probes = model.probes;
      for (const Probe& probe : model.probes) {
        layout.columns.push_back("static." + probe.name + unit_suffix(probe.unit));
        layout.units.push_back(probe.unit);
      }
    } else {
      check_swept_drive(model.scene);
      SwitchingSweepOptions defaults;
      if (options.sweep_frequencies.empty()) {
        layout.sweep_frequencies = switching_frequencies(defaults);
      } else {
        defaults.frequencies = options.sweep_frequencies;
        layout.sweep_frequencies = switching_frequencies(defaults);
      }
      for (double f : options.report_frequencies) {
        auto found = std::find_if(layout.sweep_frequencies.begin(), layout.sweep_frequencies.end(),
                                  [f](double g) { return std::abs(g - f) <= 1e-12 * f; });
        if (found == layout.sweep_frequencies.end()) layout.sweep_frequencies.push_back(f);
      }
      std::sort(layout.sweep_frequencies.begin(), layout.sweep_frequencies.end());
      for (double f : options.report_frequencies)
        layout.report_indices.push_back(static_cast<std::size_t>(
            std::find_if(layout.sweep_frequencies.begin(), layout.sweep_frequencies.end(),
                         [f](double g) { return std::abs(g - f) <= 1e-12 * f; }) -
            layout.sweep_frequencies.begin()));
      layout.sweep_outputs =
          switching_sweep_outputs(prepare_swept_model(model.scene, SwitchingSweepMethod::automatic,
                                                      {}, prepare, layout.sweep_frequencies.back())
                                      .model,
                                  {});
      layout.columns.push_back("sweep.peak_hz");
      layout.units.push_back("Hz");
      for (const Probe& output : layout.sweep_outputs)
        for (std::size_t index : layout.report_indices) {
          const std::string at = "_at_" + frequency_label(layout.sweep_frequencies[index]) + "Hz";
          layout.columns.push_back("sweep." + output.name + ".min" + at + unit_suffix(output.unit));
          layout.columns.push_back("sweep." + output.name + ".max" + at + unit_suffix(output.unit));
          layout.units.insert(layout.units.end(), {output.unit, output.unit});
        }
    }
  }
  return layout;
}

}  // namespace

void DesignStudyOptions::validate() const {
  if (analyses.empty())
    throw OptionError("analyses", "no analysis asked (modes, static, sweep-switching)");
  if (mode_count < 1 || mode_count > 100) throw OptionError("mode_count", "must be from 1 to 100");
  if (threads < 0 || threads > 1024)
    throw OptionError("threads", "must be from 1 to 1024 (0: every core)");
  if (report_frequencies.size() > 1000)
    throw OptionError("report_frequencies", "at most 1000 reported frequencies");
  for (double f : report_frequencies)
    if (!(f > 0.0) || !std::isfinite(f))
      throw OptionError("report_frequencies", "a reported frequency must be > 0 Hz");
}

namespace {

// A key that no variant can set (beam.bending_stiffness on a beam of [[section]]s) is an input
// error, not a study of failed rows: tried on the nominal scene with its own value.
void refuse_a_key_no_variant_can_set(const Scene& nominal, const SceneParameterAddress& address) {
  const NumericUse use = numeric_use(nominal, address);
  if (use.code == NumericUseCode::not_set) return;  // no nominal value: the rows decide
  if (!use.usable()) throw OptionError("variations", use.reason, address.key);
}

void refuse_a_table_that_does_not_fit(const VariantTable& table) {
  if (table.rows.size() > kMaxVariants)
    throw OptionError("variants", std::to_string(table.rows.size()) + " variants; at most " +
                                      std::to_string(kMaxVariants) + " in one study");
  for (const auto& row : table.rows)
    if (row.size() != table.keys.size())
      throw std::invalid_argument("run_design_study: a variant's values do not match its keys");
}

// The nominal scene, with the mesh and the kinematics resolved once for every variant; the keys'
// units in `result`.
Scene prepare_the_nominal_scene(const Scene& scene, const VariantTable& table,
                                const DesignStudyOptions& options, DesignStudyResult& result) {
  Scene nominal = resolve_segments(scene);
  if (scene.beam.auto_segments)
    result.notes.push_back("beam.segments = \"auto\" was resolved once, on the nominal scene: " +
                           std::to_string(nominal.beam.segments) + " segments for every variant");
  const std::size_t before = result.notes.size();
  nominal =
      resolve_kinematics(nominal, study_prepare_options(options).large_kinematics, &result.notes);
  if (result.notes.size() > before)
    result.notes.back() += " (chosen once, on the nominal scene, for every variant)";
  for (const std::string& key : table.keys) {
    const SceneParameterAddress address = find_option_parameter(nominal, key, "variations");
    result.key_units.push_back(parameter_unit(*address.info, nominal, address.entry));
    refuse_a_key_no_variant_can_set(nominal, address);
  }
  return nominal;
}

// Whether the variants' sweep is the reduced cascade: for a cascade above
// kStudyReducedCascadeUnknowns whose reduced sweep's extremes (the study's columns) meet the
// tolerance against the exact cascade's on the nominal scene, at every sweep frequency.
void choose_the_sweep_method(const Model& nominal, const DesignStudyOptions& options,
                             ColumnLayout& layout, DesignStudyResult& result) {
  layout.sweep_tolerance = nominal.scene.model.tolerance;
  if (!has(options.analyses, StudyAnalysis::switching_sweep) || nominal.scene.circuit.empty() ||
      nominal.scene.beam.kinematics == BeamKinematics::large)
    return;
  const System system = nominal.network.assemble();
  if (system.size() <= kStudyReducedCascadeUnknowns || !system.is_nonlinear() ||
      !exact_periodic_applies(system).ok())
    return;
  SwitchingSweepOptions sweep;
  sweep.frequencies = layout.sweep_frequencies;
  sweep.samples = options.sweep_samples;
  sweep.extremes_only = true;
  sweep.outputs = layout.sweep_outputs;
  sweep.first_mode = false;
  sweep.largest_rotation = false;
  const SwitchingSweepResult exact = run_switching_sweep(nominal, nominal.scene, sweep);
  if (!exact.status.ok() || exact.method != Method::exact) return;
  sweep.reduce = true;
  sweep.reduction = study_sweep_reduction(layout);
  sweep.check_reduction = false;
  const SwitchingSweepResult reduced = run_switching_sweep(nominal, nominal.scene, sweep);
  const std::string size = std::to_string(system.size()) + " unknowns";
  if (!reduced.status.ok()) {
    result.notes.push_back(
        "sweep-switching: the exact cascade for every variant (" + size +
        "); the reduced cascade failed on the nominal scene: " + reduced.status.message);
    return;
  }
  const double difference = extremes_difference(reduced, exact);
  const std::string measured =
      "its extremes differ from the exact cascade's by " + format_number("%.2g", difference) +
      " (of each output's largest) on the nominal scene at all " +
      std::to_string(layout.sweep_frequencies.size()) + " frequencies, tolerance " +
      format_number("%.3g", layout.sweep_tolerance) + " (model.tolerance)";
  if (!(difference <= layout.sweep_tolerance)) {
    result.notes.push_back("sweep-switching: the exact cascade for every variant (" + size +
                           "), since the reduced cascade does not meet the tolerance: " + measured);
    return;
  }
  layout.sweep_reduced = true;
  const ModalReduction& model = reduced.reduced_solver->reduction();
  // Where the nominal's pole search ran into a cluster, the variants ask no more than the request
  // that found its last pole.
  if (!model.all_found) {
    layout.sweep_last_request = model.useful_request;
    layout.sweep_arnoldi_request = model.useful_arnoldi_request;
  }
  result.notes.push_back(
      "sweep-switching: the reduced cascade for every variant (" + size + ": " +
      std::to_string(model.kept_modes) + " modes and " + std::to_string(model.kept_real_poles) +
      " real poles kept, the rest exact but for its transients after each edge): " + measured +
      "; the variants' reductions are not checked one by one" +
      (layout.sweep_last_request > 0
           ? ", and their pole search stops at the request that found the nominal's last pole (" +
                 std::to_string(layout.sweep_last_request) +
                 " modes; a larger one ran into a cluster), its Arnoldi run asking for the " +
                 std::to_string(layout.sweep_arnoldi_request) + " poles the nominal's ended with"
           : ""));
}

ColumnLayout lay_out_the_columns(const Scene& nominal, const DesignStudyOptions& options,
                                 DesignStudyResult& result) {
  const PrepareOptions prepare = study_prepare_options(options);
  const Model nominal_model = prepare_model(nominal, prepare);
  result.unknowns = static_cast<int>(nominal_model.network.assemble().size());
  result.segments = nominal.beam.segments;
  ColumnLayout layout = column_layout(nominal_model, options, prepare);
  choose_the_sweep_method(nominal_model, options, layout, result);
  result.columns = layout.columns;
  result.units = layout.units;
  return layout;
}

unsigned thread_count(const DesignStudyOptions& options, std::size_t count) {
  const unsigned threads = options.threads > 0 ? static_cast<unsigned>(options.threads)
                                               : std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(count, 1)));
}

// One variant: the nominal scene with its row's values set, then the analyses; a row that
// failed keeps no values.
void run_one_variant(const Scene& nominal, const VariantTable& table, std::size_t index,
                     const ColumnLayout& layout, const DesignStudyOptions& options,
                     VariantResult& row) {
  try {
    Scene variant = nominal;
    const Stopwatch set_watch;
    for (std::size_t k = 0; k < table.keys.size(); ++k)
      set_parameter(variant, table.keys[k], table.rows[index][k]);
    row.cost.build += set_watch.seconds();
    row.status = run_analyses(variant, layout, options, row.values, row.validity, row.cost);
  } catch (const std::exception& error) {
    row.status = Status::failure(error.what());
  }
  if (!row.status.ok()) row.values.clear();
}

// The variants on a pool of threads, each taking the next row not taken.
class VariantPool {
 public:
  VariantPool(const Scene& nominal, const VariantTable& table, const ColumnLayout& layout,
              const DesignStudyOptions& options, std::vector<VariantResult>& rows)
      : nominal_(nominal), table_(table), layout_(layout), options_(options), rows_(rows) {}

  void run(unsigned threads) {
    std::vector<std::thread> pool;
    for (unsigned k = 1; k < threads; ++k) pool.emplace_back([this] { work(); });
    if (options_.progress == nullptr) {
      work();
    } else {
      // The calling thread reports and asks for cancellation (a Progress may see it only there:
      // Python runs its signal handlers on its main thread); a worker of its own does the
      // calling thread's share.
      pool.emplace_back([this] { work(); });
      report_until_done();
    }
    for (auto& thread : pool) thread.join();
  }

 private:
  void work() {
    const std::size_t count = rows_.size();
    for (;;) {
      const std::size_t index = next_.fetch_add(1);
      if (index >= count) return;
      VariantResult& row = rows_[index];
      if (cancel_requested(options_.progress)) {
        row.status = cancelled_status();
      } else {
        run_one_variant(nominal_, table_, index, layout_, options_, row);
        computed_.fetch_add(1);
      }
      if (done_.fetch_add(1) + 1 == count) {
        const std::lock_guard<std::mutex> lock(finished_mutex_);
        finished_.notify_all();
      }
    }
  }

  void report_until_done() {
    const std::size_t count = rows_.size();
    for (int tick = 0; done_.load() < count; ++tick) {
      if (tick % 10 == 0)
        options_.progress->report(static_cast<long>(computed_.load()), static_cast<long>(count),
                                  "variants");
      static_cast<void>(options_.progress->cancelled());
      // Woken by the last row, so that a short study does not wait out a tick.
      std::unique_lock<std::mutex> lock(finished_mutex_);
      finished_.wait_for(lock, std::chrono::milliseconds(10),
                         [&] { return done_.load() == count; });
    }
    options_.progress->report(static_cast<long>(computed_.load()), static_cast<long>(count),
                              "variants");
  }

  const Scene& nominal_;
  const VariantTable& table_;
  const ColumnLayout& layout_;
  const DesignStudyOptions& options_;
  std::vector<VariantResult>& rows_;
  // `done_`: rows taken and finished; `computed_`: of those, the ones not skipped by a
  // cancellation (what the progress reports).
  std::atomic<std::size_t> next_{0}, done_{0}, computed_{0};
  std::mutex finished_mutex_;
  std::condition_variable finished_;
};

void count_the_failures_and_add_the_costs(DesignStudyResult& result) {
  for (const VariantResult& row : result.rows) {
    if (!row.status.ok()) ++result.failed;
    if (row.status.ok() && !row.validity.within()) ++result.outside_validity;
    result.cost.build += row.cost.build;
    result.cost.operating_point += row.cost.operating_point;
    result.cost.modes += row.cost.modes;
    result.cost.static_state += row.cost.static_state;
    result.cost.sweep += row.cost.sweep;
  }
}

}  // namespace

DesignStudyResult run_design_study(const Scene& scene, const VariantTable& table,
                                   const DesignStudyOptions& options) {
  const Stopwatch stopwatch;
  options.validate();
  refuse_a_table_that_does_not_fit(table);
  DesignStudyResult result;
  result.keys = table.keys;
  result.variants = table.rows;
  const Scene nominal = prepare_the_nominal_scene(scene, table, options, result);
  const ColumnLayout layout = lay_out_the_columns(nominal, options, result);
  result.rows.assign(table.rows.size(), VariantResult{});
  const unsigned threads = thread_count(options, table.rows.size());
  result.threads = static_cast<int>(threads);
  VariantPool(nominal, table, layout, options, result.rows).run(threads);
  count_the_failures_and_add_the_costs(result);
  result.seconds = stopwatch.seconds();
  return result;
}

}  // namespace emnet
