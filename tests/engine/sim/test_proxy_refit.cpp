// The haptic proxy's surfaces brought up to date a slice at a time (collision.proxy_refit:
// sliced, the default) answer every query as a whole refit each tick does: on the liver demo
// (its embedded 4,384-triangle surface, and its tets' boundary), with and without contact
// response, the device force, the contact and the bodies' nodes agree tick for tick; and the
// embedded vertices made current as the queries read them touch as when made current by box.
#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>

#include "collision/embedded_collision.hpp"
#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

// The world, its collision context, haptics and (when the scene has it on) contact response,
// ticked as Simulation::run does.
struct ProxyRun {
  ProxyRun(const std::string& refit, const std::vector<std::string>& overrides, size_t ticks)
      : ProxyRun(load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml",
                            schemas(), with_refit(overrides, refit)),
                 ticks) {}
  static std::vector<std::string> with_refit(std::vector<std::string> overrides,
                                             const std::string& refit) {
    overrides.push_back("collision.proxy_refit=" + refit);
    return overrides;
  }
  ProxyRun(SceneDesc desc, size_t ticks) : scene(std::move(desc)) {
    world = std::make_unique<World>(scene, plugins());
    collision = std::make_unique<CollisionContext>(*world, plugins());
    haptics = std::make_unique<HapticInteraction>(*world, *collision);
    response = std::make_unique<CollisionResponse>(*collision);
    snapshots = std::make_unique<TripleBuffer<Snapshot>>(HapticLoop::make_prototype(*world));
    loop = std::make_unique<HapticLoop>(*world, *snapshots, ticks);
    dt = 1.0 / scene.clock.haptic_rate_hz;
    for (size_t i = 0; i < world->body_count(); ++i) {
      const SoftBody b = world->body(i);
      b.model.instance->begin(b.state_view(0.0), dt);
    }
    loop->set_haptics(haptics.get());
    if (scene.collision.enabled) loop->set_response(response.get());
  }
  void tick() {
    loop->tick(next, static_cast<double>(next) * dt, dt);
    ++next;
  }
  SceneDesc scene;
  std::unique_ptr<World> world;
  std::unique_ptr<CollisionContext> collision;
  std::unique_ptr<HapticInteraction> haptics;
  std::unique_ptr<CollisionResponse> response;
  std::unique_ptr<TripleBuffer<Snapshot>> snapshots;
  std::unique_ptr<HapticLoop> loop;
  double dt = 0;
  uint64_t next = 0;
};

// Ticks two runs side by side: the same contacts and device forces every tick, bit for bit, and
// the same nodes at the end. Returns the ticks the first device was in contact.
size_t expect_same_ticks(ProxyRun& a, ProxyRun& b, size_t ticks) {
  size_t contact_ticks = 0;
  for (size_t k = 0; k < ticks; ++k) {
    a.tick();
    b.tick();
    for (size_t d = 0; d < a.world->device_count(); ++d) {
      const DeviceComponents da = a.world->device(d), db = b.world->device(d);
      EXPECT_EQ(da.contact.in_contact, db.contact.in_contact) << "tick " << k << " device " << d;
      contact_ticks += d == 0 && da.contact.in_contact ? 1 : 0;
      for (size_t i = 0; i < 3; ++i)
        EXPECT_EQ(da.contact.force[i], db.contact.force[i]) << "tick " << k << " axis " << i;
    }
    if (::testing::Test::HasFailure()) return contact_ticks;
  }
  EXPECT_EQ(a.world->body(0).nodes.positions, b.world->body(0).nodes.positions);
  return contact_ticks;
}

// Runs both refits side by side. The queries are exact either way, and of equal distances both
// answer with the lowest triangle, so the touch is the same bit for bit.
void expect_same_touch(const std::vector<std::string>& overrides, size_t ticks, bool slices) {
  ProxyRun sliced("sliced", overrides, ticks), whole("every_tick", overrides, ticks);
  const size_t contact_ticks = expect_same_ticks(sliced, whole, ticks);
  std::printf("%zu ticks, %zu in contact; %llu slices, %llu whole refits (against %llu)\n", ticks,
              contact_ticks, static_cast<unsigned long long>(sliced.collision->proxy_slices()),
              static_cast<unsigned long long>(sliced.collision->proxy_whole_refits()),
              static_cast<unsigned long long>(whole.collision->proxy_whole_refits()));
  EXPECT_GT(contact_ticks, ticks / 4);  // the stylus pressed the liver
  // The sliced run sliced (unless the response's whole refits after each step kept every box
  // fresh), and the proxy path refit whole far less often than every tick.
  if (slices) {
    EXPECT_GT(sliced.collision->proxy_slices(), 0u);
  }
  // Between presses the device in free space was found clear of the liver without a search,
  // and the touch is the same as where it searched every tick (every_tick knows no clear_of).
  std::printf("%llu free-space checks answered without a search, %llu of them by slice boxes\n",
              static_cast<unsigned long long>(sliced.collision->clear_answers()),
              static_cast<unsigned long long>(sliced.collision->clear_bound_answers()));
  EXPECT_GT(sliced.collision->clear_answers(), ticks / 10);
  // Some where the liver's motion used up the last closest point's slack (the embedded surface's
  // many slices, refit as it moves, each given its box again).
  if (slices) {
    EXPECT_GT(sliced.collision->clear_bound_answers(), 10u);
  }
  EXPECT_EQ(whole.collision->clear_answers(), 0u);
  EXPECT_LT(sliced.collision->proxy_whole_refits(), ticks / 20);
  EXPECT_EQ(whole.collision->proxy_slices(), 0u);
  EXPECT_TRUE(sliced.collision->proxy_sliced());
  EXPECT_FALSE(whole.collision->proxy_sliced());
  EXPECT_EQ(whole.collision->proxy_whole_refits(), ticks);
}

// The slices are refit after the device write, for the next tick (the haptic stage only checks
// the margins): the upkeep runs, slices while the liver settles, is pressed and let go, and its
// slices keep the margins under their cap (no whole refit after the first tick's build).
TEST(ProxyRefit, SlicesAreRefitAfterTheWriteNotInTheHapticStage) {
  ProxyRun run("sliced", {}, 1500);
  for (int k = 0; k < 1500; ++k) run.tick();
  const CollisionContext& c = *run.collision;
  EXPECT_GT(c.proxy_upkeep_slices(), 100u);
  EXPECT_EQ(c.proxy_upkeep_slices(), c.proxy_slices()) << "none in the haptic stage";
  EXPECT_EQ(c.proxy_whole_refits(), 1u) << "the first tick's build only";
}

// The upkeep runs after the step: a vertex made current earlier in a pass has moved since, and
// the slice refit (after_step) must recompute it rather than skip it as current.
TEST(ProxyRefit, AVertexMadeCurrentBeforeTheStepIsRecomputedAfterIt) {
  ProxyRun run("sliced", {}, 1);
  const SoftBody body = run.world->body(0);
  ASSERT_NE(body.surface.mesh, nullptr);
  std::vector<double> inverse_masses(body.node_count(), 1.0);
  EmbeddedCollisionSurface surface(*run.world, 0, *body.surface.mesh, body.node_count(),
                                   inverse_masses.data());
  const uint32_t triangle = 0, vertex = body.surface.mesh->triangles[0];
  const auto where = [&] {
    const double* p = &body.surface.mesh->positions[3 * size_t{vertex}];
    return std::vector<double>(p, p + 3);
  };
  const auto interpolated = [&] {
    std::vector<double> p(3);
    interpolate_vertex(*body.surface.mesh, vertex, body.nodes.positions.data(), p.data());
    return p;
  };
  surface.refresh_triangles(&triangle, 1, 7);
  EXPECT_EQ(where(), interpolated());
  for (double& x : body.nodes.positions) x += 1e-3;  // the step moves every node 1 mm a side
  surface.refresh_triangles(&triangle, 1, 7);
  EXPECT_NE(where(), interpolated()) << "current as of pass 7: skipped";
  surface.refresh_triangles(&triangle, 1, 7, true);
  EXPECT_EQ(where(), interpolated()) << "after the step: recomputed";
}

TEST(ProxyRefit, SlicedTouchesTheEmbeddedLiverAsAWholeRefitDoes) {
  expect_same_touch({}, 2600, true);  // two presses and the travel between them
}

// The tets' boundary's coarser triangles keep its margin under a mean edge for these presses:
// no slice needs refitting (the embedded surface's run above refits slices).
TEST(ProxyRefit, SlicedTouchesTheTetBoundaryAsAWholeRefitDoes) {
  expect_same_touch({"bodies.0.mesh.surface=tet_boundary"}, 2600, false);
}

// Contact response on: its rounds refit whole after the step; the proxy's slices and patches
// start from those hierarchies each tick.
TEST(ProxyRefit, SlicedTouchesAsAWholeRefitWithContactResponseOn) {
  expect_same_touch({"collision.enabled=true"}, 1500, false);
}

// The bvh plugin makes current each triangle its queries read (PROXY_MAKES_CURRENT); a proxy
// plugin that does not gets the query's whole box made current beforehand. Both read the same
// vertex positions, so the touch is the same bit for bit; the box pass makes more current.
TEST(ProxyRefit, VerticesMadeCurrentAsReadTouchAsTheWholeBoxMadeCurrent) {
  constexpr size_t kTicks = 2600;
  ProxyRun as_read("sliced", {}, kTicks), box("sliced", {}, kTicks);
  as_read.collision->set_proxy_patches(false);  // every query searches the hierarchy
  box.collision->set_eager_patches(true);
  size_t contact_ticks = 0;
  double as_read_patch_ms = 0, box_patch_ms = 0;  // the box pass's time, summed over the ticks
  for (size_t k = 0; k < kTicks; ++k) {
    as_read.tick();
    box.tick();
    as_read_patch_ms += as_read.collision->patch_ms();
    box_patch_ms += box.collision->patch_ms();
    const DeviceComponents a = as_read.world->device(0), b = box.world->device(0);
    ASSERT_EQ(a.contact.in_contact, b.contact.in_contact) << "tick " << k;
    contact_ticks += a.contact.in_contact ? 1 : 0;
    for (size_t i = 0; i < 3; ++i)
      ASSERT_EQ(a.contact.force[i], b.contact.force[i]) << "tick " << k;
  }
  EXPECT_GT(contact_ticks, kTicks / 4);
  EXPECT_EQ(as_read.world->body(0).nodes.positions, box.world->body(0).nodes.positions);
  EXPECT_EQ(as_read_patch_ms, 0.0);  // no box pass: each read made its own triangle current
  EXPECT_GT(box_patch_ms, 0.0);
}

// The proxy's patch (proxy_patch.hpp): most queries test the triangles gathered near the tool
// one by one instead of searching the hierarchy. Every triangle within a query's reach is among
// them, and of equal distances both answer with the lowest triangle, so the touch is the same
// bit for bit: device force every tick, and the nodes at the end.
// `patch` and `search` (patches off) side by side: the same touch; the patches answered at
// least a query a tick per device, and were gathered far less often.
void expect_patches_touch_as_the_search(ProxyRun& patch, ProxyRun& search, size_t ticks) {
  search.collision->set_proxy_patches(false);
  const size_t contact_ticks = expect_same_ticks(patch, search, ticks);
  const uint64_t queries = patch.collision->patch_queries();
  const uint64_t gathers = patch.collision->patch_gathers();
  std::printf("%zu ticks, %zu in contact: %llu queries answered by patches, %llu gathers\n", ticks,
              contact_ticks, static_cast<unsigned long long>(queries),
              static_cast<unsigned long long>(gathers));
  EXPECT_GT(contact_ticks, ticks / 4);
  EXPECT_GT(queries, ticks * patch.world->device_count());
  EXPECT_LT(gathers, queries / 4);
  EXPECT_EQ(search.collision->patch_queries(), 0u);
  // Most gathers were made by the upkeep, after the write, ahead of the queries that need them.
  EXPECT_GT(patch.collision->patch_upkeep_gathers(), gathers / 2);
}

void expect_patch_touches_as_the_hierarchy(const std::vector<std::string>& overrides) {
  constexpr size_t kTicks = 2600;  // two presses and the travel between them
  ProxyRun patch("sliced", overrides, kTicks), search("sliced", overrides, kTicks);
  expect_patches_touch_as_the_search(patch, search, kTicks);
}

TEST(ProxyPatch, TouchesTheEmbeddedLiverAsTheHierarchySearchDoes) {
  expect_patch_touches_as_the_hierarchy({});
}

TEST(ProxyPatch, TouchesTheTetBoundaryAsTheHierarchySearchDoes) {
  expect_patch_touches_as_the_hierarchy({"bodies.0.mesh.surface=tet_boundary"});
}

// The upkeep makes the patch current for the next tick's queries, and the haptic stage takes it
// as current only where nothing moved a node since: nodes nudged between ticks (as a restored
// checkpoint or a script may) are seen, and the touch is still the hierarchy search's, bit for bit.
TEST(ProxyPatch, NodesMovedBetweenTicksAreSeenByThePreparedPatch) {
  constexpr size_t kTicks = 1200;  // the first press
  ProxyRun patch("sliced", {}, kTicks), search("sliced", {}, kTicks);
  search.collision->set_proxy_patches(false);
  size_t nudges = 0, nudged_in_contact = 0;
  for (size_t k = 0; k < kTicks; ++k) {
    const bool nudged = k % 7 == 3;
    if (nudged) {
      for (ProxyRun* run : {&patch, &search}) {
        std::vector<double>& x = run->world->body(0).nodes.positions;
        for (size_t i = 0; i < x.size(); ++i)
          x[i] += 2e-5 * std::sin(0.37 * static_cast<double>(i + k));  // m
      }
      ++nudges;
    }
    patch.tick();
    search.tick();
    const DeviceComponents a = patch.world->device(0), b = search.world->device(0);
    ASSERT_EQ(a.contact.in_contact, b.contact.in_contact) << "tick " << k;
    nudged_in_contact += nudged && a.contact.in_contact ? 1 : 0;
    for (size_t i = 0; i < 3; ++i)
      ASSERT_EQ(a.contact.force[i], b.contact.force[i]) << "tick " << k << " axis " << i;
  }
  EXPECT_GT(nudges, 100u);
  EXPECT_GT(nudged_in_contact, 50u) << "the nudges moved a surface being pressed";
  EXPECT_GT(patch.collision->patch_queries(), kTicks);
  EXPECT_GT(patch.collision->patch_upkeep_gathers(), 0u);
  EXPECT_EQ(patch.world->body(0).nodes.positions, search.world->body(0).nodes.positions);
}

// Two styluses on the liver, pressing the demo's points in opposite orders: each device's proxy
// keeps its own patch, so neither gathers over the other's each tick, and both touch as the
// hierarchy's search does.
TEST(ProxyPatch, TwoDevicesOnOneBodyKeepTheirOwnPatches) {
  std::ifstream file(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml");
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const size_t at = text.find("\ncollision:");
  ASSERT_NE(at, std::string::npos);
  text.insert(at, R"(
  - name: second_stylus
    plugin: sim_stylus
    params:
      workspace_origin: [-0.03, 0.12, 0.02]
      pattern: palpation
      palpation_points: [0.018, 0.145, 0.010, -0.049, 0.147, 0.027, -0.078, 0.144, 0.027]
      approach_height: 0.012
      depth: 0.008
    tool:
      sphere: {radius: 0.004}
    coupling: {stiffness: 600, damping: 1.0}
    touches: liver)");
  constexpr size_t kTicks = 2600;
  ProxyRun patch(scene_from_text(text, "two_styluses"), kTicks);
  ProxyRun search(scene_from_text(text, "two_styluses"), kTicks);
  ASSERT_EQ(patch.world->device_count(), 2u);
  // One patch shared by both would be gathered again nearly every tick (a quarter of queries).
  expect_patches_touch_as_the_search(patch, search, kTicks);
}

}  // namespace
}  // namespace tacta::simtest
