// The fixed synthetic frames of the golden-image tests: analytic shapes, no simulation, so the
// pictures depend on the renderer alone. Also used by scripts/regen-goldens (through the test).
#pragma once

#include <string>
#include <vector>

#include "tacta/render/frame.hpp"

namespace tacta::render::testing {

struct NamedFrame {
  std::string name;  // golden file stem: tests/golden/<name>.png
  RenderFrame frame;
};

// A box surface of nx x ny x nz cells spanning [0, size] (m), each face its own vertex grid.
BodyDraw box_surface(int nx, int ny, int nz, const Vec3d& size);
// A UV sphere of `radius` (m) around `centre`.
BodyDraw sphere_surface(const Vec3d& centre, double radius, int slices, int stacks);

// 1. a cantilever bent by the analytic static deflection, wireframe, fixed end, colour by |u|;
// 2. a sphere coloured by height with the colour bar;
// 3. a stylus pressing a dented plate: tool mesh, proxy, contacts, force arrow, overlay text;
// 4. the fallback sphere tool over a body seen from straight above (the camera's up switch).
std::vector<NamedFrame> golden_frames();

constexpr int kGoldenWidth = 320;  // pixels: small keeps the PNGs and the software render cheap
constexpr int kGoldenHeight = 240;

}  // namespace tacta::render::testing
