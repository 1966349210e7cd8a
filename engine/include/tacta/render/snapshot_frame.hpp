// From the simulation's snapshots to pictures: what a body, the stylus, its proxy and the force
// look like in a RenderFrame, and a frame observer that writes PNG files from the render task.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "tacta/render/frame.hpp"
#include "tacta/sim/snapshot.hpp"

namespace tacta::render {

struct SnapshotStyle {
  bool colour_by_displacement = true;  // colour map over |x - x_rest|, m
  bool wireframe = false;
  std::string model_label;  // overlay text, e.g. "model: corotational_fem"
};

// A picture of the snapshot; the camera is fitted to the rest bounds so it does not wander.
RenderFrame make_render_frame(const SceneStatic& scene, const Snapshot& snapshot,
                              const SnapshotStyle& style = {});

class HeadlessRenderer;
struct Image;

// "model: a" or "models: a, b": the models the snapshot's bodies are stepped by, for the overlay.
std::string models_label(const Snapshot& snapshot);

// One picture of `snapshot` drawn by `renderer` and written as a PNG at `path` (folders made),
// labelled with its models unless style.model_label is set: what `tacta snapshot` and Python's
// Simulation.snapshot write. Throws std::runtime_error when the file cannot be written.
Image write_snapshot_png(HeadlessRenderer& renderer, const SceneStatic& scene,
                         const Snapshot& snapshot, const std::string& path,
                         SnapshotStyle style = {});

// Writes <directory>/frame_<time in ms>.png for the chosen times (s; empty = every frame).
std::unique_ptr<FrameObserver> make_png_frame_writer(const std::string& directory,
                                                     std::vector<double> times, int width,
                                                     int height);

}  // namespace tacta::render
