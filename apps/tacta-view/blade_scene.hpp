// What a scene's blades ask of the window (docs/ARCHITECTURE.md "Cutting"). A cut allocates, so
// it is made between lockstep ticks and a realtime run refuses a blade or a cut event: such a
// scene plays as lockstep steps held to wall-clock pace. The cut key (C) holds the blade's
// button on every mouse device. No GUI here, so it is testable on its own.
#pragma once

#include <cstdint>
#include <string>

#include "tacta/scene.hpp"

namespace tacta::view {

// Why the scene must play in lockstep (a device's tool, or a change_tool event's, carries a
// blade; the scene has cut events), for the panel; empty when a realtime run takes it.
std::string lockstep_play_reason(const SceneDesc& scene);

// The button bits the cut key holds: the `button` of each blade a mouse device carries or is
// given by a change_tool event; 0 when no mouse device ever holds a blade (the key does nothing).
uint32_t cut_key_buttons(const SceneDesc& scene);

}  // namespace tacta::view
