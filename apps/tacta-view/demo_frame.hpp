// A built-in animated frame for tacta-view while it cannot load scenes yet: a plate pressed by a
// stylus, the dent and the force following a 1 Hz press (analytic, no simulation).
#pragma once

#include "tacta/render/frame.hpp"

namespace tacta::view {

struct DemoState {
  double force_N = 0;     // magnitude of the drawn force
  double depth_m = 0;     // current dent depth
};

render::RenderFrame demo_frame(double time_s, bool wireframe, DemoState& state);

}  // namespace tacta::view
