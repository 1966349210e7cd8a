// A cut installed at tick boundaries while another thread draws, as a realtime run's render thread
// does: the cut's description and snapshot entries are made off the tick (prepare_picture) and
// installed with it (reshaped_at_tick); every frame must then pair a snapshot's arrays with the
// description of the revision they follow. Labelled for the ThreadSanitizer suite.
#include <atomic>
#include <chrono>
#include <thread>

#include "sim_test_support.hpp"
#include "timing/clock_session.hpp"
#include "world/body_cut.hpp"

namespace tacta::simtest {
namespace {

// Counts, on the render thread, frames whose description does not fit their snapshot.
class FitCheck final : public FrameObserver {
 public:
  void on_frame(const SceneStatic& scene, const Snapshot& s) override {
    ++frames;
    const BodyStatic& d = scene.bodies[0];
    const BodySnapshot& b = s.bodies[0];
    if (d.revision != b.revision || d.rest_positions.size() != b.positions.size() ||
        d.surface_rest_positions.size() != b.surface_positions.size() || d.triangles.empty())
      ++misfits;
    if (b.revision > 0 && d.surface_cut_triangles.empty()) ++misfits;  // the cut faces drawn
    revisions_seen |= 1u << std::min<uint32_t>(b.revision, 31);
  }
  int frames = 0, misfits = 0;
  uint32_t revisions_seen = 0;  // bit r: a frame of revision r
};

TEST(CutPicture, EveryFrameDrawsTheRevisionItsArraysFollow) {
  const SceneDesc scene =
      load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml", schemas());
  World world(scene, plugins());
  ClockSession session(world, nullptr, nullptr);
  FitCheck check;
  session.attach(&check);
  std::atomic<bool> done{false};
  std::thread render([&] {
    while (!done.load()) {
      session.render_task().frame(0.0);
      std::this_thread::sleep_for(std::chrono::microseconds(300));
    }
    session.render_task().frame(0.0);
  });
  HapticLoop& loop = session.loop();
  const double dt = 1.0 / scene.clock.haptic_rate_hz;
  uint64_t tick = 0;
  const auto run_ticks = [&](int n) {
    for (int i = 0; i < n; ++i, ++tick) {
      loop.tick(tick, static_cast<double>(tick) * dt, dt);
      if (tick % 2 == 0) loop.publish(static_cast<double>(tick + 1) * dt);
    }
  };
  // Incisions across the right lobe (planes x = const over its upper half), one every 30 ticks.
  const int cuts = 5;
  for (int k = 0; k < cuts; ++k) {
    run_ticks(30);
    const double x = -0.08 + 0.03 * k;
    const std::vector<double> blade = {x, 0.12, -0.1, x, 0.2, -0.1, x, 0.2,  0.1,
                                       x, 0.12, -0.1, x, 0.2, 0.1,  x, 0.12, 0.1};
    PreparedCut cut =
        prepare_cut(world, 0, blade, CutMode::kSeparate, world.body(0).nodes.positions);
    ASSERT_TRUE(cut.changed) << "cut " << k;
    PreparedPicture picture = session.prepare_picture(cut);
    run_ticks(3);  // the ticks go on while a worker would prepare
    apply_cut(world, cut, static_cast<double>(tick) * dt);
    session.reshaped_at_tick(picture);
    retire_cut(world, cut);
  }
  run_ticks(60);
  done.store(true);
  render.join();
  EXPECT_EQ(check.misfits, 0) << "frames whose description does not fit their arrays, of "
                              << check.frames;
  EXPECT_EQ(world.body(0).shape.cuts.revision, uint32_t{cuts});
  EXPECT_TRUE(check.revisions_seen & (1u << cuts)) << "the last revision was drawn";
  EXPECT_GT(check.frames, cuts);
  session.follow_reshaped_bodies();
  EXPECT_EQ(session.scene_static().bodies[0].revision, uint32_t{cuts})
      << "after the run the session's description follows the body";
  EXPECT_EQ(session.scene_static().bodies[0].rest_positions.size(),
            world.body(0).nodes.positions.size());
}

}  // namespace
}  // namespace tacta::simtest
