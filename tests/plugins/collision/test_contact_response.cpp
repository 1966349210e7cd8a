// Contact response (plugin ccd, respond) with vertex-shape detection (plugin convex, detect):
// a soft block driven into a plane obstacle, a moving tool sphere pressing a block, a thin
// fast tool that would tunnel, Coulomb friction against mu g, and bad input.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <limits>
#include <string>

#include "contact_pipeline.hpp"
#include "soft_block.hpp"

namespace {

// A measured value for the test's XML/JSON record, with its significant digits.
std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

using tacta::testing::ContactPipeline;
using tacta::testing::SoftBlock;

constexpr double kDt = 1e-3;         // s
constexpr double kThickness = 1e-4;  // m
constexpr double kGravity = 9.81;    // m/s^2
constexpr double kTolerance = 1e-9;  // m: allowed penetration of the thickness layer

tacta_collision_world make_world(tacta_collision_surface* surfaces, uint32_t surface_count,
                                 const tacta_collision_shape* tools, uint32_t tool_count,
                                 const tacta_collision_shape* obstacles, uint32_t obstacle_count) {
  tacta_collision_world w{};
  w.struct_size = sizeof w;
  w.surface_count = surface_count;
  w.surfaces = surfaces;
  w.shape_count = tool_count;
  w.shapes = tools;
  w.obstacle_count = obstacle_count;
  w.obstacles = obstacles;
  w.dt = kDt;
  return w;
}

TEST(ContactResponse, BlockDrivenIntoPlaneStaysAboveItAndCarriesItsWeight) {
  SoftBlock block = SoftBlock::make(3, 0.05, {0.0, 0.0, 0.004}, 0.2);
  for (uint32_t v = 0; v < block.vertex_count(); ++v) block.velocities[3 * v + 2] = -1.0;  // m/s
  tacta_collision_surface surface = block.view(0, kThickness);
  const tacta_collision_shape floor = tacta::testing::plane(0, 0, 1, 0.0);
  tacta_collision_world world = make_world(&surface, 1, nullptr, 0, &floor, 1);
  ContactPipeline pipeline(0.3);
  pipeline.prepare(world);
  double support = 0;  // N, sum over the last 100 ticks of the contact forces' z
  for (int tick = 0; tick < 600; ++tick) {
    block.integrate(kDt, {0, 0, -kGravity});
    const auto r = pipeline.tick(world);
    ASSERT_EQ(r.bits & (TACTA_COLLIDE_UNRESOLVED | TACTA_COLLIDE_NOT_FINITE), 0u)
        << "tick " << tick;
    for (uint32_t v = 0; v < block.vertex_count(); ++v)
      ASSERT_GE(block.end[3 * v + 2], kThickness - kTolerance)
          << "vertex " << v << " tick " << tick;
    if (tick >= 500)
      for (uint32_t c = 0; c < pipeline.contact_count(); ++c)
        support += pipeline.contacts()[c].force[2];
  }
  // At rest the plane carries the weight: mean contact force = m g (within 5 %).
  RecordProperty("mean_support_N", number(support / 100.0));
  EXPECT_NEAR(support / 100.0, 0.2 * kGravity, 0.05 * 0.2 * kGravity);
}

TEST(ContactResponse, MovingToolSpherePressesBlockWithoutEnteringIt) {
  SoftBlock block = SoftBlock::make(4, 0.05, {-0.025, -0.025, 0.0}, 0.5);
  block.damping = 0.1;
  for (int j = 0; j <= 4; ++j)  // bottom layer fixed
    for (int i = 0; i <= 4; ++i) block.inverse_masses[block.index(i, j, 0)] = 0.0;
  const std::vector<double> rest = block.start;
  tacta_collision_surface surface = block.view(0, kThickness);
  const double radius = 0.02, speed = 0.1;  // m, m/s downwards
  tacta_collision_shape tool =
      tacta::testing::sphere_tool(radius, 0.003, -0.002, 0.05 + radius + 0.002);
  tacta_collision_world world = make_world(&surface, 1, &tool, 1, nullptr, 0);
  ContactPipeline pipeline(0.3);
  pipeline.prepare(world);
  double push_z = 0;  // N, force of the block on the tool at the last tick
  for (int tick = 0; tick < 200; ++tick) {
    tool.pose_start = tool.pose_end;
    tool.pose_end.position[2] -= speed * kDt;
    block.integrate(kDt, {0, 0, 0});
    const auto r = pipeline.tick(world);
    ASSERT_EQ(r.bits & TACTA_COLLIDE_UNRESOLVED, 0u) << "tick " << tick;
    push_z = 0;
    for (uint32_t c = 0; c < pipeline.contact_count(); ++c)
      push_z -= pipeline.contacts()[c].force[2];
    for (uint32_t v = 0; v < block.vertex_count(); ++v) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a)
        d2 += std::pow(block.end[3 * v + a] - tool.pose_end.position[a], 2);
      ASSERT_GE(std::sqrt(d2), radius + kThickness - kTolerance)
          << "vertex " << v << " tick " << tick;
      if (block.inverse_masses[v] == 0.0) {
        for (int a = 0; a < 3; ++a) ASSERT_EQ(block.end[3 * v + a], rest[3 * v + a]);
      }
    }
  }
  // The tool went 18 mm into the block's rest shape: the block pushes it back up.
  RecordProperty("tool_push_N", number(push_z));
  EXPECT_GT(push_z, 0.1);
  EXPECT_LT(block.end[3 * block.index(2, 2, 4) + 2], 0.05 - 0.01);  // top centre pushed down
}

TEST(ContactResponse, FastThinToolCannotTunnelThroughAVertex) {
  // A 2 mm sphere moves 12 mm in one tick straight through a still vertex: the swept test
  // catches it and the vertex ends below the sphere, on the side the sphere came from.
  std::vector<double> start{0, 0, 0}, end{0, 0, 0}, velocity{0, 0, 0}, inverse_mass{10.0};
  tacta_collision_surface surface{};
  surface.vertex_count = 1;
  surface.positions_start = start.data();
  surface.positions_end = end.data();
  surface.velocities = velocity.data();
  surface.inverse_masses = inverse_mass.data();
  surface.thickness = kThickness;
  tacta_collision_shape tool = tacta::testing::sphere_tool(0.002, 0, 0, 0.006);
  tool.pose_end.position[2] = -0.006;
  tacta_collision_world world = make_world(&surface, 1, &tool, 1, nullptr, 0);
  tacta::testing::CollisionPlugin convex("tacta_convex.so", "convex");
  tacta::testing::CollisionPlugin ccd("tacta_ccd.so", "ccd");
  tacta_contact contacts[4];
  uint32_t count = 0;
  EXPECT_EQ(convex.api().detect(convex.instance(), &world, nullptr, 0, contacts, 4, &count), 0u);
  ASSERT_EQ(count, 1u);
  EXPECT_EQ(contacts[0].type, TACTA_CONTACT_SHAPE_VERTEX);
  // In the sphere's frame the vertex rises into its lower side: normal -z, not the exit side.
  EXPECT_NEAR(contacts[0].normal[2], -1.0, 1e-12);
  EXPECT_EQ(ccd.api().respond(ccd.instance(), &world, contacts, count), 0u);
  EXPECT_NEAR(end[2], -0.006 - 0.002 - kThickness, 1e-9);
  EXPECT_NEAR(velocity[2], -12.0, 1e-9);  // carried along: normal velocity = the tool's, m/s
}

// Coulomb: a block sliding on the plane decelerates at mu g (measured on its centre of mass).
double sliding_deceleration(double mu) {
  SoftBlock block = SoftBlock::make(2, 0.04, {0.0, 0.0, kThickness}, 0.1);
  block.stiffness = 300;
  block.damping = 0.1;
  for (uint32_t v = 0; v < block.vertex_count(); ++v) block.velocities[3 * v] = 1.0;  // m/s
  tacta_collision_surface surface = block.view(0, kThickness);
  const tacta_collision_shape floor = tacta::testing::plane(0, 0, 1, 0.0);
  tacta_collision_world world = make_world(&surface, 1, nullptr, 0, &floor, 1);
  ContactPipeline pipeline(mu);
  pipeline.prepare(world);
  // Least-squares slope of the mean x velocity over 50..200 ms (after the block settles).
  double st = 0, sv = 0, stt = 0, stv = 0;
  int n = 0;
  for (int tick = 1; tick <= 200; ++tick) {
    block.integrate(kDt, {0, 0, -kGravity});
    pipeline.tick(world);
    if (tick < 50) continue;
    const double v = block.momentum()[0] / 0.1, t = tick * kDt;
    st += t, sv += v, stt += t * t, stv += t * v, ++n;
  }
  return -(n * stv - st * sv) / (n * stt - st * st);
}

TEST(ContactResponse, FrictionDeceleratesSlidingBlockAtMuG) {
  const double mu = 0.4;
  const double with_friction = sliding_deceleration(mu), without = sliding_deceleration(0.0);
  RecordProperty("deceleration_mu_0_4", number(with_friction));
  RecordProperty("deceleration_mu_0", number(without));
  EXPECT_NEAR(with_friction, mu * kGravity, 0.05 * mu * kGravity);
  EXPECT_NEAR(without, 0.0, 0.05 * mu * kGravity);
}

TEST(ContactResponse, ParallelEdgesGetTheApproachNormal) {
  // Two equal horizontal triangles, one falling through the other (shifted 0.2 m along x, so
  // their edges are pairwise parallel). Every edge-edge contact, parallel pairs included, must
  // separate along +z (from the lower triangle towards the falling one).
  std::vector<double> a_start{0, 0, 1, 1, 0, 1, 0.5, 1, 1}, a_end{0, 0, -1, 1, 0, -1, 0.5, 1, -1};
  std::vector<double> b_start{0.2, 0, 0, 1.2, 0, 0, 0.7, 1, 0};
  std::vector<double> b_end = b_start;
  const std::vector<uint32_t> triangle{0, 1, 2};
  tacta_collision_surface surfaces[2]{};
  for (int i = 0; i < 2; ++i) {
    surfaces[i].body_id = static_cast<uint32_t>(i);
    surfaces[i].vertex_count = 3;
    surfaces[i].positions_start = i == 0 ? a_start.data() : b_start.data();
    surfaces[i].positions_end = i == 0 ? a_end.data() : b_end.data();
    surfaces[i].triangle_count = 1;
    surfaces[i].triangles = triangle.data();
    surfaces[i].thickness = kThickness;
  }
  tacta_collision_world world = make_world(surfaces, 2, nullptr, 0, nullptr, 0);
  tacta::testing::CollisionPlugin ccd("tacta_ccd.so", "ccd");
  tacta_contact contacts[64];
  uint32_t count = 0;
  EXPECT_EQ(ccd.api().detect(ccd.instance(), &world, nullptr, 0, contacts, 64, &count), 0u);
  int edge_edge = 0;
  for (uint32_t c = 0; c < count; ++c) {
    if (contacts[c].type != TACTA_CONTACT_EDGE_EDGE) continue;
    ++edge_edge;
    EXPECT_NEAR(contacts[c].normal[2], 1.0, 1e-5) << "contact " << c;
  }
  EXPECT_GE(edge_edge, 3);
  // After the response (rounds as the engine runs them) the corrected motion crosses nothing.
  for (int round = 0; round < 3 && count > 0; ++round) {
    EXPECT_EQ(ccd.api().respond(ccd.instance(), &world, contacts, count) & TACTA_COLLIDE_UNRESOLVED,
              0u);
    EXPECT_EQ(ccd.api().detect(ccd.instance(), &world, nullptr, 0, contacts, 64, &count), 0u);
  }
  EXPECT_EQ(count, 0u);
}

TEST(ContactResponse, BadInputIsReportedNotFatal) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Vertex 0: fixed, below the floor. Vertex 1: NaN. Vertex 2: free, squeezed between the floor
  // and a ceiling 1.5e-4 m above it, narrower than the two thickness layers (2e-4 m).
  std::vector<double> start{0, 0, 0, 1, 0, 0, 2, 0, 7.5e-5},
      end{0, 0, -0.01, nan, 0, 0, 2, 0, 7.5e-5};
  std::vector<double> velocity(9, 0.0), inverse_mass{0.0, 1.0, 1.0};
  tacta_collision_surface surface{};
  surface.vertex_count = 3;
  surface.positions_start = start.data();
  surface.positions_end = end.data();
  surface.velocities = velocity.data();
  surface.inverse_masses = inverse_mass.data();
  surface.thickness = kThickness;
  const tacta_collision_shape walls[2] = {tacta::testing::plane(0, 0, 1, 0.0),
                                          tacta::testing::plane(0, 0, -1, -1.5e-4)};
  tacta_collision_world world = make_world(&surface, 1, nullptr, 0, walls, 2);
  tacta::testing::CollisionPlugin convex("tacta_convex.so", "convex");
  tacta::testing::CollisionPlugin ccd("tacta_ccd.so", "ccd");
  tacta_contact contacts[8];
  uint32_t count = 0;
  // NaN vertex skipped and flagged; the fixed vertex skipped (nothing can move); vertex 2
  // touches both walls.
  EXPECT_EQ(convex.api().detect(convex.instance(), &world, nullptr, 0, contacts, 8, &count),
            TACTA_COLLIDE_NOT_FINITE);
  ASSERT_EQ(count, 2u);
  EXPECT_EQ(contacts[0].nodes_a[0], 2u);
  EXPECT_NE(convex.api().detect(convex.instance(), &world, nullptr, 0, contacts + 2, 1, &count) &
                TACTA_COLLIDE_OVERFLOW,
            0u);
  EXPECT_EQ(count, 1u);
  // Conflicting walls: reported unresolved, the result stays finite and between the walls.
  EXPECT_NE(ccd.api().respond(ccd.instance(), &world, contacts, 2) & TACTA_COLLIDE_UNRESOLVED, 0u);
  EXPECT_GT(end[8], 0.0);
  EXPECT_LT(end[8], 1.5e-4);
  // A contact naming the fixed vertex: nothing to move, not an error, vertex left in place.
  tacta_contact fixed = contacts[0];
  fixed.nodes_a[0] = 0;
  EXPECT_EQ(ccd.api().respond(ccd.instance(), &world, &fixed, 1), 0u);
  EXPECT_EQ(end[2], -0.01);
  // Malformed contacts: out-of-range indices, unknown type, NaN or zero normal, NaN position.
  tacta_contact bad[5];
  for (auto& c : bad) c = contacts[0];
  bad[0].index_a = 7;
  bad[1].type = 99;
  bad[2].normal[0] = nan;
  bad[3].normal[0] = bad[3].normal[1] = bad[3].normal[2] = 0;
  bad[4].nodes_a[0] = 1;  // the NaN vertex
  const double squeezed = end[8];
  const uint32_t bits = ccd.api().respond(ccd.instance(), &world, bad, 5);
  EXPECT_EQ(end[8], squeezed);
  EXPECT_NE(bits & TACTA_COLLIDE_DEGENERATE, 0u);
  EXPECT_NE(bits & TACTA_COLLIDE_NOT_FINITE, 0u);
  EXPECT_EQ(end[2], -0.01);
  EXPECT_TRUE(std::isnan(end[3]));
  EXPECT_EQ(ccd.api().respond(ccd.instance(), &world, nullptr, 0), 0u);
  // Empty world, NaN tool pose.
  tacta_collision_shape tool = tacta::testing::sphere_tool(0.01, nan, 0, 0);
  tacta_collision_world empty = make_world(nullptr, 0, &tool, 1, nullptr, 0);
  EXPECT_EQ(convex.api().detect(convex.instance(), &empty, nullptr, 0, contacts, 8, &count),
            TACTA_COLLIDE_NOT_FINITE);
  EXPECT_EQ(count, 0u);
}

}  // namespace
