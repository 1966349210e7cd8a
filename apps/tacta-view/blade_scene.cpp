#include "blade_scene.hpp"

namespace tacta::view {

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
