// libFuzzer target: scene text through the reader (read_scene_text), the resolve step and the
// model builder (prepare_model) and a static solve (solve_static), as `emnet static` runs them.
//
// Bad input must come back as an emnet::InputError; a static solve that fails must say why.
// Anything else (a crash, another exception, a sanitizer report, a leak, a hang, too much
// memory) is a finding. Scenes are read whatever they hold; models are built only for an
// explicit beam.segments of at most kMaximumSegments (kMaximumFluidSegments with fluid
// loading, whose fixed point runs up to 100 modal solves, each about 40 ms at N = 7 in this
// instrumented build), since the builder's and the solver's cost grows with N (up to the
// reader's 100 000), not with the input: a slow input then means a defect, not a large but
// legal model. For the same reason scenes with beam.segments = "auto" (whose N the resolve
// step chooses, up to 20 000) are read, not built.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "emnet/analysis/analysis.hpp"
#include "emnet/core/errors.hpp"
#include "emnet/model/model.hpp"
#include "emnet/scene/scene_reader.hpp"
#include "emnet/studies/resolve.hpp"

namespace {

constexpr int kMaximumSegments = 16;
constexpr int kMaximumFluidSegments = 8;

void build_and_solve(const emnet::Scene& scene) {
  const emnet::Model model = emnet::prepare_model(scene);
  const emnet::System system = model.network.assemble();
  const emnet::StaticResult result = emnet::solve_static(system);
  if (!result.status.ok()) {
    if (result.status.message.empty()) std::abort();  // a failure must say why
    return;
  }
  for (const emnet::Probe& probe : model.probes)
    (void)emnet::static_probe_value(system, result, probe);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    emnet::Scene scene = emnet::read_scene_text(text, "fuzz.toml");
    if (scene.beam.auto_segments) return 0;
    const bool fluid = scene.environment.fluid != emnet::Fluid::none;
    if (scene.beam.segments > (fluid ? kMaximumFluidSegments : kMaximumSegments)) return 0;
    build_and_solve(scene);
  } catch (const emnet::InputError&) {
    // refused with a message naming the file and key: what bad input should get
  }
  return 0;
}
