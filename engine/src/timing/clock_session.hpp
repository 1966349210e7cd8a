// The persistent clock of a Simulation: the haptic loop with its records, the snapshot buffer
// and the render task, built at the first step or run and kept until the Simulation closes, so
// that step(), advance_to() and run() all continue one timeline from t = 0.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "collision/collision_context.hpp"
#include "haptic_interaction/haptic_interaction.hpp"
#include "systems/haptic_loop.hpp"
#include "tacta/sim/scheduler.hpp"
#include "tacta/sim/snapshot.hpp"
#include "tacta/sim/triple_buffer.hpp"
#include "timing/body_descriptions.hpp"
#include "world/world.hpp"

namespace tacta {

class CheckpointWriter;
class CheckpointReader;

// Hands the newest snapshot to the observers at each frame (frames, VTK, a window, Python), with
// the scene description its arrays follow.
class ObserverRenderTask final : public RenderTask {
 public:
  ObserverRenderTask(TripleBuffer<Snapshot>& snapshots, const SceneStatic& scene,
                     const DescriptionChains& chains)
      : snapshots_(snapshots), scene_(scene), chains_(chains) {}
  void frame(double /*wall_time*/) override {
    if (!snapshots_.acquire()) return;
    const Snapshot& s = snapshots_.read_slot();
    const SceneStatic& scene = follow(s);
    for (FrameObserver* o : observers) o->on_frame(scene, s);
  }
  std::vector<FrameObserver*> observers;  // changed only between steps and runs

 private:
  // The session's description, or where a body's entry follows another revision (a cut installed
  // while this thread draws, whose description the session's takes only after the run) a copy
  // with that revision's description from the chains. Allocates only when a revision moves.
  const SceneStatic& follow(const Snapshot& s);
  TripleBuffer<Snapshot>& snapshots_;
  const SceneStatic& scene_;  // not changed while a run's render thread reads it
  const DescriptionChains& chains_;
  SceneStatic view_;
};

// The render side of a cut prepared off the tick (ClockSession::prepare_picture).
struct PreparedPicture {
  size_t slot = 0;
  std::unique_ptr<DescribedRevision> description;  // null: the cut changed nothing
  std::array<BodySnapshot, 3> entries;             // one per snapshot slot
};

// Work the thread that runs lockstep ticks does between two of them (Simulation's cut events).
class BetweenTicks {
 public:
  virtual ~BetweenTicks() = default;
  // s: the earliest time something is due; infinity when nothing is.
  virtual double next_due_s() const noexcept = 0;
  // Does what is due by `time` (s); may allocate. What cannot be done is reported (a warning),
  // not thrown: the run goes on.
  virtual void run_due(double time) = 0;
  // After a tick that ended at `time` (s), of `dt` (s): what is due by then, to half a tick.
  void after_tick(double time, double dt) {
    if (time + 0.5 * dt >= next_due_s()) run_due(time);
  }
};

// Work the haptic thread does at the boundary before each realtime tick (a cut prepared off the
// tick is installed there). start() and finish() bracket a realtime run on the thread that
// calls run(): finish makes what fell due by `time` (s), the run's end, and installs it.
class AtTickBoundary {
 public:
  virtual ~AtTickBoundary() = default;
  virtual void start() = 0;
  virtual void at_boundary(double time) noexcept = 0;  // allocates nothing, throws nothing
  virtual void finish(double time) noexcept = 0;
};

class ClockSession {
 public:
  // Calls each model's begin() with the body's initial state; `haptics` and `response` may be null.
  ClockSession(World& world, HapticInteraction* haptics, CollisionResponse* response);
  ~ClockSession();

  // Grows every record buffer for `ticks` more ticks (allocates; outside the 1 kHz path).
  void reserve(uint64_t ticks);
  // Lockstep ticks on the calling thread from the current time, frames at every 1/render_rate
  // of simulated time; returns the ticks run (fewer when the loop ends the run).
  uint64_t step(uint64_t ticks, const std::atomic<bool>* stop = nullptr);
  // What the ticks of the last step() raised, OR-ed over them.
  const TickStatus& step_status() const noexcept { return step_status_; }
  // A batch on `options`' clock from the current time; the clock advances by the ticks it ran.
  ScheduleResult run(const ScheduleOptions& options);

  // A body added between steps (lockstep, not during run()): its render description and snapshot
  // entries are made here (allocates), so frames, VTK and observers show it once it enters.
  void add_body(size_t slot);
  // A body a cut reshaped (between steps): its render description and snapshot entries are made
  // again for its new mesh (allocates); observers see the new revision from the next frame.
  void body_reshaped(size_t slot);

  // A cut's picture made off the tick (allocates; any thread, the body's mesh unchanged since
  // prepare_cut), then installed at the tick boundary where apply_cut installs the cut (allocates
  // nothing): the render task draws the new revision from the first snapshot that follows it.
  // `picture` gets back what it replaced, to be freed off the tick.
  PreparedPicture prepare_picture(const PreparedCut& cut) const;
  void reshaped_at_tick(PreparedPicture& picture) noexcept;
  // After a run that installed cuts at tick boundaries: the session's description takes their
  // revisions (allocates; the render thread has stopped).
  void follow_reshaped_bodies();
  // The task that hands snapshots to the observers (the render thread's, in a realtime run).
  RenderTask& render_task() noexcept { return render_; }

  // What runs between lockstep ticks (not owned; null: nothing). A realtime run never calls it:
  // its ticks run on a thread that must not allocate (Simulation::run refuses such a run).
  void set_between_ticks(BetweenTicks* work) noexcept { between_ = work; }
  // What a realtime run does at its tick boundaries (not owned; null: nothing).
  void set_at_tick_boundary(AtTickBoundary* work) noexcept { at_boundary_ = work; }

  // Checkpoints: the clock (tick, frames, the next frame boundary) and the loop's state
  // (checkpoint/loop_state.cpp). Between steps only.
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in);

  uint64_t tick() const noexcept { return tick_; }
  double dt() const noexcept { return dt_; }
  double time() const noexcept { return static_cast<double>(tick_) * dt_; }
  HapticLoop& loop() noexcept { return loop_; }
  const HapticLoop& loop() const noexcept { return loop_; }
  const SceneStatic& scene_static() const noexcept { return scene_static_; }
  // The schedule figures of everything run so far (ticks, frames, tick durations, memory).
  ScheduleResult totals() const;
  // Observers told of every frame from now on (on_start is called here).
  void attach(FrameObserver* observer);
  void detach(FrameObserver* observer);
  std::vector<FrameObserver*>& observers() noexcept { return render_.observers; }
  std::vector<double> initial_energy_J;  // per body: kinetic + elastic at t = 0

 private:
  void start_workers(bool lockstep, uint64_t ticks);

  World& world_;
  double dt_;
  uint64_t tick_ = 0;
  FrameClock frame_clock_;  // 1/render_rate boundaries of simulated time, for step()
  SceneStatic scene_static_;
  TripleBuffer<Snapshot> snapshots_;
  HapticLoop loop_;
  DescriptionChains chains_;  // per body slot: revisions installed at tick boundaries
  ObserverRenderTask render_;
  std::unique_ptr<FrameObserver> surface_feed_;  // remote devices' surface, when any
  TickStatus step_status_;
  TickRecorder step_ms_;     // durations of stepped ticks
  ScheduleResult last_run_;  // the last run()'s schedule figures
  uint64_t frames_ = 0;
  int workers_mode_ = -1;  // -1 none, 0 realtime, 1 lockstep
  BetweenTicks* between_ = nullptr;
  AtTickBoundary* at_boundary_ = nullptr;
};

SceneStatic describe_scene(World& world);

}  // namespace tacta
