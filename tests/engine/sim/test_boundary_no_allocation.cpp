// The 1 kHz path allocates nothing with boundary motion on: malloc and friends are interposed in
// this executable and counted over ticks of a body with a driven face, a sliding face, a plate
// and probes, stepped on the haptic thread. (glibc only; skipped under the sanitizers, which own
// malloc.)
#include "allocation_counter.hpp"
#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

const char* const kDrivenBlock = R"(
name: driven_block
gravity: [0, -9.81, 0]
clock: {duration_s: 0.2}
output: {trace: false}
bodies:
  - name: block
    mesh: {box_grid: {size: [0.03, 0.03, 0.03], cells: [3, 3, 3]}}
    material: {youngs_modulus: 2.0e4, poisson_ratio: 0.3, density: 1000, rayleigh_mass: 5, rayleigh_stiffness: 0.01}
    model: corotational_fem
    prescribed:
      - {region: {box: {min: [-1, -1, -1], max: [1, 0.001, 1]}}, axes: [y], displacement: [0, 0, 0]}
      - {region: {box: {min: [-1, -1, -1], max: [0.001, 1, 1]}}, displacement: {table: [[0, 0, 0, 0], [0.1, 0, 0.001, 0]]}}
    plates:
      - {name: press, region: {box: {min: [-1, 0.029, -1], max: [1, 1, 1]}}, point: [0, 0.0305, 0], normal: [0, -1, 0],
         motion: {ramp: {to: [0, -0.002, 0], duration_s: 0.1}}, contact: stuck}
    probes:
      - {name: centre, position: [0.015, 0.015, 0.015]}
)";

TEST(BoundaryMotionAllocations, TicksAllocateNothing) {
#if !TACTA_COUNT_ALLOCATIONS
  GTEST_SKIP() << "allocation counting is off under the sanitizers";
#else
  LoopHarness h(scene_from_text(kDrivenBlock, "driven_block"), 200);
  for (int i = 0; i < 5; ++i) h.tick();  // warm-up: first steps may size solver buffers
  g_allocations = 0;
  g_counting = true;
  for (int i = 0; i < 150; ++i) h.tick();
  g_counting = false;
  EXPECT_EQ(g_allocations, 0);
  EXPECT_FALSE(h.world.body(0).fault.frozen);
  EXPECT_GT(h.world.body(0).constraints.boundary->managed_count(), 0u);
#endif
}

}  // namespace
}  // namespace tacta::simtest
