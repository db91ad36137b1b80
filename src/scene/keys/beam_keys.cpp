// The keys of the beam: [beam] (length, segments, bending stiffness, mass and rotary inertia per
// length, end conditions, theory), its [[section]] entries (a stepped beam: each section's own
// stiffness, mass, shear stiffness and damping) and its [damping] (viscous to ground, Kelvin-Voigt
// material damping, or a loss factor at a frequency).
#include "scene_key_tables.hpp"

namespace emnet {
namespace scene_keys {

// [beam]
SceneTableKeys beam_table_keys() {
  SceneTableKeys keys = plain_table("beam", "the beam (required)");
  plain_field(keys.add(quantity("beam", "length", dim::length, positive(), true, "beam",
                                "L, the beam's length from the left end (x = 0) to the right end")),
              &Scene::beam, &BeamSpec::length);
  keys.back().sensitivity = true;
  {
    ParameterInfo& segments = keys.add(
        key("beam", "segments", ParameterKind::integer, "beam",
            "N, the number of segments the beam is cut into: equal on a plain beam, spread by "
            "length between the nodes that sections, masses, springs, DEA ends and loads put; "
            "\"auto\": chosen for [model]'s band and tolerance"));
    segments.required = true;
    segments.range = segment_count_range();
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
  plain_field(keys.add(quantity("beam", "bending_stiffness", dim::bending_stiffness, positive(),
                                true, "beam", "EI, the beam's bending stiffness")),
              &Scene::beam, &BeamSpec::bending_stiffness);
  keys.back().sensitivity = true;
  plain_field(keys.add(quantity("beam", "mass_per_length", dim::mass_per_length, positive(), true,
                                "beam", "rho*A, the beam's mass per unit length")),
              &Scene::beam, &BeamSpec::mass_per_length);
  keys.back().sensitivity = true;
  plain_field(
      keys.add(quantity("beam", "rotary_inertia_per_length", dim::rotary_inertia_per_length,
                        non_negative(), false, "beam",
                        "rho*I, the rotary inertia per unit length (0: Euler-Bernoulli, none)")),
      &Scene::beam, &BeamSpec::rotary_inertia_per_length);
  keys.back().sensitivity = true;
  const std::vector<std::string> ends = {"clamped", "free", "pinned", "sliding"};
  keys.add(choice("beam", "left", ends, false, "beam", "the end condition at x = 0")).text =
      [](const Scene& scene, std::size_t) {
        return std::string(end_condition_name(scene.beam.left));
      };
  keys.add(choice("beam", "right", ends, false, "beam", "the end condition at x = beam.length"))
      .text = [](const Scene& scene, std::size_t) {
    return std::string(end_condition_name(scene.beam.right));
  };

  keys.add(choice(
               "beam", "theory", {"euler_bernoulli", "timoshenko"}, false, "beam",
               "what a segment realises: bending only, or bending and shear (the shear compliance "
               "l/(kappa*G*A) of each segment)"))
      .text = [](const Scene& scene, std::size_t) {
    return std::string(beam_theory_name(scene.beam.theory));
  };
  plain_field(
      keys.add(quantity("beam", "shear_stiffness", dim::force, positive(), false,
                        "beam theory 'timoshenko'",
                        "kappa*G*A, the shear stiffness (shear correction factor times shear "
                        "modulus times cross-section)")),
      &Scene::beam, &BeamSpec::shear_stiffness);
  keys.back().sensitivity = true;
  keys.back().constraint = "with beam.theory = \"timoshenko\"";
  keys.back().default_note =
      "required with beam.theory = \"timoshenko\" (unless every section "
      "gives its own)";

  keys.add(choice("beam", "kinematics", {"small", "large", "auto"}, false, "beam",
                  "small: the linear beam network (small deflections and rotations); large: "
                  "planar, geometrically exact co-rotational segments (any rotation, dead loads); "
                  "auto: large where the small beam's geometric error max((w/L)^2, psi^2) (its "
                  "largest deflection over L and section rotation), from its static "
                  "state and its AC response to the drive, exceeds model.tolerance"))
      .text = [](const Scene& scene, std::size_t) {
    return std::string(scene.beam.kinematics_auto ? "auto"
                                                  : beam_kinematics_name(scene.beam.kinematics));
  };
  plain_field(keys.add(quantity("beam", "axial_stiffness", dim::force, positive(), false,
                                "beam kinematics 'large'",
                                "EA, the axial stiffness (Young's modulus times cross-section) "
                                "of the segments' axial compliance l/EA")),
              &Scene::beam, &BeamSpec::axial_stiffness);
  keys.back().sensitivity = true;
  keys.back().constraint = "with beam.kinematics = \"large\"";
  keys.back().default_note = "unset: the beam is inextensible (each chord keeps its length)";
  return keys;
}

// [[section]]
SceneTableKeys section_table_keys() {
  SceneTableKeys keys =
      entries_table("section", scene_limits::sections,
                    "beam sections from x = 0, one [[section]] entry each (none: a uniform beam)");
  const char* section_users = "beam sections";
  beam_entry_field(
      keys.add(quantity("section", "length", dim::length, positive(), true, section_users,
                        "the section's length; the sections follow each other from x = 0 "
                        "and add up to beam.length")),
      &BeamSpec::sections, &SectionSpec::length);
  keys.back().constraint = "the lengths add up to beam.length";
  beam_entry_field(keys.add(quantity("section", "bending_stiffness", dim::bending_stiffness,
                                     positive(), true, section_users, "EI of the section")),
                   &BeamSpec::sections, &SectionSpec::bending_stiffness);
  keys.back().sensitivity = true;
  beam_entry_field(keys.add(quantity("section", "mass_per_length", dim::mass_per_length, positive(),
                                     true, section_users, "rho*A of the section")),
                   &BeamSpec::sections, &SectionSpec::mass_per_length);
  keys.back().sensitivity = true;
  beam_entry_field(
      keys.add(quantity("section", "rotary_inertia_per_length", dim::rotary_inertia_per_length,
                        non_negative(), false, section_users, "rho*I of the section")),
      &BeamSpec::sections, &SectionSpec::rotary_inertia_per_length);
  keys.back().sensitivity = true;
  beam_entry_field(keys.add(quantity("section", "shear_stiffness", dim::force, positive(), false,
                                     section_users, "kappa*G*A of the section (Timoshenko)")),
                   &BeamSpec::sections, &SectionSpec::shear_stiffness);
  keys.back().sensitivity = true;
  keys.back().constraint = "with beam.theory = \"timoshenko\"";
  keys.back().default_note = "unset: beam.shear_stiffness";
  beam_entry_field(keys.add(quantity("section", "axial_stiffness", dim::force, positive(), false,
                                     section_users, "EA of the section (large kinematics)")),
                   &BeamSpec::sections, &SectionSpec::axial_stiffness);
  keys.back().sensitivity = true;
  keys.back().constraint = "with beam.kinematics = \"large\"";
  keys.back().default_note = "unset: beam.axial_stiffness";
  beam_entry_field(keys.add(quantity("section", "viscous_per_length", dim::damping_per_length,
                                     non_negative(), false, section_users,
                                     "the section's viscous damping to ground per length")),
                   &BeamSpec::sections, &SectionSpec::viscous_per_length);
  keys.back().sensitivity = true;
  keys.back().default_note = "unset: damping.viscous_per_length";
  beam_entry_field(keys.add(quantity("section", "kelvin_voigt_time", dim::time, non_negative(),
                                     false, section_users, "the section's Kelvin-Voigt time tau")),
                   &BeamSpec::sections, &SectionSpec::kelvin_voigt_time);
  keys.back().sensitivity = true;
  keys.back().default_note = "unset: the [damping] table's tau";
  {
    ParameterInfo& segments =
        keys.add(key("section", "segments", ParameterKind::integer, section_users,
                     "the section's own number of segments; unset or \"auto\": its share of "
                     "beam.segments by length"));
    segments.range = segment_count_range();
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
  return keys;
}

// [damping]
SceneTableKeys damping_table_keys() {
  SceneTableKeys keys = plain_table("damping", "the beam's damping");
  plain_field(
      keys.add(quantity("damping", "viscous_per_length", dim::damping_per_length, non_negative(),
                        false, "beam (damping)",
                        "viscous damping to ground per unit length (a dashpot at each node)")),
      &Scene::damping, &DampingSpec::viscous_per_length);
  keys.back().sensitivity = true;
  plain_field(
      keys.add(quantity("damping", "kelvin_voigt_time", dim::time, non_negative(), false,
                        "beam (damping)",
                        "tau of the Kelvin-Voigt material damping M = EI*(kappa + tau*dkappa/dt)")),
      &Scene::damping, &DampingSpec::kelvin_voigt_time);
  keys.back().sensitivity = true;
  keys.back().constraint = "not with damping.loss_factor";
  plain_field(keys.add(quantity("damping", "loss_factor", dim::none, non_negative(), false,
                                "beam (damping)",
                                "eta, the loss factor at damping.loss_factor_frequency: the "
                                "Kelvin-Voigt time tau = eta/(2*pi*f)")),
              &Scene::damping, &DampingSpec::loss_factor);
  keys.back().sensitivity = true;
  keys.back().constraint = "with damping.loss_factor_frequency, not with kelvin_voigt_time";
  keys.back().default_note = "unset (no loss factor)";
  plain_field(
      keys.add(quantity("damping", "loss_factor_frequency", dim::frequency, positive(), false,
                        "beam (damping)", "f, the frequency at which damping.loss_factor holds")),
      &Scene::damping, &DampingSpec::loss_factor_frequency);
  keys.back().sensitivity = true;
  keys.back().constraint = "only with damping.loss_factor";
  keys.back().default_note = "unset; required with damping.loss_factor";
  return keys;
}

}  // namespace scene_keys
}  // namespace emnet
