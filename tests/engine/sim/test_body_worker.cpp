// Bodies stepping on their own thread (step_thread: own): the same steps as on the haptic thread
// when nothing touches them, deterministic lockstep runs with a worker, faults caught on the
// haptic side with zero force in the tick they are collected, a realtime run that never waits
// for the worker, and the local contact model (local_contact: yielding) smoothing the force
// between refreshes compared with rendering the last refreshed state as it is.
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

// The cube press with a model that is stable at a 10 ms step.
std::vector<std::string> slow_cube(const std::string& thread, const std::string& extra_model = "") {
  return {"bodies.cube.model={name: corotational_fem" + extra_model + "}",
          "bodies.cube.step_rate_hz=100", "bodies.cube.step_thread=" + thread};
}

const char* const kSaggingBeam = R"(
name: sagging_beam
gravity: [0, -9.81, 0]
clock: {mode: lockstep, haptic_rate_hz: 1000, render_rate_hz: 60, duration_s: 0.35}
bodies:
  - name: beam
    mesh: {beam_grid: {size: [0.02, 0.02, 0.12], cells: [2, 2, 8]}}
    material: {youngs_modulus: 1.0e5, poisson_ratio: 0.4, density: 1000, rayleigh_mass: 1.0}
    model: corotational_fem
    step_rate_hz: 100
    fixed: [{box: {min: [-1, -1, -1], max: [1, 1, 0.001]}}]
)";

RunOptions writing_to(const std::string& dir) {
  RunOptions options;
  options.out_dir = dir;
  return options;
}

TEST(BodyWorker, WithoutContactTheWorkerTakesExactlyTheHapticThreadsSteps) {
  const RunResult haptic = run_scene(scene_from_text(kSaggingBeam, "worker_beam_haptic"));
  const RunResult own =
      run_scene(scene_from_text(kSaggingBeam, "worker_beam_own", {"bodies.beam.step_thread=own"}));
  ASSERT_EQ(own.bodies.size(), 1u);
  EXPECT_TRUE(own.bodies[0].own_thread);
  EXPECT_FALSE(haptic.bodies[0].own_thread);
  EXPECT_EQ(own.bodies[0].worker_steps, 35u) << "0.35 s at 100 Hz";
  EXPECT_GT(own.bodies[0].max_displacement_m, 1e-4)
      << "the beam must sag for the comparison to mean anything";
  // Same model, same dt, same (gravity-only) forces, steps at the same boundaries: bit for bit.
  EXPECT_EQ(own.state_hash, haptic.state_hash);
  EXPECT_EQ(own.bodies[0].max_displacement_m, haptic.bodies[0].max_displacement_m);
}

TEST(BodyWorker, LockstepRunsWithAWorkerAreDeterministic) {
  const SceneDesc scene = scene_from_text(kCubePressScene, "worker_press", slow_cube("own"));
  const std::string out = fresh_dir("worker_press");
  RunOptions options;
  options.out_dir = out;
  const RunResult a = run_scene(scene, options);
  const RunResult b = run_scene(scene);
  EXPECT_EQ(a.exit_code, 0);
  EXPECT_EQ(a.state_hash, b.state_hash);
  EXPECT_EQ(a.bodies[0].worker_steps, 40u);
  EXPECT_GT(a.bodies[0].max_displacement_m, 1e-4) << "the stylus must dent the cube";

  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& body = report["bodies"][0];
  EXPECT_EQ(body["step_thread"], "own");
  EXPECT_DOUBLE_EQ(body["step_rate_hz"].get<double>(), 100.0);
  EXPECT_EQ(body["worker"]["steps"].get<uint64_t>(), 40u);
  EXPECT_GT(body["worker"]["step_ms"]["p50"].get<double>(), 0.0);
  EXPECT_EQ(body["worker"]["late_boundaries"].get<uint64_t>(), 0u)
      << "lockstep waits, it is never late";
  const nlohmann::json& device = report["devices"][0];
  EXPECT_GT(device["max_force_N"].get<double>(), 0.2);
  EXPECT_LE(device["max_force_N"].get<double>(), device["force_limit_N"].get<double>());
}

// The force the worker's body felt is the mean of what the device got over each period, so over
// the run the body took the same impulse the tool gave (Newton's third law over time). Checked
// through the static end state: held still, the cube's dent carries the device's steady force.
TEST(BodyWorker, HeldForceMatchesTheBodySteppingEveryTick) {
  const std::string dir_own = fresh_dir("worker_steady_own"),
                    dir_fast = fresh_dir("worker_steady_fast");
  const RunResult own = run_scene(
      scene_from_text(kCubePressScene, "worker_steady_own", slow_cube("own")), writing_to(dir_own));
  const RunResult fast = run_scene(scene_from_text(kCubePressScene, "worker_steady_fast",
                                                   {"bodies.cube.model={name: corotational_fem}"}),
                                   writing_to(dir_fast));
  const Csv a = read_csv(dir_own + "/trace.csv");
  const Csv b = read_csv(dir_fast + "/trace.csv");
  ASSERT_EQ(a.rows.size(), b.rows.size());
  const size_t last = a.rows.size() - 1;
  const double fa = a.number(last, "force_N"), fb = b.number(last, "force_N");
  EXPECT_GT(fb, 0.3);
  EXPECT_NEAR(fa, fb, 0.05 * fb)
      << "held force, body on its own thread at 100 Hz vs stepped every tick";
  EXPECT_EQ(own.exit_code, 0);
  EXPECT_EQ(fast.exit_code, 0);
}

double p99_force_jump(const std::string& dir) {
  const Csv trace = read_csv(dir + "/trace.csv");
  std::vector<double> jumps;
  for (size_t i = 1; i < trace.rows.size(); ++i) {
    double d2 = 0;
    for (const char* c : {"force_x_N", "force_y_N", "force_z_N"}) {
      const double d = trace.number(i, c) - trace.number(i - 1, c);
      d2 += d * d;
    }
    jumps.push_back(std::sqrt(d2));
  }
  std::sort(jumps.begin(), jumps.end());
  return jumps[static_cast<size_t>(0.99 * static_cast<double>(jumps.size()))];
}

// Rendering the last refreshed state as it is, the force is a staircase that steps at each
// refresh; the local spring model lets the surface yield between refreshes.
TEST(BodyWorker, LocalContactModelSmoothsTheForceBetweenRefreshes) {
  std::vector<std::string> rigid = slow_cube("own");
  rigid.push_back("bodies.cube.local_contact=rigid");
  const std::string dir_yielding = fresh_dir("worker_yielding"),
                    dir_rigid = fresh_dir("worker_rigid");
  run_scene(scene_from_text(kCubePressScene, "worker_yielding", slow_cube("own")),
            writing_to(dir_yielding));
  run_scene(scene_from_text(kCubePressScene, "worker_rigid", rigid), writing_to(dir_rigid));
  const double yielding = p99_force_jump(dir_yielding), stiff = p99_force_jump(dir_rigid);
  EXPECT_GT(stiff, 0.0);
  EXPECT_LT(yielding, 0.75 * stiff)
      << "p99 tick-to-tick force change, N: yielding " << yielding << ", rigid " << stiff;
}

// A worker step that faults is caught when the haptic thread collects it: the body freezes at the
// start of that step and the device force is zero from that tick on.
TEST(BodyWorker, AFaultOnTheWorkerFreezesTheBodyAndZeroesTheForce) {
  const std::vector<std::string> overrides = {
      "bodies.cube.model={name: test_fault_model, fault_step: 30, fault_kind: nan, stiffness: 20, "
      "damping: 0.05}",
      "bodies.cube.step_rate_hz=100", "bodies.cube.step_thread=own"};
  const std::string out = fresh_dir("worker_fault");
  const RunResult r =
      run_scene(scene_from_text(kCubePressScene, "worker_fault", overrides), writing_to(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(r.bodies[0].frozen);
  EXPECT_EQ(r.faults, 1u);
  // Soft anchors (20 N/m a node) keep the test model stable at 10 ms steps. Step 30 runs over
  // [0.30, 0.31) s and is collected at the boundary tick 0.31 s, whose trace row is 0.311 s.
  const Csv trace = read_csv(out + "/trace.csv");
  int before = 0, after = 0;
  for (size_t i = 0; i < trace.rows.size(); ++i) {
    const bool zero = trace.number(i, "force_N") == 0.0;
    if (trace.number(i, "time_s") < 0.31 + 0.5e-3)
      before += zero ? 0 : 1;
    else
      after += zero ? 0 : 1;
  }
  EXPECT_GE(before, 20) << "the stylus must be pressing before the fault";
  EXPECT_EQ(after, 0) << "ticks after the collected fault that sent a force";
}

// The step posted at the last boundary (t = 0.39 s of 0.4 s) is still in flight when the run
// ends; it is collected then, and its fault is reported, not lost.
TEST(BodyWorker, AFaultInTheStepInFlightAtTheEndIsReported) {
  const std::vector<std::string> overrides = {
      "bodies.cube.model={name: test_fault_model, fault_step: 39, fault_kind: diverged, stiffness: "
      "20, damping: 0.05}",
      "bodies.cube.step_rate_hz=100", "bodies.cube.step_thread=own"};
  const RunResult r = run_scene(scene_from_text(kCubePressScene, "worker_last_fault", overrides));
  EXPECT_EQ(r.bodies[0].worker_steps, 40u);
  EXPECT_TRUE(r.bodies[0].frozen);
  EXPECT_EQ(r.faults, 1u);
  EXPECT_EQ(r.exit_code, 1);
}

TEST(BodyWorker, RealtimeRunNeverWaitsAndCountsLateSteps) {
  const SceneDesc scene = scene_from_text(kCubePressScene, "worker_realtime", slow_cube("own"));
  RunOptions options;
  options.realtime = true;
  options.duration_s = 0.2;
  const RunResult r = run_scene(scene, options);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.mode, "realtime");
  // About 20 steps of 10 ms in 0.2 s; fewer only if steps came in late (a slow, shared machine).
  EXPECT_GE(r.bodies[0].worker_steps + r.bodies[0].late_boundaries, 15u);
  EXPECT_GE(r.bodies[0].worker_steps, 5u);
  EXPECT_LE(r.bodies[0].worker_steps, 21u);
}

TEST(BodyWorker, OwnThreadNeedsARate) {
  try {
    scene_from_text(kSaggingBeam, "worker_no_rate",
                    {"bodies.beam.step_rate_hz=0", "bodies.beam.step_thread=own"});
    FAIL() << "step_thread: own without a rate must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("step_rate_hz"), std::string::npos) << e.what();
  }
  try {
    scene_from_text(kSaggingBeam, "worker_bad_word", {"bodies.beam.step_thread=onw"});
    FAIL() << "an unknown thread must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("own"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tacta::simtest
