// A cut's collision side built off the tick (CollisionContext::copy_view, prepare_replacement,
// apply_replacement) on the shipped liver palpation scene, the stylus pressing from 0.4 s: built
// on another thread while the ticks go on and swapped in at a tick boundary without allocating;
// the same forces and contacts as the surface replaced between ticks (replace_surface); a plugin
// refusing the new surface changes nothing. malloc is interposed in this executable
// (tests/support/allocation_counter.hpp); the counting cases skip under the sanitizers.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <span>
#include <thread>

#include "allocation_counter.hpp"
#include "sim_test_support.hpp"
#include "world/body_cut.hpp"

namespace tacta::simtest {
namespace {

constexpr int kTicksToPress = 500;  // at 0.5 s the stylus presses the first palpation point
// The incision of scenes/examples/liver_incision.yaml: two triangles in the plane x = -0.0635 m.
const std::vector<double> kIncision = {-0.0635, 0.095, -0.1, -0.0635, 0.2,   -0.1,
                                       -0.0635, 0.2,   0.1,  -0.0635, 0.095, -0.1,
                                       -0.0635, 0.2,   0.1,  -0.0635, 0.095, 0.1};

SceneDesc liver(const std::vector<std::string>& overrides) {
  return load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml", schemas(),
                    overrides);
}

// The cut as Simulation::Impl::cut made it before: the whole cut, then the surface described
// again and the plugins prepared again between ticks.
void cut_replacing_surface(LoopHarness& h) {
  const double time = static_cast<double>(h.next) * h.dt;
  ASSERT_TRUE(cut_body(h.world, 0, kIncision, CutMode::kSeparate, time).changed);
  h.collision.replace_surface(0);
  (void)h.collision.take_bits();
  h.collision.build_between_ticks(time, h.dt);
  EXPECT_TRUE(h.collision.take_bits() & TACTA_COLLIDE_REBUILT) << "the plugins prepared again";
  h.haptics.surface_changed(h.world, 0);
}

// The same cut through the halves, with 0 ticks between them.
void cut_by_replacement(LoopHarness& h) {
  const double time = static_cast<double>(h.next) * h.dt;
  PreparedCut cut = prepare_cut(h.world, 0, kIncision, CutMode::kSeparate,
                                h.world.body(0).nodes.positions, h.world.body(0).nodes.velocities);
  ASSERT_TRUE(cut.changed);
  ViewCopy copy;
  h.collision.reserve_view_copy(copy);
  ASSERT_TRUE(h.collision.copy_view(copy));
  SurfaceReplacement r = h.collision.prepare_replacement(0, cut, copy);
  ASSERT_TRUE(apply_cut(h.world, cut, time).changed);
  h.collision.apply_replacement(r);
  retire_cut(h.world, cut);
  (void)h.collision.take_bits();
  h.collision.build_between_ticks(time, h.dt);
  EXPECT_FALSE(h.collision.take_bits() & TACTA_COLLIDE_REBUILT)
      << "the fresh hierarchies, built for the new surface, are refit, not rebuilt";
  h.haptics.surface_changed(h.world, 0);
}

// What a tick left that a difference in the collision side would change.
struct TickRecord {
  std::array<double, 3> force{}, proxy{};
  std::vector<tacta_contact> contacts;
  std::vector<double> positions;
};
TickRecord record(LoopHarness& h) {
  TickRecord r{h.world.device(0).contact.force,
               h.world.device(0).contact.proxy,
               {h.collision.contacts(), h.collision.contacts() + h.collision.contact_count()},
               h.world.body(0).nodes.positions};
  return r;
}
void expect_same_ticks(LoopHarness& a, LoopHarness& b, int ticks) {
  for (int i = 0; i < ticks; ++i) {
    a.tick();
    b.tick();
    const TickRecord ra = record(a), rb = record(b);
    ASSERT_EQ(ra.force, rb.force) << "tick " << i << " after the cut";
    ASSERT_EQ(ra.proxy, rb.proxy) << "tick " << i;
    ASSERT_EQ(ra.positions, rb.positions) << "tick " << i;
    ASSERT_EQ(ra.contacts.size(), rb.contacts.size()) << "tick " << i;
    for (size_t c = 0; c < ra.contacts.size(); ++c)
      ASSERT_EQ(std::memcmp(&ra.contacts[c], &rb.contacts[c], sizeof(tacta_contact)), 0)
          << "tick " << i << ", contact " << c;
  }
}

class CollisionReplacement : public ::testing::TestWithParam<const char*> {
 protected:
  std::vector<std::string> overrides() const {
    return std::strlen(GetParam()) ? std::vector<std::string>{GetParam()}
                                   : std::vector<std::string>{};
  }
};

// Prepared on a worker thread while the main thread ticks 20 times, applied at a boundary
// with apply_cut: the copy, the apply and the 300 ticks after allocate nothing, and the stylus
// stays in contact with the cut liver.
TEST_P(CollisionReplacement, BuiltOnAWorkerAndSwappedInWithoutAllocating) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  LoopHarness h(liver(overrides()), kTicksToPress + 400);
  for (int i = 0; i < kTicksToPress; ++i) h.tick();
  const std::vector<double> positions = h.world.body(0).nodes.positions;
  const std::vector<double> velocities = h.world.body(0).nodes.velocities;
  ViewCopy copy;
  h.collision.reserve_view_copy(copy);
  g_allocations = 0;
  g_counting = true;
  const bool copied = h.collision.copy_view(copy);
  g_counting = false;
  ASSERT_TRUE(copied);
  EXPECT_EQ(g_allocations, 0) << "heap allocations copying the view";
  const uint32_t triangles_before = h.collision.view().surfaces[0].triangle_count;

  PreparedCut cut;
  SurfaceReplacement r;
  std::thread worker([&] {
    cut = prepare_cut(h.world, 0, kIncision, CutMode::kSeparate, positions, velocities);
    r = h.collision.prepare_replacement(0, cut, copy);
  });
  for (int i = 0; i < 20; ++i) h.tick();  // the ticks go on meanwhile
  worker.join();
  ASSERT_TRUE(still_fits(h.world, cut));
  ASSERT_TRUE(h.collision.replacement_fits(r));
  ASSERT_NE(h.world.body(0).nodes.positions, positions) << "the body moved meanwhile";

  g_allocations = 0;
  g_counting = true;
  const CutSummary summary = apply_cut(h.world, cut, static_cast<double>(h.next) * h.dt);
  h.collision.apply_replacement(r);
  g_counting = false;
  EXPECT_EQ(g_allocations, 0) << "heap allocations applying the cut and its surface";
  ASSERT_TRUE(summary.changed);
  retire_cut(h.world, cut);
  h.haptics.surface_changed(h.world, 0);
  r = SurfaceReplacement();  // the old surface and plugin instances go, off the tick

  const tacta_collision_surface& seen = h.collision.view().surfaces[0];
  EXPECT_NE(seen.triangle_count, triangles_before) << "the incision remade the surface";
  EXPECT_EQ(seen.triangle_count, h.world.body(0).surface.mesh->triangle_count());
  EXPECT_EQ(seen.vertex_count, h.world.body(0).surface.mesh->vertex_count());
  EXPECT_EQ(seen.triangles, h.world.body(0).surface.mesh->triangles.data());
  EXPECT_EQ(seen.positions_end, h.world.body(0).surface.mesh->positions.data());
  const uint64_t contacts = h.world.device(0).stats.contact_ticks;
  g_allocations = 0;
  g_counting = true;
  for (int i = 0; i < 300; ++i) h.tick();
  g_counting = false;
  EXPECT_EQ(g_allocations, 0) << "heap allocations in the 300 ticks after the cut";
  EXPECT_GT(h.world.device(0).stats.contact_ticks - contacts, 100u)
      << "the counted ticks must include the stylus pressing the cut liver";
  EXPECT_FALSE(h.world.body(0).fault.frozen);
}

// With no tick between the halves, the ticks after the cut are those of the surface replaced
// between ticks, bit for bit: the fresh hierarchies, built over the copy, are refit where the
// old path builds them, over the same positions.
TEST_P(CollisionReplacement, SameTicksAsTheSurfaceReplacedBetweenTicks) {
  LoopHarness old_path(liver(overrides()), kTicksToPress + 200);
  LoopHarness new_path(liver(overrides()), kTicksToPress + 200);
  for (int i = 0; i < kTicksToPress; ++i) {
    old_path.tick();
    new_path.tick();
  }
  cut_replacing_surface(old_path);
  cut_by_replacement(new_path);
  const uint64_t contacts = new_path.world.device(0).stats.contact_ticks;
  expect_same_ticks(old_path, new_path, 200);
  EXPECT_GT(new_path.world.device(0).stats.contact_ticks - contacts, 100u);
  EXPECT_EQ(old_path.collision.proxy_whole_refits(), new_path.collision.proxy_whole_refits());
  EXPECT_EQ(old_path.collision.proxy_slices(), new_path.collision.proxy_slices());
}

INSTANTIATE_TEST_SUITE_P(LiverPalpation, CollisionReplacement,
                         ::testing::Values("", "collision.enabled=true"),
                         [](const ::testing::TestParamInfo<const char*>& param_info) {
                           return std::strlen(param_info.param) ? std::string("WithResponse")
                                                                : std::string("AsShipped");
                         });

// A plugin refusing the new surface (here the broad phase: a triangle naming a vertex past the
// surface's count) is an InputError, and the run goes on as if the cut had never been asked for.
TEST(CollisionReplacementRefused, ChangesNothing) {
  LoopHarness refused(liver({}), kTicksToPress + 100);
  LoopHarness untouched(liver({}), kTicksToPress + 100);
  for (int i = 0; i < kTicksToPress; ++i) {
    refused.tick();
    untouched.tick();
  }
  PreparedCut cut =
      prepare_cut(refused.world, 0, kIncision, CutMode::kSeparate,
                  refused.world.body(0).nodes.positions, refused.world.body(0).nodes.velocities);
  ASSERT_TRUE(cut.changed);
  ASSERT_TRUE(cut.shape.surface) << "the liver is collided through its embedded surface";
  cut.shape.surface->triangles[1] = static_cast<uint32_t>(cut.shape.surface->vertex_count() + 7);
  ViewCopy copy;
  refused.collision.reserve_view_copy(copy);
  ASSERT_TRUE(refused.collision.copy_view(copy));
  const tacta_collision_surface before = refused.collision.view().surfaces[0];
  const uint32_t pairs = refused.collision.pairs_capacity();
  const uint32_t contacts = refused.collision.contacts_capacity();
  try {
    (void)refused.collision.prepare_replacement(0, cut, copy);
    ADD_FAILURE() << "the broad phase accepted a triangle past the vertex count";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bvh"), std::string::npos) << e.what();
  }
  const tacta_collision_surface after = refused.collision.view().surfaces[0];
  EXPECT_EQ(std::memcmp(&before, &after, sizeof before), 0);
  EXPECT_EQ(refused.collision.pairs_capacity(), pairs);
  EXPECT_EQ(refused.collision.contacts_capacity(), contacts);
  expect_same_ticks(refused, untouched, 100);
  EXPECT_EQ(refused.collision.proxy_whole_refits(), untouched.collision.proxy_whole_refits());
  EXPECT_EQ(refused.collision.proxy_slices(), untouched.collision.proxy_slices());
}

}  // namespace
}  // namespace tacta::simtest

namespace tacta::simtest {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// The fine liver's embedded surface (scenes/examples/liver_incision_fine.yaml) cut at 0.5 s: the
// tick right after apply_replacement refits the fresh hierarchies whole without rebuilding them,
// where the surface replaced between ticks is built again in it. Prints the costs (ms).
TEST(CollisionReplacementCost, TheFirstTickAfterTheSwapRefitsWithoutRebuilding) {
  const SceneDesc scene = load_scene(
      std::string(TACTA_SOURCE_DIR) + "/scenes/examples/liver_incision_fine.yaml", schemas());
  LoopHarness old_path(scene, 600), new_path(scene, 600);
  double before_ms = 0;  // the slowest of the last 10 ticks before the cut
  for (int i = 0; i < 500; ++i) {
    old_path.tick();
    const auto tick_start = std::chrono::steady_clock::now();
    new_path.tick();
    if (i >= 490) before_ms = std::max(before_ms, ms_since(tick_start));
  }
  const double time = static_cast<double>(new_path.next) * new_path.dt;
  auto start = std::chrono::steady_clock::now();
  PreparedCut cut =
      prepare_cut(new_path.world, 0, kIncision, CutMode::kSeparate,
                  new_path.world.body(0).nodes.positions, new_path.world.body(0).nodes.velocities);
  const double prepare_cut_ms = ms_since(start);
  ASSERT_TRUE(cut.changed);
  ViewCopy copy;
  new_path.collision.reserve_view_copy(copy);
  start = std::chrono::steady_clock::now();
  ASSERT_TRUE(new_path.collision.copy_view(copy));
  const double copy_ms = ms_since(start);
  start = std::chrono::steady_clock::now();
  SurfaceReplacement r = new_path.collision.prepare_replacement(0, cut, copy);
  const double prepare_ms = ms_since(start);
  start = std::chrono::steady_clock::now();
  apply_cut(new_path.world, cut, time);
  const double apply_cut_ms = ms_since(start);
  start = std::chrono::steady_clock::now();
  new_path.collision.apply_replacement(r);
  const double apply_ms = ms_since(start);
  retire_cut(new_path.world, cut);
  new_path.haptics.surface_changed(new_path.world, 0);
  const uint64_t wholes = new_path.collision.proxy_whole_refits();
  start = std::chrono::steady_clock::now();
  new_path.tick();
  const double tick_ms = ms_since(start);
  EXPECT_EQ(new_path.collision.proxy_whole_refits(), wholes + 1);
  EXPECT_FALSE(new_path.haptics.collision_bits() & TACTA_COLLIDE_REBUILT)
      << "the fresh hierarchies, built for the new surface, are refit";

  ASSERT_TRUE(cut_body(old_path.world, 0, kIncision, CutMode::kSeparate, time).changed);
  old_path.collision.replace_surface(0);
  old_path.haptics.surface_changed(old_path.world, 0);
  start = std::chrono::steady_clock::now();
  old_path.tick();
  const double old_tick_ms = ms_since(start);
  EXPECT_TRUE(old_path.haptics.collision_bits() & TACTA_COLLIDE_REBUILT);
  EXPECT_EQ(new_path.collision.proxy_whole_refits(), old_path.collision.proxy_whole_refits());
  std::printf(
      "fine liver, %u surface triangles: prepare_cut %.3f ms, copy_view %.3f ms, "
      "prepare_replacement %.3f ms, apply_cut %.3f ms, apply_replacement %.3f ms; the first tick "
      "after them %.3f ms (after replace_surface: %.3f ms)\n",
      new_path.collision.view().surfaces[0].triangle_count, prepare_cut_ms, copy_ms, prepare_ms,
      apply_cut_ms, apply_ms, tick_ms, old_tick_ms);
  start = std::chrono::steady_clock::now();
  new_path.tick();
  std::printf("second tick after the swap %.3f ms; slowest of the 10 before the cut %.3f ms\n",
              ms_since(start), before_ms);
  for (int i = 0; i < 50; ++i) new_path.tick();
  EXPECT_FALSE(new_path.world.body(0).fault.frozen);
}

}  // namespace
}  // namespace tacta::simtest
