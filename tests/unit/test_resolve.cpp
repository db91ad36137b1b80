// The resolve step and the model builder apart (emnet/studies/resolve.hpp, emnet/model/model.hpp):
// build_model runs no analysis and refuses a scene with an "auto" key left; resolve_scene
// records its choices in the scene so that the model built from it, and rebuilt from the
// model's scene, is the same. References: the notes the command line printed for the shipped
// water scene before the resolve step moved out of the builder (emnet modes and emnet static
// of the earlier program, copied here verbatim), and the models built from the same scenes.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"
#include "fixtures.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using emnet::testing::kFishfin;
const std::string kWater = std::string(EMNET_SOURCE_DIR) + "/netlists/fishfin-water.toml";
using emnet::testing::kCantilever;

// The message of the std::logic_error build_model throws for `scene` ("" when it builds).
std::string refusal(const Scene& scene) {
  try {
    (void)build_model(scene);
  } catch (const std::logic_error& error) {
    return error.what();
  }
  return "";
}

TEST(ResolveStep, BuildModelRefusesEachUnresolvedAutoKeyByName) {
  const Scene segments =
      read_scene(kCantilever, {"beam.segments=auto", "model.band=[\"0 Hz\", \"110 Hz\"]"});
  EXPECT_NE(refusal(segments).find("beam.segments"), std::string::npos) << refusal(segments);
  const Scene electrical = read_scene(kFishfin, {"drive.electrical_dynamics=auto"});
  EXPECT_NE(refusal(electrical).find("drive.electrical_dynamics"), std::string::npos);
  const Scene water = read_scene(kWater);
  EXPECT_NE(refusal(water).find("environment.frequency"), std::string::npos) << refusal(water);
  EXPECT_NE(refusal(water).find("prepare_model"), std::string::npos) << refusal(water);
  // A scene without "auto" builds directly.
  EXPECT_EQ(refusal(read_scene(kFishfin)), "");
  EXPECT_TRUE(unresolved_keys(read_scene(kFishfin)).empty());
}

TEST(ResolveStep, ResolvedSceneHasNoAutoLeftAndBuildsTheSameModelAgain) {
  const ResolvedScene resolved = resolve_scene(read_scene(
      kWater, {"beam.segments=auto", "drive.electrical_dynamics=auto", "model.band=\"10 Hz\""}));
  EXPECT_TRUE(unresolved_keys(resolved.scene).empty());
  ASSERT_EQ(resolved.automatic_choices.size(), 2u);
  EXPECT_EQ(resolved.automatic_choices[0].key, "beam.segments");
  EXPECT_EQ(resolved.automatic_choices[1].key, "drive.electrical_dynamics");
  ASSERT_TRUE(resolved.scene.environment.resonance.has_value());
  const Model model = build_model(resolved.scene);
  // The resolve step's notes are the model's first notes (the fluid loading, then each choice).
  ASSERT_GE(model.notes.size(), resolved.notes.size());
  for (size_t k = 0; k < resolved.notes.size(); ++k) EXPECT_EQ(model.notes[k], resolved.notes[k]);
  // Rebuilt from the model's scene: the same network, notes and fluid record.
  const Model again = build_model(model.scene);
  EXPECT_EQ(again.notes, model.notes);
  EXPECT_EQ(again.network.elements().size(), model.network.elements().size());
  ASSERT_TRUE(again.fluid.has_value());
  EXPECT_EQ(again.fluid->loading.frequency, model.fluid->loading.frequency);
  EXPECT_EQ(again.fluid->loading.added_mass_per_length, model.fluid->loading.added_mass_per_length);
}

TEST(ResolveStep, FluidResonanceFoundForAnotherBeamIsUnresolvedAgain) {
  Scene scene = resolve_scene(read_scene(kWater)).scene;
  ASSERT_TRUE(fluid_resonance_current(scene));
  scene.beam.bending_stiffness *= 2.0;  // the resonance it holds is now the old beam's
  EXPECT_FALSE(fluid_resonance_current(scene));
  EXPECT_NE(refusal(scene).find("environment.frequency"), std::string::npos);
  // Resolving again finds the stiffer beam's resonance: higher, by about √2 (the added mass
  // changes little with the frequency), and exactly what a fresh scene with that stiffness gives.
  const Model stiffer = prepare_model(scene);
  Scene fresh = read_scene(kWater);
  fresh.beam.bending_stiffness = scene.beam.bending_stiffness;
  const Model reference = prepare_model(fresh);
  ASSERT_TRUE(stiffer.fluid && reference.fluid);
  EXPECT_EQ(stiffer.fluid->loading.frequency, reference.fluid->loading.frequency);
  EXPECT_GT(stiffer.fluid->loading.frequency,
            1.3 * prepare_model(read_scene(kWater)).fluid->loading.frequency);
}

TEST(ResolveStep, SegmentsOnlyLeavesTheOtherKeysToChoose) {
  ResolveOptions segments_only;
  segments_only.fluid_resonance = false;
  segments_only.electrical_dynamics = false;
  const ResolvedScene resolved = resolve_scene(
      read_scene(kWater,
                 {"beam.segments=auto", "drive.electrical_dynamics=auto", "model.band=\"10 Hz\""}),
      segments_only);
  EXPECT_EQ(unresolved_keys(resolved.scene),
            (std::vector<std::string>{"environment.frequency", "drive.electrical_dynamics"}));
  ASSERT_EQ(resolved.automatic_choices.size(), 1u);
  EXPECT_EQ(resolved.automatic_choices[0].key, "beam.segments");
  EXPECT_FALSE(resolved.scene.beam.auto_segments);
}

TEST(ResolveStep, ResolveSegmentsIsTheSegmentsOnlyStepAndLeavesAFixedMeshAlone) {
  const Scene scene = read_scene(
      kWater, {"beam.segments=auto", "drive.electrical_dynamics=auto", "model.band=\"10 Hz\""});
  ResolveOptions segments_only;
  segments_only.fluid_resonance = false;
  segments_only.electrical_dynamics = false;
  const Scene expected = resolve_scene(scene, segments_only).scene;
  const Scene resolved = resolve_segments(scene);
  EXPECT_EQ(resolved.beam.segments, expected.beam.segments);
  EXPECT_FALSE(resolved.beam.auto_segments);
  EXPECT_EQ(unresolved_keys(resolved), unresolved_keys(expected));
  const Scene fixed = read_scene(kCantilever);
  EXPECT_EQ(resolve_segments(fixed).beam.segments, fixed.beam.segments);
  EXPECT_TRUE(resolve_segments(fixed).automatic_choices.empty());
}

TEST(ResolveStep, DeaVoltageAndCurrentProbesAskForTheRcDynamics) {
  EXPECT_TRUE(asks_for_dea_electrics("dea_voltage:A"));
  EXPECT_TRUE(asks_for_dea_electrics("dea_current:B"));
  EXPECT_FALSE(asks_for_dea_electrics("deflection@70mm"));
  EXPECT_FALSE(asks_for_dea_electrics("u_A"));  // an output name, not a probe text
  EXPECT_TRUE(asks_for_dea_electrics(std::vector<std::string>{"P4", "dea_current:A"}));
  EXPECT_FALSE(asks_for_dea_electrics(std::vector<std::string>{}));
  EXPECT_TRUE(prepare_options_for_probes({"tip", "dea_voltage:A"}).electrical_probe_requested);
  EXPECT_FALSE(prepare_options_for_probes({"tip"}).electrical_probe_requested);
}

// The notes of the shipped water scene exactly as the command line printed them before the
// resolve step left the model builder (`emnet modes netlists/fishfin-water.toml` and `emnet
// static ... --set beam.segments=auto --set 'model.band="10 Hz"'`): the fixed point, its steps
// and the loading are the same numbers. Only the choice's own timing is left out of the
// comparison (it is measured each time).
TEST(ResolveStep, FluidLoadingNotesAsPrintedBefore) {
  const Model water = prepare_model(read_scene(kWater));
  ASSERT_FALSE(water.notes.empty());
  EXPECT_EQ(water.notes[0],
            "fluid loading, water (rho = 998.2 kg/m^3, eta = 0.001002 Pa*s, plate width 25 mm), "
            "Sader 1998: at 2.2207 Hz, the loaded beam's first undamped resonance (fixed point in "
            "7 steps from the bare beam's 6.386 Hz): Re = 2172, Gamma = 1.0831 + 0.07078i; added "
            "mass 530.7 g/m (7.27 x the beam's), damping 0.4839 N*s/m^2 to ground");
  ASSERT_TRUE(water.fluid.has_value());
  EXPECT_EQ(water.fluid->fixed_point_steps, 7);
  // As the command line does it: N chosen once for the command (load_scene), the fluid
  // loading's resonance then found at that N for each model.
  ResolveOptions segments_only;
  segments_only.fluid_resonance = false;
  segments_only.electrical_dynamics = false;
  const Model automatic = prepare_model(
      resolve_scene(read_scene(kWater, {"beam.segments=auto", "model.band=\"10 Hz\""}),
                    segments_only)
          .scene);
  ASSERT_GE(automatic.notes.size(), 2u);
  EXPECT_EQ(automatic.notes[0],
            "fluid loading, water (rho = 998.2 kg/m^3, eta = 0.001002 Pa*s, plate width 25 mm), "
            "Sader 1998: at 2.2396 Hz, the loaded beam's first undamped resonance (fixed point in "
            "7 steps from the bare beam's 6.44 Hz): Re = 2190, Gamma = 1.0828 + 0.07051i; added "
            "mass 530.6 g/m (7.27 x the beam's), damping 0.4861 N*s/m^2 to ground");
  const std::string& choice = automatic.notes[1];
  // (The numbers since the mesher puts a node at the DEAs' end, 70 mm, for every N, and spreads
  // the segments by length at every N, 2N being N's mesh halved.)
  EXPECT_EQ(choice.rfind("beam.segments = \"auto\" on the fluid-loaded beam: N = 22: estimated "
                         "discretisation error 0.00098 over 1 mode(s) up to 2.2412 Hz",
                         0),
            0u)
      << choice;
  EXPECT_NE(choice.find("the smallest N meeting model.tolerance 0.001 in the band 0 to 10 Hz "
                        "(model.band)"),
            std::string::npos)
      << choice;
}

// Setting the drive on a resolved scene drops the record of the choice it replaces: the model
// then says "false", not what "auto" once chose.
TEST(ResolveStep, SetElectricalDynamicsDropsTheChoice) {
  Scene scene = resolve_scene(read_scene(kFishfin, {"drive.electrical_dynamics=auto"})).scene;
  ASSERT_EQ(scene.automatic_choices.size(), 1u);
  set_electrical_dynamics(scene, false);
  EXPECT_TRUE(scene.automatic_choices.empty());
  const Model model = build_model(scene);
  bool said_false = false;
  for (const auto& note : model.notes)
    said_false |= note.find("(drive.electrical_dynamics = false)") != std::string::npos;
  EXPECT_TRUE(said_false);
}

}  // namespace
}  // namespace emnet
