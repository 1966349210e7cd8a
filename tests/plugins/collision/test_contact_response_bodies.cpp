// Contact response between deformable bodies (exact CCD contacts, plugin ccd): a soft block
// dropped on another never has a vertex inside it, and the response conserves momentum and
// never adds kinetic energy.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <random>
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

tacta_collision_world two_block_world(tacta_collision_surface* surfaces,
                                      const tacta_collision_shape* obstacles,
                                      uint32_t obstacle_count) {
  tacta_collision_world w{};
  w.struct_size = sizeof w;
  w.surface_count = 2;
  w.surfaces = surfaces;
  w.obstacle_count = obstacle_count;
  w.obstacles = obstacles;
  w.dt = kDt;
  return w;
}

// Vertices of `a` inside the closed surface of `b` (winding number above one half).
int vertices_inside(const SoftBlock& a, const SoftBlock& b) {
  int inside = 0;
  for (uint32_t v = 0; v < a.vertex_count(); ++v)
    if (b.winding(&a.end[3 * v]) > 0.5) ++inside;
  return inside;
}

TEST(ContactResponseBodies, BlockDroppedOnBlockNeverEntersIt) {
  const double size = 0.04;  // m
  SoftBlock lower = SoftBlock::make(2, size, {0.0, 0.0, kThickness}, 0.1);
  SoftBlock upper = SoftBlock::make(2, size, {0.007, 0.005, size + 0.004}, 0.1);
  lower.damping = upper.damping = 0.1;  // N s/m: settle within the run
  for (uint32_t v = 0; v < upper.vertex_count(); ++v) upper.velocities[3 * v + 2] = -0.5;  // m/s
  tacta_collision_surface surfaces[2] = {lower.view(0, kThickness), upper.view(1, kThickness)};
  const tacta_collision_shape floor = tacta::testing::plane(0, 0, 1, 0.0);
  tacta_collision_world world = two_block_world(surfaces, &floor, 1);
  ContactPipeline pipeline(0.3);
  pipeline.prepare(world);
  uint32_t surface_contacts = 0;
  for (int tick = 0; tick < 150; ++tick) {
    lower.integrate(kDt, {0, 0, -9.81});
    upper.integrate(kDt, {0, 0, -9.81});
    const auto r = pipeline.tick(world);
    surface_contacts += r.surface_contacts;
    ASSERT_EQ(r.bits & (TACTA_COLLIDE_UNRESOLVED | TACTA_COLLIDE_OVERFLOW), 0u) << "tick " << tick;
    ASSERT_EQ(vertices_inside(upper, lower), 0) << "tick " << tick;
    ASSERT_EQ(vertices_inside(lower, upper), 0) << "tick " << tick;
  }
  EXPECT_GT(surface_contacts, 0u);
  // The upper block stayed on top: the centres are about one side apart (both blocks sag and
  // still oscillate after the impact), far from the lower centre it would pass if it fell in.
  double lower_centre = 0, upper_centre = 0;
  for (uint32_t v = 0; v < lower.vertex_count(); ++v)
    lower_centre += lower.end[3 * v + 2] / lower.vertex_count();
  for (uint32_t v = 0; v < upper.vertex_count(); ++v)
    upper_centre += upper.end[3 * v + 2] / upper.vertex_count();
  RecordProperty("centre_distance_m", number(upper_centre - lower_centre));
  EXPECT_GT(upper_centre - lower_centre, 0.75 * size);
  EXPECT_LT(upper_centre - lower_centre, 1.1 * size);
}

TEST(ContactResponseBodies, DeformableResponseConservesMomentum) {
  // Two free blocks with uneven vertex masses collide head on with a sideways slip (friction
  // acts), no gravity, no obstacle: every tick's response leaves sum m v and sum m x unchanged.
  const double size = 0.03;
  SoftBlock left = SoftBlock::make(2, size, {-size - 0.0015, 0.0, 0.0}, 0.1);
  SoftBlock right = SoftBlock::make(2, size, {0.0015, 0.004, 0.006}, 0.1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> mass(0.002, 0.006);  // kg
  for (SoftBlock* b : {&left, &right})
    for (uint32_t v = 0; v < b->vertex_count(); ++v) {
      b->masses[v] = mass(rng);
      b->inverse_masses[v] = 1.0 / b->masses[v];
    }
  for (uint32_t v = 0; v < left.vertex_count(); ++v) {
    left.velocities[3 * v] = 1.0;
    left.velocities[3 * v + 1] = 0.3;
    right.velocities[3 * v] = -1.0;
  }
  tacta_collision_surface surfaces[2] = {left.view(0, kThickness), right.view(1, kThickness)};
  tacta_collision_world world = two_block_world(surfaces, nullptr, 0);
  ContactPipeline pipeline(0.5);
  pipeline.prepare(world);
  int ticks_with_contacts = 0;
  double worst_p = 0, worst_x = 0;  // largest relative change of sum m v and sum m x
  for (int tick = 0; tick < 40; ++tick) {
    left.integrate(kDt, {0, 0, 0});
    right.integrate(kDt, {0, 0, 0});
    const auto p0 = left.momentum(), q0 = right.momentum();
    const auto x0 = left.first_moment(), y0 = right.first_moment();
    const double energy_before = left.kinetic_energy() + right.kinetic_energy();
    const auto r = pipeline.tick(world);
    if (r.surface_contacts > 0) ++ticks_with_contacts;
    // Inelastic impulses and friction only take kinetic energy away.
    ASSERT_LE(left.kinetic_energy() + right.kinetic_energy(), energy_before * (1 + 1e-12))
        << "tick " << tick;
    ASSERT_EQ(r.bits & TACTA_COLLIDE_UNRESOLVED, 0u);
    const auto p1 = left.momentum(), q1 = right.momentum();
    const auto x1 = left.first_moment(), y1 = right.first_moment();
    double scale_p = 0, scale_x = 0;  // kg m/s, kg m: sum of |m v| and |m x| of both blocks
    for (const SoftBlock* b : {&left, &right})
      for (uint32_t v = 0; v < b->vertex_count(); ++v)
        for (int a = 0; a < 3; ++a) {
          scale_p += b->masses[v] * std::fabs(b->velocities[3 * v + a]);
          scale_x += b->masses[v] * std::fabs(b->end[3 * v + a]);
        }
    for (size_t a = 0; a < 3; ++a) {
      worst_p = std::max(worst_p, std::fabs(p1[a] + q1[a] - p0[a] - q0[a]) / scale_p);
      worst_x = std::max(worst_x, std::fabs(x1[a] + y1[a] - x0[a] - y0[a]) / scale_x);
      ASSERT_NEAR(p1[a] + q1[a], p0[a] + q0[a], 1e-9 * scale_p) << "tick " << tick << " axis " << a;
      ASSERT_NEAR(x1[a] + y1[a], x0[a] + y0[a], 1e-9 * scale_x) << "tick " << tick << " axis " << a;
    }
    ASSERT_EQ(vertices_inside(left, right), 0) << "tick " << tick;
    ASSERT_EQ(vertices_inside(right, left), 0) << "tick " << tick;
  }
  RecordProperty("momentum_relative_change", number(worst_p));
  RecordProperty("first_moment_relative_change", number(worst_x));
  RecordProperty("ticks_with_contacts", ticks_with_contacts);
  EXPECT_GT(ticks_with_contacts, 0);
  // The exchange happened: the left block no longer moves right at 1 m/s.
  double left_mass = 0;
  for (double m : left.masses) left_mass += m;
  EXPECT_LT(left.momentum()[0] / left_mass, 0.9);
}

}  // namespace
