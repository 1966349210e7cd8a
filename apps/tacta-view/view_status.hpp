// The JSON summary tacta-view writes on exit (--status FILE): what a test checks after driving
// the window (frames shown, swaps requested and seen in the last snapshot, force, mouse).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tacta::view {

struct ViewStatus {
  int frames = 0;
  double sim_time_s = 0;                     // s, of the last snapshot shown
  std::vector<std::array<double, 2>> marks;  // (frame, simulated time shown in s) per script mark
  double wall_time_s = 0;                    // s from loading the scene (the first run) to the exit
  int swaps_requested = 0;
  std::vector<std::string> swap_history;  // "body -> model"
  std::vector<std::string> body_models;   // per body, from the last snapshot (the haptic side)
  std::vector<bool> body_frozen;          // per body: diverged and frozen by the engine
  std::vector<uint32_t> body_revisions;   // per body: its mesh's revision (each cut adds 1)
  int cut_key_frames = 0;                 // frames shown with the cut key (C) holding a blade
  double max_force_N = 0;                 // largest device force among the snapshots shown
  bool mouse = false;                     // the mouse drove a device
  std::array<double, 3> mouse_target{};   // m
  std::array<double, 3> stylus{};         // m, the first device's last position
  std::vector<std::string> script_failures;
  std::string model_error, run_error;
};

// Throws std::runtime_error when the file cannot be written.
void write_view_status(const std::string& path, const ViewStatus& status);

}  // namespace tacta::view
