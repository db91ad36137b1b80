// The scene's parameter table (emnet/scene/parameters.hpp): one entry per scene key, in the
// order of the scene's tables and, within a table, of its keys as the reader's messages list them.
//
// Defaults are not written here: a key's default is its field's value in a default-constructed
// Scene (emnet/scene/scene.hpp), read through the entry's accessor, so that the Scene type and the
// table cannot disagree. Entries whose default depends on other keys (the fluid's density) say so
// in default_note.
#include "emnet/scene/parameters.hpp"

#include "emnet/scene/scene_reader.hpp"
#include "scene_text.hpp"

namespace emnet {

// Fluid properties at 20 °C and 101.325 kPa: water ρ = 998.2 kg/m³ (CRC Handbook of Chemistry
// and Physics, density of water), η = 1.002e-3 Pa·s (ISO/TR 3666:1998, the viscosity of water
// at 20 °C); dry air ρ = 1.204 kg/m³ (ideal gas, M = 28.96 g/mol), η = 1.81e-5 Pa·s (CRC
// Handbook, viscosity of air).
FluidProperties fluid_properties(Fluid fluid) {
  switch (fluid) {
    case Fluid::water:
      return {998.2, 1.002e-3};
    case Fluid::air:
      return {1.204, 1.81e-5};
    case Fluid::none:
      break;
  }
  return {};
}

namespace {

using Limit = ParameterRange::Limit;

// ---- ranges, with the reader's messages -------------------------------------------------

ParameterRange unbounded() {
  return {};
}

ParameterRange positive() {
  return {Limit::exclusive, 0.0, Limit::none, 0.0, "must be > 0, got {}", ""};
}

ParameterRange non_negative() {
  return {Limit::inclusive, 0.0, Limit::none, 0.0, "must be >= 0, got {}", ""};
}

ParameterRange interval(Limit lower, double lower_value, Limit upper, double upper_value,
                        const std::string& message) {
  return {lower, lower_value, upper, upper_value, message, message};
}

// ---- accessors --------------------------------------------------------------------------

template <typename Spec>
void plain_field(ParameterInfo& info, Spec Scene::*table, double Spec::*member) {
  info.get = [table, member](const Scene& scene, std::size_t) -> std::optional<double> {
    return scene.*table.*member;
  };
  info.set = [table, member](Scene& scene, std::size_t, double value) {
    (scene.*table).*member = value;
  };
}

template <typename Spec>
void plain_field(ParameterInfo& info, Spec Scene::*table, std::optional<double> Spec::*member) {
  info.get = [table, member](const Scene& scene, std::size_t) { return scene.*table.*member; };
  info.set = [table, member](Scene& scene, std::size_t, double value) {
    (scene.*table).*member = value;
  };
}

template <typename Spec>
void entry_field(ParameterInfo& info, std::vector<Spec> Scene::*entries, double Spec::*member) {
  info.get = [entries, member](const Scene& scene, std::size_t entry) -> std::optional<double> {
    return (scene.*entries)[entry].*member;
  };
  info.set = [entries, member](Scene& scene, std::size_t entry, double value) {
    (scene.*entries)[entry].*member = value;
  };
}

// A field of a [[circuit]] entry's waveform (circuit[].low, .frequency, ...).
void waveform_field(ParameterInfo& info, double WaveformSpec::*member) {
  info.get = [member](const Scene& scene, std::size_t entry) -> std::optional<double> {
    return scene.circuit[entry].waveform.*member;
  };
  info.set = [member](Scene& scene, std::size_t entry, double value) {
    scene.circuit[entry].waveform.*member = value;
  };
}

// A field of the beam's [[section]], [[mass]] or [[spring]] entries (held in BeamSpec).
template <typename Spec, typename Field>
void beam_entry_field(ParameterInfo& info, std::vector<Spec> BeamSpec::*entries,
                      Field Spec::*member) {
  info.get = [entries, member](const Scene& scene, std::size_t entry) -> std::optional<double> {
    return (scene.beam.*entries)[entry].*member;
  };
  info.set = [entries, member](Scene& scene, std::size_t entry, double value) {
    (scene.beam.*entries)[entry].*member = value;
  };
}

std::string bool_text(bool value) {
  return value ? "true" : "false";
}

// ---- the entries ------------------------------------------------------------------------

ParameterInfo key(const char* table, const char* name, ParameterKind kind, const char* used_by,
                  const char* meaning) {
  ParameterInfo info;
  info.table = table;
  info.name = name;
  for (const char* entries_table : {"section", "mass", "spring", "dea", "load", "probe", "circuit"})
    if (info.table == entries_table) info.in_entries = true;
  info.kind = kind;
  info.used_by = used_by;
  info.meaning = meaning;
  return info;
}

ParameterInfo quantity(const char* table, const char* name, const Dimension& dimension,
                       ParameterRange range, bool required, const char* used_by,
                       const char* meaning) {
  ParameterInfo info = key(table, name, ParameterKind::quantity, used_by, meaning);
  info.dimension = dimension;
  info.range = std::move(range);
  info.required = required;
  return info;
}

ParameterInfo choice(const char* table, const char* name, std::vector<std::string> choices,
                     bool required, const char* used_by, const char* meaning) {
  ParameterInfo info = key(table, name, ParameterKind::choice, used_by, meaning);
  info.choices = std::move(choices);
  info.required = required;
  return info;
}

std::string drive_kinds_text(const std::vector<DriveKind>& kinds) {
  if (kinds.empty()) return "every drive kind";
  std::vector<std::string> names;
  for (DriveKind kind : kinds) names.push_back(drive_kind_name(kind));
  return std::string("drive kind") + (names.size() == 1 ? " " : "s ") +
         scene_text::quoted_list(names);
}

ParameterInfo used_by_kinds(ParameterInfo info, std::vector<DriveKind> kinds) {
  info.drive_kinds = std::move(kinds);
  info.used_by = drive_kinds_text(info.drive_kinds);
  return info;
}

std::vector<ParameterInfo> scene_keys() {
  std::vector<ParameterInfo> keys;
  auto add = [&keys](ParameterInfo info) -> ParameterInfo& {
    keys.push_back(std::move(info));
    return keys.back();
  };
  using K = ParameterKind;

  // [scene]
  add(key("scene", "name", K::text, "outputs",
          "the scene's name, in every command's output and in SPICE decks; not empty"))
      .required = true;
  add(key("scene", "title", K::text, "plots, reports", "a title for plots and reports"));
  add(key("scene", "description", K::text, "nobody (documentation)",
          "free text about the scene; not read by any command"));
  keys[0].text = [](const Scene& scene, std::size_t) { return scene.name; };
  keys[1].text = [](const Scene& scene, std::size_t) { return scene.title; };
  keys[2].text = [](const Scene&, std::size_t) { return std::string(); };

  // [beam]
  plain_field(add(quantity("beam", "length", dim::length, positive(), true, "beam",
                           "L, the beam's length from the left end (x = 0) to the right end")),
              &Scene::beam, &BeamSpec::length);
  keys.back().sensitivity = true;
  {
    ParameterInfo& segments =
        add(key("beam", "segments", K::integer, "beam",
                "N, the number of segments the beam is cut into: equal on a plain beam, spread by "
                "length between the nodes that sections, masses, springs, DEA ends and loads put; "
                "\"auto\": chosen for [model]'s band and tolerance"));
    segments.required = true;
    segments.range = {Limit::inclusive,       1.0,
                      Limit::inclusive,       100000.0,
                      "must be >= 1, got {}", "{} segments is absurdly large (at most 100000)"};
    segments.constraint = "or \"auto\"";
    segments.get = [](const Scene& scene, std::size_t) -> std::optional<double> {
      return static_cast<double>(scene.beam.segments);
    };
    segments.set = [](Scene& scene, std::size_t, double value) {
      scene.beam.segments = static_cast<int>(value);
      scene.beam.auto_segments = false;
    };
    segments.text = [](const Scene& scene, std::size_t) {
      return scene.beam.auto_segments ? std::string("auto") : std::to_string(scene.beam.segments);
    };
  }
  plain_field(add(quantity("beam", "bending_stiffness", dim::bending_stiffness, positive(), true,
                           "beam", "EI, the beam's bending stiffness")),
              &Scene::beam, &BeamSpec::bending_stiffness);
  keys.back().sensitivity = true;
  plain_field(add(quantity("beam", "mass_per_length", dim::mass_per_length, positive(), true,
                           "beam", "rho*A, the beam's mass per unit length")),
              &Scene::beam, &BeamSpec::mass_per_length);
  keys.back().sensitivity = true;
  plain_field(add(quantity("beam", "rotary_inertia_per_length", dim::rotary_inertia_per_length,
                           non_negative(), false, "beam",
                           "rho*I, the rotary inertia per unit length (0: Euler-Bernoulli, none)")),
              &Scene::beam, &BeamSpec::rotary_inertia_per_length);
  keys.back().sensitivity = true;
  const std::vector<std::string> ends = {"clamped", "free", "pinned", "sliding"};
  add(choice("beam", "left", ends, false, "beam", "the end condition at x = 0")).text =
      [](const Scene& scene, std::size_t) {
        return std::string(end_condition_name(scene.beam.left));
      };
  add(choice("beam", "right", ends, false, "beam", "the end condition at x = beam.length")).text =
      [](const Scene& scene, std::size_t) {
        return std::string(end_condition_name(scene.beam.right));
      };

  add(choice("beam", "theory", {"euler_bernoulli", "timoshenko"}, false, "beam",
             "what a segment realises: bending only, or bending and shear (the shear compliance "
             "l/(kappa*G*A) of each segment)"))
      .text = [](const Scene& scene, std::size_t) {
    return std::string(beam_theory_name(scene.beam.theory));
  };
  plain_field(add(quantity("beam", "shear_stiffness", dim::force, positive(), false,
                           "beam theory 'timoshenko'",
                           "kappa*G*A, the shear stiffness (shear correction factor times shear "
                           "modulus times cross-section)")),
              &Scene::beam, &BeamSpec::shear_stiffness);
  keys.back().sensitivity = true;
  keys.back().constraint = "with beam.theory = \"timoshenko\"";
  keys.back().default_note =
      "required with beam.theory = \"timoshenko\" (unless every section "
      "gives its own)";

  // [[section]]
  const char* section_users = "beam sections";
  beam_entry_field(add(quantity("section", "length", dim::length, positive(), true, section_users,
                                "the section's length; the sections follow each other from x = 0 "
                                "and add up to beam.length")),
                   &BeamSpec::sections, &SectionSpec::length);
  keys.back().constraint = "the lengths add up to beam.length";
  beam_entry_field(add(quantity("section", "bending_stiffness", dim::bending_stiffness, positive(),
                                true, section_users, "EI of the section")),
                   &BeamSpec::sections, &SectionSpec::bending_stiffness);
  keys.back().sensitivity = true;
  beam_entry_field(add(quantity("section", "mass_per_length", dim::mass_per_length, positive(),
                                true, section_users, "rho*A of the section")),
                   &BeamSpec::sections, &SectionSpec::mass_per_length);
  keys.back().sensitivity = true;
  beam_entry_field(
      add(quantity("section", "rotary_inertia_per_length", dim::rotary_inertia_per_length,
                   non_negative(), false, section_users, "rho*I of the section")),
      &BeamSpec::sections, &SectionSpec::rotary_inertia_per_length);
  keys.back().sensitivity = true;
  beam_entry_field(add(quantity("section", "shear_stiffness", dim::force, positive(), false,
                                section_users, "kappa*G*A of the section (Timoshenko)")),
                   &BeamSpec::sections, &SectionSpec::shear_stiffness);
  keys.back().sensitivity = true;
  keys.back().constraint = "with beam.theory = \"timoshenko\"";
  keys.back().default_note = "unset: beam.shear_stiffness";
  beam_entry_field(
      add(quantity("section", "viscous_per_length", dim::damping_per_length, non_negative(), false,
                   section_users, "the section's viscous damping to ground per length")),
      &BeamSpec::sections, &SectionSpec::viscous_per_length);
  keys.back().sensitivity = true;
  keys.back().default_note = "unset: damping.viscous_per_length";
  beam_entry_field(add(quantity("section", "kelvin_voigt_time", dim::time, non_negative(), false,
                                section_users, "the section's Kelvin-Voigt time tau")),
                   &BeamSpec::sections, &SectionSpec::kelvin_voigt_time);
  keys.back().sensitivity = true;
  keys.back().default_note = "unset: the [damping] table's tau";
  {
    ParameterInfo& segments =
        add(key("section", "segments", K::integer, section_users,
                "the section's own number of segments; unset or \"auto\": its share of "
                "beam.segments by length"));
    segments.range = {Limit::inclusive,       1.0,
                      Limit::inclusive,       100000.0,
                      "must be >= 1, got {}", "{} segments is absurdly large (at most 100000)"};
    segments.constraint = "or \"auto\"";
    segments.default_note = "auto (a share of beam.segments by length)";
    segments.get = [](const Scene& scene, std::size_t entry) -> std::optional<double> {
      const int count = scene.beam.sections[entry].segments;
      if (count == 0) return std::nullopt;
      return static_cast<double>(count);
    };
    segments.set = [](Scene& scene, std::size_t entry, double value) {
      scene.beam.sections[entry].segments = static_cast<int>(value);
    };
    segments.text = [](const Scene& scene, std::size_t entry) {
      const int count = scene.beam.sections[entry].segments;
      return count == 0 ? std::string("auto") : std::to_string(count);
    };
  }

  // [[mass]]
  add(key("mass", "name", K::name, "point masses", "the mass's name (optional; outputs name it)"));
  keys.back().constraint = "letters, digits and '_', at most 64 characters, unique";
  keys.back().default_note = "none (addressed by index: mass[0])";
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    return scene.beam.masses[entry].name;
  };
  beam_entry_field(add(quantity("mass", "at", dim::length, unbounded(), true, "point masses",
                                "where the mass sits along the beam (a node is put there)")),
                   &BeamSpec::masses, &MassSpec::at);
  keys.back().constraint = "on the beam: 0 <= at <= beam.length";
  beam_entry_field(add(quantity("mass", "mass", dim::mass, non_negative(), true, "point masses",
                                "the point mass (a sensor, a clamp's moving part)")),
                   &BeamSpec::masses, &MassSpec::mass);
  keys.back().sensitivity = true;
  beam_entry_field(
      add(quantity("mass", "rotary_inertia", dim::rotary_inertia, non_negative(), false,
                   "point masses", "its rotary inertia about the beam's axis of bending")),
      &BeamSpec::masses, &MassSpec::rotary_inertia);
  keys.back().sensitivity = true;

  // [[spring]]
  add(key("spring", "name", K::name, "springs", "the spring's name (optional; outputs name it)"));
  keys.back().constraint = "letters, digits and '_', at most 64 characters, unique";
  keys.back().default_note = "none (addressed by index: spring[0])";
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    return scene.beam.springs[entry].name;
  };
  beam_entry_field(add(quantity("spring", "at", dim::length, unbounded(), true, "springs",
                                "where the spring holds the beam (a node is put there)")),
                   &BeamSpec::springs, &SpringSpec::at);
  keys.back().constraint = "on the beam: 0 <= at <= beam.length";
  add(choice("spring", "kind", {"translational", "rotational"}, true, "springs",
             "a force k*(w(at) - w(to)) or a moment k*(phi(at) - phi(to))"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(scene.beam.springs[entry].kind == SpringKind::rotational ? "rotational"
                                                                                : "translational");
  };
  beam_entry_field(add(quantity("spring", "stiffness", dim::stiffness, positive(), true, "springs",
                                "k: N/m (translational) or N*m/rad (rotational)")),
                   &BeamSpec::springs, &SpringSpec::stiffness);
  keys.back().sensitivity = true;
  keys.back().unit_note = "N/m (translational), N*m/rad (rotational)";
  beam_entry_field(add(quantity("spring", "damping", dim::damping, non_negative(), false, "springs",
                                "the dashpot in parallel with the spring")),
                   &BeamSpec::springs, &SpringSpec::damping);
  keys.back().sensitivity = true;
  keys.back().unit_note = "N*s/m (translational), N*m*s/rad (rotational)";
  beam_entry_field(add(quantity("spring", "to", dim::length, unbounded(), false, "springs",
                                "the spring's other end on the beam; unset: ground")),
                   &BeamSpec::springs, &SpringSpec::to);
  keys.back().constraint = "on the beam: 0 <= to <= beam.length, not at";
  keys.back().default_note = "unset (to ground)";

  // [damping]
  plain_field(add(quantity("damping", "viscous_per_length", dim::damping_per_length, non_negative(),
                           false, "beam (damping)",
                           "viscous damping to ground per unit length (a dashpot at each node)")),
              &Scene::damping, &DampingSpec::viscous_per_length);
  keys.back().sensitivity = true;
  plain_field(
      add(quantity("damping", "kelvin_voigt_time", dim::time, non_negative(), false,
                   "beam (damping)",
                   "tau of the Kelvin-Voigt material damping M = EI*(kappa + tau*dkappa/dt)")),
      &Scene::damping, &DampingSpec::kelvin_voigt_time);
  keys.back().sensitivity = true;
  keys.back().constraint = "not with damping.loss_factor";
  plain_field(
      add(quantity("damping", "loss_factor", dim::none, non_negative(), false, "beam (damping)",
                   "eta, the loss factor at damping.loss_factor_frequency: the "
                   "Kelvin-Voigt time tau = eta/(2*pi*f)")),
      &Scene::damping, &DampingSpec::loss_factor);
  keys.back().sensitivity = true;
  keys.back().constraint = "with damping.loss_factor_frequency, not with kelvin_voigt_time";
  keys.back().default_note = "unset (no loss factor)";
  plain_field(
      add(quantity("damping", "loss_factor_frequency", dim::frequency, positive(), false,
                   "beam (damping)", "f, the frequency at which damping.loss_factor holds")),
      &Scene::damping, &DampingSpec::loss_factor_frequency);
  keys.back().sensitivity = true;
  keys.back().constraint = "only with damping.loss_factor";
  keys.back().default_note = "unset; required with damping.loss_factor";

  // [[dea]]
  add(key("dea", "name", K::name, "DEA", "the DEA's name (drive.deas, probes and outputs name it)"))
      .required = true;
  keys.back().constraint = "letters, digits and '_', at most 64 characters, unique";
  keys.back().text = [](const Scene& scene, std::size_t entry) { return scene.deas[entry].name; };
  entry_field(add(quantity("dea", "from", dim::length, unbounded(), true, "DEA",
                           "x0, where the DEA's electrode starts along the beam")),
              &Scene::deas, &DeaSpec::from);
  keys.back().constraint = "on the beam: 0 <= from < to";
  entry_field(add(quantity("dea", "to", dim::length, unbounded(), true, "DEA",
                           "x1, where the DEA's electrode ends along the beam")),
              &Scene::deas, &DeaSpec::to);
  keys.back().constraint = "on the beam: from < to <= beam.length";
  add(choice("dea", "face", {"top", "bottom"}, true, "DEA",
             "the beam face the DEA is on (top = +w side: energised, it bends toward -w)"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(scene.deas[entry].face == Face::top ? "top" : "bottom");
  };
  entry_field(add(quantity("dea", "lever_arm", dim::length, positive(), true, "DEA",
                           "z, the distance of the DEA's film from the beam's neutral plane")),
              &Scene::deas, &DeaSpec::lever_arm);
  keys.back().sensitivity = true;
  entry_field(add(quantity("dea", "relative_permittivity", dim::none, positive(), true, "DEA",
                           "epsilon_r, the film's relative permittivity")),
              &Scene::deas, &DeaSpec::relative_permittivity);
  keys.back().sensitivity = true;
  entry_field(add(quantity("dea", "dielectric_thickness", dim::length, positive(), true, "DEA",
                           "d, the film's thickness in its capacitance (and the validity "
                           "check's field V/d)")),
              &Scene::deas, &DeaSpec::dielectric_thickness);
  keys.back().sensitivity = true;
  entry_field(add(quantity("dea", "force_thickness", dim::length, positive(), true, "DEA",
                           "d', the film's thickness in the electrostatic force (the paper's "
                           "Eq. 16)")),
              &Scene::deas, &DeaSpec::force_thickness);
  keys.back().sensitivity = true;
  entry_field(add(quantity("dea", "electrode_width", dim::length, positive(), true, "DEA",
                           "the electrode's width across the beam")),
              &Scene::deas, &DeaSpec::electrode_width);
  keys.back().sensitivity = true;
  entry_field(add(quantity("dea", "electrode_resistance", dim::resistance, positive(), true, "DEA",
                           "the electrodes' series resistance (the RC loop with the film)")),
              &Scene::deas, &DeaSpec::electrode_resistance);
  keys.back().sensitivity = true;
  add(key("dea", "back_coupling", K::boolean, "DEA",
          "true: the film's current has the motional part V*dC/dt (the beam loads the "
          "electrical side)"))
      .text = [](const Scene& scene, std::size_t entry) {
    return bool_text(scene.deas[entry].back_coupling);
  };
  entry_field(add(quantity("dea", "breakdown_field", dim::electric_field, positive(), false,
                           "validity check",
                           "the film's breakdown field: a larger V/d is flagged as outside the "
                           "model (default: ELASTOSIL Film 2030's data sheet)")),
              &Scene::deas, &DeaSpec::breakdown_field);

  // [drive]
  using D = DriveKind;
  const std::vector<std::string> kinds = {"none", "antagonistic", "switched", "bias_differential",
                                          "single"};
  add(choice("drive", "kind", kinds, false, "every drive kind",
             "what drives the DEAs: none (loads only), antagonistic or switched square waves, "
             "bias_differential or single sines"))
      .text = [](const Scene& scene, std::size_t) {
    return std::string(drive_kind_name(scene.drive.kind));
  };
  {
    ParameterInfo& deas = add(used_by_kinds(
        key("drive", "deas", K::name_list, "", "the driven DEAs by name: [A, B] or [A]"),
        {D::antagonistic, D::switched, D::bias_differential, D::single}));
    deas.required = true;
    deas.constraint = "two names (antagonistic, bias_differential) or one (switched, single)";
    deas.text = [](const Scene& scene, std::size_t) {
      std::string list;
      for (const std::string& name : scene.drive.deas)
        list += (list.empty() ? "" : ", ") + ("\"" + name + "\"");
      return "[" + list + "]";
    };
  }
  plain_field(add(used_by_kinds(quantity("drive", "voltage", dim::voltage, non_negative(), true, "",
                                         "V, the square wave's switched level (0/V)"),
                                {D::antagonistic, D::switched})),
              &Scene::drive, &DriveSpec::voltage);
  keys.back().sensitivity = true;
  plain_field(add(used_by_kinds(quantity("drive", "bias", dim::voltage, non_negative(), true, "",
                                         "V0, the sine drive's constant part"),
                                {D::bias_differential, D::single})),
              &Scene::drive, &DriveSpec::bias);
  keys.back().sensitivity = true;
  plain_field(add(used_by_kinds(quantity("drive", "amplitude", dim::voltage, non_negative(), true,
                                         "", "v, the sine drive's amplitude: V0 + v*sin(2*pi*f*t)"),
                                {D::bias_differential, D::single})),
              &Scene::drive, &DriveSpec::amplitude);
  plain_field(
      add(used_by_kinds(quantity("drive", "frequency", dim::frequency, positive(), true, "",
                                 "the switching or sine frequency (drive kind none: only "
                                 "the period of tran --periods)"),
                        {D::none, D::antagonistic, D::switched, D::bias_differential, D::single})),
      &Scene::drive, &DriveSpec::frequency);
  keys.back().used_by = "every drive kind";
  keys.back().default_note = "required (optional with drive kind none)";
  plain_field(
      add(used_by_kinds(quantity("drive", "duty", dim::none,
                                 interval(Limit::exclusive, 0.0, Limit::exclusive, 1.0,
                                          "must be between 0 and 1 (exclusive), got {}"),
                                 false, "", "the fraction of each period DEA A (or the DEA) is on"),
                        {D::antagonistic, D::switched})),
      &Scene::drive, &DriveSpec::duty);
  plain_field(add(used_by_kinds(quantity("drive", "rise_time", dim::time, non_negative(), false, "",
                                         "the time each edge of the square wave takes"),
                                {D::antagonistic, D::switched})),
              &Scene::drive, &DriveSpec::rise_time);
  keys.back().constraint = "shorter than half a period";
  plain_field(add(used_by_kinds(quantity("drive", "overlap", dim::time, unbounded(), false, "",
                                         "how long A stays on after B has switched on (negative: "
                                         "a dead time between them)"),
                                {D::antagonistic})),
              &Scene::drive, &DriveSpec::overlap);
  keys.back().constraint = "DEA A's on-time duty*T + overlap inside the period, clear of the edges";
  add(key("drive", "electrical_dynamics", K::boolean, "every drive kind",
          "true: each DEA is its capacitor behind its electrode resistance; false: an ideal "
          "voltage-driven force; \"auto\": chosen for [model]'s band"))
      .text = [](const Scene& scene, std::size_t) {
    return scene.drive.electrical_dynamics_auto ? std::string("auto")
                                                : bool_text(scene.drive.electrical_dynamics);
  };
  keys.back().constraint = "or \"auto\"";

  // [[load]]
  add(choice("load", "kind", {"force", "moment"}, true, "loads",
             "a point force or a point moment on the beam"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(scene.loads[entry].kind == LoadKind::force ? "force" : "moment");
  };
  entry_field(add(quantity("load", "at", dim::length, unbounded(), true, "loads",
                           "where the load acts along the beam")),
              &Scene::loads, &LoadSpec::at);
  keys.back().constraint = "on the beam: 0 <= at <= beam.length";
  entry_field(add(quantity("load", "value", dim::force, unbounded(), true, "loads",
                           "the load's value (its static value and its AC amplitude)")),
              &Scene::loads, &LoadSpec::value);
  keys.back().unit_note = "N (a force), N*m (a moment)";

  // [[probe]]
  add(key("probe", "name", K::name, "probes", "the probe's name (--probe NAME, outputs)"))
      .required = true;
  keys.back().constraint = "letters, digits and '_', at most 64 characters, unique";
  keys.back().text = [](const Scene& scene, std::size_t entry) { return scene.probes[entry].name; };
  add(choice(
          "probe", "quantity",
          {"deflection", "velocity", "rotation", "angular_velocity", "dea_voltage", "dea_current",
           "reaction_force", "reaction_moment", "spring_force", "strain", "dea_force"},
          true, "probes",
          "what the probe measures: a beam quantity at probe[].at (reaction_force and "
          "reaction_moment: the support's force or moment on the beam at a held end, at = 0 "
          "or beam.length; strain: at a face, probe[].face and probe[].distance), a spring's "
          "force (probe[].spring), or a DEA's voltage, current or force k_F*u^2 (probe[].dea)"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(probe_quantity_name(scene.probes[entry].quantity));
  };
  entry_field(add(quantity("probe", "at", dim::length, unbounded(), true,
                           "probes of beam quantities (deflection, velocity, rotation, "
                           "angular_velocity, strain, reaction_force, reaction_moment)",
                           "where along the beam the probe measures")),
              &Scene::probes, &ProbeSpec::at);
  keys.back().constraint =
      "on the beam: 0 <= at <= beam.length; a reaction: at a held end, 0 or beam.length";
  add(key("probe", "dea", K::name, "probes dea_voltage, dea_current, dea_force",
          "the DEA whose voltage, current or force the probe measures"))
      .required = true;
  keys.back().constraint = "a DEA of the scene";
  keys.back().text = [](const Scene& scene, std::size_t entry) { return scene.probes[entry].dea; };
  add(key("probe", "spring", K::name, "probes spring_force",
          "the spring whose force (a rotational spring: moment) the probe measures, by its "
          "spring[].name or its index in the [[spring]] list (0, 1, ...)"))
      .required = true;
  keys.back().constraint = "a spring of the scene: its name, or its index";
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    return scene.probes[entry].spring;
  };
  add(choice("probe", "face", {"top", "bottom"}, true, "probes strain",
             "the face whose strain the probe measures (top = +w side, compressed when the "
             "beam bends toward +w)"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(scene.probes[entry].face == Face::top ? "top" : "bottom");
  };
  entry_field(add(quantity("probe", "distance", dim::length, positive(), true, "probes strain",
                           "z, the distance of the face from the beam's neutral plane: the "
                           "strain is -z*dpsi/dx on the top face, +z*dpsi/dx on the bottom")),
              &Scene::probes, &ProbeSpec::distance);

  // [[circuit]]
  const char* circuit_users = "circuit elements";
  add(key("circuit", "name", K::name, circuit_users,
          "the element's name (it names the element in SPICE decks and messages)"))
      .required = true;
  keys.back().constraint = "letters, digits and '_', at most 64 characters, unique";
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    return scene.circuit[entry].name;
  };
  add(choice("circuit", "kind",
             {"resistor", "capacitor", "inductor", "voltage_source", "current_source"}, true,
             circuit_users, "what the element is"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(circuit_kind_name(scene.circuit[entry].kind));
  };
  for (const char* end : {"from", "to"}) {
    add(key("circuit", end, K::text, circuit_users,
            std::string(end) == "from"
                ? "the node of the element's first end: a name of the circuit's own, \"ground\" "
                  "(or \"0\"), or \"dea.X\" (DEA X's terminal, in front of its electrode "
                  "resistance); a voltage source's + terminal, where a current source's current "
                  "leaves"
                : "the node of the element's second end (as circuit[].from); a voltage source's "
                  "- terminal, where a current source's current enters"))
        .required = true;
    keys.back().constraint =
        "a node touched by two element ends at least, with a DC path to ground";
    const bool first = std::string(end) == "from";
    keys.back().text = [first](const Scene& scene, std::size_t entry) {
      return first ? scene.circuit[entry].from : scene.circuit[entry].to;
    };
  }
  entry_field(add(quantity("circuit", "value", dim::resistance, unbounded(), true, circuit_users,
                           "the resistance, capacitance or inductance; a source's constant value "
                           "(waveform dc)")),
              &Scene::circuit, &CircuitSpec::value);
  keys.back().sensitivity = true;
  keys.back().unit_note = "Ohm (resistor), F (capacitor), H (inductor), V or A (sources)";
  keys.back().constraint = "> 0 for a resistor, capacitor or inductor";
  keys.back().default_note = "required (sources: with waveform dc)";
  add(choice("circuit", "waveform", {"dc", "sine", "square", "pulse", "pwl"}, false,
             "circuit sources", "the source's time function"))
      .text = [](const Scene& scene, std::size_t entry) {
    return std::string(waveform_kind_name(scene.circuit[entry].waveform.kind));
  };
  const char* level_unit = "V (voltage_source), A (current_source)";
  auto level = [&](const char* name, const char* users, bool required, const char* meaning,
                   double WaveformSpec::*member) {
    waveform_field(
        add(quantity("circuit", name, dim::voltage, unbounded(), required, users, meaning)),
        member);
    keys.back().unit_note = level_unit;
  };
  level("low", "source waveforms square, pulse", true, "the level before and between the pulses",
        &WaveformSpec::low);
  level("high", "source waveforms square, pulse", true, "the pulses' level", &WaveformSpec::high);
  waveform_field(add(quantity("circuit", "frequency", dim::frequency, positive(), true,
                              "source waveforms square, sine",
                              "the square wave's or sine's "
                              "frequency")),
                 &WaveformSpec::frequency);
  waveform_field(add(quantity("circuit", "duty", dim::none,
                              interval(Limit::exclusive, 0.0, Limit::exclusive, 1.0,
                                       "must be between 0 and 1 (exclusive), got {}"),
                              false, "source waveform square",
                              "the fraction of each period at the high level (its rise "
                              "included)")),
                 &WaveformSpec::duty);
  waveform_field(add(quantity("circuit", "rise", dim::time, non_negative(), false,
                              "source waveforms square, pulse", "the rising edge's time")),
                 &WaveformSpec::rise);
  {
    ParameterInfo& fall =
        add(quantity("circuit", "fall", dim::time, non_negative(), false,
                     "source waveforms square, pulse", "the falling edge's time"));
    fall.get = [](const Scene& scene, std::size_t entry) -> std::optional<double> {
      return scene.circuit[entry].waveform.fall_time();
    };
    fall.set = [](Scene& scene, std::size_t entry, double value) {
      scene.circuit[entry].waveform.fall = value;
    };
    fall.default_note = "the rise time (square), 0 s (pulse)";
  }
  waveform_field(add(quantity("circuit", "delay", dim::time, non_negative(), false,
                              "source waveforms square, pulse, sine",
                              "the time before the waveform starts (the first pulse's rise, the "
                              "sine's t = 0)")),
                 &WaveformSpec::delay);
  waveform_field(add(quantity("circuit", "width", dim::time, non_negative(), true,
                              "source waveform pulse", "the time at the high level")),
                 &WaveformSpec::width);
  waveform_field(add(quantity("circuit", "period", dim::time, non_negative(), false,
                              "source waveform pulse", "the pulse's period (0: one pulse)")),
                 &WaveformSpec::period);
  keys.back().constraint = "0 or at least rise + width + fall";
  level("offset", "source waveform sine", false, "the sine's constant part", &WaveformSpec::offset);
  level("amplitude", "source waveform sine", true,
        "the sine's amplitude: offset + amplitude*sin(2*pi*f*(t - delay) + phase)",
        &WaveformSpec::amplitude);
  waveform_field(
      add(quantity("circuit", "phase", dim::none, unbounded(), false, "source waveform sine",
                   "the sine's phase at t = delay, in degrees (a plain number)")),
      &WaveformSpec::phase_degrees);
  keys.back().unit_note = "deg";
  add(key("circuit", "points", K::text, "source waveform pwl",
          "the piecewise-linear waveform inline: [[\"0 s\", \"0 V\"], [\"1 ms\", \"3 kV\"], ...], "
          "times increasing"));
  keys.back().constraint = "either points or file";
  keys.back().default_note = "required with waveform pwl (or file)";
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    const WaveformSpec& waveform = scene.circuit[entry].waveform;
    if (!waveform.file.empty()) return std::string();
    std::string list;
    for (const auto& [time, value] : waveform.points)
      list += (list.empty() ? "[" : ", [") + scene_text::format_number(time) + ", " +
              scene_text::format_number(value) + "]";
    return "[" + list + "]";
  };
  add(key("circuit", "file", K::text, "source waveform pwl",
          "the piecewise-linear waveform from a CSV file (relative to the scene file's folder): "
          "time [s], value [SI] per line, one header line allowed"));
  keys.back().constraint = "either points or file";
  keys.back().default_note = "none";
  keys.back().text = [](const Scene& scene, std::size_t entry) {
    return scene.circuit[entry].waveform.file;
  };
  entry_field(add(quantity("circuit", "ac", dim::voltage, unbounded(), false, "circuit sources",
                           "the source's magnitude in the AC analysis")),
              &Scene::circuit, &CircuitSpec::ac);
  keys.back().unit_note = level_unit;

  // [ac]
  plain_field(add(quantity("ac", "from", dim::frequency, non_negative(), false, "ac",
                           "the AC sweep's lowest frequency")),
              &Scene::ac, &AcSpec::from);
  keys.back().constraint = "> 0 on a log scale";
  plain_field(add(quantity("ac", "to", dim::frequency, unbounded(), false,
                           "ac; the band of \"auto\" choices", "the AC sweep's highest frequency")),
              &Scene::ac, &AcSpec::to);
  keys.back().constraint = "> ac.from";
  {
    ParameterInfo& points =
        add(key("ac", "points", K::integer, "ac", "the number of frequencies of the AC sweep"));
    points.range = interval(Limit::inclusive, 2.0, Limit::inclusive, 1000000.0,
                            "must be between 2 and 1000000, got {}");
    points.get = [](const Scene& scene, std::size_t) -> std::optional<double> {
      return static_cast<double>(scene.ac.points);
    };
    points.set = [](Scene& scene, std::size_t, double value) {
      scene.ac.points = static_cast<int>(value);
    };
  }
  add(choice("ac", "scale", {"lin", "log"}, false, "ac",
             "the AC sweep's spacing: linear or logarithmic"))
      .text = [](const Scene& scene, std::size_t) {
    return std::string(scene.ac.log ? "log" : "lin");
  };

  // [environment]
  add(choice("environment", "fluid", {"none", "air", "water"}, false, "fluid loading",
             "the fluid around the beam (added mass and damping of a plate in it)"))
      .text = [](const Scene& scene, std::size_t) {
    return std::string(fluid_name(scene.environment.fluid));
  };
  const char* fluid_users = "fluid loading (fluid air, water)";
  plain_field(add(quantity("environment", "density", dim::density, positive(), false, fluid_users,
                           "rho, the fluid's density")),
              &Scene::environment, &EnvironmentSpec::density);
  keys.back().default_note = "the fluid's at 20 C: water 998.2 kg/m^3, air 1.204 kg/m^3";
  plain_field(add(quantity("environment", "dynamic_viscosity", dim::dynamic_viscosity, positive(),
                           false, fluid_users, "eta, the fluid's dynamic viscosity")),
              &Scene::environment, &EnvironmentSpec::dynamic_viscosity);
  keys.back().default_note = "the fluid's at 20 C: water 1.002e-3 Pa*s, air 1.81e-5 Pa*s";
  plain_field(add(quantity("environment", "width", dim::length, positive(), true, fluid_users,
                           "b, the plate's width across the motion")),
              &Scene::environment, &EnvironmentSpec::width);
  keys.back().default_note = "required with a fluid";
  plain_field(
      add(quantity("environment", "frequency", dim::frequency, positive(), false, fluid_users,
                   "the frequency at which the hydrodynamic function is evaluated")),
      &Scene::environment, &EnvironmentSpec::frequency);
  keys.back().default_note = "unset: the loaded beam's first resonance (a fixed point)";

  // [model]
  {
    ParameterInfo& band =
        add(key("model", "band", K::band, "the \"auto\" choices",
                "the frequency band the automatic choices must be accurate in: \"130 Hz\" (from "
                "0) or [from, to]"));
    band.dimension = dim::frequency;
    band.range = non_negative();
    band.constraint = "0 <= from < to";
    band.default_note =
        "unset: 0 to the larger of ac.to (with an [ac] table) and 10 x drive.frequency";
    band.text = [](const Scene& scene, std::size_t) {
      if (!scene.model.band_to) return std::string("unset");
      return "[\"" + format_quantity(scene.model.band_from.value_or(0.0), dim::frequency) +
             "\", \"" + format_quantity(*scene.model.band_to, dim::frequency) + "\"]";
    };
  }
  plain_field(add(quantity("model", "tolerance", dim::none,
                           interval(Limit::exclusive, 0.0, Limit::exclusive, 0.5,
                                    "must lie in (0, 0.5) (a relative error), got {}"),
                           false, "the \"auto\" choices",
                           "the relative accuracy the automatic choices hold the band's "
                           "resonances to")),
              &Scene::model, &ModelSpec::tolerance);
  plain_field(
      add(quantity("model", "deflection_limit", dim::none,
                   interval(Limit::exclusive, 0.0, Limit::inclusive, 1.0,
                            "must be > 0 and at most 1 (a fraction of beam.length), got {}"),
                   false, "validity check",
                   "the largest |deflection| trusted to the linear beam, a fraction of "
                   "beam.length; beyond it a result is flagged")),
      &Scene::model, &ModelSpec::deflection_limit);

  // [provenance]
  add(key("provenance", "*", K::free_form,
          "identify (only identified: and assumed: values are "
          "fitted), documentation",
          "where a value comes from: \"dotted.key\" = \"paper: ...\", \"data sheet: ...\", "
          "\"assumed: ...\" or \"identified: ...\""))
      .default_note = "none";
  keys.back().text = [](const Scene&, std::size_t) { return std::string(); };

  return keys;
}

std::vector<SceneTableInfo> tables_of(const std::vector<ParameterInfo>& keys) {
  std::vector<SceneTableInfo> tables = {
      {"scene", false, false, 0, {}, "the scene's name and title (required)"},
      {"beam", false, false, 0, {}, "the beam (required)"},
      {"section",
       true,
       false,
       scene_limits::sections,
       {},
       "beam sections from x = 0, one [[section]] entry each (none: a uniform beam)"},
      {"mass",
       true,
       false,
       scene_limits::masses,
       {},
       "point masses on the beam, one [[mass]] each"},
      {"spring",
       true,
       false,
       scene_limits::springs,
       {},
       "springs and dashpots to ground or between two points, one [[spring]] each"},
      {"damping", false, false, 0, {}, "the beam's damping"},
      {"dea", true, false, scene_limits::deas, {}, "the DEAs, one [[dea]] entry each"},
      {"drive", false, false, 0, {}, "what drives the DEAs"},
      {"load", true, false, scene_limits::loads, {}, "point loads, one [[load]] entry each"},
      {"probe", true, false, scene_limits::probes, {}, "named outputs, one [[probe]] entry each"},
      {"circuit",
       true,
       false,
       scene_limits::circuit_elements,
       {},
       "electrical circuit elements around the DEAs, one [[circuit]] entry each"},
      {"ac", false, false, 0, {}, "the AC sweep's defaults"},
      {"environment", false, false, 0, {}, "the fluid around the beam"},
      {"model", false, false, 0, {}, "what the automatic choices and the validity check aim at"},
      {"provenance", false, true, 0, {}, "where each value comes from"},
  };
  for (SceneTableInfo& table : tables)
    for (const ParameterInfo& info : keys)
      if (info.table == table.name && !table.free_form) table.keys.push_back(info.name);
  return tables;
}

}  // namespace

const std::vector<ParameterInfo>& parameter_table() {
  static const std::vector<ParameterInfo> table = scene_keys();
  return table;
}

const std::vector<SceneTableInfo>& scene_tables() {
  static const std::vector<SceneTableInfo> tables = tables_of(parameter_table());
  return tables;
}

}  // namespace emnet
