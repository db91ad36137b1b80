// Design studies (emnet/studies/design_study.hpp): variants of a scene's numeric keys, run on a
// pool of threads, one row per variant.
#include "emnet/studies/design_study.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <random>
#include <sstream>
#include <thread>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/operating_point.hpp"
#include "emnet/analysis/periodic.hpp"
#include "emnet/core/bounded_file.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/stopwatch.hpp"
#include "emnet/core/terminal_text.hpp"
#include "emnet/core/units.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "emnet/studies/switching_sweep.hpp"
#include "option_parameter.hpp"

namespace emnet {

namespace {

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  const auto end = text.find_last_not_of(" \t\r\n");
  return text.substr(begin, end - begin + 1);
}

std::vector<std::string> split(const std::string& text, const std::string& separators) {
  std::vector<std::string> parts;
  std::string part;
  for (char c : text) {
    if (separators.find(c) != std::string::npos) {
      parts.push_back(trim(part));
      part.clear();
    } else {
      part += c;
    }
  }
  parts.push_back(trim(part));
  return parts;
}

// A number, a quantity of the key's dimension, or a percentage of `nominal`.
double parse_study_value(const std::string& text, const Dimension& dimension,
                         std::optional<double> nominal, bool fraction_only) {
  const std::string value = trim(text);
  if (!value.empty() && value.back() == '%') {
    const double percent = parse_quantity(trim(value.substr(0, value.size() - 1)), Dimension{});
    if (fraction_only) return percent / 100.0;
    if (!nominal)
      throw std::invalid_argument(
          "a percentage needs the key's value in the scene, which is not "
          "set; give the value itself");
    return *nominal * percent / 100.0;
  }
  // A plain number is in the key's SI unit.
  char* end = nullptr;
  errno = 0;
  const double number = std::strtod(value.c_str(), &end);
  if (!value.empty() && end == value.c_str() + value.size() && errno != ERANGE &&
      std::isfinite(number))
    return number;
  return parse_quantity(value, fraction_only ? Dimension{} : dimension);
}

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
};

bool has(const std::vector<StudyAnalysis>& analyses, StudyAnalysis analysis) {
  return std::find(analyses.begin(), analyses.end(), analysis) != analyses.end();
}

// What the study's analyses do with large kinematics: the static state alone takes any beam;
// modes (about the deflected state) and the sweep (by shooting) need the dynamics' EA.
PrepareOptions study_prepare_options(const DesignStudyOptions& options) {
  PrepareOptions prepare;
  prepare.large_kinematics = has(options.analyses, StudyAnalysis::modes) ||
                                     has(options.analyses, StudyAnalysis::switching_sweep)
                                 ? LargeKinematicsUse::dynamics
                                 : LargeKinematicsUse::static_state;
  return prepare;
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
  std::vector<DeflectionPeak> deflections;  // for the validity check
  for (StudyAnalysis analysis : options.analyses) {
    stopwatch.restart();
    if (analysis == StudyAnalysis::modes) {
      ModalOptions modal;
      modal.count = options.mode_count;
      modal.keep_vectors = false;
      const ModalResult result = run_modes(system, op.rest.operating_point, modal);
      cost.modes += stopwatch.seconds();
      if (!result.status.ok()) return result.status.with_context("modes: ");
      if (result.modes.size() < static_cast<std::size_t>(options.mode_count))
        return Status::failure("modes: " + std::to_string(result.modes.size()) +
                               " oscillatory mode(s) found, " + std::to_string(options.mode_count) +
                               " asked");
      for (int k = 0; k < options.mode_count; ++k) {
        const Mode& mode = result.modes[static_cast<std::size_t>(k)];
        if (!mode.error_bounded)
          return Status::failure("modes: the rounding error of mode " + std::to_string(k + 1) +
                                 " cannot be bounded: " + mode.unbounded_reason);
        values.push_back(mode.frequency_hz);
        values.push_back(mode.damping_ratio);
        values.push_back(mode.pole_error / (2.0 * M_PI));
      }
    } else if (analysis == StudyAnalysis::static_state) {
      for (const Probe& probe : layout.static_probes) {
        values.push_back(static_probe_value(system, op.rest, probe));
        if (probe.quantity == ProbeQuantity::deflection)
          deflections.push_back({probe.name + " (static)", std::abs(values.back())});
      }
      cost.static_state += stopwatch.seconds();
    } else {
      // As `emnet sweep-switching` chooses (SwitchingSweepMethod::automatic): the exact
      // method's model, the DEAs as ideal voltage-driven forces, where the scene has their
      // electrical model through [drive]; shooting on the model as it is where a [[circuit]]
      // drives them (the nominal scene passed prepare_swept_model's checks in column_layout);
      // shooting on the model as it is with large kinematics.
      std::optional<Model> ideal;
      if (system.is_nonlinear() && model.scene.circuit.empty() &&
          model.scene.beam.kinematics != BeamKinematics::large) {
        Scene ideal_scene = model.scene;
        set_electrical_dynamics(ideal_scene, false);
        ideal = prepare_model(ideal_scene, prepare);
      }
      const Model& swept = ideal ? *ideal : model;
      // The sweep peak needs the last output at every frequency; the other outputs are columns
      // at the reported frequencies only: two runs, each solving what its columns need.
      SwitchingSweepOptions sweep;
      sweep.frequencies = layout.sweep_frequencies;
      sweep.samples = options.sweep_samples;
      sweep.outputs = {layout.sweep_outputs.back()};
      sweep.first_mode = false;
      const SwitchingSweepResult peak = run_switching_sweep(swept, swept.scene, sweep);
      if (!peak.status.ok()) return peak.status.with_context("sweep-switching: ");
      values.push_back(peak.peak_frequency);
      if (layout.sweep_outputs.back().quantity == ProbeQuantity::deflection) {
        double largest = 0.0;  // over every frequency of the sweep
        for (std::size_t k = 0; k < peak.frequencies.size(); ++k)
          largest = std::max(
              {largest, std::abs(peak.outputs[0].left[k]), std::abs(peak.outputs[0].right[k])});
        deflections.push_back({layout.sweep_outputs.back().name + " (sweep)", largest});
      }
      if (!layout.report_indices.empty()) {
        sweep.frequencies.clear();
        for (std::size_t index : layout.report_indices)
          sweep.frequencies.push_back(layout.sweep_frequencies[index]);
        sweep.outputs = layout.sweep_outputs;
        sweep.solver = peak.solver;  // one decomposition per variant
        const SwitchingSweepResult at = run_switching_sweep(swept, swept.scene, sweep);
        if (!at.status.ok()) return at.status.with_context("sweep-switching: ");
        for (const SwitchingSweepOutput& output : at.outputs)
          for (std::size_t k = 0; k < layout.report_indices.size(); ++k) {
            values.push_back(output.left[k]);
            values.push_back(output.right[k]);
            if (output.probe.quantity == ProbeQuantity::deflection)
              deflections.push_back(
                  {output.probe.name + " (sweep)",
                   std::max(std::abs(output.left[k]), std::abs(output.right[k]))});
          }
      }
      cost.sweep += stopwatch.seconds();
    }
  }
  for (double value : values)
    if (!std::isfinite(value)) return Status::failure("a result is not finite");
  validity = check_validity(model.scene, deflections, drive_peak_voltages(model.scene));
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

constexpr const char* kVariations = "variations";

OptionError refuse_variation(const std::string& key, const std::string& reason) {
  return OptionError(kVariations, reason, key);
}

// The keys after the first of "KEY+KEY2+...=SPEC": each changes by its ratio to the first key's
// value in the scene.
void link_the_keys_varied_together(const Scene& scene, const std::vector<std::string>& given_keys,
                                   const SceneParameterAddress& address,
                                   const std::optional<double>& nominal, Variation& variation) {
  for (std::size_t k = 1; k < given_keys.size(); ++k) {
    const SceneParameterAddress linked = find_option_parameter(scene, given_keys[k], kVariations);
    if (!linked.info->numeric())
      throw refuse_variation(linked.key, "is not numeric; a study varies numeric keys only");
    double linked_value = 0.0;
    try {
      linked_value = get_parameter(scene, linked.key);
    } catch (const InputError&) {
      throw refuse_variation(linked.key, "has no value in the scene to change with " + address.key);
    }
    if (!nominal || *nominal == 0.0)
      throw refuse_variation(address.key,
                             "keys varied together change by the same ratio, which needs a "
                             "non-zero value of " +
                                 address.key + " in the scene");
    variation.linked.push_back(linked.key);
    variation.linked_ratios.push_back(linked_value / *nominal);
  }
}

// The SPEC of one varied key: a list of values, linspace/logspace, or a distribution.
class VariationSpecReader {
 public:
  VariationSpecReader(const std::string& key, const std::string& spec, Dimension dimension,
                      std::optional<double> nominal)
      : key_(key), spec_(spec), dimension_(dimension), nominal_(nominal) {}

  void read_into(Variation& variation) const {
    const auto open = spec_.find('(');
    if (open != std::string::npos && !spec_.empty() && spec_.back() == ')')
      read_function(open, variation);
    else
      read_list(variation);
  }

 private:
  double value(const std::string& field, bool fraction_only = false) const {
    try {
      return parse_study_value(field, dimension_, nominal_, fraction_only);
    } catch (const std::invalid_argument& error) {
      throw refuse_variation(key_, "'" + terminal_excerpt(field, 60) + "': " + error.what());
    }
  }

  void expect(const std::vector<std::string>& arguments, std::size_t count,
              const std::string& form) const {
    if (arguments.size() != count)
      throw refuse_variation(key_,
                             "expected " + form + ", got '" + terminal_excerpt(spec_, 60) + "'");
  }

  void read_list(Variation& variation) const {
    for (const std::string& field : split(spec_, ",")) {
      if (field.empty()) throw refuse_variation(key_, "an empty value in '" + spec_ + "'");
      variation.values.push_back(value(field));
    }
  }

  void read_function(std::size_t open, Variation& variation) const {
    const std::string name = trim(spec_.substr(0, open));
    const auto arguments = split(spec_.substr(open + 1, spec_.size() - open - 2), ",");
    if (name == "linspace" || name == "logspace")
      read_spaced_values(name, arguments, variation);
    else if (name == "uniform" || name == "normal" || name == "lognormal")
      read_distribution(name, arguments, variation);
    else
      throw refuse_variation(key_, "unknown distribution '" + name +
                                       "'; expected linspace, logspace, uniform, normal or "
                                       "lognormal");
  }

  void read_spaced_values(const std::string& name, const std::vector<std::string>& arguments,
                          Variation& variation) const {
    expect(arguments, 3, name + "(from,to,count)");
    const double from = value(arguments[0]), to = value(arguments[1]);
    char* end = nullptr;
    const long count = std::strtol(arguments[2].c_str(), &end, 10);
    if (end == arguments[2].c_str() || *end != '\0' || count < 1 || count > 1000000)
      throw refuse_variation(key_, "the count of " + name +
                                       " must be an integer from 1 to 1000000, got '" +
                                       terminal_excerpt(arguments[2], 60) + "'");
    if (name == "logspace" && !(from > 0.0 && to > 0.0))
      throw refuse_variation(key_, "logspace needs from > 0 and to > 0");
    for (long k = 0; k < count; ++k) {
      const double t = count == 1 ? 0.0 : static_cast<double>(k) / static_cast<double>(count - 1);
      variation.values.push_back(
          name == "linspace" ? from + t * (to - from)
                             : std::exp(std::log(from) + t * (std::log(to) - std::log(from))));
    }
    // The ends exactly as given, not as the formula rounds them.
    variation.values.back() = to;
    if (count == 1) variation.values.back() = from;
  }

  void read_distribution(const std::string& name, const std::vector<std::string>& arguments,
                         Variation& variation) const {
    if (name == "uniform") {
      expect(arguments, 2, "uniform(lower,upper)");
      variation.kind = VariationKind::uniform;
      variation.first = value(arguments[0]);
      variation.second = value(arguments[1]);
      if (!(variation.first <= variation.second))
        throw refuse_variation(key_, "uniform(lower,upper) needs lower <= upper");
    } else if (name == "normal") {
      expect(arguments, 2, "normal(mean,sd)");
      variation.kind = VariationKind::normal;
      variation.first = value(arguments[0]);
      variation.second = value(arguments[1]);
      if (!(variation.second >= 0.0)) throw refuse_variation(key_, "normal(mean,sd) needs sd >= 0");
    } else {
      expect(arguments, 2, "lognormal(median,s)");
      variation.kind = VariationKind::log_normal;
      variation.first = value(arguments[0]);
      variation.second = value(arguments[1], true);
      if (!(variation.first > 0.0) || !(variation.second >= 0.0))
        throw refuse_variation(key_, "lognormal(median,s) needs median > 0 and s >= 0");
    }
  }

  const std::string& key_;
  const std::string& spec_;
  const Dimension dimension_;
  const std::optional<double> nominal_;
};

}  // namespace

Variation parse_variation(const Scene& scene, const std::string& text) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw refuse_variation(text,
                           "expected KEY=SPEC, e.g. beam.bending_stiffness=normal(100%,5%) or "
                           "dea.A.lever_arm=1.4mm,1.55mm,1.7mm");
  const std::vector<std::string> given_keys = split(text.substr(0, equals), "+");
  const std::string given_key = given_keys.front();
  const std::string spec = trim(text.substr(equals + 1));
  const SceneParameterAddress address = find_option_parameter(scene, given_key, kVariations);
  if (!address.info->numeric())
    throw refuse_variation(address.key, "is not numeric; a study varies numeric keys only");
  const Dimension dimension = parameter_dimension(*address.info, scene, address.entry);
  std::optional<double> nominal;
  try {
    nominal = get_parameter(scene, address.key);
  } catch (const InputError&) {
    // Not set in the scene: no percentage of it (parse_study_value says so).
  }
  Variation variation;
  variation.key = address.key;
  link_the_keys_varied_together(scene, given_keys, address, nominal, variation);
  VariationSpecReader(address.key, spec, dimension, nominal).read_into(variation);
  return variation;
}

VariantTable make_variants(const std::vector<Variation>& variations, std::size_t samples,
                           std::uint64_t seed) {
  VariantTable table;
  bool random = false;
  std::size_t grid_points = 1;
  for (const Variation& variation : variations) {
    std::vector<std::string> keys{variation.key};
    keys.insert(keys.end(), variation.linked.begin(), variation.linked.end());
    for (const std::string& key : keys) {
      if (std::find(table.keys.begin(), table.keys.end(), key) != table.keys.end())
        throw OptionError("variations", "is varied twice", key);
      table.keys.push_back(key);
    }
    random = random || variation.random();
    if (!variation.random()) {
      if (variation.values.empty()) throw OptionError("variations", "has no values", variation.key);
      if (grid_points > kMaxVariants / variation.values.size())
        throw OptionError("variations",
                          "the grid has more than " + std::to_string(kMaxVariants) + " variants",
                          variation.key);
      grid_points *= variation.values.size();
    }
  }
  if (random && samples == 0)
    throw OptionError("samples",
                      "a random variation (uniform, normal, lognormal) needs {samples} N");
  if (!random && samples != 0)
    throw OptionError("samples",
                      "{samples} draws random variations, and none is given (uniform(a,b), "
                      "normal(mean,sd), lognormal(median,s))");
  const std::size_t draws = random ? samples : 1;
  if (grid_points > kMaxVariants / draws)
    throw OptionError("samples", "grid points x samples is more than " +
                                     std::to_string(kMaxVariants) + " variants");
  std::mt19937_64 generator(seed);
  std::vector<std::size_t> digits(variations.size(), 0);
  for (std::size_t point = 0; point < grid_points; ++point) {
    // The grid point's index in mixed radix, the last variation fastest.
    std::size_t rest = point;
    for (std::size_t k = variations.size(); k-- > 0;)
      if (!variations[k].random()) {
        digits[k] = rest % variations[k].values.size();
        rest /= variations[k].values.size();
      }
    for (std::size_t draw = 0; draw < draws; ++draw) {
      std::vector<double> row;
      for (std::size_t k = 0; k < variations.size(); ++k) {
        const Variation& v = variations[k];
        switch (v.kind) {
          case VariationKind::values:
            row.push_back(v.values[digits[k]]);
            break;
          case VariationKind::uniform:
            row.push_back(std::uniform_real_distribution<double>(v.first, v.second)(generator));
            break;
          case VariationKind::normal:
            row.push_back(v.second == 0.0
                              ? v.first
                              : std::normal_distribution<double>(v.first, v.second)(generator));
            break;
          case VariationKind::log_normal:
            row.push_back(v.second == 0.0 ? v.first
                                          : std::lognormal_distribution<double>(
                                                std::log(v.first), v.second)(generator));
            break;
        }
        const double drawn = row.back();
        for (double ratio : v.linked_ratios) row.push_back(drawn * ratio);
      }
      table.rows.push_back(std::move(row));
    }
  }
  return table;
}

namespace {

// The text of a variants file: a regular file of at most 256 MiB (a FIFO blocked, /dev/zero grew
// to 8.4 GB); its errors name the file and the field "variants".
std::string read_variants_file(const std::string& path) {
  try {
    return read_bounded_regular_file(path, 256u * 1024u * 1024u, "the variants file", "variants");
  } catch (const OptionError&) {
    throw;
  } catch (const InputError& error) {
    throw OptionError::in_file("variants", error.where(), "", input_error_reason(error));
  }
}

}  // namespace

VariantTable read_variants_csv(const Scene& scene, const std::string& path) {
  std::istringstream stream(read_variants_file(path));
  VariantTable table;
  std::vector<Dimension> dimensions;
  std::vector<std::optional<double>> nominals;
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(stream, line)) {
    ++line_number;
    const std::string where = path + ":" + std::to_string(line_number);
    const std::string text = trim(line);
    if (text.empty() || text[0] == '#') continue;
    const auto fields = split(text, ",;");
    if (table.keys.empty()) {
      for (const std::string& field : fields) {
        std::string key = field;
        if (key.size() >= 2 && key.front() == '"' && key.back() == '"')
          key = key.substr(1, key.size() - 2);
        const SceneParameterAddress address = find_scene_parameter_address(scene, key, where);
        if (!address.info->numeric())
          throw InputError(where, address.key, "is not numeric; a study varies numeric keys only");
        if (std::find(table.keys.begin(), table.keys.end(), address.key) != table.keys.end())
          throw InputError(where, address.key, "is a column twice");
        table.keys.push_back(address.key);
        dimensions.push_back(parameter_dimension(*address.info, scene, address.entry));
        std::optional<double> nominal;
        try {
          nominal = get_parameter(scene, address.key);
        } catch (const InputError&) {
        }
        nominals.push_back(nominal);
      }
      continue;
    }
    if (fields.size() != table.keys.size())
      throw OptionError::in_file("variants", where, "",
                                 "expected " + std::to_string(table.keys.size()) +
                                     " values (one per key of the header), got " +
                                     std::to_string(fields.size()));
    if (table.rows.size() >= kMaxVariants)
      throw OptionError::in_file("variants", where, "",
                                 "more than " + std::to_string(kMaxVariants) + " variants");
    std::vector<double> row;
    for (std::size_t k = 0; k < fields.size(); ++k) {
      try {
        row.push_back(parse_study_value(fields[k], dimensions[k], nominals[k], false));
      } catch (const std::invalid_argument& error) {
        throw InputError(where, table.keys[k],
                         "'" + terminal_excerpt(fields[k], 60) + "': " + error.what());
      }
    }
    table.rows.push_back(std::move(row));
  }
  if (table.keys.empty())
    throw OptionError::in_file("variants", path, "", "no header line of keys");
  if (table.rows.empty())
    throw OptionError::in_file("variants", path, "", "no variant (no line of values)");
  return table;
}

std::vector<StudyAnalysis> parse_study_analyses(const std::string& text) {
  constexpr const char* field = "analyses";
  std::vector<StudyAnalysis> analyses;
  for (const std::string& name : split(text, ",")) {
    StudyAnalysis analysis;
    if (name == "modes") {
      analysis = StudyAnalysis::modes;
    } else if (name == "static") {
      analysis = StudyAnalysis::static_state;
    } else if (name == "sweep-switching" || name == "sweep_switching") {
      analysis = StudyAnalysis::switching_sweep;
    } else {
      throw OptionError(field, "unknown analysis '" + name +
                                   "'; expected modes, static or sweep-switching "
                                   "(comma-separated, e.g. modes,static)");
    }
    if (has(analyses, analysis)) throw OptionError(field, "'" + name + "' is given twice");
    analyses.push_back(analysis);
  }
  return analyses;
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

ColumnLayout lay_out_the_columns(const Scene& nominal, const DesignStudyOptions& options,
                                 DesignStudyResult& result) {
  const PrepareOptions prepare = study_prepare_options(options);
  const Model nominal_model = prepare_model(nominal, prepare);
  result.unknowns = static_cast<int>(nominal_model.network.assemble().size());
  result.segments = nominal.beam.segments;
  ColumnLayout layout = column_layout(nominal_model, options, prepare);
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
