// The World's entities as docs/ARCHITECTURE.md lists them: every body slot an entity with every
// body component, its embedded surface an entity of its own, a device with its three components
// and a Tool entity, an obstacle with a Collider; the systems' InScene view holds exactly the
// bodies present, and a removed body keeps its components (its last state) for the report.
#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

const char* const kScene = R"(
name: entities
gravity: [0, -9.81, 0]
clock: {mode: lockstep, duration_s: 0.2}
bodies:
  - name: cube
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [2, 2, 2], origin: [-0.05, 0, -0.05]}}
    material: {youngs_modulus: 2.0e4, poisson_ratio: 0.4, density: 1000}
    model: corotational_fem
    fixed: [{box: {min: [-1, -0.001, -1], max: [1, 0.001, 1]}}]
  - name: beam
    mesh: {beam_grid: {size: [0.3, 0.04, 0.04], cells: [6, 1, 1], origin: [0, 0.3, 0]}}
    material: {youngs_modulus: 2.0e6, poisson_ratio: 0.4, density: 1000}
    model: corotational_fem
    fixed: [{box: {min: [-0.001, -1, -1], max: [0.001, 1, 1]}}]
devices:
  - name: stylus
    plugin: mouse
    tool: {capsule: {radius: 0.003, half_length: 0.01}}
    touches: cube
obstacles:
  - name: table
    shape: {plane: {normal: [0, 1, 0], offset: 0}}
  - name: wall
    shape: {box: {half_extents: [0.01, 0.2, 0.2], position: [0.5, 0, 0]}}
collision: {broad_phase: bvh}
capacity: {bodies: 3}
)";

template <class... Ts>
size_t count(World& world) {
  return world.registry().view<Ts...>().count();
}

TEST(WorldEntities, EveryThingIsAnEntityWithItsComponents) {
  LoopHarness h(scene_from_text(kScene, "entities"), 10);
  World& w = h.world;
  ASSERT_EQ(w.body_capacity(), 3u);
  // Every slot (used or not) has every body component, and an embedded surface entity.
  EXPECT_EQ((count<BodyInfo, BodyPresence, NodeState, NodeLoads, RestShape, BodyModel, BodySettings,
                   StepProgress, BodyConstraints, FaultState, Recording, SurfaceLink>(w)),
            3u);
  EXPECT_EQ(count<BodySurface>(w), 3u);
  EXPECT_EQ(count<InScene>(w), 2u) << "the two scene bodies are in; the spare slot is not";
  w.registry().view<SurfaceLink>().each([&](ecs::Entity body, SurfaceLink& link) {
    ASSERT_TRUE(w.registry().valid(link.surface));
    EXPECT_NE(link.surface.index, body.index) << "a surface is an entity of its own";
    EXPECT_EQ(w.registry().get<BodySurface>(link.surface).body, body.index);
  });
  // A device: link, contact, statistics, and the tool it carries as its own entity.
  EXPECT_EQ((count<DeviceLink, DeviceContact, DeviceStats>(w)), 1u);
  const ecs::Entity tool = w.device(0).link.tool;
  ASSERT_TRUE(w.registry().valid(tool));
  EXPECT_EQ(w.registry().get<Tool>(tool).rigid.shape.type, TACTA_SHAPE_CAPSULE);
  EXPECT_EQ(count<Tool>(w), 1u);
  // Obstacles: a Collider each, in the collision plugins' view in scene order.
  EXPECT_EQ(count<Collider>(w), 2u);
  ASSERT_EQ(h.collision.view().obstacle_count, 2u);
  EXPECT_EQ(h.collision.view().obstacles[0].type, TACTA_SHAPE_PLANE);
  EXPECT_EQ(h.collision.view().obstacles[1].type, TACTA_SHAPE_BOX);
  // Collision ids: tools after every body slot, then the obstacles.
  EXPECT_EQ(w.tool(0).rigid.shape.body_id, 3u);
  EXPECT_EQ(h.collision.view().obstacles[0].body_id, 4u);
}

TEST(WorldEntities, RemovedBodyLeavesTheViewsAndKeepsItsState) {
  LoopHarness h(scene_from_text(kScene, "entities_remove"), 60);
  for (int i = 0; i < 30; ++i) h.tick();
  const std::vector<double> sagged = h.world.body(1).nodes.positions;
  h.world.remove_body(h.world.body_handle(1));
  h.tick();  // the boundary takes it out
  EXPECT_EQ(count<InScene>(h.world), 1u);
  size_t stepped_bodies = 0;
  h.world.bodies_in_scene<NodeState>().each([&](ecs::Entity e, InScene&, NodeState&) {
    EXPECT_EQ(e.index, 0u) << "only the cube is still in the scene";
    ++stepped_bodies;
  });
  EXPECT_EQ(stepped_bodies, 1u);
  for (int i = 0; i < 20; ++i) h.tick();
  EXPECT_EQ(h.world.body(1).nodes.positions, sagged) << "its last state stays, unstepped";
  EXPECT_EQ(h.world.body(1).presence.state, BodyPresence::kRemoved);
  EXPECT_FALSE(h.world.is_live(h.world.body_handle(1)));
}

}  // namespace
}  // namespace tacta::simtest
