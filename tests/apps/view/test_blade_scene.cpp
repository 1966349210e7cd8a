// What a scene's blades ask of the window: the button bits the cut key (C) holds on the mouse
// devices.
#include <gtest/gtest.h>

#include "blade_scene.hpp"

namespace tacta::view {
namespace {

DeviceDesc device(const std::string& name, const std::string& plugin,
                  std::optional<uint32_t> blade_button = std::nullopt) {
  DeviceDesc d;
  d.name = name;
  d.plugin = plugin;
  if (blade_button) {
    d.tool.blade.emplace();
    d.tool.blade->button = *blade_button;
  }
  return d;
}

BodyEventDesc tool_change(const std::string& device_name, std::optional<uint32_t> blade_button) {
  BodyEventDesc e;
  e.change_tool.emplace();
  e.change_tool->device = device_name;
  if (blade_button) {
    e.change_tool->tool.blade.emplace();
    e.change_tool->tool.blade->button = *blade_button;
  }
  return e;
}

TEST(BladeScene, WithoutABladeTheCutKeyHoldsNothing) {
  SceneDesc scene;
  scene.devices.push_back(device("hand", "mouse"));
  scene.events.push_back(tool_change("hand", std::nullopt));
  EXPECT_EQ(cut_key_buttons(scene), 0u);
}

TEST(BladeScene, TheCutKeyHoldsTheButtonsOfTheMouseDevicesBlades) {
  SceneDesc scene;
  scene.devices.push_back(device("hand", "mouse", 0));
  scene.devices.push_back(device("robot", "sim_stylus", 4));  // scripted: its own button_times
  scene.devices.push_back(device("left", "mouse"));
  scene.events.push_back(tool_change("left", 2));   // a mouse given a blade on button 2 later
  scene.events.push_back(tool_change("robot", 5));  // not a mouse: not the key's
  EXPECT_EQ(cut_key_buttons(scene), 0b101u);
}

}  // namespace
}  // namespace tacta::view
