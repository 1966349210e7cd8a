// The mouse device plugin through the real C ABI (its `input` entry feeds one instance), and the
// viewer's MouseTool feeding a device.
#include <cmath>
#include <gtest/gtest.h>

#include "mouse_tool.hpp"
#include "plugin_fixture.hpp"
#include "tacta/device_api.h"

namespace tacta::view {
namespace {

constexpr double kDt = 1e-3;  // s, the haptic period

struct MouseInstance {
  explicit MouseInstance(const testing::LoadedPlugin& plugin)
      : api(plugin.api<tacta_device_api>("mouse")),
        params(testing::default_params(plugin.descriptor("mouse"))) {
    tacta_device_setup setup{sizeof(tacta_device_setup),
                             params.data(),
                             static_cast<uint32_t>(params.size()),
                             "",
                             1,
                             kDt};
    char message[256] = {0};
    EXPECT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_OK) << message;
    EXPECT_EQ(api.connect(instance, message, sizeof message), TACTA_OK) << message;
  }
  ~MouseInstance() { api.destroy(instance); }
  tacta_device_sample read(double t) {
    tacta_device_sample s{};
    EXPECT_EQ(api.read(instance, t, &s), TACTA_DEVICE_CONNECTED);
    return s;
  }
  // Runs from t0 for `seconds` at the haptic period with a constant force; returns the end time.
  double hold(double t0, double seconds, std::array<double, 3> force) {
    const tacta_device_command command{{force[0], force[1], force[2]}, {0, 0, 0}};
    double t = t0;
    for (int k = 0; k < static_cast<int>(std::lround(seconds / kDt)); ++k) {
      api.write(instance, t, &command);
      t += kDt;
      read(t);
    }
    return t;
  }
  const tacta_device_api& api;
  testing::DefaultParams params;
  void* instance = nullptr;
};

TEST(MouseDevice, DeclaresOmniCapabilitiesAndTheInputEntry) {
  testing::LoadedPlugin plugin("tacta_mouse.so");
  MouseInstance mouse(plugin);
  ASSERT_NE(mouse.api.input, nullptr);
  tacta_device_capabilities c{};
  mouse.api.capabilities(mouse.instance, &c);
  EXPECT_DOUBLE_EQ(c.peak_force, 3.3);
  EXPECT_DOUBLE_EQ(c.workspace_max[0] - c.workspace_min[0], 0.16);
  EXPECT_EQ(c.dof_out, 3u);
}

TEST(MouseDevice, FollowsTheFedTargetAndYieldsToTheRenderedForce) {
  testing::LoadedPlugin plugin("tacta_mouse.so");
  MouseInstance mouse(plugin);
  const double start[3] = {0.01, 0.12, -0.02};
  mouse.api.input(mouse.instance, start, 3);
  tacta_device_sample s = mouse.read(0.0);  // first read: at rest on the target
  EXPECT_DOUBLE_EQ(s.position[1], 0.12);

  // Each instance has its own target: another mouse, and a NULL instance, leave this one alone.
  MouseInstance other(plugin);
  const double elsewhere[3] = {-0.05, 0.2, 0.05};
  other.api.input(other.instance, elsewhere, 3);
  mouse.api.input(nullptr, elsewhere, 3);
  EXPECT_DOUBLE_EQ(other.read(0.0).position[1], 0.2);
  EXPECT_DOUBLE_EQ(mouse.read(0.0).position[1], 0.12);

  const double moved[3] = {0.02, 0.10, -0.02};
  mouse.api.input(mouse.instance, moved, 3);
  double t = mouse.hold(0.0, 0.5, {0, 0, 0});  // critically damped, omega = 55 rad/s: settled
  s = mouse.read(t);
  EXPECT_NEAR(s.position[0], 0.02, 1e-6);
  EXPECT_NEAR(s.position[1], 0.10, 1e-6);

  // A steady 1 N up is balanced by the 300 N/m hand spring 3.33 mm above the target.
  t = mouse.hold(t, 1.0, {0, 1.0, 0});
  EXPECT_NEAR(mouse.read(t).position[1] - 0.10, 1.0 / 300.0, 1e-6);
  // 10 N is clamped to the 3.3 N peak: 11 mm.
  t = mouse.hold(t, 1.0, {0, 10.0, 0});
  EXPECT_NEAR(mouse.read(t).position[1] - 0.10, 3.3 / 300.0, 1e-6);
  // Time going back (a new run of the simulation): at rest on the target again.
  EXPECT_DOUBLE_EQ(mouse.read(0.0).position[1], 0.10);
}

TEST(MouseDevice, AFourthInputValueSetsTheButtonsAndThreeKeepThem) {
  testing::LoadedPlugin plugin("tacta_mouse.so");
  MouseInstance mouse(plugin);
  MouseInstance other(plugin);
  EXPECT_EQ(other.read(0.0).buttons, 0u) << "no button held before any input";

  const double held[4] = {0.01, 0.12, -0.02, 1.0};  // button 0 held (a blade's default bit)
  mouse.api.input(mouse.instance, held, 4);
  tacta_device_sample s = mouse.read(0.0);  // first read: at rest on the target
  EXPECT_EQ(s.buttons, 1u);
  EXPECT_DOUBLE_EQ(s.position[1], 0.12) << "the target moves with the same input";
  EXPECT_EQ(other.read(0.001).buttons, 0u) << "each instance has its own buttons";

  const double moved[3] = {0.02, 0.12, -0.02};
  mouse.api.input(mouse.instance, moved, 3);
  EXPECT_EQ(mouse.read(0.002).buttons, 1u) << "three values keep the buttons held";

  const double bits[4] = {0.02, 0.12, -0.02, 5.0};  // buttons 0 and 2
  mouse.api.input(mouse.instance, bits, 4);
  EXPECT_EQ(mouse.read(0.003).buttons, 5u);

  // A mask that is not a whole number from 0 to 2^32 - 1 is ignored (the buttons stay as they
  // were); the target in the same input still moves.
  for (const double bad : {-1.0, 0.5, 4294967296.0, std::nan(""), HUGE_VAL}) {
    const double input[4] = {0.03, 0.12, -0.02, bad};
    mouse.api.input(mouse.instance, input, 4);
    EXPECT_EQ(mouse.read(0.004).buttons, 5u) << "mask " << bad;
  }
  const double top[4] = {0.03, 0.12, -0.02, 4294967295.0};
  mouse.api.input(mouse.instance, top, 4);
  EXPECT_EQ(mouse.read(0.005).buttons, 0xFFFFFFFFu);

  const double released[4] = {0.03, 0.12, -0.02, 0.0};
  mouse.api.input(mouse.instance, released, 4);
  EXPECT_EQ(mouse.read(0.006).buttons, 0u);
}

TEST(MouseTool, DragMovesTheTargetOnTheFacingPlaneAndFeedsTheDevice) {
  testing::LoadedPlugin plugin("tacta_mouse.so");
  MouseInstance mouse(plugin);
  MouseTool tool([&mouse](std::span<const double> values) {
    mouse.api.input(mouse.instance, values.data(), static_cast<uint32_t>(values.size()));
  });
  ASSERT_TRUE(tool.available());
  EXPECT_FALSE(MouseTool({}).available()) << "no feed: a scene without a mouse device";
  Camera camera;
  camera.eye = {0, 0.1, 1};
  camera.target = {0, 0.1, 0};
  const Viewport view{800, 600};
  tool.set_target({0, 0.1, 0});
  tool.update({400, 300, true, 0, false}, camera, view);  // grab at the target's pixel
  EXPECT_TRUE(tool.dragging());
  tool.update({400, 200, true, 0, false}, camera, view);  // 100 px up: a sixth of the height
  EXPECT_NEAR(tool.target()[1], 0.1 + std::tan(0.35) / 3, 1e-12);
  EXPECT_NEAR(tool.target()[2], 0.0, 1e-12);
  tool.update({400, 200, false, 2, false}, camera, view);  // released, two notches away
  EXPECT_FALSE(tool.dragging());
  EXPECT_NEAR(tool.target()[2], -2 * 0.002, 1e-12);
  tool.update({100, 100, true, 0, true}, camera, view);  // over the panel: ignored
  EXPECT_FALSE(tool.dragging());

  // The device follows what the tool fed (first read: at rest on the target).
  const tacta_device_sample s = mouse.read(0.0);
  EXPECT_NEAR(s.position[1], tool.target()[1], 1e-12);
  EXPECT_NEAR(s.position[2], tool.target()[2], 1e-12);
}

// The window's cut key: set_buttons feeds the target and the buttons (4 values); a later move
// feeds the target alone (3 values), so the device keeps the button held while the mouse drags.
TEST(MouseTool, HeldButtonsReachTheDeviceAndOutlastMoves) {
  testing::LoadedPlugin plugin("tacta_mouse.so");
  MouseInstance mouse(plugin);
  MouseTool tool([&mouse](std::span<const double> values) {
    mouse.api.input(mouse.instance, values.data(), static_cast<uint32_t>(values.size()));
  });
  tool.set_target({0, 0.1, 0});
  EXPECT_EQ(mouse.read(0.0).buttons, 0u);
  tool.set_buttons(1);  // C down over a blade on button 0
  EXPECT_EQ(tool.buttons(), 1u);
  EXPECT_EQ(mouse.read(0.001).buttons, 1u);
  tool.set_target({0.01, 0.1, 0});
  tacta_device_sample s = mouse.read(0.5);
  EXPECT_EQ(s.buttons, 1u);
  EXPECT_NEAR(s.position[0], 0.01, 1e-4) << "the buttons' feed did not move the target";
  tool.set_buttons(0);  // C up
  s = mouse.read(0.501);
  EXPECT_EQ(s.buttons, 0u);
  EXPECT_NEAR(s.position[0], 0.01, 1e-4);
}

}  // namespace
}  // namespace tacta::view
