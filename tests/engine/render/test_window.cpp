// The GLFW window front end, run under Xvfb by ctest: it opens, presents a frame, and the
// picture it shows equals the headless one (same renderer, both on Mesa's llvmpipe).
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <stdexcept>

#include "synthetic_frames.hpp"
#include "tacta/render/headless.hpp"
#include "tacta/render/window.hpp"

namespace tacta::render::testing {
namespace {

// Runs first: GLFW is started once a process and never stopped.
TEST(Window, WithoutADisplayTheErrorSaysWhy) {
  const char* saved = std::getenv("DISPLAY");
  const std::string display = saved ? saved : "";
  unsetenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if (wayland != nullptr) GTEST_SKIP() << "Wayland session: cannot hide the display";
  bool opened = false;
  try {
    Window window(WindowOptions{64, 64, "no display", false});
    opened = true;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("window:"), std::string::npos) << e.what();
  }
  if (saved != nullptr) setenv("DISPLAY", display.c_str(), 1);
  // GLFW stays started for the process once a window opened, so only a first test sees the
  // missing display: this one is declared first; under --gtest_shuffle it may come later.
  if (opened) GTEST_SKIP() << "GLFW was already started by an earlier test in this process";
}

TEST(Window, ShowsTheSamePictureAsTheHeadlessRenderer) {
  if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr)
    GTEST_SKIP() << "no display; ctest runs this under xvfb-run";
  std::unique_ptr<Window> window;
  try {
    window =
        std::make_unique<Window>(WindowOptions{kGoldenWidth, kGoldenHeight, "tacta test", false});
  } catch (const std::runtime_error& e) {
    FAIL() << e.what();  // a display exists, so a window must open
  }
  ASSERT_EQ(window->framebuffer_width(), kGoldenWidth);
  ASSERT_EQ(window->framebuffer_height(), kGoldenHeight);
  const RenderFrame frame = golden_frames()[2].frame;  // tool, overlay, arrow: most features
  window->set_capture(true);
  bool overlay_called = false;
  for (int i = 0; i < 3; ++i) {
    window->poll_events();
    window->present(frame, [&] { overlay_called = true; });
  }
  EXPECT_TRUE(overlay_called);
  EXPECT_FALSE(window->should_close());
  const Image shown = window->last_picture();
  window.reset();

  HeadlessRenderer headless(HeadlessOptions{kGoldenWidth, kGoldenHeight, true});
  const Image expected = headless.render(frame);
  const auto out = std::filesystem::path(TACTA_BINARY_DIR) / "test-output" / "window";
  write_png(out / "window.png", shown);
  const ImageComparison c = compare_images(shown, expected);
  EXPECT_TRUE(c.matches) << c.summary() << "; picture in " << (out / "window.png");
}

}  // namespace
}  // namespace tacta::render::testing
