// The openigtlink device end to end: scenes/examples/slicer_liver.yaml runs (realtime) while a
// real OpenIGTLink client built from the same library, on a thread of the test, sends TRANSFORM
// poses that press the liver, and receives the SENSOR forces and the POLYDATA surface. The last
// surface it gets is checked against the simulation's own state at that time: vertex count,
// triangles, positions.
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <gtest/gtest.h>
#include <igtlClientSocket.h>
#include <igtlPolyDataMessage.h>
#include <igtlSensorMessage.h>
#include <igtlStringMessage.h>
#include <igtlTransformMessage.h>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "../../../plugins/devices/openigtlink/igtl_io.hpp"
#include "device_harness.hpp"
#include "igtl_test_client.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/sim/simulation.hpp"
#include "validation_row.hpp"

namespace tacta {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using igtl_device::Received;
using igtl_test::FrameKeeper;
using igtl_test::SlicerLikeClient;

// Every SENSOR the client received is the force the engine sent the device at one of its ticks,
// in tick order. Reference: the engine's own per-tick force (trace.csv, printed to 9 digits);
// tolerance: that print's rounding, 1e-8 N + 1e-8 |F| (SENSOR carries float64, so nothing else
// separates them).
void expect_sensors_are_the_engines_forces(const std::vector<std::array<double, 3>>& sensors,
                                           const fs::path& trace) {
  std::vector<std::array<double, 3>> ticks;
  std::ifstream in(trace);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::array<double, 14> v{};
    std::istringstream row(line);
    for (double& x : v) {
      row >> x;
      row.ignore(1);
    }
    ticks.push_back({v[8], v[9], v[10]});  // force_x_N, force_y_N, force_z_N
  }
  ASSERT_GT(ticks.size(), 100u) << trace;
  size_t tick = 0, matched = 0, nonzero = 0;
  double worst = 0;
  for (const auto& f : sensors) {
    // An exact zero is also what the device says before the engine's first write and after the
    // run (openigtlink.cpp): not ordered against the ticks.
    if (f[0] == 0 && f[1] == 0 && f[2] == 0) {
      ++matched;
      continue;
    }
    const auto close = [&](size_t k) {
      double d = 0, m = 0;
      for (int a = 0; a < 3; ++a) {
        d = std::max(d, std::abs(f[a] - ticks[k][a]));
        m = std::max(m, std::abs(f[a]));
      }
      return d <= 1e-8 + 1e-8 * m ? d : -1.0;
    };
    size_t k = tick;
    while (k < ticks.size() && close(k) < 0) ++k;
    if (k == ticks.size()) continue;  // not found from here on: counted below
    worst = std::max(worst, close(k));
    tick = k, ++matched, ++nonzero;
  }
  const bool pass = matched == sensors.size() && nonzero > 0;
  tacta::test::validation_row("openigtlink.sensor_equals_device_force",
                              "the engine's device force at that tick (trace.csv, 9 digits)",
                              "1e-8 N + 1e-8 |F| (the trace's rounding)",
                              std::to_string(matched) + " of " + std::to_string(sensors.size()) +
                                  " SENSOR (" + std::to_string(nonzero) +
                                  " non-zero) matched in tick order, worst " +
                                  tacta::test::validation_number(worst, 2) + " N",
                              pass);
  EXPECT_EQ(matched, sensors.size()) << "a SENSOR carried a force the engine never sent";
  EXPECT_GT(nonzero, 0u);
}

TEST(OpenIgtlinkDevice, SlicerLikeClientPressesTheLiverAndGetsForcesAndTheLiveSurface) {
  const fs::path work = fs::path(TACTA_BINARY_DIR) / "test_work" / "openigtlink";
  PluginRegistry plugins;
  plugins.load();
  const SceneDesc scene = igtl_test::slicer_liver_scene(
      work, RegistrySchemas(plugins),
      {"devices.0.stream_surface=simulation"});  // the tets' boundary, checked node by node
  SlicerLikeClient client(work / "port");
  Simulation sim(scene, plugins);  // connect waits for the client's first TRANSFORM
  FrameKeeper keeper;
  RunOptions options;
  options.realtime = true;
  options.duration_s = 1.5;
  options.observers = {&keeper};
  options.out_dir = (work / "run").string();  // trace.csv: the device force of every tick
  const RunResult result = sim.run(options);
  client.stop_sending = true;
  ASSERT_FALSE(keeper.frames.empty());
  const double final_time = keeper.frames.rbegin()->first;
  for (int i = 0; i < 300;
       ++i) {  // the final frame's POLYDATA follows within a frame period or two
    {
      std::lock_guard<std::mutex> lock(client.mutex);
      if (client.surface_time >= final_time - 1e-6) break;  // s: the stamp carries ~1 ns
    }
    std::this_thread::sleep_for(10ms);
  }
  std::printf("openigtlink: %d SENSOR (max %.3f N), %d POLYDATA in %.2f s\n", client.sensors.load(),
              client.max_force_N.load(), client.surfaces.load(), result.sim_time_s);
  EXPECT_GT(client.sensors, 100);
  EXPECT_GT(client.max_force_N, 0.3) << "pressing 8 mm into the liver should be felt";
  EXPECT_LE(client.max_force_N, 3.3 + 1e-9);
  EXPECT_GT(client.surfaces, 10);  // 60 Hz over 1.5 s
  EXPECT_EQ(result.devices.at(0).counters.empty(), false);

  std::lock_guard<std::mutex> lock(client.mutex);
  expect_sensors_are_the_engines_forces(client.sensor_forces, work / "run" / "trace.csv");
  EXPECT_EQ(client.surface_name, "liver");
  const auto state =
      keeper.frames.lower_bound(client.surface_time - 1e-6);  // s: the stamp carries ~1 ns
  ASSERT_TRUE(state != keeper.frames.end() && state->first < client.surface_time + 1e-6)
      << "the surface's time stamp " << client.surface_time << " s is no state the simulation had";
  // The streamed vertices are the nodes the boundary triangles use, in the order first used.
  std::vector<int64_t> vertex_of_node(keeper.body.rest_positions.size() / 3, -1);
  std::vector<uint32_t> node_of_vertex, expected_triangles;
  for (uint32_t n : keeper.body.triangles) {
    if (vertex_of_node[n] < 0) {
      vertex_of_node[n] = static_cast<int64_t>(node_of_vertex.size());
      node_of_vertex.push_back(n);
    }
    expected_triangles.push_back(static_cast<uint32_t>(vertex_of_node[n]));
  }
  ASSERT_EQ(client.points.size(), 3 * node_of_vertex.size());
  EXPECT_EQ(client.triangles, expected_triangles);
  double worst = 0, moved = 0;
  for (size_t v = 0; v < node_of_vertex.size(); ++v)
    for (size_t a = 0; a < 3; ++a) {
      const double simulated = state->second.positions[3 * node_of_vertex[v] + a];
      worst = std::max(worst,
                       std::abs(static_cast<double>(client.points[3 * v + a]) * 1e-3 - simulated));
      moved = std::max(moved,
                       std::abs(simulated - keeper.body.rest_positions[3 * node_of_vertex[v] + a]));
    }
  EXPECT_LT(worst, 1e-7) << "m: float32 mm carries a ~0.2 mm-long coordinate to ~1e-8 m";
  EXPECT_GT(moved, 1e-3) << "the pressed liver's surface should have moved";
}

// Through the C ABI: a corrupt message and an unknown one are dropped and counted, a lost
// connection reads DISCONNECTED (zero force), and the next client reconnects.
TEST(OpenIgtlinkDevice, CorruptAndUnknownMessagesAndADisconnectNeverCrash) {
  const fs::path work = fs::path(TACTA_BINARY_DIR) / "test_work" / "openigtlink_abi";
  fs::remove_all(work);
  fs::create_directories(work);
  testing::LoadedPlugin plugin("tacta_openigtlink.so");
  const tacta_device_api& api = plugin.api<tacta_device_api>("openigtlink");
  testing::DeviceParams params(plugin.descriptor("openigtlink"));
  params.number("port", 0)
      .text("port_file", (work / "port").string())
      .number("connect_timeout", 20);
  const auto send_pose = [](igtl::ClientSocket& socket, float y_mm, bool corrupt) {
    igtl::TransformMessage::Pointer m = igtl::TransformMessage::New();
    igtl::Matrix4x4 matrix;
    igtl::IdentityMatrix(matrix);
    matrix[1][3] = y_mm;
    m->SetMatrix(matrix);
    m->Pack();
    if (corrupt)
      static_cast<unsigned char*>(m->GetPackBodyPointer())[4] ^= 0x5A;  // the CRC no longer holds
    socket.Send(m->GetPackPointer(), static_cast<int>(m->GetPackSize()));
  };
  const auto connect = [&](igtl::ClientSocket::Pointer& socket) {
    for (int i = 0; i < 1000; ++i) {
      int port = 0;
      if (fs::exists(work / "port") && (std::ifstream(work / "port") >> port) &&
          socket->ConnectToServer("127.0.0.1", port) == 0)
        return true;
      std::this_thread::sleep_for(10ms);
    }
    return false;
  };
  igtl::ClientSocket::Pointer first = igtl::ClientSocket::New();
  std::thread peer([&] {
    if (!connect(first)) return;
    send_pose(*first, 100.0f, false);
  });
  const tacta_device_setup setup = params.setup();
  void* device = nullptr;
  char message[512] = {0};
  ASSERT_EQ(api.create(&setup, &device, message, sizeof message), TACTA_OK) << message;
  ASSERT_EQ(api.connect(device, message, sizeof message), TACTA_OK) << message;
  peer.join();
  tacta_device_sample s{};
  ASSERT_EQ(api.read(device, 0.0, &s), TACTA_DEVICE_CONNECTED);
  EXPECT_NEAR(s.position[1], 0.1, 1e-9);  // mm in, m out

  igtl::StringMessage::Pointer text = igtl::StringMessage::New();
  text->SetString("hello");
  text->Pack();
  first->Send(text->GetPackPointer(), static_cast<int>(text->GetPackSize()));
  send_pose(*first, 200.0f, true);
  std::this_thread::sleep_for(100ms);
  ASSERT_EQ(api.read(device, 0.001, &s), TACTA_DEVICE_CONNECTED);
  EXPECT_NEAR(s.position[1], 0.1, 1e-9) << "the corrupt pose was taken";
  first->CloseSocket();
  tacta_device_state state = TACTA_DEVICE_CONNECTED;
  for (int i = 0; i < 1000 && (state = api.read(device, 0.002, &s)) == TACTA_DEVICE_CONNECTED; ++i)
    std::this_thread::sleep_for(1ms);
  EXPECT_EQ(state, TACTA_DEVICE_DISCONNECTED);

  igtl::ClientSocket::Pointer second = igtl::ClientSocket::New();
  ASSERT_TRUE(connect(second));
  send_pose(*second, 120.0f, false);
  for (int i = 0; i < 1000 && (state = api.read(device, 0.003, &s)) != TACTA_DEVICE_CONNECTED; ++i)
    std::this_thread::sleep_for(1ms);
  EXPECT_EQ(state, TACTA_DEVICE_CONNECTED);
  EXPECT_NEAR(s.position[1], 0.12, 1e-7);
  tacta_device_counter c[32];
  std::map<std::string, double> counters;
  for (uint32_t i = 0, n = api.counters(device, c, 32); i < n; ++i)
    counters[c[i].name] = c[i].value;
  EXPECT_EQ(counters["dropped"], 1.0);
  EXPECT_EQ(counters["ignored"], 1.0);
  EXPECT_EQ(counters["connections"], 2.0);
  EXPECT_EQ(counters["disconnections"], 1.0);
  EXPECT_EQ(counters["watchdog_trips"], 1.0);
  second->CloseSocket();
  api.destroy(device);
}

}  // namespace
}  // namespace tacta
