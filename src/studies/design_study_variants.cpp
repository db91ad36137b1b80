// The variant table of a design study (emnet/studies/design_study.hpp): KEY=SPEC variations
// (values, linspace, logspace and random draws), their grid and Monte Carlo rows, a CSV of
// variants, and the names of the analyses.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>

#include "emnet/core/bounded_file.hpp"
#include "emnet/core/option_error.hpp"
#include "emnet/core/terminal_text.hpp"
#include "emnet/core/units.hpp"
#include "emnet/scene/parameters.hpp"
#include "emnet/studies/design_study.hpp"
#include "option_parameter.hpp"
#include "scene/scene_text.hpp"

namespace emnet {

namespace {

using scene_text::trim;

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
    if (std::find(analyses.begin(), analyses.end(), analysis) != analyses.end())
      throw OptionError(field, "'" + name + "' is given twice");
    analyses.push_back(analysis);
  }
  return analyses;
}

}  // namespace emnet
