// Cuts in a realtime run, whose ticks must not allocate. At a tick boundary the haptic thread sees
// what fell due (a scene cut event, a blade's sweep), copies what the cut needs (the blade, the
// body's positions, the collision view) into buffers reserved off the tick and posts it; a worker
// thread makes everything that allocates (prepare_cut, the collision surface and plugin
// instances built over the copy, the picture); the haptic thread installs the result at the first
// boundary after it is ready (apply_cut, apply_replacement, reshaped_at_tick), and the worker then
// frees what it replaced and reserves the buffers for the next cut. One cut is in flight at a
// time; what falls due meanwhile waits (a blade keeps sweeping into its buffer).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <span>
#include <thread>
#include <vector>

#include "collision/collision_context.hpp"
#include "haptic_interaction/haptic_interaction.hpp"
#include "timing/clock_session.hpp"
#include "world/body_cut.hpp"

namespace tacta {

class SceneCuts;

class RealtimeCuts final : public AtTickBoundary {
 public:
  // `collision` and `haptics` may be null (no device, no collision).
  RealtimeCuts(World& world, SceneCuts& schedule, CollisionContext* collision,
               HapticInteraction* haptics, ClockSession& clock);
  ~RealtimeCuts() override;
  RealtimeCuts(const RealtimeCuts&) = delete;
  RealtimeCuts& operator=(const RealtimeCuts&) = delete;

  void start() override;                            // reserves the buffers, starts the worker
  void at_boundary(double time) noexcept override;  // haptic thread
  // The haptic thread has stopped: what fell due by `time` is made and installed, the worker
  // joined.
  void finish(double time) noexcept override;

 private:
  enum State : uint32_t { kIdle, kPosted, kReady, kApplied, kStop };
  // What the haptic thread posts: one body's cut.
  struct Request {
    size_t slot = 0;
    int device = -1;  // the blade's device, -1: a scene event
    CutMode mode = CutMode::kSeparate;
    const BodyEventDesc* event = nullptr;  // the scene event asking, null: a blade
    std::span<const double> triangles;     // 9 per triangle, m: the event's, or sweep_
    std::vector<double> positions;         // the body's nodes then, 3 per node, m
    std::vector<double> velocities;        // and their velocities, m/s
    ViewCopy view;
    std::chrono::steady_clock::time_point asked;
  };
  // What the worker hands back; after the install it holds what was replaced.
  struct Prepared {
    bool ok = false;         // prepared; false: refused (the worker said why)
    bool installed = false;  // apply_cut ran: retire_cut keeps what it replaced
    PreparedCut cut;
    SurfaceReplacement surface;
    PreparedPicture picture;
  };
  void run() noexcept;  // the worker thread
  void prepare() noexcept;
  void reserve();  // the worker, between cuts: room for the next request
  bool post_next(double time) noexcept;
  bool post(size_t slot, int device, const BodyEventDesc* event, std::span<const double> triangles,
            CutMode mode) noexcept;
  void install(double time) noexcept;
  void hand_over(State to) noexcept {
    state_.store(to, std::memory_order_release);
    state_.notify_all();
  }

  World& world_;
  SceneCuts& schedule_;
  CollisionContext* collision_;
  HapticInteraction* haptics_;
  ClockSession& clock_;
  std::atomic<uint32_t> state_{kIdle};
  Request request_;
  Prepared prepared_;
  // A blade's sweep being cut body by body: its triangles (reserved like the blade's), the
  // device, the next body slot to look at; `sweeping_` false when none.
  std::vector<double> sweep_;
  size_t sweep_device_ = 0, sweep_next_ = 0;
  bool sweeping_ = false;
  bool repost_ = false;          // the last cut no longer fit its body (a model swap came first)
  std::vector<uint8_t> warned_;  // per device: a refusal of its blade was logged
  std::thread worker_;
};

}  // namespace tacta
