// Teleoperation under delay: the teleoperated_palpation scene (the net device, realtime clock)
// runs here while net_teleop_peer, a separate process with the real C client, presses the liver
// through a delay line of 0, 20, 100 and 250 ms round trip (with jitter and loss). Passivity: the
// exact work of the device's force on the hand's motion, recomputed here from the peer's logged
// positions and held forces (not the filter's own bookkeeping), never makes the hand gain energy;
// without the filter it does. The force never exceeds the device's peak and contact is held.
// Prints the latency table of docs/DEVICES.md (force error and transparency against the
// undelayed run).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <future>
#include <gtest/gtest.h>
#include <map>
#include <signal.h>
#include <spawn.h>
#include <sstream>
#include <sys/wait.h>
#include <thread>

#include "tacta/device_api.h"
#include "tacta/plugin_registry.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/sim/simulation.hpp"
#include "tacta_net_device.h"

extern char** environ;

namespace tacta {
namespace {

namespace fs = std::filesystem;
constexpr double kPressSeconds = 2.0;  // s of the peer's timeline from the first live force
constexpr double kPeakForce = 3.3;     // N, the peer's announced peak (an Omni)
// J: how far below zero the exact ledger may go. The filter keeps a reserve of twice the largest
// recent miss of its displacement prediction; a tick that misses by more costs |F| times the
// excess. 1e-6 J is one such tick at the held 1.5 N missing by 0.7 um (a 0.27 N force step on a
// steady 0.1 kg hand: 0.27 / 0.1 * (1 ms)^2 / 2); rounding in the sum is below 1e-15 J. The
// unfiltered loop reaches -1e-2 J, the sampled-power filter it replaced -1e-3 to -5e-3 J.
constexpr double kLedgerTolerance = 1e-6;

const PluginRegistry& plugins() {
  static const std::unique_ptr<PluginRegistry> registry = [] {
    auto r = std::make_unique<PluginRegistry>();
    r->load();
    return r;
  }();
  return *registry;
}

struct TeleopRun {
  std::map<std::string, double> peer;         // the peer's summary line
  std::vector<std::pair<double, double>> fy;  // (s, N): the force the hand felt, vertical
  double min_exact_ledger = 0;  // J: the lowest of -sum F(n).(x(n+1) - x(n)) over the run
  RunResult sim;
  std::map<std::string, double> link;  // the net device's counters
};

bool wait_for_file(const fs::path& file, double seconds) {
  for (int i = 0; i < static_cast<int>(seconds * 100); ++i) {
    if (fs::exists(file)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

// The teleoperated_palpation scene in a fresh work folder, its net device on a free port that it
// writes to work/port, with one more override.
SceneDesc teleop_scene(const fs::path& work, const std::string& override_) {
  fs::remove_all(work);
  fs::create_directories(work);
  const RegistrySchemas schemas(plugins());
  return load_scene(
      std::string(TACTA_SOURCE_DIR) + "/scenes/examples/teleoperated_palpation.yaml", schemas,
      {"devices.0.params.port=0", "devices.0.params.port_file=" + (work / "port").string(),
       "output.plots=[]", override_,
       // SCHED_FIFO (granted to root) would let a haptic thread slowed by a sanitizer
       // starve the peer process on a 2-core machine; the test measures delay, not jitter.
       "clock.haptic_priority=0"});
}

TeleopRun teleoperate(double round_trip_ms, double jitter_ms, double loss, bool filtered = true) {
  const fs::path work = fs::path(TACTA_BINARY_DIR) / "test_work" /
                        ("net_teleop_" + std::to_string(static_cast<int>(round_trip_ms)) +
                         (filtered ? "" : "_unfiltered"));
  const SceneDesc scene = teleop_scene(work, "devices.0.params.connect_timeout=30");
  // The simulation connects (waits for the peer's HELLO) on its own thread while the peer starts.
  auto building = std::async(std::launch::async,
                             [&] { return std::make_unique<Simulation>(scene, plugins()); });
  EXPECT_TRUE(wait_for_file(work / "port", 20.0)) << "the net device wrote no port file";
  std::string port;
  std::ifstream(work / "port") >> port;
  const std::string out_csv = (work / "peer.csv").string(), summary = (work / "peer.txt").string();
  std::vector<std::string> args{
      NET_TELEOP_PEER,      port, std::to_string(round_trip_ms), std::to_string(jitter_ms),
      std::to_string(loss), "7",  std::to_string(kPressSeconds), out_csv};
  if (!filtered) args.emplace_back("unfiltered");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, summary.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  pid_t peer = 0;
  EXPECT_EQ(posix_spawn(&peer, NET_TELEOP_PEER, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  std::unique_ptr<Simulation> sim =
      building.get();  // throws (test fails) if the peer never said HELLO

  // The run ends when the peer is done (it says BYE); the duration is only a bound.
  std::atomic<bool> peer_done{false};
  std::thread watcher([&] {
    int status = 0;
    waitpid(peer, &status, 0);
    peer_done = true;
    sim->request_stop();
  });
  RunOptions options;
  options.realtime = true;
  options.duration_s = kPressSeconds + 30.0;
  options.out_dir = (work / "run").string();
  TeleopRun run;
  run.sim = sim->run(options);
  if (!peer_done) kill(peer, SIGKILL);
  watcher.join();

  std::ifstream summary_in(summary);
  for (std::string key; summary_in >> key;) summary_in >> run.peer[key];
  std::ifstream csv(out_csv);
  std::string line;
  std::getline(csv, line);
  // The hand's energy ledger, exactly: each row is the position at a tick's start and the force
  // held over that tick, so the work the hand did against it is -F(n).(x(n+1) - x(n)).
  double ledger = 0, previous_x[3] = {0, 0, 0}, previous_f[3] = {0, 0, 0};
  bool first = true;
  while (std::getline(csv, line)) {
    std::istringstream row(line);
    double t, x[3], f[3];
    char c;
    if (!(row >> t >> c >> x[0] >> c >> x[1] >> c >> x[2] >> c >> f[0] >> c >> f[1] >> c >> f[2]))
      continue;
    if (!first) {
      for (int a = 0; a < 3; ++a) ledger -= previous_f[a] * (x[a] - previous_x[a]);
      run.min_exact_ledger = std::min(run.min_exact_ledger, ledger);
    }
    first = false;
    std::copy(x, x + 3, previous_x);
    std::copy(f, f + 3, previous_f);
    run.fy.emplace_back(t, f[1]);
  }
  for (const auto& [name, value] : run.sim.devices.at(0).counters) run.link[name] = value;
  return run;
}

// RMS (N) of the difference of two force traces over their common span, by time.
double force_error(const std::vector<std::pair<double, double>>& run,
                   const std::vector<std::pair<double, double>>& base) {
  double sum = 0;
  size_t n = 0, j = 0;
  for (const auto& [t, f] : run) {
    while (j + 1 < base.size() && base[j + 1].first <= t) ++j;
    if (j >= base.size() || std::abs(base[j].first - t) > 2e-3) continue;
    sum += (f - base[j].second) * (f - base[j].second);
    ++n;
  }
  return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : -1.0;
}

// Share of the pressed-in time the peer feels contact. Contact was lost under sanitizers (0.77
// seen under ASan) when another test shared the two cores: the slowed peer fell silent past the
// device's 50 ms watchdog, which reads DISCONNECTED (force zero) until it hears again. The cases
// now run alone (SERIAL in CMakeLists.txt) and every build holds the same bound.
constexpr double kHeldFraction = 0.8;

TEST(NetTeleoperation, StaysPassiveAndHoldsContactUpTo250msRoundTrip) {
  struct Case {
    double rtt_ms, jitter_ms, loss;
  };
  const Case cases[] = {{0, 0, 0}, {20, 1, 0.01}, {100, 5, 0.01}, {250, 12.5, 0.01}};
  std::vector<std::pair<Case, TeleopRun>> runs;
  for (const Case& c : cases) {
    SCOPED_TRACE("round trip " + std::to_string(c.rtt_ms) + " ms");
    TeleopRun run = teleoperate(c.rtt_ms, c.jitter_ms, c.loss);
    ASSERT_GT(run.peer["ticks"], 0.5 * kPressSeconds * 1000) << "the peer did not run through";
    EXPECT_GE(run.min_exact_ledger, -kLedgerTolerance)
        << "the device returned more energy than the hand put in";
    EXPECT_LE(run.peer["peak"], kPeakForce + 1e-9);
    EXPECT_GE(run.peer["held_fraction"], kHeldFraction) << "contact was not held while pressed in";
    // The peer sends every tick; 50 ms of silence (the net device's watchdog) means the link or
    // one side stalled, and the device reads DISCONNECTED (force zero) until it hears again.
    EXPECT_EQ(run.link.at("watchdog_trips"), 0.0) << "the link fell silent past the watchdog";
    EXPECT_GT(run.sim.devices.at(0).contact_ticks,
              100u);  // ticks: fewer when the engine runs late (ASan, load)
    EXPECT_LE(run.sim.devices.at(0).max_force_N, kPeakForce + 1e-9);
    if (c.rtt_ms >
        0) {  // the engine measures the injected round trip (plus loopback and a tick or two)
      EXPECT_GT(run.link["round_trip_p50_ms"], 0.8 * c.rtt_ms);
      EXPECT_LT(run.link["round_trip_p50_ms"], c.rtt_ms + 40.0);
      EXPECT_GT(run.link["dropped_out_of_order"] + run.link["late"], 0.0)
          << "jitter reordered nothing";
    }
    runs.emplace_back(c, std::move(run));
  }
  const TeleopRun& base = runs.front().second;
  std::printf(
      "| round trip (ms) | jitter (ms) | loss | RTT p50 / p99 (ms) | force error RMS (N) | "
      "transparency | "
      "min exact ledger (J) | dissipated (J) | peak (N) | watchdog trips |\n");
  for (const auto& [c, run] : runs) {
    const double transparency = run.peer.at("held_mean") / base.peer.at("held_mean");
    std::printf(
        "| %.0f | %.1f | %.0f %% | %.2f / %.2f | %.3f | %.3f | %.1e | %.1e | %.3f | %.0f |\n",
        c.rtt_ms, c.jitter_ms, c.loss * 100, run.link.at("round_trip_p50_ms"),
        run.link.at("round_trip_p99_ms"), force_error(run.fy, base.fy), transparency,
        run.min_exact_ledger, run.peer.at("dissipated"), run.peer.at("peak"),
        run.link.at("watchdog_trips"));
  }
}

// The check above can fail: the same 250 ms loop with the force only limited to the peak (no
// passivity filter) hands the operator energy the hand never put in.
TEST(NetTeleoperation, WithoutTheFilterTheDelayedLoopCreatesEnergy) {
  // A run in which the press never reached the liver says nothing about the filter (seen once in
  // an ASan build with two compilers sharing its 2 cores): such a run is repeated, twice at most.
  TeleopRun run = teleoperate(250, 12.5, 0.01, false);
  for (int retry = 0; retry < 2 && run.peer.at("peak") == 0.0; ++retry)
    run = teleoperate(250, 12.5, 0.01, false);
  ASSERT_GT(run.peer.at("ticks"), 0.5 * kPressSeconds * 1000) << "the peer did not run through";
  ASSERT_GT(run.peer.at("peak"), 0.0) << "no run of three made contact";
  std::printf("unfiltered, 250 ms: min exact ledger %.2e J, peak %.3f N\n", run.min_exact_ledger,
              run.peer.at("peak"));
  EXPECT_LT(run.min_exact_ledger, -100 * kLedgerTolerance);
}

// The engine side of a link that drops: a bridge (the C client, on a thread) that falls silent
// for 0.2 s mid-run gets zero force, is reported disconnected (a fault, exit 1) and reconnects.
TEST(NetTeleoperation, ASilentBridgeIsDisconnectedThenReconnects) {
  const fs::path work = fs::path(TACTA_BINARY_DIR) / "test_work" / "net_reconnect";
  const SceneDesc scene = teleop_scene(work, "devices.0.params.watchdog=0.1");
  std::atomic<bool> stop{false};
  std::atomic<int> silent_ms{0};
  std::thread bridge([&] {
    if (!wait_for_file(work / "port", 20.0)) return;
    unsigned port = 0;
    std::ifstream(work / "port") >> port;
    const tnet_hello caps{
        {-0.13, 0.06, -0.035}, {0.03, 0.18, 0.105}, 3.3, 0.88, 1000.0, 1000.0, 3, 3};
    tacta_net_device dev;
    char error[256];
    if (tacta_net_open(&dev, "127.0.0.1", static_cast<uint16_t>(port), &caps, error,
                       sizeof error) != 0)
      return;
    const tnet_state held{{-0.049, 0.16, 0.027}, {1, 0, 0, 0}, {0, 0, 0}, 0, 0};  // above the liver
    while (!stop) {
      if (silent_ms > 0) {
        std::this_thread::sleep_for(std::chrono::milliseconds(silent_ms.exchange(0)));
        continue;
      }
      tacta_net_send_state(&dev, &held);
      tacta_net_poll(&dev);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    tacta_net_close(&dev);
  });
  Simulation sim(scene, plugins());
  std::thread pause([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    silent_ms = 300;  // ms: three watchdogs
  });
  RunOptions options;
  options.realtime = true;
  options.duration_s = 1.2;
  options.out_dir = (work / "run").string();
  const RunResult result = sim.run(options);
  pause.join();
  stop = true;
  bridge.join();
  const DeviceResult& device = result.devices.at(0);
  std::map<std::string, double> link(device.counters.begin(), device.counters.end());
  EXPECT_GE(link["watchdog_trips"], 1.0);
  EXPECT_EQ(device.reconnections, static_cast<uint64_t>(link["watchdog_trips"]));
  EXPECT_EQ(device.state, TACTA_DEVICE_CONNECTED) << "it came back";
  EXPECT_EQ(result.faults, device.reconnections) << "each drop is reported";
  EXPECT_EQ(result.exit_code, 1);
  std::ifstream report(work / "run" / "report.json");
  const std::string text((std::istreambuf_iterator<char>(report)),
                         std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"watchdog_trips\""), std::string::npos);
  EXPECT_NE(text.find("\"reconnections\""), std::string::npos);
}

}  // namespace
}  // namespace tacta
