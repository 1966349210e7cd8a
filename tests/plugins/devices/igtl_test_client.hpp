// A 3D Slicer-like OpenIGTLink client on a thread of the test (libopenigtlink): it sends
// TRANSFORM poses along tool_position_mm at 500 Hz and keeps the SENSOR forces and the newest
// POLYDATA it receives. Shared by the openigtlink device's tests.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <igtlClientSocket.h>
#include <igtlPolyDataMessage.h>
#include <igtlSensorMessage.h>
#include <igtlTransformMessage.h>
#include <list>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "../../../plugins/devices/openigtlink/igtl_io.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/sim/snapshot.hpp"

namespace tacta::igtl_test {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// Every snapshot the render task took of the first body, by simulated time (s), and that body's
// static description (rest positions, triangles, its surface's).
struct FrameKeeper final : FrameObserver {
  void on_start(const SceneStatic& scene) override { body = scene.bodies.at(0); }
  void on_frame(const SceneStatic&, const Snapshot& s) override {
    frames[s.time_s] = s.bodies.at(0);
  }
  BodyStatic body;
  std::map<double, BodySnapshot> frames;
};
using igtl_device::Received;

// The tool's path (mm, Slicer's unit): 12 mm over a point of the liver's upper surface, down to
// 8 mm under it within 0.6 s, held there.
void tool_position_mm(double t, float out[3]) {
  const double s = std::min(t / 0.6, 1.0);
  out[0] = -49.0f;
  out[1] = static_cast<float>(159.0 + (139.0 - 159.0) * s);
  out[2] = 27.0f;
}

class SlicerLikeClient {
 public:
  explicit SlicerLikeClient(const fs::path& port_file) {
    thread_ = std::thread([this, port_file] { run(port_file); });
  }
  ~SlicerLikeClient() {
    stop_ = true;
    thread_.join();
  }
  std::atomic<double> max_force_N{0};
  std::atomic<int> sensors{0}, surfaces{0};
  std::atomic<bool> stop_sending{false};
  // The newest POLYDATA: its time stamp (s), points (mm) and triangles.
  std::mutex mutex;
  double surface_time = -1;
  std::string surface_name;
  std::vector<float> points;
  std::vector<uint32_t> triangles;
  std::vector<std::array<double, 3>> sensor_forces;  // N, every SENSOR in the order received

 private:
  void run(const fs::path& port_file) {
    int port = 0;
    igtl::ClientSocket::Pointer socket = igtl::ClientSocket::New();
    for (int i = 0; i < 1000 && !stop_; ++i) {  // the server comes up while the scene loads
      if (fs::exists(port_file) && (std::ifstream(port_file) >> port) &&
          socket->ConnectToServer("127.0.0.1", port) == 0)
        break;
      std::this_thread::sleep_for(10ms);
    }
    if (!socket->GetConnected()) return;
    socket->SetReceiveTimeout(1);
    const auto start = std::chrono::steady_clock::now();
    auto next_pose = start;
    igtl::MessageHeader::Pointer header = igtl::MessageHeader::New();
    while (!stop_) {
      const auto now = std::chrono::steady_clock::now();
      if (!stop_sending && now >= next_pose) {
        next_pose += 2ms;  // 500 Hz, a fast tracker
        igtl::TransformMessage::Pointer m = igtl::TransformMessage::New();
        m->SetDeviceName("Stylus");
        igtl::Matrix4x4 matrix;
        igtl::IdentityMatrix(matrix);
        float p[3];
        tool_position_mm(std::chrono::duration<double>(now - start).count(), p);
        for (int a = 0; a < 3; ++a) matrix[a][3] = p[a];
        m->SetMatrix(matrix);
        m->Pack();
        socket->Send(m->GetPackPointer(), static_cast<int>(m->GetPackSize()));
      }
      const Received r = igtl_device::receive_header(*socket, header);
      if (r == Received::kClosed) return;
      if (r == Received::kNothing) continue;
      bool closed = false;
      if (std::string(header->GetDeviceType()) == "SENSOR") {
        igtl::SensorMessage::Pointer m = igtl::SensorMessage::New();
        if (igtl_device::receive_body(*socket, header, m, closed) && m->GetLength() == 3) {
          const double f = std::hypot(m->GetValue(0), m->GetValue(1), m->GetValue(2));
          if (f > max_force_N) max_force_N = f;
          ++sensors;
          std::lock_guard<std::mutex> lock(mutex);
          sensor_forces.push_back({m->GetValue(0), m->GetValue(1), m->GetValue(2)});
        }
      } else if (std::string(header->GetDeviceType()) == "POLYDATA") {
        igtl::PolyDataMessage::Pointer m = igtl::PolyDataMessage::New();
        if (igtl_device::receive_body(*socket, header, m, closed)) take_surface(m, header);
      } else {
        socket->Skip(static_cast<int>(header->GetBodySizeToRead()));
      }
      if (closed) return;
    }
  }

  void take_surface(igtl::PolyDataMessage::Pointer& m, igtl::MessageHeader::Pointer& header) {
    igtl::TimeStamp::Pointer stamp = igtl::TimeStamp::New();
    header->GetTimeStamp(stamp);
    std::lock_guard<std::mutex> lock(mutex);
    surface_time = stamp->GetTimeStamp();
    surface_name = m->GetDeviceName();
    points.clear();
    igtl::PolyDataPointArray::Pointer p = m->GetPoints();
    for (int i = 0; p && i < p->GetNumberOfPoints(); ++i) {
      igtlFloat32 xyz[3];
      p->GetPoint(static_cast<unsigned>(i), xyz);
      points.insert(points.end(), xyz, xyz + 3);
    }
    triangles.clear();
    igtl::PolyDataCellArray::Pointer cells = m->GetPolygons();
    for (unsigned i = 0; cells && i < cells->GetNumberOfCells(); ++i) {
      std::list<igtlUint32> cell;
      cells->GetCell(i, cell);
      triangles.insert(triangles.end(), cell.begin(), cell.end());
    }
    ++surfaces;
  }

  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// scenes/examples/slicer_liver.yaml with its server on a free port written to WORK/port (for
// SlicerLikeClient), WORK emptied first, and the extra overrides.
inline SceneDesc slicer_liver_scene(const fs::path& work, const RegistrySchemas& schemas,
                                    std::vector<std::string> overrides = {}) {
  fs::remove_all(work);
  fs::create_directories(work);
  overrides.insert(overrides.end(), {"devices.0.params.port=0",
                                     "devices.0.params.port_file=" + (work / "port").string(),
                                     "devices.0.params.connect_timeout=30"});
  return load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/examples/slicer_liver.yaml", schemas,
                    overrides);
}

}  // namespace tacta::igtl_test
