// God-object proxy (Zilles and Salisbury 1995, with a finite-radius proxy as in Ruspini et al.
// 1997): a point that follows the device in free space and stays on the surface when the device
// goes into it, sliding to the surface point nearest the device. The coupling spring between the
// device and this proxy gives the contact force; the proxy's hit says where the reaction goes.
//
// Per tick: free -> sweep proxy to device; a hit stops the proxy on the surface. In contact ->
// the goal is the device projected on the contact's tangent plane; the proxy moves there
// (sweeping again, so it cannot cross another surface), then is re-projected onto a curved
// surface with closest_point. If the device is outside the contact plane the proxy tries to
// follow it freely and leaves contact when the sweep is clear. A device found inside a surface
// without a sweep hit (a body moved onto it) puts the proxy on the closest surface point.
#pragma once

#include "tacta/haptics/surface_query.hpp"

namespace tacta::haptics {

struct GodObjectParams {
  double radius = 0.0;          // m, proxy sphere radius (tool tip)
  double skin = 1e-6;           // m, the proxy is kept this far outside the surface
  int max_iterations = 4;       // constraint updates per tick
  double inside_search = 0.02;  // m, how far closest_point looks for a device found inside
};

class GodObjectProxy {
 public:
  explicit GodObjectProxy(const GodObjectParams& params = {}) noexcept : params_(params) {}

  void reset(const Vec3& device_position) noexcept;
  // Moves the proxy for the new device position (m) and velocity (m/s).
  void update(const SurfaceQuery& world, const Vec3& device_position,
              const Vec3& device_velocity) noexcept;

  // The touched surface jumped by `displacement` (m) since the last tick (a body stepping on its
  // own thread was refreshed): the proxy rides along, so it is neither left inside a surface that
  // moved out (the inside search would then pick a far side face) nor left behind.
  void carry(const Vec3& displacement) noexcept {
    if (!in_contact_) return;
    position_ = add(position_, displacement);
    contact_.point = add(contact_.point, displacement);
  }

  // The touched surface's triangles were made again (a cut): the contact's triangle and weights
  // mean nothing now. The proxy stays where it is and finds the surface again by its next sweep
  // towards the device, so the force goes on without a jump where material is left.
  void surface_changed() noexcept { in_contact_ = false; }

  const Vec3& position() const noexcept { return position_; }
  // m/s: the device's velocity in free space, its tangential part while sliding in contact.
  const Vec3& velocity() const noexcept { return velocity_; }
  bool in_contact() const noexcept { return in_contact_; }
  const SurfaceHit& contact() const noexcept { return contact_; }  // valid when in_contact()

 private:
  // Proxy centre touching the surface at hit.point, on the side of `centre` (m); sets hit.normal
  // to the contact normal there.
  Vec3 on_surface(SurfaceHit& hit, const Vec3& centre) const noexcept;
  bool move_in_contact(const SurfaceQuery& world, const Vec3& device) noexcept;
  GodObjectParams params_;
  Vec3 position_{0.0, 0.0, 0.0};
  Vec3 velocity_{0.0, 0.0, 0.0};
  bool in_contact_ = false;
  SurfaceHit contact_{};
};

}  // namespace tacta::haptics
