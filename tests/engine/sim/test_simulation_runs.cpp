// Whole runs through Simulation, with the build tree's real plugins: lockstep determinism, record
// then replay (bit for bit), a scheduled model swap that carries the state over, the device
// force limit, and report.json holding every key docs/REPORT.md lists.
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(SimulationRuns, LockstepRunIsDeterministic) {
  const SceneDesc scene = scene_from_text(kCubePressScene, "determinism");
  const RunResult a = run_scene(scene);
  const RunResult b = run_scene(scene);
  ASSERT_EQ(a.state_hash.size(), 16u);
  EXPECT_EQ(a.state_hash, b.state_hash);
  EXPECT_EQ(a.exit_code, 0);
  EXPECT_EQ(a.schedule.ticks, 400u);
  EXPECT_EQ(a.mode, "lockstep");
  // The hash follows the state: a shorter run ends elsewhere.
  RunOptions shorter;
  shorter.duration_s = 0.3;
  const RunResult c = run_scene(scene, shorter);
  EXPECT_EQ(c.schedule.ticks, 300u);
  EXPECT_NE(c.state_hash, a.state_hash);
}

// A smaller copy of scenes/liver_palpation.yaml: one point, shorter phases, 0.8 s.
const char* const kSmallLiver = R"(
name: liver_small
gravity: [0, -9.81, 0]
seed: 7
clock: {mode: lockstep, haptic_rate_hz: 1000, render_rate_hz: 60, duration_s: 0.8}
bodies:
  - name: liver
    mesh: {file: ../assets/meshes/liver.msh, scale: 0.03, translate: [0, -0.0065, 0]}
    material: {youngs_modulus: 15000, poisson_ratio: 0.45, density: 1060, rayleigh_mass: 5.0, rayleigh_stiffness: 0.01}
    model: corotational_fem
    fixed: [{box: {min: [-1, -1, -1], max: [1, 0.09, 1]}}]
devices:
  - name: stylus
    plugin: sim_stylus
    params:
      workspace_origin: [-0.03, 0.12, 0.02]
      pattern: palpation
      palpation_points: [-0.049, 0.147, 0.027]
      approach_height: 0.012
      depth: 0.008
      travel_duration: 0.1
      press_duration: 0.2
      dwell_duration: 0.2
    tool: {sphere: {radius: 0.004}}
    coupling: {stiffness: 600, damping: 1.0}
    touches: liver
collision: {broad_phase: bvh}
output: {trace: true}
)";

TEST(SimulationRuns, RecordThenReplayGivesTheSameStateHash) {
  const std::string out = fresh_dir("record_replay");
  const std::string log = out + "/session.csv";
  RunOptions record;
  record.record_log = log;
  record.out_dir = out + "/recorded";
  const RunResult recorded = run_scene(scene_from_text(kSmallLiver, "liver_small"), record);
  ASSERT_EQ(recorded.exit_code, 0);
  ASSERT_TRUE(std::filesystem::exists(log));
  const nlohmann::json recorded_report = read_json(out + "/recorded/report.json");
  ASSERT_GT(recorded_report["devices"][0]["contact_ticks"].get<uint64_t>(), 50u)
      << "the recorded session must touch the liver for the replay to mean something";

  // As `tacta run --replay LOG` does it.
  const SceneDesc replay_scene =
      scene_from_text(kSmallLiver, "liver_small",
                      {"devices.*.plugin=replay", "devices.*.params={log: \"" + log + "\"}"});
  ASSERT_EQ(replay_scene.devices[0].plugin, "replay");
  RunOptions replay;
  replay.out_dir = out + "/replayed";
  const RunResult replayed = run_scene(replay_scene, replay);
  EXPECT_EQ(replayed.exit_code, 0);
  EXPECT_EQ(replayed.state_hash, recorded.state_hash)
      << "a lockstep replay must reproduce the run bit for bit";
  const nlohmann::json replayed_report = read_json(out + "/replayed/report.json");
  EXPECT_EQ(replayed_report["devices"][0]["plugin"], "replay");
  EXPECT_EQ(replayed_report["devices"][0]["contact_ticks"],
            recorded_report["devices"][0]["contact_ticks"]);
  EXPECT_EQ(replayed_report["devices"][0]["max_force_N"],
            recorded_report["devices"][0]["max_force_N"]);
}

// A smaller copy of scenes/examples/beam_model_swap.yaml, stiffer (small strains, where the
// linear and corotational FEM agree), with two swaps: tensor_mass -> corotational_fem at 0.1 s,
// then -> the test model with no spring and no damper at 0.2 s, under which every free node moves
// ballistically: v1 = v0 + g dt, x1 = x0 + v1 dt, exactly what was carried over.
TEST(SimulationRuns, ScheduledSwapCarriesPositionsAndVelocitiesOver) {
  const char* const scene_text = R"(
name: swap_small
gravity: [0, -9.81, 0]
clock: {duration_s: 0.3}
bodies:
  - name: beam
    mesh: {beam_grid: {size: [0.3, 0.04, 0.04], cells: [6, 1, 1]}}
    material: {youngs_modulus: 2.0e6, poisson_ratio: 0.4, density: 1000, rayleigh_mass: 1.0}
    model: {name: tensor_mass, integrator: implicit_euler}
    fixed: [{box: {min: [-0.001, -1, -1], max: [0.001, 1, 1]}}]
    probe_node: 27
swaps:
  - {time: 0.1, body: beam, model: corotational_fem}
  - {time: 0.2, body: beam, model: {name: test_fault_model, stiffness: 0, damping: 0, fault_kind: none}}
output: {record_interval_s: 0}
)";
  const std::string out = fresh_dir("swap");
  RunOptions options;
  options.out_dir = out;
  const RunResult r = run_scene(scene_from_text(scene_text, "swap_small"), options);
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.bodies[0].model, "test_fault_model");

  const nlohmann::json report = read_json(out + "/report.json");
  const nlohmann::json& models = report["bodies"][0]["models_run"];
  ASSERT_EQ(models.size(), 3u);
  EXPECT_EQ(models[0]["model"], "tensor_mass");
  EXPECT_EQ(models[0]["time_s"].get<double>(), 0.0);
  EXPECT_EQ(models[1]["model"], "corotational_fem");
  EXPECT_DOUBLE_EQ(models[1]["time_s"].get<double>(), 0.1);
  EXPECT_EQ(models[2]["model"], "test_fault_model");
  EXPECT_DOUBLE_EQ(models[2]["time_s"].get<double>(), 0.2);

  // Node 27 (the free top corner) every tick.
  const Csv traj = read_csv(out + "/trajectory.csv");
  ASSERT_EQ(traj.rows.size(), 300u);
  auto row_at = [&](double t) {  // the row whose tick ended at t
    for (size_t i = 0; i < traj.rows.size(); ++i)
      if (std::fabs(traj.number(i, "time_s") - t) < 1e-9) return i;
    ADD_FAILURE() << "no row at t = " << t;
    return size_t{0};
  };
  auto change = [&](size_t i, std::initializer_list<const char*> columns) {  // |q(i) - q(i-1)|
    double d2 = 0;
    for (const char* c : columns) d2 += std::pow(traj.number(i, c) - traj.number(i - 1, c), 2);
    return std::sqrt(d2);
  };
  // First swap: the tick starting at 0.1 s runs the new model; nothing jumps there.
  const size_t first = row_at(0.101);
  double largest_step = 0, largest_dv = 0;
  for (size_t i = first - 10; i < first + 10; ++i)
    if (i != first) {
      largest_step = std::max(largest_step, change(i, {"x", "y", "z"}));
      largest_dv = std::max(largest_dv, change(i, {"vx", "vy", "vz"}));
    }
  ASSERT_GT(largest_step, 1e-6) << "node 27 must be moving at the swap";
  EXPECT_LE(change(first, {"x", "y", "z"}), 2.0 * largest_step) << "position jump at the swap";
  // The two models' forces differ at this strain (on the symmetric split the first corotational
  // tick changes v by 2.4x a neighbouring tick's): a new force, not a lost state, so the bound is 3x.
  EXPECT_LE(change(first, {"vx", "vy", "vz"}), 3.0 * largest_dv + 1e-9)
      << "velocity jump at the swap";

  // Second swap, exactly: the ballistic model continues from the carried-over state.
  const size_t second = row_at(0.201);
  const double dt = 1e-3, g = -9.81;
  EXPECT_NE(traj.number(second - 1, "vy"), 0.0);
  EXPECT_NEAR(traj.number(second, "vx"), traj.number(second - 1, "vx"), 1e-10);
  EXPECT_NEAR(traj.number(second, "vy"), traj.number(second - 1, "vy") + g * dt, 1e-10);
  EXPECT_NEAR(traj.number(second, "vz"), traj.number(second - 1, "vz"), 1e-10);
  for (const auto& [x, v] : {std::pair{"x", "vx"}, std::pair{"y", "vy"}, std::pair{"z", "vz"}})
    EXPECT_NEAR(traj.number(second, x), traj.number(second - 1, x) + dt * traj.number(second, v),
                1e-10)
        << x;
}

TEST(SimulationRuns, DeviceForceNeverExceedsThePeak) {
  // A stiff coupling and a hand pushing hard: the coupling asks for far more than the peak.
  const SceneDesc scene = scene_from_text(
      kCubePressScene, "force_limit",
      {"devices.stylus.coupling={stiffness: 3000, damping: 1.0}",
       "devices.stylus.params.hand_stiffness=3000",
       "devices.stylus.params.waypoints=[0, 0.011, 0.115, 0.007,  0.1, 0.011, 0.07, 0.007]"});
  const std::string out = fresh_dir("force_limit");
  RunOptions options;
  options.out_dir = out;
  const RunResult r = run_scene(scene, options);
  ASSERT_EQ(r.exit_code, 0);
  const nlohmann::json report = read_json(out + "/report.json");
  const double peak = report["devices"][0]["force_limit_N"].get<double>();
  EXPECT_DOUBLE_EQ(peak, 3.3) << "sim_stylus declares the Omni's 3.3 N peak";
  const Csv trace = read_csv(out + "/trace.csv");
  ASSERT_EQ(trace.rows.size(), 400u);
  double largest = 0;
  for (size_t i = 0; i < trace.rows.size(); ++i) {
    const double f = trace.number(i, "force_N");
    largest = std::max(largest, f);
    EXPECT_LE(f, peak * (1 + 1e-9)) << "t = " << trace.number(i, "time_s");
  }
  EXPECT_GT(largest, 0.95 * peak) << "the test must drive the force to the limit";
  EXPECT_LE(report["devices"][0]["max_force_N"].get<double>(), peak);
  RecordProperty("largest_force_N", std::to_string(largest));
}

// Every key docs/REPORT.md's report.json table lists (first column), and the per-body and
// per-device keys its text names, are in a real report.
TEST(SimulationRuns, ReportJsonHasEveryDocumentedKey) {
  const std::string out = fresh_dir("report_keys");
  RunOptions options;
  options.out_dir = out;
  options.duration_s = 0.2;
  run_scene(scene_from_text(kCubePressScene, "report_keys"), options);
  const nlohmann::json report = read_json(out + "/report.json");

  std::ifstream doc(std::string(TACTA_SOURCE_DIR) + "/docs/REPORT.md");
  ASSERT_TRUE(doc.good());
  std::string line;
  bool in_table = false;
  std::set<std::string> top;
  const std::regex key_in_backticks("`([a-z_0-9]+)(\\[\\])?`");
  while (std::getline(doc, line)) {
    if (line.rfind("## report.json", 0) == 0)
      in_table = true;
    else if (line.rfind("## ", 0) == 0)
      in_table = false;
    if (!in_table || line.rfind("| `", 0) != 0) continue;
    const std::string first_cell = line.substr(1, line.find('|', 1) - 1);
    for (std::sregex_iterator it(first_cell.begin(), first_cell.end(), key_in_backticks), end;
         it != end; ++it)
      top.insert((*it)[1].str());
  }
  ASSERT_GE(top.size(), 15u) << "could not read the key table of docs/REPORT.md";
  for (const std::string& key : top)
    EXPECT_TRUE(report.contains(key)) << "report.json lacks '" << key << "'";
  for (const char* key : {"p50", "p99", "p999", "max", "mean"})
    EXPECT_TRUE(report["tick_ms"].contains(key)) << "tick_ms." << key;
  ASSERT_EQ(report["bodies"].size(), 1u);
  for (const char* key : {"name", "model", "models_run", "nodes", "elements", "max_displacement_m",
                          "kinetic_energy_J", "elastic_energy_J", "initial_energy_J", "faults"})
    EXPECT_TRUE(report["bodies"][0].contains(key)) << "bodies[0]." << key;
  ASSERT_EQ(report["devices"].size(), 1u);
  for (const char* key : {"name", "plugin", "max_force_N", "force_limit_N", "first_contact_peak_N",
                          "steady_contact_N", "energy_injected_J", "contact_ticks",
                          "first_contact_time_s", "zero_force_ticks", "clamped_ticks", "state"})
    EXPECT_TRUE(report["devices"][0].contains(key)) << "devices[0]." << key;
  // Values that the run fixes.
  EXPECT_EQ(report["ticks"].get<uint64_t>(), 200u);
  EXPECT_DOUBLE_EQ(report["sim_time_s"].get<double>(), 0.2);
  EXPECT_EQ(report["mode"], "lockstep");
  EXPECT_EQ(report["bodies"][0]["nodes"].get<uint64_t>(), 64u);
  EXPECT_EQ(report["bodies"][0]["model"], "tensor_mass");
  EXPECT_EQ(report["devices"][0]["state"], "connected");
  EXPECT_EQ(report["state_hash"].get<std::string>().size(), 16u);
  EXPECT_GT(report["tick_ms"]["max"].get<double>(), 0.0);
}

}  // namespace
}  // namespace tacta::simtest
