// Fuzzes what a restore reads inside a checkpoint (engine/src/checkpoint: bodies with their cut
// shape and embedded surface, boundary motion, devices with a blade's sweep, haptic channels,
// clock and records). The input is a checkpoint's payload; the harness frames it with a valid
// header and checksum for fuzz/restore_scene.yaml (a beam with prescribed and sliding nodes and a
// scalpel whose button is held) after a cut, so the fuzzer reaches past the checksum, and restores
// it into a fresh Simulation. A payload is either restored (then stepped) or refused with an
// InputError; anything else (a crash, a sanitizer report, another exception) is a finding. The
// seed (fuzz/corpus/restore/) is that checkpoint's payload.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "checkpoint/checkpoint_format.hpp"
#include "tacta/error.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/sim/simulation.hpp"

namespace {

struct Fixture {
  tacta::PluginRegistry plugins;
  std::unique_ptr<tacta::RegistrySchemas> schemas;
  tacta::SceneDesc scene;
  tacta::CheckpointHeader header;
  Fixture() {
    plugins.load();
    schemas = std::make_unique<tacta::RegistrySchemas>(plugins);
    scene = tacta::load_scene(TACTA_FUZZ_RESTORE_SCENE, *schemas);
    tacta::Simulation sim(scene, plugins);
    // As fuzz/make_restore_seed.py makes the seed: 25 ticks, a separation at x = 0.04, 5 ticks.
    sim.step(25);
    const std::vector<double> plane = {0.04, -1, -1, 0.04, 1, -1, 0.04, 1,  1,
                                       0.04, -1, -1, 0.04, 1, 1,  0.04, -1, 1};
    sim.cut(sim.body("beam"), plane, tacta::CutMode::kSeparate);
    sim.step(5);
    const std::vector<uint8_t> bytes = sim.save_state();
    std::span<const uint8_t> payload;
    header = tacta::read_checkpoint_header(bytes, "fuzz", payload);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static Fixture fixture;
  const std::vector<uint8_t> framed =
      tacta::frame_checkpoint(fixture.header, std::vector<uint8_t>(data, data + size));
  tacta::Simulation sim(fixture.scene, fixture.plugins);
  try {
    sim.restore_state(std::span<const uint8_t>(framed));
    sim.step(2);  // a restored state must step
  } catch (const tacta::InputError&) {
  }
  return 0;
}
