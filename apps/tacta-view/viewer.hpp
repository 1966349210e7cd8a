// The tacta-view window: a scene running on a SimSession, drawn with the shared renderer through
// the GLFW front end, with a Dear ImGui panel (play/pause/step, model swaps and parameter
// sliders, the mouse as a device, live plots of force and tick time).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "live_plots.hpp"
#include "model_panel.hpp"
#include "mouse_tool.hpp"
#include "sim_session.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/render/snapshot_frame.hpp"
#include "tacta/render/window.hpp"
#include "tacta/scene.hpp"
#include "view_script.hpp"

namespace tacta::view {

struct ViewerOptions {
  std::string scene;
  std::vector<std::string> overrides;  // --set key.path=value
  bool mouse = false;                  // replace the scene's devices by the mouse
  bool paused = false;
  double quit_after_s = 0;         // wall-clock seconds; 0: until the window closes
  std::string screenshot;          // PNG of the last frame, written on exit
  std::string status;              // JSON summary, written on exit
  std::string script;              // see view_script.hpp
  int width = 1280, height = 800;  // pixels
};

class Viewer final : public ScriptHost {
 public:
  // Loads the scene and builds the simulation; throws InputError on bad input.
  explicit Viewer(const ViewerOptions& options);
  ~Viewer() override;
  int run();  // the window's loop; returns the exit code

  // ScriptHost
  bool swap(const std::string& body, const std::string& model) override;
  bool set_param(const std::string& body, const std::string& name, double value) override;
  void play() override { session_->play(); }
  void pause() override { session_->pause(); }
  void step() override { session_->step(); }
  void quit() override { quit_requested_ = true; }
  void mark() override {
    marks_.push_back({static_cast<double>(frames_), have_snapshot_ ? snapshot_.time_s : 0.0});
  }
  std::optional<std::array<double, 2>> pixel_of(const Vec3d& point) const override;
  Vec3d mouse_target() const override { return mouse_.target(); }
  Vec3d top_point() const override { return top_point_; }
  bool key(const std::string& name, bool down) override;

 private:
  void on_scene(const SceneStatic& scene);  // the first time the session hands it over
  void update_cut_key(bool held);           // feeds the blade's button to the mouse devices
  void draw_panel(double frame_ms);
  void write_status(const std::string& path, double wall_time_s) const;

  ViewerOptions options_;
  std::chrono::steady_clock::time_point created_ =
      std::chrono::steady_clock::now();  // the run starts here
  PluginRegistry plugins_;
  SceneDesc scene_desc_;
  std::unique_ptr<Simulation> simulation_;
  MouseTool mouse_;
  std::unique_ptr<ModelPanel> models_;
  std::unique_ptr<SimSession> session_;  // after the simulation: joined before it is destroyed
  std::optional<ScriptPlayer> script_;

  SceneStatic scene_;
  bool have_scene_ = false;
  uint64_t scene_version_ = 0;  // of scene_, as the session counts them (cuts, added bodies)
  Snapshot snapshot_;
  bool have_snapshot_ = false;
  render::SnapshotStyle style_;
  render::Camera camera_;
  Viewport viewport_;
  Vec3d top_point_{0, 0, 0};
  bool mouse_driven_ = false;    // a device of the scene is the mouse plugin
  uint32_t cut_buttons_ = 0;     // held while the cut key is down (0: no mouse device has a blade)
  bool script_cut_key_ = false;  // the script holds C
  int cut_frames_ = 0;           // frames shown with the cut key held
  RingPlot<300> force_plot_;     // N, one sample a new snapshot
  RingPlot<300> tick_plot_;      // ms
  double max_force_N_ = 0;
  int frames_ = 0;
  bool quit_requested_ = false;
  std::vector<std::array<double, 2>> marks_;  // (frame, simulated time shown in s) per script mark
};

}  // namespace tacta::view
