// Faults in the 1 kHz path: a model that writes NaN (or reports TACTA_STEP_DIVERGED) at a chosen
// step. The body is frozen (positions of the start of that tick, velocities zero), the run exits
// with 1, the fault is reported with its time, and the force sent to the device is exactly zero
// from that tick on (trace.csv rows and the recorded device log).
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

// The cube press with the test model that faults at step 200 (t = 0.2 s), well into contact.
std::vector<std::string> faulting(const std::string& kind) {
  return {"bodies.cube.model={name: test_fault_model, fault_step: 200, fault_kind: " + kind + "}",
          "output.plot_nodes=[63]"};
}
constexpr double kFaultTime_s = 0.2;

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

void expect_fault_run(const std::string& kind, uint32_t expected_bits) {
  const SceneDesc scene = scene_from_text(kCubePressScene, "fault_" + kind, faulting(kind));
  const std::string out = fresh_dir("fault_" + kind);
  RunOptions options;
  options.out_dir = out;
  options.record_log = out + "/session.csv";
  const RunResult r = run_scene(scene, options);

  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.faults, 1u);
  ASSERT_EQ(r.bodies.size(), 1u);
  EXPECT_TRUE(r.bodies[0].frozen);
  EXPECT_NE(r.bodies[0].fault.find("0.2"), std::string::npos) << r.bodies[0].fault;
  EXPECT_EQ(r.schedule.ticks, 400u) << "a fault freezes the body, it does not stop the run";

  const nlohmann::json report = read_json(out + "/report.json");
  ASSERT_EQ(report["faults"].size(), 1u);
  EXPECT_DOUBLE_EQ(report["faults"][0]["time_s"].get<double>(), kFaultTime_s);
  EXPECT_EQ(report["faults"][0]["body"].get<int>(), 0);
  EXPECT_EQ(report["faults"][0]["bits"].get<uint32_t>(), expected_bits);
  ASSERT_EQ(report["bodies"][0]["faults"].size(), 1u);
  EXPECT_DOUBLE_EQ(report["bodies"][0]["faults"][0]["time_s"].get<double>(), kFaultTime_s);
  EXPECT_TRUE(report["bodies"][0]["faults"][0]["frozen"].get<bool>());

  // trace.csv: time_s is the end of the tick; the faulting tick ends at 0.201 s.
  const Csv trace = read_csv(out + "/trace.csv");
  ASSERT_EQ(trace.rows.size(), 400u);
  int forces_before = 0, nonzero_after = 0;
  for (size_t i = 0; i < trace.rows.size(); ++i) {
    const double t = trace.number(i, "time_s");
    const bool zero = trace.number(i, "force_x_N") == 0 && trace.number(i, "force_y_N") == 0 &&
                      trace.number(i, "force_z_N") == 0;
    if (t < kFaultTime_s + 0.5e-3)
      forces_before += zero ? 0 : 1;
    else if (!zero) {
      ++nonzero_after;
      if (nonzero_after <= 3)
        ADD_FAILURE() << "trace.csv: force " << trace.rows[i][trace.column("force_N")]
                      << " N sent at t = " << t << " s, after the fault at " << kFaultTime_s;
    }
  }
  EXPECT_GE(forces_before, 20) << "the stylus must be pressing before the fault";
  EXPECT_EQ(nonzero_after, 0) << "ticks after the fault that sent a force";

  // The device log holds the forces actually sent, stamped with the tick's start.
  const Csv log = read_csv(out + "/session.csv");
  ASSERT_EQ(log.rows.size(), 400u);
  int log_nonzero_after = 0;
  for (size_t i = 0; i < log.rows.size(); ++i)
    if (log.number(i, "time_s") >= kFaultTime_s - 1e-9 &&
        (log.number(i, "fx") != 0 || log.number(i, "fy") != 0 || log.number(i, "fz") != 0))
      ++log_nonzero_after;
  EXPECT_EQ(log_nonzero_after, 0);

  // trajectory.csv (node 63, a free top corner): frozen where it was at the start of the
  // faulting tick, with zero velocity, from then on.
  const Csv traj = read_csv(out + "/trajectory.csv");
  ASSERT_EQ(traj.rows.size(), 400u);
  const size_t before = 199;  // row at t = 0.200: the state the faulting step started from
  EXPECT_NEAR(traj.number(before, "time_s"), kFaultTime_s, 1e-9);
  for (size_t i = before + 1; i < traj.rows.size(); ++i) {
    for (const char* c : {"x", "y", "z"})
      EXPECT_EQ(traj.rows[i][traj.column(c)], traj.rows[before][traj.column(c)]) << "row " << i;
    for (const char* c : {"vx", "vy", "vz"}) EXPECT_EQ(traj.number(i, c), 0.0) << "row " << i;
  }
}

TEST(SimulationFaults, NanFromAModelFreezesTheBodyAndZeroesTheForce) {
  expect_fault_run("nan", TACTA_STEP_NOT_FINITE);
}

TEST(SimulationFaults, DivergedStepFreezesTheBodyAndZeroesTheForce) {
  expect_fault_run("diverged", TACTA_STEP_DIVERGED);
}

// Bit for bit through the loop itself: the frozen positions are exactly those of the start of the
// faulting tick and velocities are zero.
TEST(SimulationFaults, FrozenStateIsTheStartOfTheFaultingTick) {
  const SceneDesc scene = scene_from_text(kCubePressScene, "fault_harness", faulting("nan"));
  LoopHarness h(scene, 400);
  for (int k = 0; k < 200; ++k) h.tick();
  const SoftBody body = h.world.body(0);
  ASSERT_FALSE(body.fault.frozen);
  const std::vector<double> start = body.nodes.positions;
  bool moving = false;
  for (double v : body.nodes.velocities) moving = moving || v != 0.0;
  EXPECT_TRUE(moving) << "the body should be moving under the stylus before the fault";
  h.tick();  // tick 200: the model writes NaN
  EXPECT_TRUE(body.fault.frozen);
  EXPECT_EQ(body.fault.bits, TACTA_STEP_NOT_FINITE);
  EXPECT_DOUBLE_EQ(body.fault.time_s, kFaultTime_s);
  EXPECT_EQ(body.nodes.positions, start) << "positions are restored to the start of the tick";
  for (double v : body.nodes.velocities) ASSERT_EQ(v, 0.0);
  const DeviceComponents dev = h.world.device(0);
  EXPECT_EQ(dev.contact.force, (std::array<double, 3>{0, 0, 0})) << "zero force in the same tick";
  EXPECT_EQ(dev.stats.zero_force_ticks, 1u);
  int moved = 0, forced = 0, first_forced = -1;
  for (int k = 201; k < 251; ++k) {
    h.tick();
    if (body.nodes.positions != start) ++moved;
    if (dev.contact.force != std::array<double, 3>{0, 0, 0} && forced++ == 0) first_forced = k;
  }
  EXPECT_EQ(moved, 0) << "ticks in which the frozen body moved";
  EXPECT_EQ(forced, 0) << "ticks after the fault that sent a force, the first at tick "
                       << first_forced;
  EXPECT_EQ(h.loop.faults().rows().size(), 1u) << "a frozen body faults once";
}

}  // namespace
}  // namespace tacta::simtest
