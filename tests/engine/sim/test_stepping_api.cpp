// The stepping API (Simulation::step, advance_to, state access, loads, set_param, report):
// stepping in any chunks gives the state run() gives, bit for bit; runs continue one clock; a
// load moves the body; live parameters change without a swap, others by one; bad input throws.
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

const char* const kBeam = kSaggingBeamScene;

SceneDesc beam() { return scene_from_text(kBeam, "beam_stepping"); }

std::string read_file(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

std::string run_hash(double duration_s) {
  Simulation simulation(beam(), plugins());
  RunOptions options;
  options.duration_s = duration_s;
  return simulation.run(options).state_hash;
}

TEST(SteppingApi, StepsInAnyChunksGiveTheStateRunGives) {
  const std::string reference = run_hash(0.2);
  Simulation one(beam(), plugins());
  EXPECT_EQ(one.step(1).ticks, 1u);
  EXPECT_EQ(one.step(199).ticks, 199u);
  EXPECT_EQ(one.tick(), 200u);
  EXPECT_EQ(one.report().state_hash, reference);

  Simulation many(beam(), plugins());
  for (int i = 0; i < 40; ++i) many.step(5);
  EXPECT_EQ(many.report().state_hash, reference);
  EXPECT_NE(run_hash(0.1), reference) << "the hash must see the state";
}

TEST(SteppingApi, RunsAndStepsContinueOneClock) {
  const std::string reference = run_hash(0.2);
  Simulation simulation(beam(), plugins());
  RunOptions options;
  options.duration_s = 0.1;
  const RunResult first = simulation.run(options);
  EXPECT_DOUBLE_EQ(first.sim_time_s, 0.1);
  EXPECT_EQ(simulation.advance_to(0.15).ticks, 50u);
  EXPECT_NEAR(simulation.time(), 0.15, 1e-12);
  options.duration_s = 0.05;
  const RunResult last = simulation.run(options);
  EXPECT_NEAR(last.sim_time_s, 0.2, 1e-12);
  EXPECT_EQ(last.state_hash, reference);
  EXPECT_EQ(simulation.advance_to(0.1).ticks, 0u) << "the clock never goes back";
}

TEST(SteppingApi, AnAppliedLoadMovesTheBodyUntilCleared) {
  Simulation loaded(beam(), plugins()), free(beam(), plugins());
  const BodyArrays arrays = loaded.body_arrays(loaded.body("beam"));
  // The tip nodes (x = 0.3 m) pulled up by 1 N in all.
  std::vector<uint32_t> tip;
  for (uint32_t n = 0; n < arrays.nodes; ++n)
    if (arrays.rest_positions[3 * n] > 0.299) tip.push_back(n);
  ASSERT_FALSE(tip.empty());
  std::vector<double> forces;
  for (size_t i = 0; i < tip.size(); ++i)
    forces.insert(forces.end(), {0.0, 1.0 / static_cast<double>(tip.size()), 0.0});
  loaded.set_applied_forces(loaded.body("beam"), tip, forces);
  loaded.step(100);
  free.step(100);
  const double y_loaded = loaded.body_arrays(loaded.body("beam")).positions[3 * tip[0] + 1];
  const double y_free = free.body_arrays(free.body("beam")).positions[3 * tip[0] + 1];
  EXPECT_GT(y_loaded - y_free, 1e-4) << "1 N up against the beam's weight (0.48 N)";
  loaded.clear_applied_forces(loaded.body("beam"));
  EXPECT_THROW(loaded.set_applied_forces(loaded.body("beam"), {100000}, {0, 1, 0}), InputError);
  EXPECT_THROW(loaded.set_applied_forces(loaded.body("beam"), tip, {1.0}), InputError);
}

TEST(SteppingApi, LiveParametersChangeWithoutASwapOthersByOne) {
  Simulation simulation(beam(), plugins());
  simulation.step(10);
  EXPECT_TRUE(simulation.set_param(simulation.body("beam"), "max_iterations", 50))
      << "corotational_fem takes it live";
  EXPECT_EQ(simulation.body_params(simulation.body("beam")).find("max_iterations")->number, 50);
  simulation.step(10);
  const size_t before = simulation.report().schedule.ticks;
  EXPECT_FALSE(simulation.set_param(simulation.body("beam"), "restart_factor", 4))
      << "not live: a swap to the same model";
  EXPECT_EQ(simulation.body_params(simulation.body("beam")).find("restart_factor")->number, 4);
  EXPECT_EQ(simulation.body_params(simulation.body("beam")).find("max_iterations")->number, 50)
      << "the swap keeps the live change";
  EXPECT_THROW(simulation.set_param(simulation.body("beam"), "no_such_parameter", 1), InputError);
  EXPECT_THROW(simulation.set_param(simulation.body("beam"), "max_iterations", -3), InputError);
  EXPECT_THROW(simulation.set_param(simulation.body("beam"), "max_iterations", 2.5), InputError);
  simulation.step(10);
  EXPECT_EQ(simulation.report().schedule.ticks, before + 10);
  EXPECT_EQ(simulation.report().faults, 0u);
}

TEST(SteppingApi, AWrittenStateIsWhatTheNextStepStartsFrom) {
  Simulation simulation(beam(), plugins());
  simulation.step(50);
  const BodyArrays a = simulation.body_arrays(simulation.body("beam"));
  for (size_t i = 0; i < 3 * a.nodes; ++i) {
    a.positions[i] = a.rest_positions[i];
    a.velocities[i] = 0.0;
  }
  simulation.state_written(simulation.body("beam"));
  Simulation fresh(beam(), plugins());
  simulation.step(10);
  fresh.step(10);
  const BodyArrays b = fresh.body_arrays(fresh.body("beam"));
  double difference = 0;
  for (size_t i = 0; i < 3 * a.nodes; ++i)
    difference = std::max(difference, std::fabs(a.positions[i] - b.positions[i]));
  EXPECT_LT(difference, 1e-12) << "from rest at rest velocity, 10 steps match a fresh start";
  EXPECT_GT(simulation.kinetic_energy(simulation.body("beam")), 0.0);
}

TEST(SteppingApi, StepStatusSaysWhatTheLastStepRaised) {
  Simulation simulation(beam(), plugins());
  const TickStatus clean = simulation.step(20).status;
  EXPECT_EQ(clean.model_bits & TACTA_STEP_FAULT_MASK, 0u);
  EXPECT_FALSE(clean.error) << "a clean beam raises no error";
  BodyArrays a = simulation.body_arrays(simulation.body("beam"));
  a.positions[3 * (a.nodes - 1)] = std::nan("");  // the free tip
  simulation.state_written(simulation.body("beam"));
  const TickStatus faulted = simulation.step(5).status;
  EXPECT_TRUE(faulted.error) << "the body faulted and froze in these ticks";
  EXPECT_NE(faulted.model_bits & TACTA_STEP_FAULT_MASK, 0u);
  EXPECT_FALSE(simulation.step(5).status.error) << "a frozen body raises nothing more";
  EXPECT_EQ(simulation.report().faults, 1u);
}

TEST(SteppingApi, WritesTheReportSoFar) {
  Simulation simulation(beam(), plugins());
  simulation.advance_to(0.05);
  const std::string out = fresh_dir("stepping_outputs");
  simulation.write_outputs(out);
  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["state_hash"], simulation.report().state_hash);
  EXPECT_THROW(simulation.body_arrays(BodyHandle{3, 0}), InputError);
  EXPECT_EQ(simulation.body("beam").index, 0u);
  EXPECT_THROW(simulation.body("nope"), InputError);
}

}  // namespace
}  // namespace tacta::simtest

namespace tacta::simtest {
namespace {

// SOFA's beam (1,824 tets: 456 batches of four) with `threads` workers for its element pass.
std::vector<double> beam_after(uint32_t threads, uint64_t ticks) {
  const std::string text = R"(
name: threaded_beam
threads: )" + std::to_string(threads) +
                           R"(
gravity: [0, -9, 0]
clock: {haptic_rate_hz: 100}
bodies:
  - name: beam
    mesh: {beam_grid: {size: [10, 10, 40], cells: [4, 4, 19]}}
    material: {youngs_modulus: 1000, poisson_ratio: 0.4, density: 0.2, rayleigh_mass: 0.1, rayleigh_stiffness: 0.1}
    model: corotational_fem
    fixed: [{box: {min: [-100, -100, -1], max: [100, 100, 0.1]}}]
)";
  Simulation simulation(scene_from_text(text, "threaded_beam"), plugins());
  simulation.step(ticks);
  const BodyArrays a = simulation.body_arrays(simulation.body("beam"));
  return {a.positions, a.positions + 3 * a.nodes};
}

// What `tacta snapshot` and Python's Simulation.snapshot draw: the state at the current tick (not
// the last frame's), and taking it records nothing (energy.csv is that of a run without it).
TEST(SteppingApi, SnapshotIsTheStateNowAndRecordsNothing) {
  Simulation plain(beam(), plugins()), pictured(beam(), plugins());
  plain.step(37);
  pictured.step(37);  // 37 ms: between two 60 Hz frames
  const Snapshot now = pictured.snapshot();
  EXPECT_NEAR(now.time_s, 0.037, 1e-12);
  const BodyArrays state = pictured.body_arrays(pictured.body("beam"));
  ASSERT_EQ(now.bodies.size(), 1u);
  EXPECT_EQ(now.bodies[0].positions,
            std::vector<double>(state.positions, state.positions + 3 * state.nodes));
  EXPECT_EQ(now.bodies[0].model, "corotational_fem");
  EXPECT_GT(now.bodies[0].elastic_J, 0.0);
  ASSERT_EQ(pictured.scene_static().bodies.size(), 1u);
  EXPECT_EQ(pictured.scene_static().bodies[0].rest_positions.size(), 3 * state.nodes);
  plain.step(63);
  pictured.step(63);
  EXPECT_EQ(pictured.report().state_hash, plain.report().state_hash);
  const std::string a = fresh_dir("snapshot_plain"), b = fresh_dir("snapshot_pictured");
  plain.write_outputs(a);
  pictured.write_outputs(b);
  EXPECT_EQ(read_file(a + "/energy.csv"), read_file(b + "/energy.csv"));
}

TEST(HostServices, TwoWorkersGiveTheSerialPassToRoundingAndRepeat) {
  const std::vector<double> serial = beam_after(1, 50), parallel = beam_after(2, 50);
  ASSERT_EQ(serial.size(), parallel.size());
  double difference = 0, largest = 0;
  for (size_t i = 0; i < serial.size(); ++i) {
    difference = std::max(difference, std::fabs(serial[i] - parallel[i]));
    largest = std::max(largest, std::fabs(serial[i]));
  }
  EXPECT_LT(difference, 1e-9 * largest) << "the coloured pass only reorders sums";
  EXPECT_GT(difference, 0.0) << "reordered sums differ in the last bits: the coloured pass ran";
  EXPECT_EQ(beam_after(2, 50), parallel) << "a thread count gives one result, run after run";
}

// Bodies due on the same tick step together, one per job on the scene's threads: inside its job
// a corotational_fem or tensor_mass body runs its serial step (its model's parallel_for cannot
// spread there), so its state is, bit for bit, what it reaches alone with `threads: 1`, and
// within rounding of what it reaches alone with the scene's `threads` (corotational_fem's
// element pass then runs in tiles on the workers). A body of corotational_fem's threaded-solve
// size takes that solve alone and the serial one in a group
// (BodiesOfThreadedSizeTakeTheSerialStepInAGroup). A body that faults in the group freezes; the
// others step on.
std::string beams_scene(uint32_t threads, const std::vector<std::string>& bodies) {
  std::string text = "name: beams_together\nthreads: " + std::to_string(threads) +
                     "\ngravity: [0, -9, 0]\nclock: {haptic_rate_hz: 100}\nbodies:\n";
  for (const std::string& b : bodies) text += b;
  return text;
}

std::string beam_body(const std::string& name, double x, const std::string& model,
                      double youngs_modulus = 1000) {
  return "  - name: " + name + "\n    mesh: {beam_grid: {size: [10, 10, 40], cells: [2, 2, 10], " +
         "origin: [" + std::to_string(x) + ", -5, 0]}}\n" +
         "    material: {youngs_modulus: " + std::to_string(youngs_modulus) +
         ", poisson_ratio: 0.4, density: 0.2, " +
         "rayleigh_mass: 0.1, rayleigh_stiffness: 0.1}\n    model: " + model + "\n" +
         "    fixed: [{box: {min: [-100, -100, -1], max: [100, 100, 0.1]}}]\n";
}

std::vector<double> positions_after(const std::string& text, const std::string& body,
                                    uint64_t ticks) {
  Simulation simulation(scene_from_text(text, "beams_together"), plugins());
  simulation.step(ticks);
  const BodyArrays a = simulation.body_arrays(simulation.body(body));
  return {a.positions, a.positions + 3 * a.nodes};
}

TEST(HostServices, BodiesDueTogetherStepOnTheWorkersAsEachStepsAlone) {
  const std::vector<std::string> bodies = {
      beam_body("polar", 0, "{name: corotational_fem, rotation: polar}"),
      beam_body("svd", 20, "{name: corotational_fem, rotation: svd}"),
      beam_body("tensor", 40, "{name: tensor_mass, integrator: implicit_euler}")};
  const std::string together = beams_scene(2, bodies);
  for (size_t b = 0; b < bodies.size(); ++b) {
    const std::string name = b == 0 ? "polar" : (b == 1 ? "svd" : "tensor");
    const std::vector<double> grouped = positions_after(together, name, 40);
    EXPECT_EQ(grouped, positions_after(beams_scene(1, {bodies[b]}), name, 40)) << name;
    const std::vector<double> alone = positions_after(beams_scene(2, {bodies[b]}), name, 40);
    // corotational_fem alone on 2 threads runs its element pass in tiles: other sums.
    if (b < 2) {
      EXPECT_NE(alone, grouped) << name;
    }
    double difference = 0, largest = 0;
    for (size_t i = 0; i < alone.size(); ++i) {
      difference = std::max(difference, std::fabs(alone[i] - grouped[i]));
      largest = std::max(largest, std::fabs(alone[i]));
    }
    EXPECT_LT(difference, 1e-9 * largest) << name;
  }
}

// corotational_fem's threaded step is taken where the body has the workers to itself: in a
// group a body's bits are those of `threads: 1`; alone, the threaded step's (tiled element
// pass, threaded solve), equal to them to rounding (637 nodes, 2,592 tets a beam).
TEST(HostServices, BodiesOfThreadedSizeTakeTheSerialStepInAGroup) {
  const auto beam = [](const std::string& name, double x, const std::string& extra) {
    std::string text = beam_body(name, x, "{name: corotational_fem" + extra + "}");
    const std::string cells = "cells: [2, 2, 10]";
    text.replace(text.find(cells), cells.size(), "cells: [6, 6, 12]");
    return text;
  };
  const std::string grouped = beams_scene(2, {beam("a", 0, ""), beam("b", 20, "")});
  const std::vector<double> in_group = positions_after(grouped, "a", 30);
  const std::vector<double> serial = positions_after(beams_scene(1, {beam("a", 0, "")}), "a", 30);
  const std::vector<double> alone = positions_after(beams_scene(2, {beam("a", 0, "")}), "a", 30);
  ASSERT_EQ(in_group.size(), 3u * 637u);
  EXPECT_EQ(in_group, serial) << "in a group: the serial step, bit for bit";
  EXPECT_NE(alone, serial) << "alone: the threaded step (sums in another order)";
  double difference = 0, largest = 0;
  for (size_t i = 0; i < alone.size(); ++i) {
    difference = std::max(difference, std::fabs(alone[i] - serial[i]));
    largest = std::max(largest, std::fabs(serial[i]));
  }
  EXPECT_LT(difference, 1e-9 * largest);
  EXPECT_EQ(positions_after(beams_scene(2, {beam("a", 0, "")}), "a", 30), alone) << "repeats";
}

TEST(HostServices, ABodyFaultingInTheGroupFreezesAndTheOthersStepOn) {
  const std::vector<std::string> bodies = {
      beam_body("steady", 0, "corotational_fem"),
      // Explicit steps of 10 ms far past their stability limit: it diverges within ticks.
      beam_body("fragile", 20, "{name: tensor_mass, integrator: central_difference}", 1e9),
      beam_body("other", 40, "corotational_fem")};
  Simulation simulation(scene_from_text(beams_scene(2, bodies), "beams_together"), plugins());
  simulation.step(20);
  const RunResult report = simulation.report();
  ASSERT_EQ(report.bodies.size(), 3u);
  EXPECT_TRUE(report.bodies[1].frozen);
  EXPECT_FALSE(report.bodies[0].frozen);
  EXPECT_FALSE(report.bodies[2].frozen);
  // The steady body steps on as it would alone (serially, as in any group).
  EXPECT_EQ(positions_after(beams_scene(1, {bodies[0]}), "steady", 20), [&] {
    const BodyArrays a = simulation.body_arrays(simulation.body("steady"));
    return std::vector<double>(a.positions, a.positions + 3 * a.nodes);
  }());
}

}  // namespace
}  // namespace tacta::simtest
