// Every status bit a plugin returns reaches the tick's status: Simulation::step() returns it with
// the ticks that ran, and report.json counts it. One test per plugin kind: a model's step
// (TACTA_STEP_DIVERGED), a collision plugin's hierarchy update (TACTA_COLLIDE_NOT_FINITE) and a
// device's read (TACTA_DEVICE_FAULT), each from a test plugin that returns it on purpose.
#include <nlohmann/json.hpp>

#include "systems/status_bits.hpp"
#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

nlohmann::json report_of(Simulation& simulation, const std::string& name) {
  const std::string out = fresh_dir(name);
  simulation.write_outputs(out);
  std::ifstream in(out + "/report.json");
  return nlohmann::json::parse(in);
}

bool lists_bit(const nlohmann::json& status, const std::string& bit) {
  for (const nlohmann::json& entry : status)
    if (entry["bit"] == bit && entry["ticks"].get<uint64_t>() > 0) return true;
  return false;
}

const char* const kCube = R"(
name: status_cube
clock: {mode: lockstep, haptic_rate_hz: 1000, render_rate_hz: 60, duration_s: 1}
bodies:
  - name: cube
    mesh: {box_grid: {size: [0.04, 0.04, 0.04], cells: [2, 2, 2], origin: [-0.02, -0.02, -0.02]}}
    material: {youngs_modulus: 2.0e4, poisson_ratio: 0.4, density: 1000}
)";

TEST(StepStatus, AModelsErrorBitIsInStepsResultAndTheReport) {
  Simulation simulation(
      scene_from_text(
          std::string(kCube) +
              "    model: {name: test_fault_model, fault_kind: diverged, fault_step: 300}\n",
          "status_model"),
      plugins());
  const StepResult clean = simulation.step(2);
  EXPECT_EQ(clean.ticks, 2u);
  EXPECT_FALSE(clean.status.error);
  // The only body freezes at its faulting step and nothing is left to step: the run ends there.
  const StepResult faulted = simulation.step(1000);
  EXPECT_LT(faulted.ticks, 1000u);
  EXPECT_TRUE(faulted.status.error);
  EXPECT_NE(faulted.status.model_bits & TACTA_STEP_DIVERGED, 0u);
  const nlohmann::json report = report_of(simulation, "status_model");
  EXPECT_TRUE(lists_bit(report["bodies"][0]["status"], "diverged")) << report["bodies"][0].dump();
}

TEST(StepStatus, ACollisionPluginsUpdateBitsAreInStepsResultAndTheReport) {
  // Before, the hierarchy update's answer was dropped: a broad phase that could not use its input
  // went unreported.
  Simulation simulation(
      scene_from_text(std::string(kCube) +
                          "    model: tensor_mass\n"
                          "collision: {enabled: true, broad_phase: test_faulty_broad_phase, "
                          "narrow_phase: ccd, convex: convex}\n",
                      "status_collision"),
      plugins());
  const StepResult r = simulation.step(10);
  EXPECT_EQ(r.ticks, 10u);
  EXPECT_NE(r.status.collision_bits & TACTA_COLLIDE_NOT_FINITE, 0u);
  EXPECT_TRUE(r.status.error) << "not_finite is an error bit of the collision pipeline";
  const nlohmann::json report = report_of(simulation, "status_collision");
  EXPECT_TRUE(lists_bit(report["collision"]["status"], "not_finite")) << report["collision"].dump();
}

TEST(StepStatus, ADevicesFaultIsInStepsResultAndTheReport) {
  Simulation simulation(
      scene_from_text(
          std::string(kCube) +
              "    model: tensor_mass\n"
              "devices:\n"
              "  - {name: still, plugin: test_faulty_device, params: {fault_time: 0.01},"
              " tool: {sphere: {radius: 0.004}}}\n",
          "status_device"),
      plugins());
  const StepResult before = simulation.step(5);
  EXPECT_EQ(before.status.device_bits, 0u);
  const StepResult r = simulation.step(20);
  EXPECT_NE(r.status.device_bits & kDeviceFault, 0u);
  EXPECT_TRUE(r.status.error);
  const nlohmann::json report = report_of(simulation, "status_device");
  EXPECT_TRUE(lists_bit(report["devices"][0]["status"], "fault")) << report["devices"][0].dump();
}

}  // namespace
}  // namespace tacta::simtest
