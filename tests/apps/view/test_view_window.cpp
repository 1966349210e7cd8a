// tacta-view driven under a virtual X server (the test binary runs inside xvfb-run): the
// liver palpation scene with the mouse as its device, a scripted model swap, a parameter change
// and a press with the mouse; then start-paused stepping; then cutting with the mouse's blade
// while the script holds C. Checks the screenshot is a real picture and the status JSON the
// viewer writes on exit.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <spawn.h>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

#include "tacta/render/image.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;

struct ViewRun {
  int exit_code = -1;
  std::string out, err;
};

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(TACTA_BINARY_DIR) / "test_output" / "apps_view" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs tacta-view in the source folder (scene paths are relative to it), output kept in `dir`.
ViewRun run_view(std::vector<std::string> args, const fs::path& dir) {
  args.insert(args.begin(), TACTA_VIEW);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string out = (dir / "stdout.txt").string(), err = (dir / "stderr.txt").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addchdir_np(&actions, TACTA_SOURCE_DIR);
  pid_t pid = 0;
  ViewRun run;
  if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) == 0) {
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  }
  posix_spawn_file_actions_destroy(&actions);
  run.out = read_text(out);
  run.err = read_text(err);
  return run;
}

// The status file tacta-view wrote on exit, parsed (null when it is missing or not JSON).
nlohmann::json read_status(const fs::path& file) {
  return nlohmann::json::parse(read_text(file), nullptr, false);
}

// Fraction of pixels that differ from the top-left background pixel by more than 30/255.
double non_background_fraction(const tacta::render::Image& image) {
  size_t differing = 0;
  const size_t pixels = image.rgba.size() / 4;
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c)
      if (std::abs(image.rgba[4 * p + c] - image.rgba[static_cast<size_t>(c)]) > 30) {
        ++differing;
        break;
      }
  return static_cast<double>(differing) / static_cast<double>(pixels);
}

TEST(TactaViewWindow, SwapsModelsAndPressesWithTheMouse) {
  const fs::path dir = fresh_dir("swap_and_press");
  // Frames at the window's 60 Hz: ~1.3 s. --quit-after is only a guard for slow (sanitizer) builds.
  const ViewRun run = run_view(
      {"scenes/liver_palpation.yaml", "--mouse", "--size", "640x400", "--quit-after", "60",
       "--screenshot", (dir / "view.png").string(), "--status", (dir / "status.json").string(),
       "--script",
       "5:set liver max_iterations 40; 10:swap liver mass_spring; 15:press 0.012 15; 75:quit"},
      dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  nlohmann::json status = read_status(dir / "status.json");
  ASSERT_TRUE(status.is_object()) << run.out << run.err;
  EXPECT_GE(status["frames"].get<int>(), 75);
  EXPECT_EQ(status["swaps_requested"].get<int>(), 2);
  EXPECT_EQ(status["swap_history"],
            nlohmann::json({"liver -> corotational_fem", "liver -> mass_spring"}));
  // The haptic side runs the swapped model: the name comes from the last snapshot.
  EXPECT_EQ(status["body_models"], nlohmann::json::array({"mass_spring"}));
  EXPECT_EQ(status["body_frozen"], nlohmann::json::array({false}));
  EXPECT_EQ(status["mouse"], true);
  EXPECT_EQ(status["script_failures"], nlohmann::json::array());
  EXPECT_EQ(status["run_error"], "");
  // The press reached the liver: the coupling rendered a force.
  EXPECT_GT(status["max_force_N"].get<double>(), 0.05) << status;
  EXPECT_GT(status["sim_time_s"].get<double>(), 0.1);

  const tacta::render::Image shot = tacta::render::read_png(dir / "view.png");
  EXPECT_EQ(shot.width, 640);
  EXPECT_EQ(shot.height, 400);
  EXPECT_GT(non_background_fraction(shot), 0.1) << "the screenshot looks blank";
}

TEST(TactaViewWindow, PausedStartAdvancesOnlyBySteps) {
  const fs::path dir = fresh_dir("paused_steps");
  const ViewRun run = run_view(
      {"scenes/liver_palpation.yaml", "--paused", "--size", "320x240", "--quit-after", "60",
       "--status", (dir / "status.json").string(), "--script", "5:step; 10:step; 40:quit"},
      dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  nlohmann::json status = read_status(dir / "status.json");
  ASSERT_TRUE(status.is_object()) << run.out << run.err;
  // The first picture is the state before any tick; each step goes on to the next frame, the
  // first tick at or past k/60 s: two steps are 34 ticks of 1 ms, nothing in between although
  // the window ran for 40 frames.
  EXPECT_NEAR(status["sim_time_s"].get<double>(), 0.034, 1e-9) << status;
  EXPECT_EQ(status["mouse"], false);  // the scene's own scripted stylus
}

// Realtime play alike for a scene without a blade (liver_palpation) and with one (mouse_scalpel).
TEST(TactaViewWindow, PauseStopsTheClockWhileTheWindowRuns) {
  for (const std::string scene : {"liver_palpation.yaml", "examples/mouse_scalpel.yaml"}) {
    const fs::path dir = fresh_dir("pause_" + fs::path(scene).stem().string());
    const ViewRun run = run_view({"scenes/" + scene, "--size", "320x240", "--quit-after", "60",
                                  "--status", (dir / "status.json").string(), "--script",
                                  "20:pause; 30:mark; 80:mark; 81:step; 90:mark; 91:step; 100:mark; 101:quit"},
                                 dir);
    ASSERT_EQ(run.exit_code, 0) << scene << run.err;
    nlohmann::json status = read_status(dir / "status.json");
    ASSERT_TRUE(status.is_object()) << run.out << run.err;
    // (frame, simulated time shown) ten frames after the pause and fifty frames later: it
    // played, then the clock stood still while the window ran on (at least 50/60 s of wall
    // time); then two Steps, each to the next frame: the first tick at or past k/60 s.
    ASSERT_EQ(status["marks"].size(), 4u) << status;
    double mark_frame[4], mark_time[4];
    for (size_t m = 0; m < 4; ++m) {
      mark_frame[m] = status["marks"][m][0].get<double>();
      mark_time[m] = status["marks"][m][1].get<double>();
    }
    EXPECT_EQ(mark_frame[0], 30);
    EXPECT_EQ(mark_frame[1], 80);
    EXPECT_GT(mark_time[0], 0.0) << scene << status;
    EXPECT_EQ(mark_time[1], mark_time[0]) << scene << status;
    // The pause shows the tick it stopped at (anywhere in a frame); the first step goes on at
    // most a frame period to a frame, the second a whole one: 16 or 17 ticks of 1 ms.
    const auto frame_tick = [](double time_s) {  // a 1/60 s boundary lies in (t - 1 ms, t]
      const double tick = std::round(time_s * 1000);
      const auto frames_by = [](double t) { return std::floor(60 * (t / 1000 + 1e-9)); };
      return frames_by(tick) > frames_by(tick - 1);
    };
    EXPECT_GT(mark_time[2], mark_time[1]) << scene << status;
    EXPECT_LE(mark_time[2] - mark_time[1], 0.017 + 1e-9) << scene << status;
    EXPECT_TRUE(frame_tick(mark_time[2])) << scene << status;
    EXPECT_GE(mark_time[3] - mark_time[2], 0.016 - 1e-9) << scene << status;
    EXPECT_LE(mark_time[3] - mark_time[2], 0.017 + 1e-9) << scene << status;
    EXPECT_TRUE(frame_tick(mark_time[3])) << scene << status;
    EXPECT_EQ(status["sim_time_s"].get<double>(), mark_time[3]);
  }
}

// scenes/examples/mouse_scalpel.yaml: the mouse holds a blade; Play runs realtime runs, which cut
// off the haptic tick. The stylus is pressed onto the liver's top, then dragged
// sideways: with C held (the script's keydown) the blade's button is held and the liver is cut
// (its mesh revision moves on); the same drag without C cuts nothing.
TEST(TactaViewWindow, HoldingCCutsWithTheMouseBlade) {
  const std::string press = "5:press 0.01 20; 28:release; ";
  for (const bool hold_c : {true, false}) {
    const fs::path dir = fresh_dir(hold_c ? "cut_with_c" : "drag_without_c");
    const std::string script = hold_c
                                   ? press + "30:keydown c; 32:drag 120 0 50; 90:keyup c; 100:quit"
                                   : press + "32:drag 120 0 50; 100:quit";
    const ViewRun run =
        run_view({"scenes/examples/mouse_scalpel.yaml", "--size", "640x400", "--quit-after", "60",
                  "--status", (dir / "status.json").string(), "--script", script},
                 dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    nlohmann::json status = read_status(dir / "status.json");
    ASSERT_TRUE(status.is_object()) << run.out << run.err;
    EXPECT_EQ(status["run_error"], "");
    EXPECT_EQ(status["script_failures"], nlohmann::json::array());
    ASSERT_EQ(status["body_revisions"].size(), 1u) << status;
    if (hold_c) {
      EXPECT_GE(status["cut_key_frames"].get<int>(), 60) << status;  // frames 30 to 89
      EXPECT_GT(status["body_revisions"][0].get<int>(), 0) << status;
    } else {
      EXPECT_EQ(status["cut_key_frames"].get<int>(), 0) << status;
      EXPECT_EQ(status["body_revisions"][0].get<int>(), 0) << status;
    }
  }
}

TEST(TactaViewWindow, BadScriptIsBadInput) {
  const fs::path dir = fresh_dir("bad_script");
  const ViewRun run = run_view({"scenes/liver_palpation.yaml", "--script", "3:fly away"}, dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("unknown verb 'fly'"), std::string::npos) << run.err;
}

}  // namespace
