// Hands each device that takes a body surface (device_api.h `surface`, e.g. OpenIGTLink's
// POLYDATA stream to 3D Slicer) the deformed surface of the body it touches, at every frame the
// render task takes: the body it touched last, else the first body. Runs on the render thread.
#pragma once

#include <memory>
#include <vector>

#include "tacta/sim/snapshot.hpp"
#include "world/world.hpp"

namespace tacta {

// Null when no device of the world takes a surface.
std::unique_ptr<FrameObserver> make_device_surface_feed(World& world);

}  // namespace tacta
