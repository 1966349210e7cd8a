// tacta-view driven under a virtual X server (the test binary runs inside xvfb-run): the
// liver palpation scene with the mouse as its device, a scripted model swap, a parameter change
// and a press with the mouse; then start-paused stepping. Checks the screenshot is a real
// picture and the status JSON the viewer writes on exit.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
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

// The text after "key": up to the end of its line, without the trailing comma (the status JSON
// has one key a line); empty when absent. (No std::regex: GCC 12 warns inside it under ASan.)
std::string json_raw(const std::string& json, const std::string& key) {
  const std::string label = "\"" + key + "\": ";
  const size_t at = json.find(label);
  if (at == std::string::npos) return "";
  std::string value = json.substr(at + label.size(), json.find('\n', at) - at - label.size());
  if (!value.empty() && value.back() == ',') value.pop_back();
  return value;
}

double json_number(const std::string& json, const std::string& key) {
  const std::string raw = json_raw(json, key);
  return raw.empty() ? std::nan("") : std::strtod(raw.c_str(), nullptr);
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
  const std::string status = read_text(dir / "status.json");
  ASSERT_FALSE(status.empty()) << run.out << run.err;
  EXPECT_GE(json_number(status, "frames"), 75);
  EXPECT_EQ(json_number(status, "swaps_requested"), 2);
  EXPECT_EQ(json_raw(status, "swap_history"),
            R"(["liver -> corotational_fem", "liver -> mass_spring"])");
  // The haptic side runs the swapped model: the name comes from the last snapshot.
  EXPECT_EQ(json_raw(status, "body_models"), R"(["mass_spring"])");
  EXPECT_EQ(json_raw(status, "body_frozen"), "[false]");
  EXPECT_EQ(json_raw(status, "mouse"), "true");
  EXPECT_EQ(json_raw(status, "script_failures"), "[]");
  EXPECT_EQ(json_raw(status, "run_error"), R"("")");
  // The press reached the liver: the coupling rendered a force.
  EXPECT_GT(json_number(status, "max_force_N"), 0.05) << status;
  EXPECT_GT(json_number(status, "sim_time_s"), 0.1);

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
  const std::string status = read_text(dir / "status.json");
  // Three lockstep runs of one 1/60 s frame each (the first picture and two steps), nothing in
  // between although the window ran for 40 frames: 17 ticks of 1 ms each.
  EXPECT_NEAR(json_number(status, "sim_time_s"), 3 * 0.017, 1.5e-3) << status;
  EXPECT_EQ(json_raw(status, "mouse"), "false");  // the scene's own scripted stylus
}

TEST(TactaViewWindow, PauseStopsTheClockWhileTheWindowRuns) {
  const fs::path dir = fresh_dir("pause");
  const ViewRun run = run_view(
      {"scenes/liver_palpation.yaml", "--size", "320x240", "--quit-after", "60", "--status",
       (dir / "status.json").string(), "--script", "20:pause; 30:mark; 80:mark; 81:quit"},
      dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string status = read_text(dir / "status.json");
  // (frame, simulated time shown) ten frames after the pause and fifty frames later: it played,
  // then the clock stood still while the window ran on (at least 50/60 s of wall time).
  double mark_frame[2] = {0, 0}, mark_time[2] = {0, 0};
  ASSERT_EQ(std::sscanf(json_raw(status, "marks").c_str(), "[[%lf, %lf], [%lf, %lf]]",
                        &mark_frame[0], &mark_time[0], &mark_frame[1], &mark_time[1]),
            4)
      << status;
  EXPECT_EQ(mark_frame[0], 30);
  EXPECT_EQ(mark_frame[1], 80);
  EXPECT_GT(mark_time[0], 0.0) << status;
  EXPECT_EQ(mark_time[1], mark_time[0]) << status;
  EXPECT_EQ(json_number(status, "sim_time_s"), mark_time[0]);
}

TEST(TactaViewWindow, BadScriptIsBadInput) {
  const fs::path dir = fresh_dir("bad_script");
  const ViewRun run = run_view({"scenes/liver_palpation.yaml", "--script", "3:fly away"}, dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("unknown verb 'fly'"), std::string::npos) << run.err;
}

}  // namespace
