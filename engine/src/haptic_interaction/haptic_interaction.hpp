// Haptic rendering between each device and the bodies, run before the bodies step, as four
// named stages of the tick (HapticLoop::tick calls them in this order): tool update, refit of
// the touched surfaces' hierarchies, proxy (god-object) query, coupling (first-contact shaping ->
// virtual coupling -> passivity controller -> force limit). The device gets F; the body gets -F
// on the touched triangle's nodes by barycentric weights (Newton's third law), and the collision
// layer sees the tool as a sphere at the proxy.
#pragma once

#include <chrono>
#include <vector>

#include "collision/collision_context.hpp"
#include "tacta/haptics/contact_renderer.hpp"
#include "world/world.hpp"

namespace tacta {

class CheckpointWriter;
class CheckpointReader;

// The haptic stage's parts in one tick, ms: bringing the touched surfaces up to date for the
// proxy (hierarchy refit, embedded vertices), the proxy's queries, and the rest (tool update,
// coupling, passivity, limits, the reaction on the body).
struct HapticParts {
  double surface_update = 0, proxy_query = 0, coupling = 0;
};

class HapticInteraction {
 public:
  HapticInteraction(World& world, CollisionContext& collision);
  // Tool update: a changed tool restarts its proxy; a device gone (or whose body went) renders
  // nothing; the tool's swept shape starts at the proxy; a body on its own thread hands its
  // latest state to the channel's local contact model.
  void update_tools(World& world) noexcept;
  // Refit: the touched surfaces' hierarchies brought up to date for the proxies' queries.
  void refit_surfaces(double time, double dt) noexcept;
  // Proxy: each rendering device's proxy follows it against the surfaces.
  void move_proxies(World& world) noexcept;
  // Coupling: each device's force, and its reaction on the touched body's nodes.
  void couple(World& world, double time, double dt) noexcept;
  // The renderer's energy observers integrate the force each device really held.
  void after_write(World& world) noexcept;
  // After the write, off the read-to-write path: the surfaces' hierarchies follow what the tick
  // moved, for the next tick's queries (CollisionContext::upkeep_for_proxy; `time`: the next
  // tick's start, s). Returns the TACTA_COLLIDE_* bits the refits raised.
  uint32_t upkeep_surfaces(double time, double dt) noexcept {
    collision_.upkeep_for_proxy(time, dt);
    return collision_.take_bits();
  }
  const HapticParts& parts() const noexcept { return parts_; }
  // Body `body`'s surface was made again by a cut (between ticks): proxies touching it let go of
  // their contact triangle and find the new surface at the next tick.
  void surface_changed(World& world, size_t body) noexcept;
  // Checkpoints: each device's channel (proxy, first contact, coupling, passivity, local model)
  // as plain bytes (checkpoint/loop_state.cpp). Between ticks only.
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in);
  // TACTA_COLLIDE_* bits the collision plugins returned to this tick's refit and queries.
  uint32_t collision_bits() const noexcept { return collision_bits_; }

 private:
  // What a channel keeps to render a body on its own thread through its local contact model
  // (tacta/haptics/local_compliance.hpp): the forces the worker's steps were driven with, and the
  // body's point stiffness as its refreshed states show it.
  struct LocalModel {
    int body = -1;  // the worker body these numbers are about
    uint64_t refreshes_seen = 0;
    Vec3 impulse{0, 0, 0};    // N s: device force summed over the ticks since the last post
    double impulse_time = 0;  // s
    Vec3 posted{0, 0, 0};     // N: mean device force the step in flight is driven with
    Vec3 felt{0, 0, 0};       // N: mean device force the refreshed state has felt
    double stiffness = 0;     // N/m: k_l, first the punch estimate, then measured
    bool pressing = false;    // a contact episode is on, with its onset material point:
    int onset_triangle = -1;
    double onset_barycentric[3] = {0, 0, 0};
    Vec3 onset_point{0, 0, 0};  // m, where that point was when the contact began
    Vec3 onset_normal{0, 0, 1};
    int triangle = -1;  // last contact triangle and the point's barycentric weights
    double barycentric[3] = {0, 0, 0};
  };
  struct Channel {  // one per device
    haptics::ContactRenderer renderer;
    bool started = false;
    LocalModel local;
    uint32_t tool_revision = 0;  // the device's Tool::revision this channel renders
    bool rendering = false;      // this tick: connected, with a body to touch
    Vec3 device{0, 0, 0};        // m, this tick's sample
    Vec3 velocity{0, 0, 0};      // m/s
  };
  void apply_reaction(World& world, const haptics::SurfaceHit& hit,
                      const Vec3& force_on_body) noexcept;
  // Before the renderer's tick: take in a refresh of the worker body, set the local model.
  void prepare_local_model(World& world, Channel& ch, const DeviceComponents& dev) noexcept;
  // After it: the force joins the period's impulse; a new contact records its onset point.
  void follow_local_model(World& world, Channel& ch, const haptics::ContactRendering& out,
                          double dt) noexcept;
  CollisionContext& collision_;
  std::vector<Channel> channels_;
  HapticParts parts_;
  uint32_t collision_bits_ = 0;
  std::chrono::steady_clock::time_point tools_start_, refit_start_, refit_end_;
};

// Contact response after the bodies step (bodies against obstacles, the tool, each other).
class CollisionResponse final {
 public:
  explicit CollisionResponse(CollisionContext& collision) : collision_(collision) {}
  // Contact response: detection and response rounds over the stepped bodies; returns this
  // tick's TACTA_COLLIDE_* bits (those of the hierarchies' updates included).
  uint32_t respond(double time, double dt) noexcept;
  uint32_t bits() const noexcept { return bits_; }  // every tick's, ORed
  uint64_t contacts_total() const noexcept { return contacts_total_; }

 private:
  CollisionContext& collision_;
  uint32_t bits_ = 0;
  uint64_t contacts_total_ = 0;
};

}  // namespace tacta
