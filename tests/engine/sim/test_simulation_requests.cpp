// Requests from outside the haptic thread (Simulation::request_model_swap, request_stop): a swap
// posted before run() is taken at the first tick and listed in report.json's models_run; a stop
// ends the run after the current tick and is consumed, so the next run() runs in full.
#include <atomic>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <thread>

#include "sim_test_support.hpp"
#include "tacta/param_defaults.hpp"

namespace tacta::simtest {
namespace {

const char* const kBeam = R"(
name: beam_requests
gravity: [0, -9.81, 0]
clock: {duration_s: 0.05}
bodies:
  - name: beam
    mesh: {beam_grid: {size: [0.3, 0.04, 0.04], cells: [6, 1, 1]}}
    material: {youngs_modulus: 2.0e6, poisson_ratio: 0.4, density: 1000, rayleigh_mass: 1.0}
    model: tensor_mass
    fixed: [{box: {min: [-0.001, -1, -1], max: [0.001, 1, 1]}}]
)";

TEST(SimulationRequests, SwapWithDefaultParametersBeforeRun) {
  Simulation simulation(scene_from_text(kBeam, "beam_requests"), plugins());
  ASSERT_EQ(simulation.bodies().size(), 1u);
  const BodyHandle beam = simulation.bodies()[0];
  EXPECT_EQ(simulation.body_name(beam), "beam");
  // "empty = the defaults" (simulation.hpp).
  ASSERT_NO_THROW(
      simulation.request_model_swap(simulation.body("beam"), "corotational_fem", ParamSet{}));
  EXPECT_EQ(simulation.body_model(simulation.body("beam")), "corotational_fem");
  const std::string out = fresh_dir("requests_swap");
  RunOptions options;
  options.out_dir = out;
  const RunResult r = simulation.run(options);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.bodies[0].model, "corotational_fem");
  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& models = report["bodies"][0]["models_run"];
  ASSERT_EQ(models.size(), 2u);
  EXPECT_EQ(models[0]["model"], "tensor_mass");
  EXPECT_EQ(models[1]["model"], "corotational_fem");
  EXPECT_EQ(models[1]["time_s"].get<double>(), 0.0) << "taken at the start of the first tick";
}

TEST(SimulationRequests, BadSwapRequestsAreInputErrors) {
  Simulation simulation(scene_from_text(kBeam, "beam_requests"), plugins());
  EXPECT_THROW(simulation.request_model_swap(BodyHandle{3, 0}, "corotational_fem", ParamSet{}),
               InputError);
  EXPECT_THROW(simulation.request_model_swap(simulation.body("beam"), "no_such_model", ParamSet{}),
               InputError);
  EXPECT_EQ(simulation.body_model(simulation.body("beam")), "tensor_mass")
      << "a refused request changes nothing";
}

TEST(SimulationRequests, StopEndsOneRunAndIsConsumed) {
  Simulation simulation(scene_from_text(kBeam, "beam_requests"), plugins());
  simulation.request_stop();
  const RunResult stopped = simulation.run({});
  EXPECT_EQ(stopped.schedule.ticks, 1u);
  EXPECT_TRUE(stopped.schedule.stopped_early);
  const RunResult full = simulation.run({});
  EXPECT_EQ(full.schedule.ticks, 50u);
  EXPECT_FALSE(full.schedule.stopped_early);
}

// Realtime: the haptic thread runs on the wall clock while this thread posts a swap, as the viewer
// does; the swap is taken mid-run and every tick's duration is measured.
TEST(SimulationRequests, SwapPostedDuringARealtimeRun) {
  Simulation simulation(scene_from_text(kBeam, "beam_requests"), plugins());
  const std::string out = fresh_dir("requests_realtime");
  RunOptions options;
  options.out_dir = out;
  options.realtime = true;
  options.duration_s = 0.5;
  // The swap is posted once a frame shows the run under way (a sleep alone races a loaded machine).
  struct Started final : FrameObserver {
    std::atomic<bool> running{false};
    void on_frame(const SceneStatic&, const Snapshot& s) override {
      if (s.time_s > 0.02) running.store(true);
    }
  } started;
  options.observers.push_back(&started);
  RunResult result;
  std::thread runner([&] { result = simulation.run(options); });
  while (!started.running.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const ParamSet params =
      defaults_of(*plugins().require(TACTA_KIND_MODEL, "corotational_fem").descriptor);
  simulation.request_model_swap(simulation.body("beam"), "corotational_fem", params);
  runner.join();
  EXPECT_EQ(result.mode, "realtime");
  EXPECT_EQ(result.schedule.ticks, 500u);
  EXPECT_EQ(result.schedule.tick.ticks, 500u);
  EXPECT_GT(result.schedule.tick.p50_ms, 0.0);
  EXPECT_EQ(result.bodies[0].model, "corotational_fem");
  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["mode"], "realtime");
  const nlohmann::json& models = report["bodies"][0]["models_run"];
  ASSERT_EQ(models.size(), 2u);
  EXPECT_GT(models[1]["time_s"].get<double>(), 0.0);
  EXPECT_LT(models[1]["time_s"].get<double>(), 0.5);
}

// Two mouse devices over the beam (no gravity: the styluses settle on their targets).
const char* const kTwoMice = R"(
name: two_mice
gravity: [0, 0, 0]
clock: {duration_s: 0.3}
bodies:
  - name: beam
    mesh: {beam_grid: {size: [0.3, 0.04, 0.04], cells: [6, 1, 1]}}
    material: {youngs_modulus: 2.0e6, poisson_ratio: 0.4, density: 1000}
    model: tensor_mass
    fixed: [{box: {min: [-0.001, -1, -1], max: [0.001, 1, 1]}}]
devices:
  - {name: left, plugin: mouse, params: {start_position: [0, 0.3, 0]}}
  - {name: right, plugin: mouse, params: {start_position: [0, 0.3, 0]}}
)";

// Device input from outside the haptic thread (Simulation::device_input): each mouse device of
// the scene follows its own target, fed to the instance the simulation owns.
TEST(SimulationRequests, DeviceInputReachesEachDeviceInstance) {
  Simulation simulation(scene_from_text(kTwoMice, "two_mice"), plugins());
  const std::vector<DeviceHandle> devices = simulation.devices();
  ASSERT_EQ(devices.size(), 2u);
  EXPECT_EQ(simulation.device_plugin(devices[1]), "mouse");
  const double left[3] = {0.05, 0.25, 0.0}, right[3] = {-0.05, 0.35, 0.02};
  EXPECT_TRUE(simulation.device_input(devices[0], left, 3));
  EXPECT_TRUE(simulation.device_input(devices[1], right, 3));
  EXPECT_THROW(simulation.device_input(DeviceHandle{2, devices[0].generation}, left, 3),
               InputError);
  EXPECT_THROW(simulation.device_input(DeviceHandle{0, devices[0].generation + 1}, left, 3),
               InputError)
      << "another simulation's handle";
  const std::string out = fresh_dir("two_mice");
  RunOptions options;
  options.out_dir = out;
  simulation.run(options);
  // trace.csv: the last row of each device is where its stylus settled (critically damped hand).
  const Csv trace = read_csv(out + "/trace.csv");
  double settled[2][3] = {};
  for (size_t i = 0; i < trace.rows.size(); ++i) {
    const auto d = static_cast<size_t>(trace.number(i, "device"));
    for (int a = 0; a < 3; ++a)
      settled[d][a] = trace.number(i, std::string("device_") + "xyz"[a] + "_m");
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(settled[0][a], left[a], 1e-4) << "axis " << a;
    EXPECT_NEAR(settled[1][a], right[a], 1e-4) << "axis " << a;
  }
}

// The viewer's case: a target fed from the GUI thread while the haptic thread reads the device
// (realtime; only the first mouse is fed). The stylus ends where the last target was; clean under ThreadSanitizer
// (build-tsan/bin/sim_threads_test --gtest_filter='*DeviceInput*').
TEST(SimulationRequests, DeviceInputDuringARealtimeRun) {
  Simulation simulation(
      scene_from_text(kTwoMice, "one_mouse", {"clock.mode=realtime", "clock.duration_s=0.4"}),
      plugins());
  const std::string out = fresh_dir("one_mouse");
  std::atomic<bool> done{false};
  std::thread runner([&] {
    RunOptions options;
    options.out_dir = out;
    simulation.run(options);
    done.store(true);
  });
  // Sweep the target for 0.15 s of wall time, then leave it at its last value.
  const double last[3] = {0.02, 0.28, 0.01};
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; std::chrono::steady_clock::now() - start < std::chrono::milliseconds(150); ++k) {
    const double target[3] = {0.02 * std::sin(0.1 * k), 0.28, 0.01};
    simulation.device_input(simulation.devices()[0], target, 3);
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  simulation.device_input(simulation.devices()[0], last, 3);
  runner.join();
  ASSERT_TRUE(done.load());
  const Csv trace = read_csv(out + "/trace.csv");
  ASSERT_FALSE(trace.rows.empty());
  size_t end = trace.rows.size() - 1;  // the last row of device 0, the one fed
  while (end > 0 && trace.number(end, "device") != 0) --end;
  EXPECT_NEAR(trace.number(end, "device_y_m"), last[1], 2e-3)
      << "the stylus follows the fed target";
}

}  // namespace
}  // namespace tacta::simtest
