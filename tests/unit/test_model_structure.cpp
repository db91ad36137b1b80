// The model's record of what each node and element is (emnet/model/structure.hpp) and its
// output lists (emnet/model/outputs.hpp). References: the fish fin's network as the builder
// lays it out (7 segments of nR, nT and a lever; a mass on each free node; per DEA a source,
// an electrode resistance and a transducer, or one ideal force per coupling node), and the
// output names `emnet tran` printed before the lists had a home in the model layer
// (dx2 dx3 dx4 tip u_A i_A u_B i_B; the SPICE decks' P1..P4, tip, dx2..dx4, u_A ... i_B).
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "emnet/model/model.hpp"
#include "emnet/model/outputs.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/spice/spice_netlist.hpp"
#include "fixtures.hpp"
#include "shipped_scenes.hpp"

namespace emnet {
namespace {

using emnet::testing::kFishfin;

std::vector<std::string> names_of(const std::vector<ModelOutput>& outputs) {
  std::vector<std::string> names;
  for (const auto& output : outputs) names.push_back(output.probe.name);
  return names;
}

TEST(ModelStructure, EveryElementAndNodeOfTheFishFinIsRecorded) {
  const Model model = build_model(read_scene(kFishfin));
  const auto& elements = model.network.elements();
  ASSERT_EQ(model.structure.elements.size(), elements.size());
  ASSERT_EQ(model.structure.nodes.size(), model.network.nodes().size());
  std::map<Component, int> count;
  for (size_t k = 0; k < elements.size(); ++k) {
    const ElementRecord& record = *model.structure.element(k);
    ++count[record.component];
    EXPECT_FALSE(record.meaning.empty()) << elements[k]->name();
    const std::string& name = elements[k]->name();
    switch (record.component) {
      case Component::beam_segment: {
        const std::string id = std::to_string(record.index);
        const std::string expected = record.part == ElementPart::rotational_compliance ? "nR"
                                     : record.part == ElementPart::translational_compliance
                                         ? "nT"
                                         : "lever";
        EXPECT_EQ(name, expected + id);
        break;
      }
      case Component::beam_node:
        EXPECT_EQ(record.part, ElementPart::mass);
        EXPECT_EQ(name, "mass" + std::to_string(record.index));
        break;
      case Component::drive_source:
        EXPECT_EQ(record.part, ElementPart::source_voltage);
        EXPECT_EQ(name, "V_" + record.dea);
        break;
      case Component::dea:
        EXPECT_EQ(name, (record.part == ElementPart::transducer ? "dea_" : "Re_") + record.dea);
        break;
      case Component::load:
      case Component::point_mass:
      case Component::spring:
      case Component::circuit:
        ADD_FAILURE() << "the fish fin has no loads, masses, springs or circuits: " << name;
        break;
    }
  }
  EXPECT_EQ(count[Component::beam_segment], 3 * 7);
  EXPECT_EQ(count[Component::beam_node], 7);  // nodes 1..7 (node 0 is clamped)
  EXPECT_EQ(count[Component::drive_source], 2);
  EXPECT_EQ(count[Component::dea], 4);
  // Nodes: v1..v7, r1..r7, m0..m6 and each DEA's source and electrode node.
  const NodeRecord* electrode = model.structure.node(model.find_dea("B")->electrode_node);
  ASSERT_NE(electrode, nullptr);
  EXPECT_EQ(electrode->role, NodeRole::dea_electrode);
  EXPECT_EQ(electrode->dea, "B");
  const NodeRecord* tip = model.structure.node(model.beam.velocity.back());
  ASSERT_NE(tip, nullptr);
  EXPECT_EQ(tip->role, NodeRole::beam_velocity);
  EXPECT_EQ(tip->index, 7);
}

TEST(ModelStructure, IdealDriveForcesAndLoadsAreRecordedWithTheirGroup) {
  Scene scene = read_scene(kFishfin, {"drive.electrical_dynamics=false"});
  scene.loads.push_back(testing::load(LoadKind::force, 0.1, 0.01));  // inside segment 5
  const Model model = build_model(scene);
  int forces = 0, loads = 0;
  for (size_t k = 0; k < model.network.elements().size(); ++k) {
    const ElementRecord& record = *model.structure.element(k);
    if (record.component == Component::drive_source) {
      ++forces;
      EXPECT_EQ(record.part, ElementPart::ideal_force);
      EXPECT_EQ(record.force_part, 0);  // a square wave's force is one waveform
      const DeaLayout* dea = model.find_dea(record.dea);
      ASSERT_NE(dea, nullptr);
      ASSERT_LT(record.coupling, static_cast<int>(dea->coupling.size()));
      EXPECT_EQ(
          model.network.elements()[k]->name(),
          "F_" + record.dea + "_" +
              model.network.node(dea->coupling[static_cast<size_t>(record.coupling)].node).name);
    }
    if (record.component == Component::load) {
      ++loads;
      EXPECT_EQ(record.index, 0);
    }
  }
  size_t coupling = 0;
  for (const DeaLayout& dea : model.deas) coupling += dea.coupling.size();
  EXPECT_EQ(forces, static_cast<int>(coupling));
  // The mesher puts a node under the load (emnet/model/mesh.hpp): one share, on its velocity node.
  EXPECT_EQ(loads, 1);
  // An element added after the build has no record.
  Model extended = model;
  extended.network.add<Conductance>("extra", extended.beam.velocity[1], ground, 1.0);
  EXPECT_EQ(extended.structure.element(extended.network.elements().size() - 1), nullptr);
}

TEST(ModelOutputs, FishFinListsAsTheCommandsPrintedThem) {
  const Model model = build_model(read_scene(kFishfin));
  const std::vector<ModelOutput> transient = transient_output_list(model);
  EXPECT_EQ(names_of(transient),
            (std::vector<std::string>{"dx2", "dx3", "dx4", "tip", "u_A", "i_A", "u_B", "i_B"}));
  const std::vector<ModelOutput> deck = deck_output_list(model);
  EXPECT_EQ(names_of(deck), (std::vector<std::string>{"P1", "P2", "P3", "P4", "tip", "dx2", "dx3",
                                                      "dx4", "u_A", "i_A", "u_B", "i_B"}));
  std::vector<std::string> spice;
  for (const Probe& probe : spice_output_probes(model)) spice.push_back(probe.name);
  EXPECT_EQ(spice, names_of(deck));
  // dx4 = P4 − P1: its record names both, its terms are P4's then −P1's.
  const ModelOutput& dx4 = transient[2];
  EXPECT_EQ(dx4.origin, OutputOrigin::speckle_point_difference);
  EXPECT_EQ(model.probes[static_cast<size_t>(dx4.probe_index)].name, "P4");
  EXPECT_EQ(model.probes[static_cast<size_t>(dx4.reference_index)].name, "P1");
  LinearTerms expected = model.probes[3].terms;
  for (const auto& [index, c] : model.probes[0].terms) expected.emplace_back(index, -c);
  EXPECT_EQ(dx4.probe.terms, expected);
  EXPECT_EQ(dx4.probe.description, "P4 - P1");
  EXPECT_EQ(transient[4].origin, OutputOrigin::dea_voltage);
  EXPECT_EQ(transient[4].dea, "A");
  // mismatch's default: the last speckle-point difference.
  ASSERT_NE(default_deflection_output(transient), nullptr);
  EXPECT_EQ(default_deflection_output(transient)->probe.name, "dx4");
  EXPECT_EQ(default_deflection_output(deck)->probe.name, "dx4");
}

// The gripper finger's scene has a probe u_A of DEA A's voltage: the built-in u_A is not listed
// a second time (it was, as two equal columns), while i_A, which no probe shows, is.
TEST(ModelOutputs, ADeaQuantityAProbeShowsIsListedOnce) {
  const Model model =
      build_model(read_scene(std::string(EMNET_SOURCE_DIR) + "/netlists/gripper-finger.toml"));
  EXPECT_EQ(names_of(transient_output_list(model)),
            (std::vector<std::string>{"tip", "body_end", "u_A", "i_A"}));
  EXPECT_EQ(names_of(deck_output_list(model)),
            (std::vector<std::string>{"tip", "body_end", "u_A", "i_A"}));
  EXPECT_EQ(transient_output_list(model)[2].origin, OutputOrigin::scene_probe);
}

TEST(ModelOutputs, WithoutSpecklePointsTheLastDeflection) {
  Scene scene = testing::cantilever_scene(4);
  scene.probes = {testing::beam_probe("mid", ProbeQuantity::deflection, 0.25),
                  testing::beam_probe("end", ProbeQuantity::deflection, 0.5),
                  testing::beam_probe("turn", ProbeQuantity::rotation, 0.5)};
  const Model model = build_model(scene);
  EXPECT_TRUE(speckle_point_differences(model).empty());
  const std::vector<ModelOutput> outputs = transient_output_list(model);
  EXPECT_EQ(names_of(outputs), (std::vector<std::string>{"mid", "end", "turn"}));
  ASSERT_NE(default_deflection_output(outputs), nullptr);
  EXPECT_EQ(default_deflection_output(outputs)->probe.name, "end");
  // A P1 alone is the reference of nothing: left out of the transient list, kept in a deck's.
  scene.probes = {testing::beam_probe("P1", ProbeQuantity::deflection, 0.0),
                  testing::beam_probe("turn", ProbeQuantity::rotation, 0.5)};
  const Model lone = build_model(scene);
  EXPECT_EQ(names_of(transient_output_list(lone)), (std::vector<std::string>{"turn"}));
  EXPECT_EQ(default_deflection_output(transient_output_list(lone)), nullptr);
  EXPECT_EQ(names_of(deck_output_list(lone)), (std::vector<std::string>{"P1", "turn"}));
}

}  // namespace
}  // namespace emnet
