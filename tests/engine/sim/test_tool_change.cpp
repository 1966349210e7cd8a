// A device's tool changed while the scene runs, from the scene's `events` and through the
// stepping API: the change lands at a tick boundary, the proxy takes the new radius (on a rigid
// block it rests one radius above the top face), the report counts the change, and bad requests
// are InputErrors naming the key. (The collision view's shape and the tick's allocations:
// test_haptic_tick_no_allocation.cpp.)
#include <cmath>

#include "sim_test_support.hpp"
#include "tacta/scene_loader.hpp"

namespace tacta::simtest {
namespace {

// A rigid block (every node fixed: a device still touches it) with its top face at y = 0.1 m,
// and a mouse-driven stylus whose hand pulls it 10 mm into the block.
const char* const kPressedBlock = R"(
name: tool_change
gravity: [0, 0, 0]
clock: {mode: lockstep, haptic_rate_hz: 1000, render_rate_hz: 60, duration_s: 1.0}
bodies:
  - name: block
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [2, 2, 2], origin: [-0.05, 0, -0.05]}}
    material: {youngs_modulus: 2.0e4, poisson_ratio: 0.3, density: 1000}
    model: corotational_fem
    fixed: [{box: {min: [-1, -1, -1], max: [1, 1, 1]}}]
devices:
  - name: stylus
    plugin: mouse
    params: {start_position: [0.005, 0.09, 0.005]}
    tool: {sphere: {radius: 0.002}}
    coupling: {stiffness: 400, damping: 1.0}
    touches: block
collision: {broad_phase: bvh}
)";

constexpr double kTop_m = 0.1;

double proxy_height(const Simulation& s) {
  return s.device_reading(s.devices()[0]).proxy[1] - kTop_m;
}

TEST(ToolChange, SceneEventChangesTheProxyRadiusAtItsTime) {
  const std::string events = std::string(kPressedBlock) +
                             "events: [{time: 0.4, change_tool: {device: stylus, tool: {sphere: "
                             "{radius: 0.006}}}}]\n";
  Simulation simulation(scene_from_text(events, "tool_change_event"), plugins());
  simulation.step(399);
  ASSERT_TRUE(simulation.device_reading(simulation.devices()[0]).in_contact);
  EXPECT_NEAR(proxy_height(simulation), 0.002, 1e-4) << "the first tool's radius above the top";
  simulation.step(401);
  ASSERT_TRUE(simulation.device_reading(simulation.devices()[0]).in_contact);
  EXPECT_NEAR(proxy_height(simulation), 0.006, 1e-4) << "the new tool's radius above the top";
  const RunResult r = simulation.report();
  ASSERT_EQ(r.devices.size(), 1u);
  EXPECT_EQ(r.devices[0].tool_changes, 1u);
}

TEST(ToolChange, SteppingApiChangesTheToolAtTheNextTick) {
  Simulation simulation(scene_from_text(kPressedBlock, "tool_change_api"), plugins());
  simulation.step(300);
  EXPECT_NEAR(proxy_height(simulation), 0.002, 1e-4);
  simulation.change_tool(simulation.devices()[0],
                         std::string("{capsule: {radius: 0.004, half_length: 0.01}}"));
  // One change waits at a time per device; the next tick takes it.
  try {
    simulation.change_tool(simulation.devices()[0], std::string("{sphere: {radius: 0.001}}"));
    ADD_FAILURE() << "a second change before the tick must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("still waiting"), std::string::npos) << e.what();
  }
  simulation.step(300);
  EXPECT_NEAR(proxy_height(simulation), 0.004, 1e-4);
  simulation.change_tool(simulation.devices()[0],
                         std::string("{sphere: {radius: 0.003}}"));  // taken: free again
  simulation.step(300);
  EXPECT_NEAR(proxy_height(simulation), 0.003, 1e-4);
  EXPECT_EQ(simulation.report().devices[0].tool_changes, 2u);
}

// Realtime: the haptic thread runs on the wall clock while this thread changes the tool twice;
// both are taken at tick boundaries (ThreadSanitizer: clean, ctest -L tsan).
TEST(ToolChange, ChangedDuringARealtimeRun) {
  Simulation simulation(scene_from_text(kPressedBlock, "tool_change_realtime"), plugins());
  RealtimeRun run(simulation, 0.4);
  run.wait_until(0.1);
  simulation.change_tool(simulation.devices()[0], std::string("{sphere: {radius: 0.004}}"));
  run.wait_until(0.25);  // 150 ticks later: the first change was taken long ago
  simulation.change_tool(simulation.devices()[0],
                         std::string("{capsule: {radius: 0.003, half_length: 0.01}}"));
  const RunResult& result = run.join();
  EXPECT_EQ(result.schedule.ticks, 400u);
  ASSERT_EQ(result.devices.size(), 1u);
  EXPECT_EQ(result.devices[0].tool_changes, 2u);
  EXPECT_NEAR(proxy_height(simulation), 0.003, 2e-4);
}

TEST(ToolChange, BadRequestsAreInputErrors) {
  Simulation simulation(scene_from_text(kPressedBlock, "tool_change_bad"), plugins());
  const DeviceHandle past{1, simulation.devices()[0].generation};
  EXPECT_THROW(simulation.change_tool(past, std::string("{sphere: {radius: 0.003}}")), InputError);
  EXPECT_THROW(
      simulation.change_tool(simulation.devices()[0], std::string("{sphere: {radius: -1}}")),
      InputError);
  EXPECT_THROW(simulation.change_tool(simulation.devices()[0], std::string("{cube: {}}")),
               InputError);
  const std::string unknown = std::string(kPressedBlock) +
                              "events: [{time: 0.1, change_tool: {device: pen, tool: {sphere: "
                              "{radius: 0.003}}}}]\n";
  try {
    scene_from_text(unknown, "tool_change_unknown");
    ADD_FAILURE() << "an event naming no device must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no device named 'pen'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("change_tool"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tacta::simtest
