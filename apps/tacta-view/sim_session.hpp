// Runs a Simulation for the window on a worker thread, and hands the newest snapshot to the GUI.
//
// Play: realtime runs (haptic thread at 1 kHz, render task at the scene's frame rate) of
// kSessionSeconds each, one after another while playing. Pause: request_stop() ends the run
// after its current tick; the world keeps its state, so the picture stays and Play goes on from
// it. Step (while paused): ticks on this worker up to the next frame the render task is given
// (at most one frame period), so the picture shows where the clock is. Runs and steps
// continue the Simulation's one clock, so the GUI sees a continuous time.
//
// The snapshot slot's mutex is shared by the render task's thread (or this worker, in a step)
// and the GUI thread only: the haptic thread never sees it. The scene description in the slot
// follows the snapshots: it is replaced when a body was cut or added.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "tacta/sim/simulation.hpp"
#include "tacta/sim/snapshot.hpp"

namespace tacta::view {

class SimSession final : public FrameObserver {
 public:
  static constexpr double kSessionSeconds = 60;  // s of one realtime run (bounds its records)

  // `before_first_tick` runs on the worker once, with the scene, before the first tick (e.g. to
  // place the mouse device's target).
  SimSession(Simulation& simulation, double frame_period_s,
             std::function<void(const SceneStatic&)> before_first_tick = {});
  ~SimSession() override;  // stops the run and joins the worker
  SimSession(const SimSession&) = delete;
  SimSession& operator=(const SimSession&) = delete;

  void play();
  void pause();
  void step();  // to the next frame (at most one frame period), only while paused
  bool playing() const;
  bool running() const { return running_.load(std::memory_order_acquire); }

  // Copies the newest snapshot (time made continuous across runs) into `out`; false when none
  // arrived since the last call. When the scene description changed since `scene_version` (a
  // cut or an added body), copies it into `scene` too and updates `scene_version`.
  bool take_latest(Snapshot& out, SceneStatic& scene, uint64_t& scene_version);
  // The scene description from the first run; false before it started.
  bool scene(SceneStatic& out) const;
  // The message of an exception a run threw (the session is then paused), else empty.
  std::string error() const;

  void on_start(const SceneStatic& scene) override;
  void on_frame(const SceneStatic& scene, const Snapshot& snapshot) override;

 private:
  enum class Mode { Paused, Playing, Quitting };
  void work();

  Simulation& simulation_;
  const double frame_period_s_;
  std::function<void(const SceneStatic&)> before_first_tick_;
  std::atomic<bool> running_{false};
  std::atomic<uint64_t> frames_seen_{0};  // on_frame calls; a step ends at the next one

  mutable std::mutex command_mutex_;  // GUI thread and worker
  std::condition_variable wake_;
  Mode mode_ = Mode::Paused;
  int pending_steps_ = 0;
  std::string error_;

  mutable std::mutex slot_mutex_;  // render task (or worker) and GUI thread
  Snapshot slot_;
  bool slot_new_ = false;
  SceneStatic scene_;
  bool have_scene_ = false;
  uint64_t scene_version_ = 0;  // +1 each time scene_ is replaced after the first

  std::thread worker_;  // last: started once everything above exists
};

}  // namespace tacta::view
