// VTK output as a frame observer: a .vtu per frame interval and a .pvd series for ParaView,
// with point data displacement (m), velocity (m/s) and von Mises stress (Pa) where the model
// gives it.
#pragma once

#include <memory>
#include <string>

#include "tacta/sim/snapshot.hpp"

namespace tacta {

// Writes every body's snapshot every interval_s of simulated time into directory.
std::unique_ptr<FrameObserver> make_vtk_observer(const std::string& directory, double interval_s);

}  // namespace tacta
