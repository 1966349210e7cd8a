// A whole HapticLoop tick allocates nothing once warm: engine, model plugin, device plugin, the
// god-object proxy's surface queries and (second case) collision detection and response, over
// the shipped liver palpation scene through its first press. malloc and friends are interposed
// in this executable (tests/support/allocation_counter.hpp); skipped under the sanitizers.
// Last cases: the ticks after a cut (made between ticks, as Simulation::cut, scene cut events and
// blades make it) allocate nothing either, and installing a cut prepared off the tick
// (apply_cut) allocates nothing on any model that takes topology edits.
#include <chrono>
#include <span>
#include <thread>

#include "allocation_counter.hpp"
#include "cut_beam_scene.hpp"
#include "sim_test_support.hpp"
#include "simulation/realtime_cuts.hpp"
#include "simulation/simulation_impl.hpp"
#include "world/body_cut.hpp"

namespace tacta::simtest {
namespace {

constexpr int kWarmUpTicks = 10;  // first steps size solver workspaces and warm-start caches
// Through the approach (0.4 s), the first contact and press (0.3 s) and into the dwell.
constexpr int kCountedTicks = 900;

struct Counted {
  long allocations = 0;
  uint64_t contact_ticks = 0;
  bool frozen = false;
  uint64_t proxy_slices = 0, proxy_whole_refits = 0;  // the proxy's hierarchy refits counted
};

Counted count_ticks(const std::vector<std::string>& overrides) {
  const SceneDesc scene = load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml",
                                     schemas(), overrides);
  LoopHarness h(scene, kWarmUpTicks + kCountedTicks);
  for (int i = 0; i < kWarmUpTicks; ++i) h.tick();
  const uint64_t contacts_before = h.world.device(0).stats.contact_ticks;
  const uint64_t slices_before = h.collision.proxy_slices();
  const uint64_t wholes_before = h.collision.proxy_whole_refits();
  g_allocations = 0;
  g_counting = true;
  for (int i = 0; i < kCountedTicks; ++i) h.tick();
  g_counting = false;
  return {g_allocations, h.world.device(0).stats.contact_ticks - contacts_before,
          h.world.body(0).fault.frozen, h.collision.proxy_slices() - slices_before,
          h.collision.proxy_whole_refits() - wholes_before};
}

// The counter sees an allocation made through operator new (so a zero below means something).
TEST(HapticTickAllocations, CounterSeesNew) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  g_allocations = 0;
  g_counting = true;
  auto box = std::make_unique<std::vector<double>>(16);
  g_counting = false;
  EXPECT_EQ(g_allocations, 2) << "the vector object and its storage";
}

TEST(HapticTickAllocations, LiverPalpationAsShipped) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  const Counted run = count_ticks({});
  EXPECT_EQ(run.allocations, 0) << "heap allocations in " << kCountedTicks << " ticks";
  EXPECT_GT(run.contact_ticks, 100u) << "the counted ticks must include the stylus pressing";
  EXPECT_FALSE(run.frozen);
  // The counted ticks went through the sliced refit and the embedded patch (the default).
  EXPECT_GT(run.proxy_slices, 0u);
  std::printf("%llu slices, %llu whole refits\n", static_cast<unsigned long long>(run.proxy_slices),
              static_cast<unsigned long long>(run.proxy_whole_refits));
}

TEST(HapticTickAllocations, LiverPalpationWithCollisionResponse) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  const Counted run = count_ticks({"collision.enabled=true"});
  EXPECT_EQ(run.allocations, 0) << "heap allocations in " << kCountedTicks << " ticks";
  EXPECT_GT(run.contact_ticks, 100u);
  EXPECT_FALSE(run.frozen);
}

// A body added while the scene runs, then the liver removed: the requests allocate (they build
// the body) but the ticks that take them in and out, and the ticks after, allocate nothing.
TEST(HapticTickAllocations, AddAndRemoveBodiesAtTickBoundaries) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  const SceneDesc scene =
      load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml", schemas());
  LoopHarness h(scene, kWarmUpTicks + kCountedTicks);
  for (int i = 0; i < kWarmUpTicks; ++i) h.tick();
  const BodyDesc cube = load_body_from_string(R"(
name: dropped
mesh: {box_grid: {size: [0.04, 0.04, 0.04], cells: [2, 2, 2], origin: [0.2, 0.1, 0]}}
material: {youngs_modulus: 20000, poisson_ratio: 0.4, density: 1000}
model: corotational_fem
)",
                                              scene.path, schemas());
  const auto count_100_ticks = [&] {  // with a snapshot now and then, as the render task takes them
    g_allocations = 0;
    g_counting = true;
    for (int i = 0; i < 100; ++i) {
      h.tick();
      if (i % 16 == 0) h.loop.publish(static_cast<double>(h.next) * h.dt);
    }
    g_counting = false;
    return g_allocations;
  };
  const ecs::Entity added = h.world.add_body(cube);
  const long around_add = count_100_ticks();
  h.world.remove_body(h.world.body_handle(0));
  g_allocations = count_100_ticks();
  EXPECT_EQ(around_add, 0) << "heap allocations in the 100 ticks that took the body in";
  EXPECT_EQ(g_allocations, 0) << "heap allocations in the 100 ticks that took the liver out";
  EXPECT_TRUE(h.world.body(1).present());
  EXPECT_TRUE(h.world.is_live(added));
  EXPECT_GT(h.world.body(1).fault.max_displacement_m, 0.0) << "the added cube falls";
  EXPECT_FALSE(h.world.body(0).present());
}

// A tool changed while the liver is pressed: the request builds the new shape (allocates, on
// the requesting side); the tick that swaps it in and the proxy that restarts with its radius
// allocate nothing, and the collision view carries the new shape from that tick.
TEST(HapticTickAllocations, ToolChangeAtATickBoundary) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  const SceneDesc scene =
      load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml", schemas());
  LoopHarness h(scene, kWarmUpTicks + 700);
  for (int i = 0; i < kWarmUpTicks + 500; ++i) h.tick();
  const uint32_t id = h.collision.view().shapes[0].body_id;
  ShapeDesc capsule;
  capsule.kind = ShapeDesc::Kind::Capsule;
  capsule.radius = 0.005;
  capsule.half_length = 0.01;
  h.world.change_tool(0, capsule);
  g_allocations = 0;
  g_counting = true;
  for (int i = 0; i < 100; ++i) h.tick();
  g_counting = false;
  EXPECT_EQ(g_allocations, 0) << "heap allocations in the 100 ticks that took the new tool";
  EXPECT_EQ(h.world.tool(0).revision, 1u);
  const tacta_collision_shape& seen = h.collision.view().shapes[0];
  EXPECT_EQ(seen.type, TACTA_SHAPE_CAPSULE);
  EXPECT_EQ(seen.radius, 0.005);
  EXPECT_EQ(seen.body_id, id) << "the new tool keeps the collision id";
  const tacta_pose& pose = h.world.tool(0).rigid.shape.pose_end;  // follows the proxy
  for (int a = 0; a < 3; ++a)
    EXPECT_EQ(pose.position[a], h.world.device(0).contact.proxy[static_cast<size_t>(a)]);
}

// A cut as Simulation::Impl::cut makes it between two ticks (simulation/simulation_cut.cpp): the
// body's mesh and everything derived from it, the collision surface, the proxies, the snapshot
// entries the render task fills.
void cut_between_ticks(LoopHarness& h, std::span<const double> blade, CutMode mode) {
  ASSERT_TRUE(cut_body(h.world, 0, blade, mode, static_cast<double>(h.next) * h.dt).changed);
  h.collision.replace_surface(0);
  h.haptics.surface_changed(h.world, 0);
  const BodySnapshot prototype = HapticLoop::body_prototype(h.world.body(0));
  h.snapshots.for_each_slot([&](Snapshot& s) { s.bodies[0] = prototype; });
}

// The liver is cut while the stylus presses it (a separation along the incision of
// scenes/examples/liver_incision.yaml, then a removal across the right lobe): the cut allocates
// (it rebuilds the mesh, model, surface and buffers, and begins the new model); the ticks after
// it, from the very first, allocate nothing, with a snapshot now and then.
TEST(HapticTickAllocations, TicksAfterACut) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  const SceneDesc scene =
      load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml", schemas());
  LoopHarness h(scene, 2000);
  const auto count_ticks = [&](int ticks) {
    g_allocations = 0;
    g_counting = true;
    for (int i = 0; i < ticks; ++i) {
      h.tick();
      if (i % 16 == 0) h.loop.publish(static_cast<double>(h.next) * h.dt);
    }
    g_counting = false;
    return g_allocations;
  };
  // At 0.5 s the stylus is over the first point, pressing from 0.4 s.
  for (int i = 0; i < 500; ++i) h.tick();
  const std::vector<double> incision = {-0.0635, 0.095, -0.1, -0.0635, 0.2,   -0.1,
                                        -0.0635, 0.2,   0.1,  -0.0635, 0.095, -0.1,
                                        -0.0635, 0.2,   0.1,  -0.0635, 0.095, 0.1};
  cut_between_ticks(h, incision, CutMode::kSeparate);
  const uint64_t contacts = h.world.device(0).stats.contact_ticks;
  const long after_separation = count_ticks(300);
  const uint64_t contacts_after_separation = h.world.device(0).stats.contact_ticks - contacts;
  const std::vector<double> notch = {0.0, 0.12, -0.1, 0.0, 0.2, -0.1, 0.0, 0.2,  0.1,
                                     0.0, 0.12, -0.1, 0.0, 0.2, 0.1,  0.0, 0.12, 0.1};
  cut_between_ticks(h, notch, CutMode::kRemove);
  const long after_removal = count_ticks(300);
  EXPECT_EQ(after_separation, 0) << "heap allocations in the 300 ticks after the separation";
  EXPECT_EQ(after_removal, 0) << "heap allocations in the 300 ticks after the removal";
  EXPECT_GT(contacts_after_separation, 100u)
      << "the counted ticks must include the stylus pressing";
  EXPECT_EQ(h.world.body(0).shape.cuts.revision, 2u);
  EXPECT_FALSE(h.world.body(0).fault.frozen);
}

// A cut prepared on another thread from a copy of the positions taken at a tick boundary, while
// the ticks go on, then installed at a later boundary by apply_cut: installing it (the state
// carried, the shape exchanged, the new model begun) allocates nothing, on every model that takes
// topology edits, for a beam with prescribed and sliding nodes cut through its sliding face.
class PreparedCutAllocations : public ::testing::TestWithParam<const char*> {};

TEST_P(PreparedCutAllocations, ApplyingItAllocatesNothing) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  const SceneDesc scene = scene_from_text(beam_scene(GetParam(), kPrescribedBeam), "beam");
  LoopHarness h(scene, 300);
  for (int i = 0; i < 50; ++i) h.tick();
  const std::vector<double> positions = h.world.body(0).nodes.positions;
  const std::vector<double> blade = plane_x(0.05);
  PreparedCut cut;
  const std::vector<double> velocities = h.world.body(0).nodes.velocities;
  std::thread worker(
      [&] { cut = prepare_cut(h.world, 0, blade, CutMode::kSeparate, positions, velocities); });
  for (int i = 0; i < 20; ++i) h.tick();  // the ticks go on meanwhile: the state moves
  worker.join();
  ASSERT_TRUE(cut.changed);
  ASSERT_TRUE(still_fits(h.world, cut));
  const std::vector<double> now = h.world.body(0).nodes.positions;
  ASSERT_NE(now, positions);
  g_allocations = 0;
  g_counting = true;
  const CutSummary summary = apply_cut(h.world, cut, static_cast<double>(h.next) * h.dt);
  g_counting = false;
  EXPECT_EQ(g_allocations, 0) << "heap allocations installing the prepared cut";
  EXPECT_EQ(summary.revision, 1u);
  EXPECT_EQ(summary.nodes_added, 9u) << "the 3 x 3 nodes of the face x = 0.05 copied";
  EXPECT_FALSE(still_fits(h.world, cut)) << "the body has moved on to the new mesh";
  const std::vector<double>& carried = h.world.body(0).nodes.positions;
  ASSERT_EQ(carried.size(), 3 * cut.node_source.size());
  for (size_t n = 0; n < cut.node_source.size(); ++n)  // the state at the apply, not the prepare
    for (size_t a = 0; a < 3; ++a)
      ASSERT_EQ(carried[3 * n + a], now[3 * size_t{cut.node_source[n]} + a]) << "node " << n;
  retire_cut(h.world, cut);
  h.collision.replace_surface(0);
  for (int i = 0; i < 50; ++i) h.tick();
  EXPECT_FALSE(h.world.body(0).fault.frozen);
}

// A realtime run's cuts as the haptic thread makes them (simulation/realtime_cuts.hpp): the
// scalpel's sweeps posted at tick boundaries, prepared on the cut worker (which allocates by
// design, so only this thread is counted), installed at a later boundary with the collision
// surface and the picture, every tick publishing a snapshot now and then.
TEST(HapticTickAllocations, RealtimeCutsAllocateNothingOnTheHapticThread) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  const SceneDesc scene =
      scene_from_text(beam_scene("corotational_fem", kScalpelDevice), "cut_beam");
  World world(scene, plugins());
  CollisionContext collision(world, plugins());
  HapticInteraction haptics(world, collision);
  ClockSession session(world, &haptics, nullptr);
  SceneCuts schedule(world, [](size_t, std::span<const double>, CutMode) -> CutSummary {
    ADD_FAILURE() << "a realtime run never cuts between ticks";
    return {};
  });
  RealtimeCuts cuts(world, schedule, &collision, &haptics, session);
  cuts.start();
  HapticLoop& loop = session.loop();
  const double dt = 1.0 / scene.clock.haptic_rate_hz;
  t_allocations = 0;
  for (uint64_t k = 0; k < 250; ++k) {
    const double time = static_cast<double>(k) * dt;
    g_counting = k >= 10;  // first steps size solver workspaces
    cuts.at_boundary(time);
    loop.tick(k, time, dt);
    if (k % 16 == 0) loop.publish(time + dt);
    g_counting = false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));  // the worker's time, as at 1 kHz
  }
  const uint64_t installed = world.device(0).stats.blade_cuts;
  cuts.finish(250 * dt);
  EXPECT_EQ(t_allocations, 0) << "heap allocations on the haptic thread in 240 ticks";
  EXPECT_GT(installed, 0u) << "cuts installed at tick boundaries within the counted ticks";
  EXPECT_EQ(world.device(0).stats.blade_cuts_refused, 0u);
  EXPECT_GT(world.body(0).shape.cuts.revision, 0u);
  EXPECT_FALSE(world.body(0).fault.frozen);
}

INSTANTIATE_TEST_SUITE_P(ModelsTakingEdits, PreparedCutAllocations,
                         ::testing::Values("corotational_fem", "hyperelastic", "tensor_mass",
                                           "mass_spring", "vbd"));

}  // namespace
}  // namespace tacta::simtest
