#include "blade_scene.hpp"

namespace tacta::view {

std::string lockstep_play_reason(const SceneDesc& scene) {
  for (const DeviceDesc& d : scene.devices)
    if (d.tool.blade) return "device '" + d.name + "' holds a blade";
  for (const BodyEventDesc& e : scene.events) {
    if (e.change_tool && e.change_tool->tool.blade)
      return "device '" + e.change_tool->device + "' is given a blade";
    if (e.cut) return "the scene cuts body '" + e.cut->body + "'";
  }
  return {};
}

uint32_t cut_key_buttons(const SceneDesc& scene) {
  uint32_t buttons = 0;
  const auto hold = [&buttons](const ShapeDesc& tool) {
    if (tool.blade && tool.blade->button < 32) buttons |= 1u << tool.blade->button;
  };
  for (const DeviceDesc& d : scene.devices) {
    if (d.plugin != "mouse") continue;
    hold(d.tool);
    for (const BodyEventDesc& e : scene.events)
      if (e.change_tool && e.change_tool->device == d.name) hold(e.change_tool->tool);
  }
  return buttons;
}

}  // namespace tacta::view
