// Outputs besides deflection: a support's reaction force and moment, a spring's force, the
// strain at a face and a DEA's force, against closed forms (docs/model.md, Outputs).
//
// Sign conventions under test: a reaction is what the support exerts on the beam, a force
// positive along +w, a moment positive as +ψ (so a cantilever under a tip force F along +w has
// R = −F and M_R = −F·L); a spring's force is k·(w(at) − w(to)) + c·rate (positive stretched
// along +w at its `at` end); the strain is −z·dψ/dx on the top face, +z·dψ/dx on the bottom.
//
// Statics are exact for every N (the segment network has the exact massless segment's
// flexibility and the mesher puts nodes at every load and spring), so the only error is the
// rounding of a sparse LU: 1e-10 relative, as in test_beam_components.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>

#include "emnet/analysis/analysis.hpp"
#include "emnet/analysis/transient.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/elements/dea.hpp"
#include "emnet/model/model.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using emnet::testing::kPi;

struct Built {
  Model model;
  System system;
  StaticResult rest;
};

Built build(const std::string& text, const std::vector<std::string>& overrides = {}) {
  Built built{prepare_model(read_scene_text(text, "test.toml", overrides)), {}, {}};
  built.system = built.model.network.assemble();
  built.rest = solve_static(built.system);
  EXPECT_TRUE(built.rest.status.ok()) << built.rest.status.message;
  return built;
}

double static_value(const Built& built, const std::string& probe) {
  return static_probe_value(built.system, built.rest, built.model.parse_probe(probe));
}

std::string beam(const std::string& left, const std::string& right, int segments,
                 const std::string& more = "") {
  return "[scene]\nname = \"t\"\n[beam]\nlength = 0.5\nbending_stiffness = 2.0\n"
         "mass_per_length = 0.3\nsegments = " +
         std::to_string(segments) + "\nleft = \"" + left + "\"\nright = \"" + right + "\"\n" +
         more + "\n";
}

std::string load(double at, double value, const std::string& kind = "force") {
  return "[[load]]\nkind = \"" + kind + "\"\nat = " + std::to_string(at) +
         "\nvalue = " + std::to_string(value) + "\n";
}

// ---- reactions -----------------------------------------------------------------------------

// Cantilever, tip force F = 1.3 N, L = 0.5 m: R = −F, M_R = −F·L at the clamp, for every N.
TEST(Reaction, CantileverTipForce) {
  const double force = 1.3, length = 0.5;
  for (int segments : {1, 3, 10}) {
    const Built built = build(beam("clamped", "free", segments) + load(length, force));
    EXPECT_NEAR(static_value(built, "reaction_force@0"), -force, 1e-10 * force)
        << "N = " << segments;
    EXPECT_NEAR(static_value(built, "reaction_moment@0"), -force * length, 1e-10 * force * length)
        << "N = " << segments;
  }
}

// Clamped at the right end instead (mirror image): R = −F, M_R = +F·L (the mirror turns the
// sense of rotation).
TEST(Reaction, CantileverClampedOnTheRight) {
  const double force = 1.3, length = 0.5;
  for (int segments : {1, 4}) {
    const Built built = build(beam("free", "clamped", segments) + load(0.0, force));
    EXPECT_NEAR(static_value(built, "reaction_force@0.5"), -force, 1e-10 * force);
    EXPECT_NEAR(static_value(built, "reaction_moment@0.5"), force * length, 1e-10 * force * length);
  }
}

// Central force F: each support takes −F/2; clamped–clamped end moments ∓F·L/8 (left −, right
// +: Σ moments about x = 0 is M_L + M_R + L·R_R + (L/2)·F = 0). Pinned–pinned: −F/2 each.
TEST(Reaction, ClampedClampedAndPinnedPinnedCentralForce) {
  const double force = 2.0, length = 0.5;
  for (int segments : {2, 4, 10}) {
    const Built clamped = build(beam("clamped", "clamped", segments) + load(0.25, force));
    EXPECT_NEAR(static_value(clamped, "reaction_force@0"), -force / 2, 1e-10 * force);
    EXPECT_NEAR(static_value(clamped, "reaction_force@0.5"), -force / 2, 1e-10 * force);
    EXPECT_NEAR(static_value(clamped, "reaction_moment@0"), -force * length / 8,
                1e-10 * force * length);
    EXPECT_NEAR(static_value(clamped, "reaction_moment@0.5"), force * length / 8,
                1e-10 * force * length);
    const Built pinned = build(beam("pinned", "pinned", segments) + load(0.25, force));
    EXPECT_NEAR(static_value(pinned, "reaction_force@0"), -force / 2, 1e-10 * force);
    EXPECT_NEAR(static_value(pinned, "reaction_force@0.5"), -force / 2, 1e-10 * force);
  }
}

// Without distributed loads the reactions balance the applied ones exactly: a clamped–pinned
// beam under two forces and a moment, ΣF = 0 and Σ moments about x = 0 = 0.
TEST(Reaction, EquilibriumOfAStaticallyIndeterminateBeam) {
  const double f1 = 1.1, f2 = -0.4, m = 0.3, length = 0.5;
  const Built built = build(beam("clamped", "pinned", 7) + load(0.13, f1) + load(0.41, f2) +
                            load(0.3, m, "moment"));
  const double r0 = static_value(built, "reaction_force@0");
  const double r1 = static_value(built, "reaction_force@0.5");
  const double m0 = static_value(built, "reaction_moment@0");
  EXPECT_NEAR(r0 + r1 + f1 + f2, 0.0, 1e-10 * std::abs(f1));
  EXPECT_NEAR(m0 + length * r1 + 0.13 * f1 + 0.41 * f2 + m, 0.0, 1e-10 * std::abs(f1));
}

// ---- springs -------------------------------------------------------------------------------

// Pinned at x = 0, free at L, a translational spring to ground at a = 0.3 m and a tip force F:
// moments about the pin give the spring's force S = F·L/a, and the pin's reaction R = S − F.
TEST(SpringForce, PinnedBeamOnASpringUnderATipForce) {
  const double force = 1.3, length = 0.5, a = 0.3;
  for (int segments : {1, 5}) {
    const Built built =
        build(beam("pinned", "free", segments) + load(length, force) +
              "[[spring]]\nname = \"prop\"\nat = 0.3\nkind = \"translational\"\nstiffness = 500\n");
    const double spring = force * length / a;
    EXPECT_NEAR(static_value(built, "spring_force:prop"), spring, 1e-10 * spring);
    EXPECT_NEAR(static_value(built, "spring_force:0"), spring, 1e-10 * spring);
    EXPECT_NEAR(static_value(built, "reaction_force@0"), spring - force, 1e-10 * spring);
  }
}

// A rotational spring at a pinned root carries the whole moment F·L of a tip force; the pin the
// force (R = −F).
TEST(SpringForce, RotationalSpringAtAPinnedRoot) {
  const double force = 1.3, length = 0.5;
  const Built built =
      build(beam("pinned", "free", 4) + load(length, force) +
            "[[spring]]\nname = \"root\"\nat = 0\nkind = \"rotational\"\nstiffness = 30\n");
  EXPECT_NEAR(static_value(built, "spring_force:root"), force * length, 1e-10 * force * length);
  EXPECT_EQ(built.model.parse_probe("spring_force:root").unit, "N*m");
  EXPECT_NEAR(static_value(built, "reaction_force@0"), -force, 1e-10 * force);
}

// A free end on springs is no support: the reaction there is refused, naming the spring.
TEST(SpringForce, ReactionAtAFreeEndIsRefused) {
  const Built built = build(beam("free", "free", 2) + load(0.5, 1.0) +
                            "[[spring]]\nat = 0\nkind = \"translational\"\nstiffness = 30\n"
                            "[[spring]]\nat = 0\nkind = \"rotational\"\nstiffness = 30\n");
  try {
    built.model.parse_probe("reaction_force@0");
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("spring_force"), std::string::npos) << error.what();
  }
  EXPECT_THROW(build(beam("clamped", "pinned", 2)).model.parse_probe("reaction_moment@0.5"),
               InputError);
}

// ---- strain --------------------------------------------------------------------------------

// Cantilever, tip force F: ε(x) = ∓z·F·(L − x)/EI, at x inside a segment, for every N (the
// exact massless segment's curvature is linear in x).
TEST(Strain, CantileverTipForce) {
  const double force = 1.3, length = 0.5, ei = 2.0, z = 1.5e-3, x = 0.37;
  const double exact = z * force * (length - x) / ei;
  for (int segments : {1, 3, 10}) {
    const Built built = build(beam("clamped", "free", segments) + load(length, force));
    EXPECT_NEAR(static_value(built, "strain@0.37,top,1.5mm"), -exact, 1e-10 * exact);
    EXPECT_NEAR(static_value(built, "strain@370mm,bottom,0.0015"), exact, 1e-10 * exact);
  }
}

// ---- AC ------------------------------------------------------------------------------------

// One segment (k = 3EI/L³ at the tip, its rotation massless), tip mass M_t = M + ρA·L/2, tip
// force F: W = F/(k·(1 + jωτ) − M_t·ω²); the segment carries S = k·(1 + jωτ)·W (Kelvin–Voigt:
// K → K·(1 + jωτ) on every compliance), so R = −S and M_R = −L·S. Exact network: 1e-9.
TEST(Reaction, AcOfATipMassOnASegmentWithAndWithoutMaterialDamping) {
  const double length = 0.5, ei = 2.0, rho_a = 0.3, mass = 0.2, force = 1.0;
  const double k = 3 * ei / std::pow(length, 3), tip_mass = mass + rho_a * length / 2;
  for (double tau : {0.0, 2e-3}) {
    const Built built = build(
        beam("clamped", "free", 1, "[damping]\nkelvin_voigt_time = " + std::to_string(tau) + "\n") +
        load(length, force) + "[[mass]]\nat = 0.5\nmass = 0.2\n");
    const std::vector<Probe> probes = {built.model.parse_probe("reaction_force@0"),
                                       built.model.parse_probe("reaction_moment@0")};
    const std::vector<double> frequencies = {1.0, 3.0, 7.5, 20.0};
    const AcResult ac = run_ac(built.system, built.rest.operating_point, frequencies, probes);
    ASSERT_TRUE(ac.status.ok()) << ac.status.message;
    for (size_t i = 0; i < frequencies.size(); ++i) {
      const double omega = 2 * kPi * frequencies[i];
      const std::complex<double> stiffness = k * std::complex<double>(1.0, omega * tau);
      const std::complex<double> carried =
          stiffness * force / (stiffness - tip_mass * omega * omega);
      EXPECT_LT(std::abs(ac.values[0][i] + carried), 1e-9 * std::abs(carried))
          << "tau = " << tau << ", f = " << frequencies[i];
      EXPECT_LT(std::abs(ac.values[1][i] + length * carried), 1e-9 * std::abs(length * carried))
          << "tau = " << tau << ", f = " << frequencies[i];
    }
  }
}

// ---- transient -----------------------------------------------------------------------------

// A cantilever of 3 segments with a tip mass and material damping, a step force at the tip from
// rest. Dynamic equilibrium: R(t) + F = dP/dt, P = Σ m_k·v_k the momentum of the lumped masses
// (the exact method, P differentiated by central differences with h = 1e-5 s: truncation
// h²·P'''/6 and rounding ε·P/h both below 1e-6·F). The exact method's R against IDA's at
// relative tolerance 1e-9: within 1e-5·F.
TEST(Reaction, TransientEquilibriumAndExactAgainstIda) {
  const double length = 0.5, force = 1.0, rho_a = 0.3, mass = 0.2;
  const Built built = build(beam("clamped", "free", 3, "[damping]\nkelvin_voigt_time = 1e-3\n") +
                            load(length, force) + "[[mass]]\nat = 0.5\nmass = 0.2\n");
  const Model& model = built.model;
  std::vector<Probe> probes = {model.parse_probe("reaction_force@0"),
                               model.parse_probe("reaction_moment@0")};
  std::vector<double> masses;
  for (size_t k = 1; k < model.beam.x.size(); ++k) {
    probes.push_back(model.parse_probe("velocity@" + std::to_string(model.beam.x[k])));
    const double l = model.beam.segment_lengths[k - 1];
    masses.push_back(rho_a * l * (k + 1 < model.beam.x.size() ? 1.0 : 0.5) +
                     (k + 1 < model.beam.x.size() ? 0.0 : mass));
  }
  const double h = 1e-5;
  TransientOptions options;
  options.end_time = 0.1;
  for (double t : {0.01, 0.023, 0.05, 0.077})
    for (double offset : {-h, 0.0, h}) options.output_times.push_back(t + offset);
  const TransientResult exact = run_transient_exact(built.system, probes, options);
  ASSERT_TRUE(exact.status.ok()) << exact.status.message;
  options.relative_tolerance = 1e-9;
  const TransientResult ida = run_transient_ida(built.system, probes, options);
  ASSERT_TRUE(ida.status.ok()) << ida.status.message;
  auto momentum = [&](size_t i) {
    double p = 0.0;
    for (size_t k = 0; k < masses.size(); ++k) p += masses[k] * exact.values[k + 2][i];
    return p;
  };
  for (size_t i = 1; i < options.output_times.size(); i += 3) {
    const double rate = (momentum(i + 1) - momentum(i - 1)) / (2 * h);
    EXPECT_NEAR(exact.values[0][i] + force, rate, 1e-6 * force) << "t = " << exact.times[i];
    EXPECT_NEAR(exact.values[0][i], ida.values[0][i], 1e-5 * force) << "t = " << exact.times[i];
    EXPECT_NEAR(exact.values[1][i], ida.values[1][i], 1e-5 * force * length)
        << "t = " << exact.times[i];
  }
}

// ---- DEA force -----------------------------------------------------------------------------

// The fish fin at rest with DEA A at 4 kV (antagonistic drive, first half period): its force is
// k_F·V² = 0.097 N (the paper's Eq. 16 numbers, netlists/fishfin.toml), B's zero; the DEA's
// moment pair is internal, so the clamp carries no moment and no force.
TEST(DeaForce, FishFinAtRest) {
  const Scene scene = read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml",
                                 {"drive.electrical_dynamics=true"});
  const Model model = prepare_model(scene);
  const System system = model.network.assemble();
  const StaticResult rest = solve_static(system);
  ASSERT_TRUE(rest.status.ok()) << rest.status.message;
  const double k_force = dea_force_constant(2.8, 51e-6, 51e-6, 25e-3);
  const double expected = k_force * 4000.0 * 4000.0;
  EXPECT_NEAR(expected, 0.097, 0.0005);
  const Probe force_a = model.parse_probe("dea_force:A");
  EXPECT_EQ(force_a.unit, "N");
  EXPECT_NEAR(static_probe_value(system, rest, force_a), expected, 1e-10 * expected);
  EXPECT_NEAR(static_probe_value(system, rest, model.parse_probe("dea_force:B")), 0.0, 1e-15);
  const double moment_scale = expected * 1.55e-3;
  EXPECT_NEAR(static_probe_value(system, rest, model.parse_probe("reaction_moment@0")), 0.0,
              1e-10 * moment_scale);
  EXPECT_NEAR(static_probe_value(system, rest, model.parse_probe("reaction_force@0")), 0.0,
              1e-10 * expected);
  // Linearised for AC and mode shapes: 2·k_F·u₀·U, said in the description.
  const Probe linear = linearised_probe(force_a, rest.operating_point);
  ASSERT_EQ(linear.terms.size(), 1u);
  EXPECT_NEAR(linear.terms[0].second, 2 * k_force * 4000.0, 1e-10 * 2 * k_force * 4000.0);
  EXPECT_NE(linear.description.find("linearised"), std::string::npos);
  // Not written to SPICE decks, with a note.
  EXPECT_FALSE(deck_exports(model, force_a));
}

// The ideal drive has no electrical loop: the force is its source waveform, refused by name.
TEST(DeaForce, IdealDriveRefused) {
  const Scene scene = read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin.toml",
                                 {"drive.electrical_dynamics=false"});
  const Model model = prepare_model(scene);
  try {
    model.parse_probe("dea_force:A");
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("drive.electrical_dynamics"), std::string::npos)
        << error.what();
  }
}

// ---- parsing and reading -------------------------------------------------------------------

TEST(OutputProbes, ParseProbeStrings) {
  const Built built =
      build(beam("clamped", "free", 2) + load(0.5, 1.0) +
            "[[spring]]\nname = \"s\"\nat = 0.5\nkind = \"translational\"\nstiffness = 30\n");
  const Model& model = built.model;
  EXPECT_EQ(model.parse_probe("reaction_force@0").quantity, ProbeQuantity::reaction_force);
  EXPECT_EQ(model.parse_probe("reaction_moment@0mm").unit, "N*m");
  EXPECT_EQ(model.parse_probe("spring_force:s").quantity, ProbeQuantity::spring_force);
  const Probe strain = model.parse_probe("strain@0.1,bottom,2mm");
  EXPECT_EQ(strain.unit, "");
  EXPECT_EQ(strain.integrations, 1);
  EXPECT_THROW(model.parse_probe("strain@0.1"), InputError);
  EXPECT_THROW(model.parse_probe("strain@0.1,side,2mm"), InputError);
  EXPECT_THROW(model.parse_probe("spring_force:nope"), InputError);
  EXPECT_THROW(model.parse_probe("reaction_force@0.2"), InputError);
  EXPECT_THROW(model.parse_probe("dea_force:A"), InputError);
}

std::string read_message(const std::string& text) {
  try {
    read_scene_text(text, "test.toml");
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected an InputError";
  return "";
}

TEST(OutputProbes, ReaderMessages) {
  const std::string base =
      beam("clamped", "free", 2) +
      "[[spring]]\nname = \"s\"\nat = 0.5\nkind = \"translational\"\nstiffness = 30\n";
  auto probe = [&](const std::string& keys) {
    return base + "[[probe]]\nname = \"p\"\n" + keys + "\n";
  };
  // Read fine: every new quantity with its keys.
  const Scene scene = read_scene_text(
      probe("quantity = \"strain\"\nat = 0.1\nface = \"top\"\ndistance = \"1 mm\"") +
          "[[probe]]\nname = \"q\"\nquantity = \"spring_force\"\nspring = 0\n"
          "[[probe]]\nname = \"r\"\nquantity = \"reaction_moment\"\nat = 0\n",
      "test.toml");
  ASSERT_EQ(scene.probes.size(), 3u);
  EXPECT_EQ(scene.probes[0].distance, 1e-3);
  EXPECT_EQ(scene.probes[1].spring, "0");
  std::string message = read_message(probe("quantity = \"spring_force\""));
  EXPECT_NE(message.find("probe[p].spring"), std::string::npos) << message;
  EXPECT_NE(message.find("missing"), std::string::npos) << message;
  message = read_message(probe("quantity = \"spring_force\"\nspring = \"t\""));
  EXPECT_NE(message.find("unknown spring 't'"), std::string::npos) << message;
  message = read_message(probe("quantity = \"spring_force\"\nspring = 3"));
  EXPECT_NE(message.find("no spring of index 3"), std::string::npos) << message;
  message = read_message(probe("quantity = \"strain\"\nat = 0.1\ndistance = 0.001"));
  EXPECT_NE(message.find("probe[p].face"), std::string::npos) << message;
  message = read_message(probe("quantity = \"strain\"\nat = 0.1\nface = \"top\""));
  EXPECT_NE(message.find("probe[p].distance"), std::string::npos) << message;
  message = read_message(probe("quantity = \"deflection\"\nat = 0.1\nface = \"top\""));
  EXPECT_NE(message.find("only used by probe quantity 'strain'"), std::string::npos) << message;
  message = read_message(probe("quantity = \"reaction_force\"\nat = 0\nspring = \"s\""));
  EXPECT_NE(message.find("only used by probe quantity 'spring_force'"), std::string::npos)
      << message;
  message = read_message(probe("quantity = \"spring_force\"\nspring = \"s\"\nat = 0.1"));
  EXPECT_NE(message.find("probe[p].at"), std::string::npos) << message;
}

}  // namespace
}  // namespace emnet
