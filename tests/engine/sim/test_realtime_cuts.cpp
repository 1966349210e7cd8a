// Cuts in realtime runs (simulation/realtime_cuts.hpp): prepared on a worker thread, installed at
// a tick boundary, drawn by another thread. First the picture alone: a cut's description and
// snapshot entries made off the tick (prepare_picture) and installed with it (reshaped_at_tick)
// while another thread draws; every frame must pair a snapshot's arrays with the description of
// the revision they follow. Then whole realtime runs from scene files. Labelled for the
// ThreadSanitizer suite.
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <thread>

#include "cut_beam_scene.hpp"
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
    PreparedCut cut = prepare_cut(world, 0, blade, CutMode::kSeparate,
                                  world.body(0).nodes.positions, world.body(0).nodes.velocities);
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

nlohmann::json report_in(const std::string& dir) {
  std::ifstream in(dir + "/report.json");
  return nlohmann::json::parse(in);
}

// The scalpel of cut_beam_scene.hpp in a realtime run: its sweep is cut off the tick and the beam
// parts at x = 0.05, as in lockstep; the picture and the VTK series follow the new mesh. Without
// gravity: a sweep waiting behind a cut in flight is tested against the beam as it stands when
// it is posted, and where preparing takes tens of ms (ASan) a partly cut beam sagging meanwhile
// lets later strokes pass below faces they crossed (docs/ARCHITECTURE.md, "Not there yet").
TEST(RealtimeCut, ABladeCutsTheBeamInTwo) {
  SceneDesc scene = scene_from_text(beam_scene("corotational_fem", kScalpelDevice), "cut_beam");
  scene.output.vtk = true;
  scene.gravity = {0, 0, 0};
  Simulation sim(scene, plugins());
  RunOptions options;
  options.realtime = true;
  options.duration_s = 0.25;
  options.out_dir = fresh_dir("realtime_blade");
  const RunResult r = sim.run(options);
  EXPECT_EQ(r.mode, "realtime");
  EXPECT_EQ(r.faults, 0u);
  const BodyHandle beam = sim.body("beam");
  EXPECT_GT(sim.body_revision(beam), 0u);
  EXPECT_TRUE(Pieces(sim.body_mesh(beam)).in_two()) << "the clamped end and the tip are apart";
  const nlohmann::json report = report_in(options.out_dir);
  EXPECT_GT(report["devices"][0]["blade"]["cuts"].get<int>(), 0);
  EXPECT_EQ(report["devices"][0]["blade"]["cuts_refused"], 0);
  EXPECT_GT(report["bodies"][0]["cuts"]["wall_ms_max"].get<double>(), 0.0)
      << "the time from the sweep's end to the new mesh in place";
  // After the run the description the API hands out is the cut mesh's.
  EXPECT_EQ(sim.scene_static().bodies[0].revision, sim.body_revision(beam));
  EXPECT_EQ(sim.scene_static().bodies[0].rest_positions.size(), 3 * sim.body_arrays(beam).nodes);
}

// A scene's cut events in a realtime run: each is cut off the tick at its time; a later lockstep
// step goes on from the cut mesh. Without gravity, so the piece cut free stays where the second
// blade expects it however late that cut is posted (a loaded ASan build: tens of ms).
TEST(RealtimeCut, SceneEventsAreCutAndSteppingGoesOn) {
  const std::string events = R"(
events:
  - {time: 0.03, cut: {body: beam, mode: separate, quad: [[0.05, -1, -1], [0.05, 1, -1], [0.05, 1, 1], [0.05, -1, 1]]}}
  - {time: 0.06, cut: {body: beam, mode: remove, quad: [[0.085, -1, -1], [0.085, 1, -1], [0.085, 1, 1], [0.085, -1, 1]]}}
)";
  SceneDesc scene = scene_from_text(beam_scene("corotational_fem", events), "cut_beam");
  scene.gravity = {0, 0, 0};
  Simulation sim(scene, plugins());
  RunOptions options;
  options.realtime = true;
  options.duration_s = 0.1;
  options.out_dir = fresh_dir("realtime_events");
  sim.run(options);
  const BodyHandle beam = sim.body("beam");
  EXPECT_EQ(sim.body_revision(beam), 2u);
  const nlohmann::json cuts = report_in(options.out_dir)["bodies"][0]["cuts"];
  EXPECT_EQ(cuts["nodes_added"], 9);
  const double cell_mass = 1000 * 0.01 * 0.01 * 0.01;  // kg: density x one cell's volume
  EXPECT_NEAR(cuts["removed_mass_kg"].get<double>(), 4 * cell_mass, 1e-12)
      << "the layer of 2 x 2 cells the second blade crosses";
  EXPECT_TRUE(Pieces(sim.body_mesh(beam)).in_two());
  EXPECT_EQ(sim.step(50).ticks, 50u);
  EXPECT_EQ(sim.body_revision(beam), 2u);
}

// A beam with a sliding face and a lifted tip (cut_beam_scene.hpp's kPrescribedBeam) separated
// at the sliding face by a cut event in a realtime run: the cut is prepared while the boundary
// motion is stepped on the haptic thread, and both sides of the cut keep their motion.
TEST(RealtimeCut, PrescribedAndSlidingNodesKeepTheirMotion) {
  const std::string events = R"(
events:
  - {time: 0.05, cut: {body: beam, mode: separate, quad: [[0.05, -1, -1], [0.05, 1, -1], [0.05, 1, 1], [0.05, -1, 1]]}}
)";
  SceneDesc scene =
      scene_from_text(beam_scene("corotational_fem", kPrescribedBeam + events), "cut_beam");
  scene.gravity = {0, 0, 0};  // the face stays on the blade's plane however late the cut is posted
  Simulation sim(scene, plugins());
  RunOptions options;
  options.realtime = true;
  options.duration_s = 0.15;
  const RunResult r = sim.run(options);
  EXPECT_EQ(r.faults, 0u);
  const BodyHandle beam = sim.body("beam");
  ASSERT_EQ(sim.body_revision(beam), 1u);
  const BodyArrays a = sim.body_arrays(beam);
  const std::vector<double>& rest = sim.body_mesh(beam).positions;
  size_t sliding = 0, tip = 0;
  for (size_t n = 0; n < a.nodes; ++n) {
    if (std::abs(rest[3 * n] - 0.05) < 1e-9) {
      ++sliding;
      EXPECT_NEAR(a.positions[3 * n + 1], rest[3 * n + 1], 1e-12) << "node " << n;
    }
    if (std::abs(rest[3 * n] - 0.1) < 1e-9) {
      ++tip;
      const double lift = 0.005 * sim.time() / 0.2;  // the ramp at this time, m
      EXPECT_NEAR(a.positions[3 * n + 2], rest[3 * n + 2] + lift, 1e-12) << "node " << n;
    }
  }
  EXPECT_EQ(sliding, 18u) << "the face's 9 nodes and their 9 copies";
  EXPECT_EQ(tip, 9u);
}

}  // namespace
}  // namespace tacta::simtest
