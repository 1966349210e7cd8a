// Haptic rendering between each device and the bodies, run before the bodies step:
// proxy (god-object) on the touched surface -> first-contact shaping -> virtual coupling ->
// passivity controller -> force limit. The device gets F; the body gets -F on the touched
// triangle's nodes by barycentric weights (Newton's third law), and the collision layer sees the
// tool as a sphere at the proxy.
#pragma once

#include <vector>

#include "collision_context.hpp"
#include "haptic_loop.hpp"
#include "tacta/haptics/contact_renderer.hpp"

namespace tacta {

class HapticInteraction final : public Interaction {
 public:
  HapticInteraction(World& world, CollisionContext& collision);
  void before_step(World& world, double time, double dt) noexcept override;
  void after_step(World& world, double time, double dt) noexcept override;
  // The renderer's energy observers integrate the force each device really held.
  void after_write(World& world) noexcept override;
  const HapticParts* haptic_parts() const noexcept override { return &parts_; }

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
  };
  // Each device's proxy, coupling and reaction for this tick.
  void render_devices(World& world, double time, double dt) noexcept;
  void apply_reaction(World& world, const haptics::SurfaceHit& hit,
                      const Vec3& force_on_body) noexcept;
  // Before the renderer's tick: take in a refresh of the worker body, set the local model.
  void prepare_local_model(World& world, Channel& ch, const DeviceSlot& slot) noexcept;
  // After it: the force joins the period's impulse; a new contact records its onset point.
  void follow_local_model(World& world, Channel& ch, const haptics::ContactRendering& out,
                          double dt) noexcept;
  CollisionContext& collision_;
  std::vector<Channel> channels_;
  HapticParts parts_;
};

// Contact response after the bodies step (bodies against obstacles, the tool, each other).
class CollisionResponse final : public Interaction {
 public:
  explicit CollisionResponse(CollisionContext& collision) : collision_(collision) {}
  void before_step(World&, double, double) noexcept override { tick_bits_ = 0; }
  void after_step(World& world, double time, double dt) noexcept override;
  uint32_t collision_bits() const noexcept override { return tick_bits_; }
  uint32_t bits() const noexcept { return bits_; }  // every tick's, ORed
  uint64_t contacts_total() const noexcept { return contacts_total_; }

 private:
  CollisionContext& collision_;
  uint32_t bits_ = 0;
  uint32_t tick_bits_ = 0;
  uint64_t contacts_total_ = 0;
};

}  // namespace tacta
