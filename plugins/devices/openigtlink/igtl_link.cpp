#include "igtl_link.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <igtlMath.h>
#include <igtlPolyDataMessage.h>
#include <igtlPositionMessage.h>
#include <igtlQuaternionTrackingDataMessage.h>
#include <igtlSensorMessage.h>
#include <igtlTransformMessage.h>
#include <igtlUnit.h>
#include <stdexcept>

#include "igtl_io.hpp"

namespace tacta::igtl_device {

namespace {
constexpr int kReceiveTimeoutMs = 2;  // how long a read waits before the thread does other work
constexpr unsigned long kAcceptWaitMs = 50;  // how long the server waits for a client per round
constexpr double kVelocitySmoothing = 0.5;   // weight of the newest finite difference
constexpr double kVelocityGap = 0.2;  // s: poses further apart than this restart the velocity
}  // namespace

IgtlLink::IgtlLink(const LinkSettings& settings) : settings_(settings) {
  if (settings_.server) {
    server_ = igtl::ServerSocket::New();
    if (server_->CreateServer(settings_.port) != 0)
      throw std::invalid_argument("openigtlink: cannot listen on TCP port " +
                                  std::to_string(settings_.port) + " (taken, or not allowed)");
    port_ = server_->GetServerPort();
  } else {
    port_ = settings_.port;
  }
  thread_ = std::thread([this] { serve(); });
}

IgtlLink::~IgtlLink() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  if (socket_) socket_->CloseSocket();
  if (server_) server_->CloseSocket();
}

bool IgtlLink::wait_for_pose(double timeout_s) {
  std::unique_lock<std::mutex> lock(pose_mutex_);
  return pose_arrived_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                                [this] { return have_pose_; });
}

void IgtlLink::serve() {
  while (!stop_.load(std::memory_order_relaxed)) {
    if (!socket_ && !establish()) continue;
    serve_connection();
  }
}

bool IgtlLink::establish() {
  if (settings_.server) {
    socket_ = server_->WaitForConnection(kAcceptWaitMs);
  } else {
    igtl::ClientSocket::Pointer client = igtl::ClientSocket::New();
    if (client->ConnectToServer(settings_.host.c_str(), settings_.port) == 0)
      socket_ = client;
    else
      std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the server is not up yet
  }
  if (!socket_) return false;
  socket_->SetReceiveTimeout(kReceiveTimeoutMs);
  counts_.connections.fetch_add(1, std::memory_order_relaxed);
  last_pose_time_ = -1;
  return true;
}

void IgtlLink::lose_connection() {
  socket_->CloseSocket();
  socket_ = nullptr;
  counts_.disconnections.fetch_add(1, std::memory_order_relaxed);
  std::array<double, PoseSlot::kSize> p{};
  if (pose_.load(p)) {
    p[PoseSlot::kLive] = 0.0;
    pose_.store(p);
  }
}

void IgtlLink::serve_connection() {
  igtl::MessageHeader::Pointer header = igtl::MessageHeader::New();
  const Received r = receive_header(*socket_, header);
  if (r == Received::kClosed) return lose_connection();
  if (r == Received::kMessage) {
    counts_.messages_in.fetch_add(1, std::memory_order_relaxed);
    const std::string type = header->GetDeviceType();
    bool closed = false, ok = false;
    double position[3] = {0, 0, 0}, q[4] = {1, 0, 0, 0};  // q: w x y z
    float pf[3] = {0, 0, 0}, qf[4] = {0, 0, 0, 1};        // OpenIGTLink quaternions are x y z w
    if (type == "TRANSFORM") {
      igtl::TransformMessage::Pointer m = igtl::TransformMessage::New();
      if ((ok = receive_body(*socket_, header, m, closed))) {
        igtl::Matrix4x4 matrix;
        m->GetMatrix(matrix);
        for (int a = 0; a < 3; ++a) pf[a] = matrix[a][3];
        igtl::MatrixToQuaternion(matrix, qf);
      }
    } else if (type == "POSITION") {
      igtl::PositionMessage::Pointer m = igtl::PositionMessage::New();
      if ((ok = receive_body(*socket_, header, m, closed))) {
        m->GetPosition(pf);
        m->GetQuaternion(qf);
      }
    } else if (type == "QTDATA") {
      igtl::QuaternionTrackingDataMessage::Pointer m = igtl::QuaternionTrackingDataMessage::New();
      if ((ok = receive_body(*socket_, header, m, closed)) &&
          m->GetNumberOfQuaternionTrackingDataElements() > 0) {
        igtl::QuaternionTrackingDataElement::Pointer e;
        m->GetQuaternionTrackingDataElement(0, e);
        e->GetPosition(pf);
        e->GetQuaternion(qf);
      } else {
        ok = false;
      }
    } else {
      // Any other message (STATUS, STRING, IMAGE...) is skipped whole.
      counts_.ignored.fetch_add(1, std::memory_order_relaxed);
      if (socket_->Skip(static_cast<int>(header->GetBodySizeToRead())) == 0)
        return lose_connection();
    }
    if (closed) return lose_connection();
    if (type == "TRANSFORM" || type == "POSITION" || type == "QTDATA") {
      for (int a = 0; a < 3; ++a) position[a] = pf[a];
      q[0] = qf[3], q[1] = qf[0], q[2] = qf[1], q[3] = qf[2];
      const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      const bool finite = std::isfinite(position[0] + position[1] + position[2] + norm);
      if (ok && finite && norm > 0.5) {
        for (double& c : q) c /= norm;
        take_pose(position, q);
        send_force();
      } else {
        counts_.dropped.fetch_add(1,
                                  std::memory_order_relaxed);  // a bad CRC, or numbers no pose has
      }
    }
  }
  send_surface();
}

void IgtlLink::take_pose(const double position_units[3], const double q[4]) {
  const double now = now_seconds();
  double x[3];
  for (int a = 0; a < 3; ++a) x[a] = position_units[a] * settings_.metres_per_unit;
  const double dt = now - last_pose_time_;
  for (int a = 0; a < 3; ++a) {
    if (last_pose_time_ < 0 || dt > kVelocityGap)
      velocity_[a] = 0.0;
    else if (dt > 1e-3)
      velocity_[a] += kVelocitySmoothing * ((x[a] - last_position_[a]) / dt - velocity_[a]);
    last_position_[a] = x[a];
  }
  last_pose_time_ = now;
  pose_.store({x[0], x[1], x[2], q[0], q[1], q[2], q[3], velocity_[0], velocity_[1], velocity_[2],
               now, 1.0});
  counts_.poses.fetch_add(1, std::memory_order_relaxed);
  std::lock_guard<std::mutex> lock(pose_mutex_);
  if (!have_pose_) {
    have_pose_ = true;
    pose_arrived_.notify_all();
  }
}

void IgtlLink::send_force() {
  std::array<double, 3> f{0, 0, 0};
  force_.load(f);
  igtl::SensorMessage::Pointer m = igtl::SensorMessage::New();
  m->SetDeviceName(settings_.force_name.c_str());
  m->SetLength(3);
  igtl::Unit::Pointer newton = igtl::Unit::New();
  newton->SetPrefix(igtl::Unit::SI_PREFIX_NONE);
  newton->Append(igtl::Unit::SI_DERIVED_NEWTON, 1);
  m->SetUnit(newton);
  for (unsigned a = 0; a < 3; ++a) m->SetValue(a, f[a]);
  m->Pack();
  if (socket_->Send(m->GetPackPointer(), static_cast<int>(m->GetPackSize())) != 0)
    counts_.messages_out.fetch_add(1, std::memory_order_relaxed);
}

void IgtlLink::send_surface() {
  const double now = now_seconds();
  if (!socket_ || settings_.surface_rate_hz <= 0 || now < next_surface_time_) return;
  const SurfaceFrame* frame = nullptr;
  const SurfaceShape* shape = nullptr;
  if (!surfaces_.take(frame, shape)) return;
  // On a fixed schedule, not "a period after the last send": the loop's 2 ms receive timeouts
  // and the send itself would otherwise add to every period (45 Hz measured for 60 asked, with
  // a 4,000-triangle surface). After a stall the schedule restarts rather than bursting.
  const double period = 1.0 / settings_.surface_rate_hz;
  next_surface_time_ = std::max(next_surface_time_ + period, now);
  // Built per message on the network thread: libopenigtlink's arrays are its own objects.
  igtl::PolyDataPointArray::Pointer points = igtl::PolyDataPointArray::New();
  const size_t vertices = frame->points.size() / 3;
  points->SetNumberOfPoints(static_cast<int>(vertices));
  const double scale = 1.0 / settings_.metres_per_unit;
  for (size_t v = 0; v < vertices; ++v)
    points->SetPoint(static_cast<unsigned>(v),
                     static_cast<igtlFloat32>(frame->points[3 * v] * scale),
                     static_cast<igtlFloat32>(frame->points[3 * v + 1] * scale),
                     static_cast<igtlFloat32>(frame->points[3 * v + 2] * scale));
  igtl::PolyDataCellArray::Pointer polygons = igtl::PolyDataCellArray::New();
  for (size_t t = 0; t + 2 < shape->triangles.size(); t += 3) {
    igtlUint32 cell[3] = {shape->triangles[t], shape->triangles[t + 1], shape->triangles[t + 2]};
    polygons->AddCell(3, cell);
  }
  igtl::PolyDataMessage::Pointer m = igtl::PolyDataMessage::New();
  m->SetDeviceName(shape->body.c_str());
  m->SetPoints(points);
  m->SetPolygons(polygons);
  igtl::TimeStamp::Pointer stamp = igtl::TimeStamp::New();
  stamp->SetTime(frame->time);  // the simulated time of the state, s
  m->SetTimeStamp(stamp);
  m->Pack();
  if (socket_->Send(m->GetPackPointer(), static_cast<int>(m->GetPackSize())) != 0) {
    counts_.messages_out.fetch_add(1, std::memory_order_relaxed);
    counts_.surfaces_out.fetch_add(1, std::memory_order_relaxed);
  }
}

}  // namespace tacta::igtl_device
