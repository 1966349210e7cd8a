// The OpenIGTLink device's connection and the thread that serves it (libopenigtlink): as a
// server it waits for a client (3D Slicer's OpenIGTLinkIF, a tracker, a robot), as a client it
// connects to one, and reconnects after a loss. It takes poses from TRANSFORM, POSITION and
// QTDATA messages into a lock-free slot for the 1 kHz path, answers each pose with a SENSOR
// message holding the force the 1 kHz path left in its slot, and streams the newest surface the
// render thread offered as POLYDATA at a fixed rate.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <igtlClientSocket.h>
#include <igtlServerSocket.h>
#include <mutex>
#include <string>
#include <thread>

#include "surface_frame.hpp"
#include "tacta_devices/monotonic_clock.hpp"
#include "tacta_devices/seqlock_slot.hpp"

namespace tacta::igtl_device {

inline double now_seconds() noexcept { return devices::monotonic_seconds(); }  // s

struct LinkSettings {
  bool server = true;
  std::string host;               // client mode: where the server is
  int port = 18944;               // server mode: 0 for an ephemeral port
  double metres_per_unit = 1e-3;  // OpenIGTLink peers (3D Slicer) speak millimetres
  double surface_rate_hz = 60;    // POLYDATA messages per second; 0: none
  std::string force_name = "TactaForce";
};

// Newest pose: position 3 (m), orientation 4 (w x y z), velocity 3 (m/s), arrival (s), live.
struct PoseSlot {
  enum { kPosition = 0, kOrientation = 3, kVelocity = 7, kArrival = 10, kLive = 11, kSize = 12 };
};

struct LinkCounts {
  std::atomic<uint64_t> messages_in{0}, messages_out{0}, poses{0}, surfaces_out{0};
  std::atomic<uint64_t> dropped{0}, ignored{0}, connections{0}, disconnections{0};
};

class IgtlLink {
 public:
  // Server mode creates the server socket here (throws std::invalid_argument when the port is taken).
  explicit IgtlLink(const LinkSettings& settings);
  ~IgtlLink();
  IgtlLink(const IgtlLink&) = delete;
  IgtlLink& operator=(const IgtlLink&) = delete;

  int port() const noexcept { return port_; }
  // Blocks (not the 1 kHz path) until a peer is connected and sent a pose; false on timeout.
  bool wait_for_pose(double timeout_s);

  devices::SeqlockSlot<PoseSlot::kSize>& pose() noexcept { return pose_; }
  devices::SeqlockSlot<3>& force() noexcept { return force_; }  // N, world frame
  SurfaceFeed& surfaces() noexcept { return surfaces_; }
  const LinkCounts& counts() const noexcept { return counts_; }

 private:
  void serve();
  bool establish();
  void serve_connection();
  void take_pose(const double position_units[3], const double quaternion_wxyz[4]);
  void send_force();
  void send_surface();
  void lose_connection();

  LinkSettings settings_;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  igtl::ServerSocket::Pointer server_;
  igtl::ClientSocket::Pointer socket_;
  devices::SeqlockSlot<PoseSlot::kSize> pose_;
  devices::SeqlockSlot<3> force_;
  SurfaceFeed surfaces_;
  LinkCounts counts_;
  std::mutex pose_mutex_;
  std::condition_variable pose_arrived_;
  bool have_pose_ = false;
  // Network thread only.
  double last_pose_time_ = -1, next_surface_time_ = -1e30;  // s, monotonic
  double last_position_[3] = {0, 0, 0}, velocity_[3] = {0, 0, 0};
};

}  // namespace tacta::igtl_device
