// Checkpoints of cut bodies: a run checkpointed after cuts (or with a blade mid-sweep) and resumed
// in a fresh Simulation ends bit for bit where the uninterrupted run does, for every model that
// takes topology edits; a checkpoint from before any cut, restored into a Simulation cut since,
// gives the scene's mesh back; a forged cut mesh is refused before anything changes.
#include <algorithm>
#include <cstring>
#include <gtest/gtest.h>
#include <string>
#include <vector>

#include "checkpoint/checkpoint_format.hpp"
#include "cut_beam_scene.hpp"
#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

// The tick, state hash, node count, positions and velocities of both runs, compared exactly.
void expect_same_state(Simulation& straight, Simulation& resumed, const char* body = "beam") {
  ASSERT_EQ(straight.tick(), resumed.tick());
  EXPECT_EQ(straight.report().state_hash, resumed.report().state_hash);
  const BodyHandle a = straight.body(body), b = resumed.body(body);
  EXPECT_EQ(straight.body_revision(a), resumed.body_revision(b));
  const BodyArrays x = straight.body_arrays(a), y = resumed.body_arrays(b);
  ASSERT_EQ(x.nodes, y.nodes);
  EXPECT_EQ(std::memcmp(x.positions, y.positions, 3 * x.nodes * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(x.velocities, y.velocities, 3 * x.nodes * sizeof(double)), 0);
  EXPECT_EQ(straight.body_mesh(a).tets, resumed.body_mesh(b).tets);
}

// Separated at x = 0.055 at 30 ms, 2.5 mm carved away at x = 0.025 at 60 ms (ticks of 1 ms).
void cut_twice(Simulation& sim, uint64_t ticks) {
  const BodyHandle beam = sim.body("beam");
  for (uint64_t done = 0; done < ticks; ++done) {
    if (sim.tick() == 30) sim.cut(beam, plane_x(0.055), CutMode::kSeparate);
    if (sim.tick() == 60) sim.cut(beam, plane_x(0.025), CutMode::kRemove);
    sim.step(1);
  }
}

TEST(CutCheckpoint, EveryClaimingModelResumesBitForBitAfterCuts) {
  for (const char* model :
       {"corotational_fem", "hyperelastic", "tensor_mass", "mass_spring", "vbd"}) {
    if (plugins().find(TACTA_KIND_MODEL, model) == nullptr) continue;
    SCOPED_TRACE(model);
    const SceneDesc scene = scene_from_text(beam_scene(model), "cut_beam");
    Simulation straight(scene, plugins());
    cut_twice(straight, 120);
    std::vector<uint8_t> bytes;
    {
      Simulation first(scene, plugins());
      cut_twice(first, 80);
      ASSERT_EQ(first.body_revision(first.body("beam")), 2u);
      bytes = first.save_state();
    }
    Simulation resumed(scene, plugins());
    resumed.restore_state(bytes);
    EXPECT_EQ(resumed.body_revision(resumed.body("beam")), 2u);
    resumed.step(40);
    expect_same_state(straight, resumed);
    EXPECT_EQ(resumed.report().faults, 0u);
  }
}

// The beam with prescribed and sliding nodes (cut_beam_scene.hpp), cut through the sliding ones:
// the boundary motion carried to the cut mesh, and its state, resume bit for bit.
TEST(CutCheckpoint, PrescribedMotionResumesBitForBitAfterCuts) {
  const SceneDesc scene =
      scene_from_text(beam_scene("corotational_fem", kPrescribedBeam), "cut_beam");
  Simulation straight(scene, plugins());
  cut_twice(straight, 120);
  Simulation first(scene, plugins());
  cut_twice(first, 80);
  const std::vector<uint8_t> bytes = first.save_state();
  Simulation resumed(scene, plugins());
  resumed.restore_state(bytes);
  resumed.step(40);
  expect_same_state(straight, resumed);
  // Rewound to before the cuts, the same Simulation runs as one never cut.
  Simulation never_cut(scene, plugins());
  never_cut.step(100);
  const std::vector<uint8_t> uncut = checkpoint_after(scene, 20);
  first.restore_state(uncut);
  first.step(80);
  expect_same_state(never_cut, first);
}

// The liver incision (an embedded fine surface, a scalpel from sim_stylus) checkpointed between
// two of its cuts: the cut surface comes back with its cut triangles and the run goes on alike.
TEST(CutCheckpoint, TheLiverIncisionResumesWithItsCutSurface) {
  const SceneDesc scene = load_scene(scene_path("examples/liver_incision"), schemas(),
                                     {"output.plots=[]", "output.frames=false"});
  Simulation straight(scene, plugins());
  straight.step(700);
  ASSERT_GT(straight.body_revision(straight.body("liver")), 0u);
  Simulation resumed(scene, plugins());
  resumed.restore_state(checkpoint_after(scene, 606));
  resumed.step(94);
  expect_same_state(straight, resumed, "liver");
  const BodyStatic& x = straight.scene_static().bodies[0];
  const BodyStatic& y = resumed.scene_static().bodies[0];
  ASSERT_FALSE(x.surface_triangles.empty());
  EXPECT_EQ(x.surface_triangles, y.surface_triangles);
  EXPECT_EQ(x.surface_rest_positions, y.surface_rest_positions);
  EXPECT_EQ(x.surface_cut_triangles, y.surface_cut_triangles);
  EXPECT_GT(std::count(y.surface_cut_triangles.begin(), y.surface_cut_triangles.end(), 1), 0);
}

// Rewinding: the checkpoint of the uncut beam restored into the same Simulation after it was cut,
// then stepped on, is the run that was never cut.
TEST(CutCheckpoint, AnUncutCheckpointGivesACutSimulationTheScenesMeshBack) {
  const SceneDesc scene = scene_from_text(beam_scene("corotational_fem"), "cut_beam");
  Simulation never_cut(scene, plugins());
  never_cut.step(100);
  Simulation sim(scene, plugins());
  sim.step(20);
  const std::vector<uint8_t> uncut = sim.save_state();
  cut_twice(sim, 50);
  ASSERT_EQ(sim.body_revision(sim.body("beam")), 2u);
  sim.restore_state(uncut);
  EXPECT_EQ(sim.body_revision(sim.body("beam")), 0u);
  sim.step(80);
  expect_same_state(never_cut, sim);
}

// A device's blade checkpointed while its button is held and its sweep not yet cut: the resumed
// run makes the same cuts and ends where the uninterrupted one does.
TEST(CutCheckpoint, ABladeMidSweepResumes) {
  const SceneDesc scene =
      scene_from_text(beam_scene("corotational_fem", kScalpelDevice), "cut_beam");
  Simulation straight(scene, plugins());
  straight.step(200);
  ASSERT_GT(straight.body_revision(straight.body("beam")), 0u);
  // Before the blade meets the beam; mid-cut, with a sweep not yet cut.
  for (const uint64_t at : {uint64_t{45}, uint64_t{95}}) {
    SCOPED_TRACE(at);
    Simulation resumed(scene, plugins());
    resumed.restore_state(checkpoint_after(scene, at));
    resumed.step(200 - at);
    expect_same_state(straight, resumed);
    EXPECT_EQ(straight.report().devices[0].max_force_N, resumed.report().devices[0].max_force_N);
  }
}

// The checkpoint with `find`'s bytes replaced by `replace`'s, framed again (a valid checksum): what
// a forged or corrupted file that passes the checksum looks like.
std::vector<uint8_t> forge(const std::vector<uint8_t>& bytes, const std::vector<uint8_t>& find,
                           const std::vector<uint8_t>& replace) {
  std::span<const uint8_t> payload;
  const CheckpointHeader header = read_checkpoint_header(bytes, "test", payload);
  std::vector<uint8_t> body(payload.begin(), payload.end());
  const auto at = std::search(body.begin(), body.end(), find.begin(), find.end());
  EXPECT_NE(at, body.end()) << "the bytes to forge are not in the checkpoint";
  if (at != body.end()) std::copy(replace.begin(), replace.end(), at);
  return frame_checkpoint(header, body);
}

template <class T>
std::vector<uint8_t> bytes_of(const std::vector<T>& values) {
  const auto* p = reinterpret_cast<const uint8_t*>(values.data());
  return {p, p + values.size() * sizeof(T)};
}

TEST(CutCheckpoint, AForgedCutMeshIsRefusedBeforeAnythingChanges) {
  const SceneDesc scene = scene_from_text(beam_scene("corotational_fem"), "cut_beam");
  Simulation sim(scene, plugins());
  cut_twice(sim, 80);
  const std::vector<uint8_t> bytes = sim.save_state();
  const std::vector<uint32_t> tets = sim.body_mesh(sim.body("beam")).tets;

  std::vector<uint32_t> past = tets;
  past[5] = 1u << 30;  // a tet corner past the nodes
  std::vector<uint32_t> flat = tets;
  flat[3] = flat[2];  // a tet with a repeated corner: no volume
  for (const auto& [forged, expected] :
       {std::pair{forge(bytes, bytes_of(tets), bytes_of(past)), "the cut mesh"},
        std::pair{forge(bytes, bytes_of(tets), bytes_of(flat)), "the cut mesh"}}) {
    Simulation fresh(scene, plugins());
    try {
      fresh.restore_state(forged);
      ADD_FAILURE() << "a forged cut mesh was restored";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
    EXPECT_EQ(fresh.body_revision(fresh.body("beam")), 0u);
    fresh.restore_state(bytes);  // the refusal left it usable
    EXPECT_EQ(fresh.body_revision(fresh.body("beam")), 2u);
  }
}

}  // namespace
}  // namespace tacta::simtest
