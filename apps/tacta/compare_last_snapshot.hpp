// A frame observer that keeps the newest snapshot and the scene's static description. In lockstep
// the scheduler publishes the state after the last tick, so after Simulation::run() `last()` is
// the final state: what `tacta compare` reads the probe from and `tacta snapshot` draws.
#pragma once

#include "tacta/sim/snapshot.hpp"

namespace tacta::cli {

class LastSnapshotKeeper final : public FrameObserver {
 public:
  void on_start(const SceneStatic& scene) override { scene_ = scene; }
  // Copy-assignment reuses the buffers after the first frame: at most one allocation a body.
  void on_frame(const SceneStatic& /*scene*/, const Snapshot& snapshot) override {
    last_ = snapshot;
    ++frames_;
  }

  const SceneStatic& scene() const { return scene_; }
  const Snapshot& last() const { return last_; }
  bool has_frame() const { return frames_ > 0; }

 private:
  SceneStatic scene_;
  Snapshot last_;
  unsigned long frames_ = 0;
};

}  // namespace tacta::cli
