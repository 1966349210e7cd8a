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

 private:
  struct Channel {  // one per device
    haptics::ContactRenderer renderer;
    bool started = false;
  };
  void apply_reaction(World& world, const haptics::SurfaceHit& hit, const Vec3& force_on_body) noexcept;
  CollisionContext& collision_;
  std::vector<Channel> channels_;
};

// Contact response after the bodies step (bodies against obstacles, the tool, each other).
class CollisionResponse final : public Interaction {
 public:
  explicit CollisionResponse(CollisionContext& collision) : collision_(collision) {}
  void before_step(World&, double, double) noexcept override {}
  void after_step(World& world, double time, double dt) noexcept override;
  uint32_t bits() const noexcept { return bits_; }
  uint64_t contacts_total() const noexcept { return contacts_total_; }

 private:
  CollisionContext& collision_;
  uint32_t bits_ = 0;
  uint64_t contacts_total_ = 0;
};

}  // namespace tacta
