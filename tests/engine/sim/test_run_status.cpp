// Run-time status: a model's warning bit is counted per body with its remedy in report.json and
// printed once, without failing the run; an error bit makes the run exit 1 and is reported too.
// The bit table has one entry per (source, bit), each with a remedy.
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

#include "systems/status_bits.hpp"
#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

nlohmann::json body_status(const std::string& dir) {
  std::ifstream in(dir + "/report.json");
  return nlohmann::json::parse(in)["bodies"][0]["status"];
}

RunResult run_cube(const std::string& model, const std::string& out) {
  const SceneDesc scene =
      scene_from_text(kCubePressScene, "status_" + model, {"bodies.cube.model=" + model});
  RunOptions options;
  options.out_dir = out;
  return run_scene(scene, options);
}

TEST(RunStatus, ModelWarningIsCountedWithRemedyAndDoesNotFail) {
  const std::string out = fresh_dir("status_warn");
  const RunResult r = run_cube("{name: test_fault_model, fault_kind: warn, fault_step: 100}", out);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.status.errors, 0u);
  const nlohmann::json status = body_status(out);
  ASSERT_EQ(status.size(), 1u) << status.dump();
  EXPECT_EQ(status[0]["bit"], "solver_not_converged");
  EXPECT_EQ(status[0]["value"].get<uint64_t>(), uint64_t{TACTA_STEP_SOLVER_NOT_CONVERGED});
  EXPECT_EQ(status[0]["severity"], "warning");
  EXPECT_EQ(status[0]["ticks"].get<uint64_t>(), 300u) << "steps 100 to 399 of a 0.4 s run at 1 kHz";
  EXPECT_NEAR(status[0]["first_time_s"].get<double>(), 0.1, 1e-9);
  EXPECT_FALSE(status[0]["remedy"].get<std::string>().empty());
  size_t lines = 0;
  for (const std::string& line : r.status.lines)
    lines += line.find("solver_not_converged") != std::string::npos;
  EXPECT_EQ(lines, 1u) << "one console line per kind, not per tick";
}

TEST(RunStatus, ModelErrorBitExitsOne) {
  const std::string out = fresh_dir("status_error");
  const RunResult r =
      run_cube("{name: test_fault_model, fault_kind: diverged, fault_step: 200}", out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_GE(r.status.errors, 1u);
  const nlohmann::json status = body_status(out);
  ASSERT_EQ(status.size(), 1u) << status.dump();
  EXPECT_EQ(status[0]["bit"], "diverged");
  EXPECT_EQ(status[0]["severity"], "error");
  EXPECT_EQ(status[0]["ticks"].get<uint64_t>(), 1u);
}

TEST(RunStatus, CleanRunReportsNoStatus) {
  const std::string out = fresh_dir("status_clean");
  const RunResult r = run_cube("{name: test_fault_model, fault_kind: none}", out);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(body_status(out).empty());
  EXPECT_EQ(r.status.errors + r.status.warnings, 0u)
      << (r.status.lines.empty() ? "" : r.status.lines[0]);
}

TEST(RunStatus, RunEndsWhenNothingIsLeftToStep) {
  // No device and the only body frozen at step 10: the tick says so and the run ends there.
  const std::string text = R"(
name: lone_cube
clock: {mode: lockstep, haptic_rate_hz: 1000, render_rate_hz: 60, duration_s: 0.4}
bodies:
  - name: cube
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [2, 2, 2]}}
    material: {youngs_modulus: 2.0e4, poisson_ratio: 0.4, density: 1000}
    model: {name: test_fault_model, fault_kind: diverged, fault_step: 10}
    fixed: [{box: {min: [-1, -0.001, -1], max: [1, 0.001, 1]}}]
)";
  const RunResult r = run_scene(scene_from_text(text, "lone_cube"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.schedule.ticks, 11u) << "ticks 0 to 10, the last one faulting";
}

TEST(RunStatus, BitTableHasOneEntryPerBitEachWithARemedy) {
  std::set<std::pair<int, uint32_t>> seen;
  for (const StatusBitInfo& e : status_bit_table()) {
    EXPECT_TRUE(seen.insert({static_cast<int>(e.source), e.bit}).second) << e.name;
    EXPECT_NE(std::string(e.remedy), "") << e.name;
  }
  EXPECT_TRUE(has_error_bit(StatusSource::Model, TACTA_STEP_NOT_FINITE));
  EXPECT_FALSE(has_error_bit(StatusSource::Model, TACTA_STEP_INVERTED_ELEMENT));
}

}  // namespace
}  // namespace tacta::simtest
