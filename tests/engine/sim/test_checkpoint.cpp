// Checkpoint and restore (Simulation::save_state / restore_state): a fresh Simulation of the same
// scene that restores a checkpoint taken at tick M and steps on to N ends bit for bit where one
// that stepped N straight does, for every model, with the stylus in contact; a checkpoint of
// another scene, truncated, damaged or of a newer version is refused saying so.
#include <chrono>
#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

SceneDesc demo(const std::vector<std::string>& overrides = {}) {
  std::vector<std::string> all = {"output.plots=[]"};
  all.insert(all.end(), overrides.begin(), overrides.end());
  return load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml", schemas(), all);
}

// Everything a resumed run must carry, compared exactly.
void expect_same_run(Simulation& straight, Simulation& resumed) {
  ASSERT_EQ(straight.tick(), resumed.tick());
  const RunResult a = straight.report(), b = resumed.report();
  EXPECT_EQ(a.state_hash, b.state_hash);
  for (size_t i = 0; i < straight.bodies().size(); ++i) {
    const BodyArrays x = straight.body_arrays(straight.bodies()[i]);
    const BodyArrays y = resumed.body_arrays(resumed.bodies()[i]);
    ASSERT_EQ(x.nodes, y.nodes);
    EXPECT_EQ(std::memcmp(x.positions, y.positions, 3 * x.nodes * sizeof(double)), 0)
        << "body " << i;
    EXPECT_EQ(std::memcmp(x.velocities, y.velocities, 3 * x.nodes * sizeof(double)), 0)
        << "body " << i;
    EXPECT_EQ(a.bodies[i].max_displacement_m, b.bodies[i].max_displacement_m);
    EXPECT_EQ(a.bodies[i].model, b.bodies[i].model);
  }
  ASSERT_EQ(a.devices.size(), b.devices.size());
  for (size_t d = 0; d < a.devices.size(); ++d) {
    EXPECT_EQ(a.devices[d].max_force_N, b.devices[d].max_force_N);
    EXPECT_EQ(a.devices[d].contact_ticks, b.devices[d].contact_ticks);
    const DeviceReading p = straight.device_reading(straight.devices()[d]);
    const DeviceReading q = resumed.device_reading(resumed.devices()[d]);
    EXPECT_EQ(std::memcmp(p.force, q.force, sizeof p.force), 0);
    EXPECT_EQ(std::memcmp(p.proxy, q.proxy, sizeof p.proxy), 0);
    EXPECT_EQ(p.in_contact, q.in_contact);
  }
  EXPECT_EQ(a.faults, b.faults);
  EXPECT_EQ(a.schedule.ticks, b.schedule.ticks);
  EXPECT_EQ(a.schedule.frames, b.schedule.frames);
}

// N ticks straight against M ticks, a checkpoint, a fresh Simulation restoring it, N - M ticks.
void check_resume(const SceneDesc& scene, uint64_t m, uint64_t n) {
  Simulation straight(scene, plugins());
  straight.step(n);
  Simulation resumed(scene, plugins());
  resumed.restore_state(checkpoint_after(scene, m));
  EXPECT_EQ(resumed.tick(), m);
  resumed.step(n - m);
  expect_same_run(straight, resumed);
}

class CheckpointEveryModel : public ::testing::TestWithParam<const char*> {};

// The liver under the stylus, checkpointed at 0.45 s (in contact from about 0.4 s).
TEST_P(CheckpointEveryModel, ResumesBitForBitInContact) {
  const std::string model = GetParam();
  if (!plugins().find(TACTA_KIND_MODEL, model)) GTEST_SKIP() << model << " is not in this build";
  check_resume(demo({"bodies.*.model=" + model}), 450, 520);
}

INSTANTIATE_TEST_SUITE_P(Models, CheckpointEveryModel,
                         ::testing::Values("corotational_fem", "hyperelastic", "mass_spring",
                                           "fd_debunne", "tensor_mass", "vbd", "bullet_softbody"));

// Find a tick where the stylus presses the liver, checkpoint there; the run to 5 s then gives
// the straight run's state hash and the figures that depend on the whole run.
TEST(Checkpoint, DemoMidContact) {
  const SceneDesc scene = demo();
  Simulation probe(scene, plugins());
  uint64_t at = 0;
  for (uint64_t t = 0; t < 700 && at == 0; ++t) {
    probe.step(1);
    if (probe.device_reading(probe.devices()[0]).in_contact && t > 420) at = probe.tick();
  }
  ASSERT_GT(at, 0u) << "the stylus never touched the liver";
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<uint8_t> bytes = probe.save_state();
  const auto t1 = std::chrono::steady_clock::now();
  Simulation resumed(scene, plugins());
  resumed.restore_state(bytes);
  const auto t2 = std::chrono::steady_clock::now();
  EXPECT_TRUE(resumed.device_reading(resumed.devices()[0]).in_contact);
  std::printf("demo checkpoint at tick %llu: %zu bytes, save %.2f ms, restore %.2f ms\n",
              static_cast<unsigned long long>(at), bytes.size(),
              std::chrono::duration<double, std::milli>(t1 - t0).count(),
              std::chrono::duration<double, std::milli>(t2 - t1).count());
  // To the scene's end (5 s): past the bounding hierarchy's rebuilds (it keeps the shape it was
  // built in, so the restored one is first built where the saved run's was, at t = 0).
  Simulation straight(scene, plugins());
  straight.step(5000);
  resumed.step(5000 - at);
  expect_same_run(straight, resumed);
  EXPECT_GT(resumed.report().devices[0].contact_ticks, 0u);
  // report.json's figures over the whole run: devices (first-contact peak, steady force,
  // energy injected), bodies (models run, energies, counters, status), faults, records dropped.
  const auto report_of = [](Simulation& sim, const std::string& name) {
    std::ifstream file(sim.write_report(fresh_dir(name)));
    return nlohmann::json::parse(file);
  };
  const nlohmann::json p = report_of(straight, "ckpt_straight"),
                       q = report_of(resumed, "ckpt_resumed");
  for (const char* key : {"devices", "bodies", "faults", "status_errors", "status_warnings",
                          "dropped_records", "state_hash", "sim_time_s"})
    EXPECT_EQ(p[key], q[key]) << key;
}

// A checkpoint after the scene's timed tool change (0.5 s): the restore takes the scene's events
// the saved run took, so the tool and its proxy go on as they did.
TEST(Checkpoint, CarriesTheScenesTimedEvents) {
  const SceneDesc scene =
      load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/examples/tool_change.yaml", schemas(),
                 {"output.plots=[]"});
  check_resume(scene, 650, 900);
}

std::string restore_error(Simulation& sim, const std::vector<uint8_t>& bytes) {
  try {
    sim.restore_state(bytes);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Checkpoint, RefusesAnotherSceneDamageTruncationAndANewerVersion) {
  Simulation saved(demo(), plugins());
  saved.step(10);
  const std::vector<uint8_t> bytes = saved.save_state();

  Simulation other(scene_from_text(kCubePressScene, "cube_press"), plugins());
  EXPECT_NE(restore_error(other, bytes).find("another scene"), std::string::npos)
      << restore_error(other, bytes);

  Simulation fresh(demo(), plugins());
  std::vector<uint8_t> cut(bytes.begin(), bytes.end() - 100);
  EXPECT_NE(restore_error(fresh, cut).find("truncated"), std::string::npos)
      << restore_error(fresh, cut);
  std::vector<uint8_t> damaged = bytes;
  damaged[damaged.size() / 2] ^= 0x40;
  EXPECT_NE(restore_error(fresh, damaged).find("damaged"), std::string::npos)
      << restore_error(fresh, damaged);
  std::vector<uint8_t> newer = bytes;
  newer[8] = 3;  // the format version follows the 8-byte magic
  EXPECT_NE(restore_error(fresh, newer).find("version 3 is newer than this engine's 2"),
            std::string::npos)
      << restore_error(fresh, newer);
  std::vector<uint8_t> not_one = bytes;
  not_one[0] = 'X';
  EXPECT_NE(restore_error(fresh, not_one).find("not a Tacta checkpoint"), std::string::npos);
  // A parameter set on the command line (--set) makes it another scene too.
  Simulation stiffer(demo({"bodies.*.material.youngs_modulus=9000"}), plugins());
  EXPECT_NE(restore_error(stiffer, bytes).find("another scene"), std::string::npos);
  // The refused restores left the fresh one usable: the good bytes restore.
  fresh.restore_state(bytes);
  EXPECT_EQ(fresh.tick(), 10u);
}

TEST(Checkpoint, AModelWithoutStateEntriesIsRefusedNamingBodyAndModel) {
  const SceneDesc scene = scene_from_text(kCubePressScene, "cube_press",
                                          {"bodies.*.model=test_fault_model", "devices=[]"});
  Simulation sim(scene, plugins());
  sim.step(2);
  try {
    (void)sim.save_state();
    FAIL() << "saved";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("body 'cube'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("test_fault_model"), std::string::npos) << e.what();
  }
}

// A model changed between steps (set_param swap, then a runtime swap) is rebuilt on restore.
TEST(Checkpoint, CarriesRuntimeSwapsAndAppliedForces) {
  const SceneDesc scene = scene_from_text(kCubePressScene, "cube_press");
  auto drive = [&](Simulation& sim, uint64_t from, uint64_t to) {
    for (uint64_t t = from; t < to; ++t) {
      if (t == 40) sim.request_model_swap(sim.bodies()[0], "mass_spring", {});
      if (t == 60) sim.set_applied_forces(sim.bodies()[0], {5, 6}, {0, -1, 0, 0, -2, 0});
      sim.step(1);
    }
  };
  Simulation straight(scene, plugins());
  drive(straight, 0, 150);
  std::vector<uint8_t> bytes;
  {
    Simulation first(scene, plugins());
    drive(first, 0, 90);
    bytes = first.save_state();
  }
  Simulation resumed(scene, plugins());
  resumed.restore_state(bytes);
  drive(resumed, 90, 150);
  expect_same_run(straight, resumed);
  EXPECT_EQ(resumed.report().bodies[0].model, "mass_spring");
}

}  // namespace
}  // namespace tacta::simtest
