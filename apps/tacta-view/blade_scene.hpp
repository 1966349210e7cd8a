// What a scene's blades ask of the window (docs/ARCHITECTURE.md "Cutting"): the cut key (C) holds
// the blade's button on every mouse device; the cuts themselves are made off the haptic tick by
// the realtime run. No GUI here, so it is testable on its own.
#pragma once

#include <cstdint>
#include <string>

#include "tacta/scene.hpp"

namespace tacta::view {

// The button bits the cut key holds: the `button` of each blade a mouse device carries or is
// given by a change_tool event; 0 when no mouse device ever holds a blade (the key does nothing).
uint32_t cut_key_buttons(const SceneDesc& scene);

}  // namespace tacta::view
