// The EGL headless renderer on llvmpipe: it draws what the frame says, where the camera says,
// and the same frame twice gives the same bytes.
#include <cmath>
#include <gtest/gtest.h>
#include <thread>

#include "headless_fixture.hpp"
#include "tacta/error.hpp"

namespace tacta::render::testing {
namespace {

std::array<int, 3> pixel(const Image& image, int x, int y) {
  const size_t i =
      (static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x)) * 4;
  return {image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]};
}

int byte(float v) { return static_cast<int>(std::lround(v * 255.0f)); }

RenderFrame empty_frame() {
  RenderFrame frame;
  frame.floor_height.reset();
  frame.axes = false;
  return frame;
}

using HeadlessRender = HeadlessTest;

TEST_F(HeadlessRender, ReportsASoftwareCoreContext) {
  const std::string what = renderer().description();
  EXPECT_NE(what.find("Core Profile"), std::string::npos) << what;
  EXPECT_NE(what.find("llvmpipe"), std::string::npos) << what;  // deterministic mode forces it
}

TEST_F(HeadlessRender, EmptyFrameIsTheBackgroundColour) {
  RenderFrame frame = empty_frame();
  frame.background = {0.2f, 0.4f, 0.6f};
  const Image image = renderer().render(frame);
  ASSERT_EQ(image.width, kGoldenWidth);
  ASSERT_EQ(image.height, kGoldenHeight);
  for (auto [x, y] : {std::pair{0, 0}, {kGoldenWidth - 1, kGoldenHeight - 1}, {160, 120}})
    EXPECT_EQ(pixel(image, x, y), (std::array<int, 3>{byte(0.2f), byte(0.4f), byte(0.6f)}));
}

TEST_F(HeadlessRender, SphereInFrontOfTheCameraCoversTheCentreOnly) {
  RenderFrame frame = empty_frame();
  frame.background = {0, 0, 0};
  BodyDraw ball = sphere_surface({0, 0, 0}, 0.1, 24, 12);
  ball.base_colour = {0.0f, 1.0f, 0.0f};  // pure green: lit pixels have no red or blue
  frame.bodies.push_back(ball);
  frame.camera.eye = {0, 0, 1};
  frame.camera.target = {0, 0, 0};
  frame.camera.vertical_fov_rad = 0.5;
  // Projected radius: 0.1 / (1 * tan(0.25)) of the half height = 0.39 * 120 = 47 pixels.
  const Image image = renderer().render(frame);
  const auto centre = pixel(image, 160, 120);
  EXPECT_GT(centre[1], 100);
  EXPECT_EQ(centre[0], centre[2]);  // only the white specular adds red and blue, equally
  EXPECT_EQ(pixel(image, 160, 120 - 55), (std::array<int, 3>{0, 0, 0}));  // just outside
  EXPECT_GT(pixel(image, 160, 120 - 40)[1], 20);                          // just inside
  EXPECT_EQ(pixel(image, 160 + 55, 120), (std::array<int, 3>{0, 0, 0}));
  EXPECT_GT(pixel(image, 160 + 40, 120)[1], 20);
}

TEST_F(HeadlessRender, ImageRowZeroIsTheTop) {
  RenderFrame frame = empty_frame();
  frame.background = {0, 0, 0};
  BodyDraw ball = sphere_surface({0, 0.25, 0}, 0.1, 16, 8);  // above the view axis
  ball.base_colour = {1, 1, 1};
  frame.bodies.push_back(ball);
  frame.camera.eye = {0, 0, 1};
  frame.camera.target = {0, 0, 0};
  const Image image = renderer().render(frame);
  int top_lit = 0, bottom_lit = 0;
  for (int y = 0; y < kGoldenHeight; ++y)
    for (int x = 0; x < kGoldenWidth; ++x)
      (y < kGoldenHeight / 2 ? top_lit : bottom_lit) += pixel(image, x, y)[0] > 0 ? 1 : 0;
  EXPECT_GT(top_lit, 500);
  EXPECT_EQ(bottom_lit, 0);
}

TEST_F(HeadlessRender, SameFrameTwiceGivesTheSameBytes) {
  const auto frames = golden_frames();
  const Image first = renderer().render(frames[2].frame);
  const Image second = renderer().render(frames[2].frame);
  EXPECT_EQ(first.rgba, second.rgba);
}

TEST_F(HeadlessRender, AnotherThreadCanRenderTheSamePicture) {
  const RenderFrame frame = golden_frames()[0].frame;
  const Image here = renderer().render(frame);
  Image there;
  std::thread render_task([&] { there = renderer().render(frame); });
  render_task.join();
  EXPECT_EQ(here.rgba, there.rgba);
}

TEST_F(HeadlessRender, OverlayTextDrawsInkInThePanel) {
  RenderFrame frame = empty_frame();
  frame.background = {0, 0, 0};
  frame.overlay_lines = {"force: 1.00 N"};
  const Image image = renderer().render(frame);
  int ink = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 200; ++x) ink += pixel(image, x, y)[0] > 200 ? 1 : 0;
  EXPECT_GT(ink, 30);
  EXPECT_EQ(pixel(image, 300, 200), (std::array<int, 3>{0, 0, 0}));
}

TEST_F(HeadlessRender, BadTriangleIndexIsAnInputErrorNamingTheBody) {
  RenderFrame frame = empty_frame();
  frame.bodies.resize(2);
  frame.bodies[1].positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  frame.bodies[1].triangles = {0, 1, 3};
  try {
    renderer().render(frame);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bodies[1]"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("index 3"), std::string::npos) << e.what();
  }
  // The renderer stays usable after the error.
  EXPECT_EQ(renderer().render(empty_frame()).width, kGoldenWidth);
}

TEST(FitCamera, BoundsFitInsideTheFieldOfView) {
  RenderFrame frame;
  frame.bodies.push_back(box_surface(1, 1, 1, {0.2, 0.1, 0.1}));
  fit_camera(frame, {0, 0, 1});
  EXPECT_NEAR(frame.camera.target[0], 0.1, 1e-12);
  EXPECT_NEAR(frame.camera.target[1], 0.05, 1e-12);
  const double radius = 0.5 * std::sqrt(0.2 * 0.2 + 0.1 * 0.1 + 0.1 * 0.1);
  const double distance = frame.camera.eye[2] - frame.camera.target[2];
  EXPECT_NEAR(std::sin(frame.camera.vertical_fov_rad / 2) * distance, 1.05 * radius, 1e-9);
}

}  // namespace
}  // namespace tacta::render::testing
