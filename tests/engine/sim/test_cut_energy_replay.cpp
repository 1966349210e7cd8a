// Cutting's energy ledger and replay (issue 22, "Haptics" and "Replay"): a separation keeps the
// kinetic plus elastic energy at the cut instant; a removal takes exactly the removed material's
// share, as report.json says; a recorded session with cut events and a held stylus button
// replays bit for bit, the buttons included.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <numeric>
#include <vector>

#include "cut_haptics_support.hpp"
#include "tacta/device_log.hpp"

namespace tacta::simtest {
namespace {

double total_energy(const Simulation& sim, BodyHandle body) {
  return sim.kinetic_energy(body) + sim.elastic_energy(body);
}
double total_mass(Simulation& sim, BodyHandle body) {
  const BodyArrays a = sim.body_arrays(body);
  return std::accumulate(a.masses, a.masses + a.nodes, 0.0);
}
nlohmann::json read_report(Simulation& sim, const std::string& dir) {
  std::ifstream in(sim.write_report(dir));
  return nlohmann::json::parse(in);
}

// A beam clamped at x = 0 swinging under gravity (bent and moving) is separated at mid-span.
// The same tets stay at the same positions and a split node's copies share its velocity and its
// mass, so kinetic plus elastic energy is unchanged but for the summation order (1e-9 relative
// allows a million times the round-off of sums over a few hundred terms).
TEST(CutEnergy, SeparationKeepsKineticPlusElasticEnergy) {
  const std::string beam = R"(
name: cut_beam
gravity: [0, 0, -9.81]
output: {frames: false, vtk: false}
bodies:
  - name: beam
    mesh: {beam_grid: {size: [0.1, 0.02, 0.02], cells: [10, 2, 2]}}
    material: {youngs_modulus: 1.0e5, poisson_ratio: 0.3, density: 1000}
    model: MODEL
    fixed: [{box: {min: [-1, -1, -1], max: [0.0001, 1, 1]}}]
)";
  int models = 0;
  for (const char* model :
       {"corotational_fem", "hyperelastic", "tensor_mass", "mass_spring", "vbd"}) {
    if (plugins().find(TACTA_KIND_MODEL, model) == nullptr) continue;
    SCOPED_TRACE(model);
    ++models;
    std::string text = beam;
    text.replace(text.find("MODEL"), 5, model);
    Simulation sim(scene_from_text(text, "cut_beam"), plugins());
    const BodyHandle body = sim.body("beam");
    sim.advance_to(0.03);
    const double kinetic = sim.kinetic_energy(body), elastic = sim.elastic_energy(body);
    ASSERT_GT(kinetic, 0.0);
    ASSERT_GT(elastic, 0.0);
    ASSERT_TRUE(sim.cut(body, plane_x(0.055), CutMode::kSeparate).changed);
    const double after = total_energy(sim, body);
    std::printf("%s: before %.12g J (kinetic %.6g, elastic %.6g), after %.12g J, relative %.2g\n",
                model, kinetic + elastic, kinetic, elastic, after,
                (after - (kinetic + elastic)) / (kinetic + elastic));
    EXPECT_NEAR(after, kinetic + elastic, 1e-9 * (kinetic + elastic));
    EXPECT_NEAR(
        read_report(sim, fresh_dir("cut_energy_separate"))["bodies"][0]["cuts"]["removed_energy_J"]
            .get<double>(),
        0.0, 1e-9 * (kinetic + elastic));
  }
  EXPECT_GT(models, 0);
}

// A free cube, stretched 1 % along x and moving at 0.2 m/s along y (the same strain and velocity
// everywhere), loses its column x in [0, 25] mm (a quarter of it) to a removal. Energy per unit
// mass is then the same everywhere, so the removed energy is the removed mass fraction of the
// whole, independently of the model's numbers; report.json's removed_energy_J is that drop.
TEST(CutEnergy, RemovalTakesTheRemovedMaterialsShare) {
  const std::string cube = R"(
name: cut_free_cube
gravity: [0, 0, 0]
output: {frames: false, vtk: false}
bodies:
  - name: cube
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [4, 4, 4], origin: [-0.05, 0, -0.05]}}
    material: {youngs_modulus: 2.0e4, poisson_ratio: 0.4, density: 1000}
    model: corotational_fem
)";
  Simulation sim(scene_from_text(cube, "cut_free_cube"), plugins());
  const BodyHandle body = sim.body("cube");
  BodyArrays a = sim.body_arrays(body);
  for (size_t n = 0; n < a.nodes; ++n) {
    a.positions[3 * n] = 1.01 * a.rest_positions[3 * n];
    a.velocities[3 * n + 1] = 0.2;
  }
  sim.state_written(body);
  const double mass = total_mass(sim, body), before = total_energy(sim, body);
  ASSERT_GT(sim.elastic_energy(body), 0.0);
  const CutSummary carve = sim.cut(body, plane_x(0.0125), CutMode::kRemove);
  ASSERT_EQ(carve.tets_removed, 4u * 4 * 6);
  const double removed_mass = mass - total_mass(sim, body);
  const double drop = before - total_energy(sim, body);
  const double expected = before * removed_mass / mass;
  const nlohmann::json cuts = read_report(sim, fresh_dir("cut_energy_remove"))["bodies"][0]["cuts"];
  std::printf(
      "removed %.6g of the mass: energy %.12g J -> drop %.12g J, expected %.12g J, "
      "report %.12g J\n",
      removed_mass / mass, before, drop, expected, cuts["removed_energy_J"].get<double>());
  EXPECT_NEAR(removed_mass / mass, 0.25, 1e-12);
  EXPECT_NEAR(drop, expected, 1e-9 * before);
  EXPECT_NEAR(cuts["removed_energy_J"].get<double>(), drop, 1e-9 * before);
  EXPECT_NEAR(cuts["removed_mass_kg"].get<double>(), removed_mass, 1e-12 * mass);
}

// ---- Replay -------------------------------------------------------------------------------

// The stylus presses the cube and holds its button from 0.1 s to 0.2 s; the scene separates the
// cube at 0.12 s and carves its far column at 0.25 s. The session log is replayed (as
// `tacta run --replay LOG`) with the same events: the same state hash, the same cuts, and the
// replay's own log has the same buttons, sample for sample.
TEST(CutReplay, RecordedCuttingSessionReplaysBitForBit) {
  const std::string events = R"(
events:
  - {time: 0.12, cut: {body: cube, mode: separate, quad: [[0.025, -1, -1], [0.025, 1, -1], [0.025, 1, 1], [0.025, -1, 1]]}}
  - {time: 0.25, cut: {body: cube, mode: remove, quad: [[0.0375, 0.051, -1], [0.0375, 1, -1], [0.0375, 1, 1], [0.0375, 0.051, 1]]}}
)";
  const std::string text = cube_scene("corotational_fem", press_waypoints(-0.0125, 0.092),
                                      "      button_times: [0.1, 0.2]", events);
  const std::string out = fresh_dir("cut_replay");
  RunOptions record;
  record.record_log = out + "/session.csv";
  record.out_dir = out + "/recorded";
  const RunResult recorded = run_scene(scene_from_text(text, "cut_cube"), record);
  ASSERT_EQ(recorded.exit_code, 0);
  ASSERT_GT(recorded.devices[0].contact_ticks, 100u) << "the session must press the cube";

  const SceneDesc replay_scene = scene_from_text(
      text, "cut_cube",
      {"devices.*.plugin=replay", "devices.*.params={log: \"" + out + "/session.csv\"}"});
  RunOptions replay;
  replay.record_log = out + "/replayed.csv";
  replay.out_dir = out + "/replayed";
  const RunResult replayed = run_scene(replay_scene, replay);
  EXPECT_EQ(replayed.exit_code, 0);
  EXPECT_EQ(replayed.state_hash, recorded.state_hash) << "a lockstep replay must be bit for bit";
  EXPECT_EQ(replayed.devices[0].contact_ticks, recorded.devices[0].contact_ticks);
  for (const char* run : {"/recorded", "/replayed"}) {
    std::ifstream in(out + run + "/report.json");
    const nlohmann::json cuts = nlohmann::json::parse(in)["bodies"][0]["cuts"];
    EXPECT_EQ(cuts["revision"], 2) << run;
  }

  const std::vector<DeviceLogSample> logged = read_device_log(out + "/session.csv");
  const std::vector<DeviceLogSample> again = read_device_log(out + "/replayed.csv");
  ASSERT_EQ(again.size(), logged.size());
  size_t held = 0, wrong = 0, differ = 0;
  for (size_t i = 0; i < logged.size(); ++i) {
    const double t = logged[i].time;
    wrong += logged[i].buttons != ((t >= 0.1 && t < 0.2) ? 1u : 0u);
    differ += again[i].buttons != logged[i].buttons || again[i].time != t;
    held += logged[i].buttons == 1u;
  }
  EXPECT_EQ(held, 100u) << "button 0 held for the 100 ticks in [0.1, 0.2) s";
  EXPECT_EQ(wrong, 0u) << "samples whose logged buttons are not the stylus's";
  EXPECT_EQ(differ, 0u) << "samples whose replayed buttons differ from the recorded ones";
}

}  // namespace
}  // namespace tacta::simtest
