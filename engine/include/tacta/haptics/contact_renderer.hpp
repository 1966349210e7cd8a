// One tool rendered against the world for one device, per haptic tick (1 kHz path: noexcept, no
// allocation): god-object proxy -> first-contact stretch limit -> virtual coupling -> passivity
// controller -> device force limit. Also keeps the per-device numbers report.json wants.
//
// Newton's third law: the reaction for the touched body is exactly minus the force sent to the
// device (after limiting and the passivity damper), applied at the proxy's contact point, so the
// force felt and the force that deforms the body agree. Out of contact the device force is zero
// and the passivity controller is idle (no drag in free space).
#pragma once

#include "tacta/haptics/first_contact.hpp"
#include "tacta/haptics/force_limiter.hpp"
#include "tacta/haptics/god_object.hpp"
#include "tacta/haptics/local_compliance.hpp"
#include "tacta/haptics/passivity.hpp"
#include "tacta/haptics/virtual_coupling.hpp"

namespace tacta::haptics {

struct ContactStatsParams {
  double onset_window = 0.25;  // s after the first contact begins: its peak is first_contact_peak
  double settle_delay = 0.4;   // s after the first onset at which the steady window starts
  double steady_window = 0.1;  // s over which the force is averaged for steady_contact
};

struct ContactRendererParams {
  VirtualCouplingParams coupling{};
  GodObjectParams proxy{};
  bool first_contact_enabled = true;
  FirstContactParams first_contact{};
  PassivityParams passivity{};
  double peak_force = 3.3;  // N, the device's declared peak (capabilities.peak_force)
  ContactStatsParams stats{};
};

// The per-device report numbers (N, J).
struct ContactStats {
  double max_force = 0.0;               // N, largest force sent
  double force_limit = 0.0;             // N, the peak it was limited to
  double first_contact_peak = 0.0;      // N, largest force in the onset window of the first contact
  double steady_contact = 0.0;          // N, mean force in the steady window of the first contact
  double energy_injected = 0.0;         // J, worst energy the coupling returned beyond what it took
  double first_contact_time = -1.0;     // s, -1 before any contact
  unsigned long non_finite_forces = 0;  // ticks where a NaN/inf force was zeroed
  unsigned long limited_forces = 0;     // ticks where the force was scaled down to the peak
};

struct ContactRendering {
  Vec3 device_force{0.0, 0.0, 0.0};   // N, to write to the device
  Vec3 body_reaction{0.0, 0.0, 0.0};  // N, on the touched body at contact.point (= -device_force)
  bool in_contact = false;
  SurfaceHit contact{};  // valid when in_contact
};

class ContactRenderer {
 public:
  explicit ContactRenderer(const ContactRendererParams& params = {}) noexcept;

  void reset(const Vec3& device_position) noexcept;
  // time (s) of this tick, measured device position (m) and velocity (m/s), tick dt (s).
  // tick() is move_proxy() then couple(): a host with several devices runs every proxy, then
  // every coupling, as named stages of its tick.
  ContactRendering tick(const SurfaceQuery& world, double time, const Vec3& device_position,
                        const Vec3& device_velocity, double dt) noexcept;
  // The proxy follows the device against the world; a non-finite sample leaves it where it was
  // (and makes the next couple() send zero).
  void move_proxy(const SurfaceQuery& world, const Vec3& device_position,
                  const Vec3& device_velocity) noexcept;
  // The coupling force (N) between the proxy as move_proxy() left it and the device.
  ContactRendering couple(double time, const Vec3& device_position, const Vec3& device_velocity,
                          double dt) noexcept;

  // The touched body's local contact model for the next ticks (a body on its own thread); the
  // default, inactive, renders the surface as the proxy finds it.
  void set_local_compliance(const LocalCompliance& local) noexcept { local_ = local; }
  // The touched surface jumped by `displacement` (m) before this tick (GodObjectProxy::carry).
  void carry_proxy(const Vec3& displacement) noexcept { proxy_.carry(displacement); }
  // The touched surface was cut (GodObjectProxy::surface_changed).
  void surface_changed() noexcept { proxy_.surface_changed(); }
  const ContactStats& stats() const noexcept { return stats_; }
  const GodObjectProxy& proxy() const noexcept { return proxy_; }
  const PassivityController& passivity() const noexcept { return passivity_; }
  // J: energy the coupling (spring, damper, limits) has taken from the device and the body in
  // the current contact; the first-contact limit never lets its spring hold more.
  double coupling_energy() const noexcept { return coupling_energy_; }
  // When the host sends something else than tick()'s device_force (a fault zeroes it), it says
  // so here, so that the energy observers integrate the force the device really held (N).
  void override_sent(const Vec3& force) noexcept {
    passivity_.record_sent(force);
    last_sent_ = force;
  }

 private:
  void update_stats(double time, double force) noexcept;
  // Updates the coupling's energy ledger for this contact tick; returns the largest stretch (m)
  // whose spring energy it covers (the first-contact limit's budget).
  double onset_budget(const Vec3& stretch) noexcept;
  ContactRendererParams params_;
  GodObjectProxy proxy_;
  FirstContactLimiter onset_;
  VirtualCoupling coupling_;
  PassivityController passivity_;
  ForceLimiter limiter_;
  ContactStats stats_{};
  LocalCompliance local_{};
  double steady_sum_ = 0.0;
  unsigned long steady_count_ = 0;
  Vec3 last_stretch_{0.0, 0.0, 0.0};  // m, proxy - device at the last contact tick
  Vec3 last_sent_{0.0, 0.0, 0.0};     // N, the force sent last tick (held over this one)
  double coupling_energy_ = 0.0;      // J, energy the coupling has taken in this contact
  bool was_in_contact_ = false;
  bool sample_finite_ = true;  // the sample move_proxy() last saw
};

}  // namespace tacta::haptics
