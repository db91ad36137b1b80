// Scene parameters by key: the split of dotted keys, which keys a scene uses, and get_parameter /
// set_parameter on a Scene's fields (emnet/scene/parameters.hpp).
#include <algorithm>
#include <cmath>

#include "emnet/core/errors.hpp"
#include "emnet/scene/parameters.hpp"
#include "parameter_keys.hpp"
#include "parameter_relations.hpp"
#include "scene_text.hpp"

namespace emnet {

using scene_text::did_you_mean;
using scene_text::is_all_digits;
using scene_text::quoted_list;

// ---- dotted keys ------------------------------------------------------------------------

ParameterKeyParts split_parameter_key(const std::string& key, const std::string& where) {
  // Candidates for "did you mean": every plain key.
  std::vector<std::string> candidates;
  for (const SceneTableInfo& table : scene_tables()) {
    for (const std::string& name : table.keys) {
      candidates.push_back(table.entries ? table.name + ".<name>." + name
                                         : table.name + "." + name);
    }
  }
  auto unknown_key = [&](const std::vector<std::string>& extra_candidates) {
    std::vector<std::string> all = candidates;
    all.insert(all.end(), extra_candidates.begin(), extra_candidates.end());
    return InputError(where, key, "unknown key" + did_you_mean(key, all));
  };
  auto has_key = [](const SceneTableInfo& table, const std::string& name) {
    for (const std::string& known : table.keys)
      if (known == name) return true;
    return false;
  };

  ParameterKeyParts parts;
  const std::size_t split = key.find_first_of(".[");
  const std::string table_name = key.substr(0, split);
  parts.table = find_scene_table(table_name);
  const SceneTableInfo* table = parts.table;
  if (table != nullptr && split == std::string::npos) {
    throw InputError(where, key,
                     "names a table, not a key; override one of its keys, e.g. " +
                         (table->keys.empty() ? key + ".beam.length"
                          : table->entries    ? key + ".0." + table->keys.front()
                                              : key + "." + table->keys.front()));
  }
  if (table == nullptr || split == std::string::npos || split + 1 >= key.size()) {
    throw unknown_key({});
  }
  if (table->free_form) {
    if (key[split] != '.') throw unknown_key({});
    parts.name = key.substr(split + 1);
    parts.prefix = key.substr(0, split + 1);
    return parts;
  }
  if (!table->entries) {
    parts.name = key.substr(split + 1);
    if (key[split] != '.' || !has_key(*table, parts.name)) throw unknown_key({});
    parts.prefix = key.substr(0, split + 1);
    return parts;
  }
  // dea.A.lever_arm, dea[A].lever_arm, dea.0.lever_arm or dea[0].lever_arm
  std::size_t after_selector = std::string::npos;
  if (key[split] == '[') {
    const std::size_t close = key.find(']', split);
    if (close != std::string::npos && close + 1 < key.size() && key[close + 1] == '.') {
      parts.selector = key.substr(split + 1, close - split - 1);
      after_selector = close + 2;
    }
  } else {
    const std::size_t dot = key.find('.', split + 1);
    if (dot != std::string::npos) {
      parts.selector = key.substr(split + 1, dot - split - 1);
      after_selector = dot + 1;
    }
  }
  if (parts.selector.empty() || after_selector == std::string::npos) {
    throw InputError(where, key,
                     "an entry of [[" + table_name + "]] is addressed as " + table_name +
                         ".<name or index>.<key>, e.g. " + table_name + ".0." +
                         table->keys.front());
  }
  parts.name = key.substr(after_selector);
  parts.prefix = key.substr(0, after_selector);
  if (!has_key(*table, parts.name)) {
    std::vector<std::string> extra;
    for (const std::string& name : table->keys) extra.push_back(parts.prefix + name);
    throw unknown_key(extra);
  }
  return parts;
}

std::optional<std::size_t> select_entry(const std::vector<std::optional<std::string>>& names,
                                        const std::string& selector) {
  for (std::size_t index = 0; index < names.size(); ++index)
    if (names[index] && *names[index] == selector) return index;
  if (is_all_digits(selector) && selector.size() < 9) {
    const std::size_t index = std::stoul(selector);
    if (index < names.size()) return index;
  }
  return std::nullopt;
}

std::string missing_entry_message(const std::string& table, const std::string& selector,
                                  std::size_t count,
                                  const std::vector<std::optional<std::string>>& names) {
  std::vector<std::string> named;
  for (const auto& name : names)
    if (name) named.push_back(*name);
  std::string known = "the scene has " + std::to_string(count) + " [[" + table + "]] entr" +
                      (count == 1 ? "y" : "ies");
  if (!named.empty()) known += " named " + quoted_list(named);
  return "no [[" + table + "]] entry '" + selector + "'; " + known;
}

// ---- which keys a scene uses ----------------------------------------------------------

namespace {

// "the 0/V square wave on DEA A, then on DEA B": what each kind is, for messages.
const char* drive_kind_meaning(DriveKind kind) {
  switch (kind) {
    case DriveKind::none:
      return "no DEA driven, the scene's loads only";
    case DriveKind::antagonistic:
      return "a 0/V square wave on DEA A, then on DEA B";
    case DriveKind::switched:
      return "a 0/V square wave on one DEA";
    case DriveKind::bias_differential:
      return "V_A,B = V0 +/- v*sin(2*pi*f*t)";
    case DriveKind::single:
      return "the sine V = V0 + v*sin(2*pi*f*t) on one DEA";
  }
  return "?";
}

bool on_dea(ProbeQuantity quantity) {
  return quantity == ProbeQuantity::dea_voltage || quantity == ProbeQuantity::dea_current ||
         quantity == ProbeQuantity::dea_force;
}

// The waveforms of a [[circuit]] source that use the waveform key `name`; empty for a key that is
// no waveform key (name, kind, from, to, value, waveform, ac).
std::vector<WaveformKind> waveforms_using(const std::string& name) {
  using W = WaveformKind;
  if (name == "low" || name == "high" || name == "rise" || name == "fall")
    return {W::square, W::pulse};
  if (name == "frequency") return {W::square, W::sine};
  if (name == "duty") return {W::square};
  if (name == "delay") return {W::square, W::pulse, W::sine};
  if (name == "width" || name == "period") return {W::pulse};
  if (name == "offset" || name == "amplitude" || name == "phase") return {W::sine};
  if (name == "points" || name == "file") return {W::pwl};
  return {};
}

const char* waveform_meaning(WaveformKind kind) {
  switch (kind) {
    case WaveformKind::dc:
      return "the constant circuit[].value";
    case WaveformKind::sine:
      return "offset + amplitude*sin(2*pi*frequency*(t - delay) + phase)";
    case WaveformKind::square:
      return "low/high at frequency, duty, rise, fall, delay";
    case WaveformKind::pulse:
      return "SPICE PULSE: low, high, delay, rise, fall, width, period";
    case WaveformKind::pwl:
      return "piecewise linear: points or file";
  }
  return "?";
}

std::string circuit_unused_reason(const ParameterInfo& info, const CircuitSpec& element) {
  const std::string& name = info.name;
  const bool source = is_source(element.kind);
  const std::string kind = circuit_kind_name(element.kind);
  const std::vector<WaveformKind> users = waveforms_using(name);
  if (!source && (name == "waveform" || name == "ac" || !users.empty()))
    return "is only used by sources (voltage_source, current_source), not by a " + kind;
  if (name == "value" && source && element.waveform.kind != WaveformKind::dc)
    return std::string("is not used by waveform '") + waveform_kind_name(element.waveform.kind) +
           "' (" + waveform_meaning(element.waveform.kind) +
           "); a source's value is its constant level with waveform = \"dc\"";
  if (users.empty()) return "";
  for (WaveformKind user : users)
    if (user == element.waveform.kind) return "";
  std::vector<std::string> names;
  for (WaveformKind user : users) names.push_back(waveform_kind_name(user));
  return std::string("is not used by waveform '") + waveform_kind_name(element.waveform.kind) +
         "' (" + waveform_meaning(element.waveform.kind) + "); it is used by waveform" +
         (names.size() == 1 ? " " : "s ") + quoted_list(names);
}

}  // namespace

std::string parameter_unused_reason(const ParameterInfo& info, const Scene& scene,
                                    std::size_t entry) {
  if (info.table == "drive" && !info.drive_kinds.empty()) {
    const DriveKind kind = scene.drive.kind;
    for (DriveKind user : info.drive_kinds)
      if (user == kind) return "";
    std::vector<std::string> users;
    for (DriveKind user : info.drive_kinds) users.push_back(drive_kind_name(user));
    std::string hint;
    if (kind == DriveKind::single && info.name == "voltage")
      hint = "; a 0/V square wave on one DEA is drive.kind = \"switched\"";
    return std::string("is not used by drive kind '") + drive_kind_name(kind) + "' (" +
           drive_kind_meaning(kind) + "); it is used by drive kind" +
           (users.size() == 1 ? " " : "s ") + quoted_list(users) + hint;
  }
  if (info.table == "beam" && !scene.beam.sections.empty() &&
      (info.name == "bending_stiffness" || info.name == "mass_per_length" ||
       info.name == "rotary_inertia_per_length"))
    return "is given per section when the beam has [[section]] entries (section[]." + info.name +
           ")";
  if ((info.table == "beam" || info.table == "section") && info.name == "shear_stiffness" &&
      scene.beam.theory != BeamTheory::timoshenko)
    return "is only used with beam.theory = \"timoshenko\"";
  if ((info.table == "beam" || info.table == "section") && info.name == "axial_stiffness" &&
      scene.beam.kinematics != BeamKinematics::large && !scene.beam.kinematics_auto)
    return "is only used with beam.kinematics = \"large\" (small deflections have no axial "
           "motion)";
  if (info.table == "environment" && info.name != "fluid" && scene.environment.fluid == Fluid::none)
    return "is only used with environment.fluid = \"air\" or \"water\"";
  if (info.table == "probe" && entry < scene.probes.size()) {
    const ProbeQuantity quantity = scene.probes[entry].quantity;
    const std::string quantity_name = probe_quantity_name(quantity);
    if (info.name == "at" && on_dea(quantity))
      return "is not used by probe quantity '" + quantity_name + "' (it names a DEA)";
    if (info.name == "at" && quantity == ProbeQuantity::spring_force)
      return "is not used by probe quantity 'spring_force' (it names a spring: probe[].spring)";
    if (info.name == "dea" && !on_dea(quantity))
      return "is only used by probe quantities 'dea_voltage', 'dea_current' and 'dea_force', "
             "not '" +
             quantity_name + "'";
    if (info.name == "spring" && quantity != ProbeQuantity::spring_force)
      return "is only used by probe quantity 'spring_force', not '" + quantity_name + "'";
    if ((info.name == "face" || info.name == "distance") && quantity != ProbeQuantity::strain)
      return "is only used by probe quantity 'strain', not '" + quantity_name + "'";
  }
  if (info.table == "circuit" && entry < scene.circuit.size())
    return circuit_unused_reason(info, scene.circuit[entry]);
  if (info.table == "damping") {
    const DampingSpec& damping = scene.damping;
    if (info.name == "kelvin_voigt_time" && damping.loss_factor)
      return "give either damping.kelvin_voigt_time or damping.loss_factor (with "
             "damping.loss_factor_frequency), not both";
    if (info.name == "loss_factor" && !damping.loss_factor_frequency)
      return "needs damping.loss_factor_frequency (Hz), the frequency at which it holds";
    if (info.name == "loss_factor_frequency" && !damping.loss_factor)
      return "is only used with damping.loss_factor, which is missing";
  }
  return "";
}

Dimension parameter_dimension(const ParameterInfo& info, const Scene& scene, std::size_t entry) {
  if (info.table == "load" && info.name == "value" && entry < scene.loads.size() &&
      scene.loads[entry].kind == LoadKind::moment)
    return dim::moment;
  if (info.table == "spring" && entry < scene.beam.springs.size() &&
      scene.beam.springs[entry].kind == SpringKind::rotational) {
    if (info.name == "stiffness") return dim::moment;  // N*m/rad
    if (info.name == "damping") return dim::rotational_damping;
  }
  if (info.table == "circuit" && entry < scene.circuit.size()) {
    const CircuitKind kind = scene.circuit[entry].kind;
    const bool level = info.name == "value" || info.name == "low" || info.name == "high" ||
                       info.name == "offset" || info.name == "amplitude" || info.name == "ac";
    if (level) {
      switch (kind) {
        case CircuitKind::resistor:
          return info.name == "value" ? dim::resistance : dim::voltage;
        case CircuitKind::capacitor:
          return info.name == "value" ? dim::capacitance : dim::voltage;
        case CircuitKind::inductor:
          return info.name == "value" ? dim::inductance : dim::voltage;
        case CircuitKind::voltage_source:
          return dim::voltage;
        case CircuitKind::current_source:
          return dim::current;
      }
    }
  }
  return info.dimension;
}

std::string parameter_unit(const ParameterInfo& info, const Scene& scene, std::size_t entry) {
  if (info.kind != ParameterKind::quantity) return "";
  const std::string unit = si_unit_symbol(parameter_dimension(info, scene, entry));
  const bool rotational_spring = info.table == "spring" && entry < scene.beam.springs.size() &&
                                 scene.beam.springs[entry].kind == SpringKind::rotational;
  return rotational_spring && (info.name == "stiffness" || info.name == "damping") ? unit + "/rad"
                                                                                   : unit;
}

// ---- parameters of a Scene ------------------------------------------------------------

namespace {

constexpr const char* kGetWhere = "get_parameter";
constexpr const char* kSetWhere = "set_parameter";

// The names of a scene's entries of `table` (nullopt for entries without names: loads).
std::vector<std::optional<std::string>> entry_names(const Scene& scene, const std::string& table) {
  std::vector<std::optional<std::string>> names;
  if (table == "dea")
    for (const DeaSpec& dea : scene.deas) names.emplace_back(dea.name);
  if (table == "probe")
    for (const ProbeSpec& probe : scene.probes) names.emplace_back(probe.name);
  if (table == "load") names.resize(scene.loads.size());
  if (table == "circuit")
    for (const CircuitSpec& element : scene.circuit) names.emplace_back(element.name);
  if (table == "section") names.resize(scene.beam.sections.size());
  if (table == "mass")
    for (const MassSpec& mass : scene.beam.masses)
      names.emplace_back(mass.name.empty() ? std::nullopt : std::optional<std::string>(mass.name));
  if (table == "spring")
    for (const SpringSpec& spring : scene.beam.springs)
      names.emplace_back(spring.name.empty() ? std::nullopt
                                             : std::optional<std::string>(spring.name));
  return names;
}

// "dea[A].lever_arm", "load[0].value", "beam.length"
std::string canonical_key(const ParameterInfo& info,
                          const std::vector<std::optional<std::string>>& names, std::size_t entry) {
  if (!info.in_entries) return info.table + "." + info.name;
  const std::optional<std::string>& name = names[entry];
  const bool by_name = name && scene_text::is_identifier(*name);
  return info.table + "[" + (by_name ? *name : std::to_string(entry)) + "]." + info.name;
}

// The address of a key a caller already holds, checked for a number the scene uses.
void check_numeric_use(const Scene& scene, const SceneParameterAddress& address,
                       const std::string& where) {
  const NumericUse use = numeric_use(scene, address);
  if (use.code == NumericUseCode::not_numeric)
    throw InputError(where, address.key, use.reason + "; " + where + " takes numeric keys");
  if (use.code == NumericUseCode::unused) throw InputError(where, address.key, use.reason);
}

// Positions within kBeamEndTolerance of an end are put on it, as the reader does.
void snap_positions_to_the_beam(Scene& scene) {
  const double length = scene.beam.length;
  auto snap = [length](double& position) { position = std::min(std::max(position, 0.0), length); };
  for (DeaSpec& dea : scene.deas) {
    snap(dea.from);
    snap(dea.to);
  }
  for (LoadSpec& load : scene.loads) snap(load.at);
  for (ProbeSpec& probe : scene.probes) snap(probe.at);
  for (MassSpec& mass : scene.beam.masses) snap(mass.at);
  for (SpringSpec& spring : scene.beam.springs) {
    snap(spring.at);
    if (spring.to) snap(*spring.to);
  }
}

}  // namespace

NumericUse numeric_use(const Scene& scene, const SceneParameterAddress& address) {
  const ParameterInfo& info = *address.info;
  if (!info.numeric())
    return {NumericUseCode::not_numeric,
            std::string("is not a number but a ") + parameter_kind_name(info.kind) + " key"};
  std::string reason = parameter_unused_reason(info, scene, address.entry);
  if (!reason.empty()) return {NumericUseCode::unused, std::move(reason)};
  if (!info.get(scene, address.entry))
    return {NumericUseCode::not_set, "is not set in scene '" + scene.name + "'"};
  return {};
}

SceneParameterAddress find_scene_parameter_address(const Scene& scene, const std::string& key,
                                                   const std::string& where) {
  const ParameterKeyParts parts = split_parameter_key(key, where);
  SceneParameterAddress address;
  if (parts.table->free_form) {
    address.info = &parameter_info(parts.table->name, "*");
    address.key = key;
    return address;
  }
  address.info = &parameter_info(parts.table->name, parts.name);
  if (!parts.table->entries) {
    address.key = canonical_key(*address.info, {}, 0);
    return address;
  }
  const std::vector<std::optional<std::string>> names = entry_names(scene, parts.table->name);
  const std::optional<std::size_t> entry = select_entry(names, parts.selector);
  if (!entry) {
    throw InputError(where, key,
                     missing_entry_message(parts.table->name, parts.selector, names.size(), names));
  }
  address.entry = *entry;
  address.key = canonical_key(*address.info, names, *entry);
  return address;
}

std::vector<SceneParameterAddress> scene_numeric_parameters(const Scene& scene) {
  std::vector<SceneParameterAddress> addresses;
  for (const SceneTableInfo& table : scene_tables()) {
    const std::vector<std::optional<std::string>> names = entry_names(scene, table.name);
    const std::size_t entries = table.entries ? names.size() : 1;
    for (std::size_t entry = 0; entry < entries; ++entry) {
      for (const std::string& name : table.keys) {
        const ParameterInfo& info = parameter_info(table.name, name);
        if (!info.numeric() || !parameter_unused_reason(info, scene, entry).empty()) continue;
        if (!info.get(scene, entry)) continue;
        addresses.push_back({&info, entry, canonical_key(info, names, entry)});
      }
    }
  }
  return addresses;
}

double get_parameter(const Scene& scene, const std::string& key) {
  const SceneParameterAddress address = find_scene_parameter_address(scene, key, kGetWhere);
  check_numeric_use(scene, address, kGetWhere);
  const std::optional<double> value = address.info->get(scene, address.entry);
  if (!value) throw InputError(kGetWhere, address.key, "is not set in scene '" + scene.name + "'");
  return *value;
}

void set_parameter(Scene& scene, const std::string& key, double value_si) {
  const SceneParameterAddress address = find_scene_parameter_address(scene, key, kSetWhere);
  check_numeric_use(scene, address, kSetWhere);
  const ParameterInfo& info = *address.info;
  const Dimension dimension = parameter_dimension(info, scene, address.entry);
  auto fail = [&](const std::string& message) {
    throw InputError(kSetWhere, address.key, message);
  };
  if (!std::isfinite(value_si)) fail("must be finite, got " + scene_text::format_number(value_si));
  if (info.kind == ParameterKind::integer && value_si != std::floor(value_si))
    fail("must be an integer, got " + scene_text::format_number(value_si));
  if (const std::string subnormal = subnormal_violation(value_si, dimension); !subnormal.empty())
    fail(subnormal);
  const std::string outside =
      parameter_range_violation(info, value_si, shown_parameter_value(info, value_si, dimension));
  if (!outside.empty()) fail(outside);
  Scene changed = scene;
  info.set(changed, address.entry, value_si);
  if (const std::optional<KeyMessage> broken = scene_relation_violation(changed))
    throw InputError(kSetWhere, broken->name, broken->message);
  snap_positions_to_the_beam(changed);
  scene = std::move(changed);
}

}  // namespace emnet
