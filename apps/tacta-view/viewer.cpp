#include "viewer.hpp"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <imgui.h>
#include <thread>

#include "blade_scene.hpp"
#include "tacta/log.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/vec3.hpp"
#include "view_status.hpp"

namespace tacta::view {
namespace {

constexpr double kFramePeriod_s = 1.0 / 60;  // the window's pace when vsync does not block

struct Placement {
  Vec3d top{0, 0, 0};    // m, the highest rest node
  Vec3d start{0, 0, 0};  // m, where the mouse target starts: above the top
  double depth_step_m = 0.002;
};

// The mouse target starts a tenth of the scene's size (at least 2 cm) above its highest point.
Placement placement(const SceneStatic& scene) {
  Placement p;
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const BodyStatic& b : scene.bodies)
    for (size_t n = 0; n + 2 < b.rest_positions.size(); n += 3) {
      if (b.rest_positions[n + 1] > hi[1])
        p.top = {b.rest_positions[n], b.rest_positions[n + 1], b.rest_positions[n + 2]};
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], b.rest_positions[n + a]);
        hi[a] = std::max(hi[a], b.rest_positions[n + a]);
      }
    }
  if (lo[0] > hi[0]) return p;  // no bodies
  const double size =
      std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
  p.start = {p.top[0], p.top[1] + std::max(0.02, 0.1 * size), p.top[2]};
  p.depth_step_m = 0.01 * size;
  return p;
}

std::vector<std::string> with_mouse(std::vector<std::string> overrides, bool mouse) {
  if (mouse) {
    // The scene's devices become the mouse, keeping their tools and couplings (as --replay does).
    overrides.push_back("devices.*.plugin=mouse");
    overrides.push_back("devices.*.params={}");
  }
  return overrides;
}

// The viewer's pointer drives every mouse device of the scene, through the instances the
// simulation owns; no feed when the scene has none.
MouseTool::Feed mouse_feed(Simulation& simulation) {
  std::vector<DeviceHandle> mice;
  for (const DeviceHandle d : simulation.devices())
    if (simulation.device_plugin(d) == "mouse") mice.push_back(d);
  if (mice.empty()) return {};
  return [&simulation, mice](std::span<const double> values) {
    for (const DeviceHandle d : mice)
      simulation.device_input(d, values.data(), static_cast<uint32_t>(values.size()));
  };
}

PluginRegistry& loaded(PluginRegistry& plugins) {
  plugins.load();
  return plugins;
}

}  // namespace

Viewer::Viewer(const ViewerOptions& options)
    : options_(options),
      scene_desc_(load_scene(options.scene, RegistrySchemas(loaded(plugins_)),
                             with_mouse(options.overrides, options.mouse))),
      simulation_(std::make_unique<Simulation>(scene_desc_, plugins_)),
      mouse_(mouse_feed(*simulation_)),
      models_(std::make_unique<ModelPanel>(plugins_, *simulation_, scene_desc_)) {
  for (const DeviceDesc& d : scene_desc_.devices)
    mouse_driven_ = mouse_driven_ || d.plugin == "mouse";
  cut_buttons_ = cut_key_buttons(scene_desc_);
  if (!options.script.empty()) script_.emplace(parse_script(options.script));
  const double frame_period = 1.0 / scene_desc_.clock.render_rate_hz;
  session_ =
      std::make_unique<SimSession>(*simulation_, frame_period, [this](const SceneStatic& scene) {
        if (mouse_driven_)
          mouse_.feed(placement(scene).start);  // before the first tick reads the device
      });
  if (options.paused)
    session_->step();  // the first picture: the state before any tick
  else
    session_->play();
}

Viewer::~Viewer() = default;

bool Viewer::swap(const std::string& body, const std::string& model) {
  return models_->swap_model(body, model);
}

bool Viewer::set_param(const std::string& body, const std::string& name, double value) {
  return models_->set_param(body, name, value);
}

bool Viewer::key(const std::string& name, bool down) {
  if (name != "c" && name != "C") return false;  // the cut key is the only one scripts hold
  script_cut_key_ = down;
  return true;
}

void Viewer::update_cut_key(bool held) {
  const uint32_t buttons = held ? cut_buttons_ : 0;
  if (buttons != mouse_.buttons()) mouse_.set_buttons(buttons);
  if (buttons != 0) ++cut_frames_;
}

std::optional<std::array<double, 2>> Viewer::pixel_of(const Vec3d& point) const {
  return project(camera_, viewport_, point);
}

void Viewer::on_scene(const SceneStatic& scene) {
  scene_ = scene;
  have_scene_ = true;
  const Placement p = placement(scene);
  top_point_ = p.top;
  mouse_.set_depth_step(p.depth_step_m);
  if (mouse_driven_) mouse_.set_target(p.start);
}

void Viewer::draw_panel(double frame_ms) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - 10, 10), ImGuiCond_FirstUseEver, ImVec2(1, 0));
  ImGui::SetNextWindowSize(ImVec2(360, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Tacta");
  ImGui::PushItemWidth(170);  // pixels, leaves room for the parameter names
  ImGui::Text("%s", scene_desc_.name.c_str());
  ImGui::Text("t = %.3f s   frame %.1f ms", have_snapshot_ ? snapshot_.time_s : 0.0, frame_ms);
  const bool playing = session_->playing();
  if (ImGui::Button(playing ? "Pause" : "Play")) playing ? session_->pause() : session_->play();
  ImGui::SameLine();
  ImGui::BeginDisabled(playing);
  if (ImGui::Button("Step")) session_->step();
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::Checkbox("Wireframe", &style_.wireframe);
  const std::string error = session_->error();
  if (!error.empty())
    ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "run stopped: %s", error.c_str());

  if (ImGui::CollapsingHeader("Model", ImGuiTreeNodeFlags_DefaultOpen)) models_->draw();
  if (ImGui::CollapsingHeader("Device", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (mouse_driven_ && mouse_.available()) {
      const Vec3d& t = mouse_.target();
      ImGui::Text("mouse target %.1f %.1f %.1f mm", 1e3 * t[0], 1e3 * t[1], 1e3 * t[2]);
      ImGui::TextDisabled("left drag: move on the view plane; wheel: depth");
      if (cut_buttons_ != 0) {
        if (mouse_.buttons() != 0)
          ImGui::TextColored(ImVec4(1, 0.5f, 0.3f, 1), "cutting (C held)");
        else
          ImGui::TextDisabled("hold C to cut with the blade");
      }
    } else {
      ImGui::TextDisabled(scene_desc_.devices.empty()
                              ? "no device"
                              : "scripted device (run with --mouse to drive it)");
    }
  }
  if (ImGui::CollapsingHeader("Plots", ImGuiTreeNodeFlags_DefaultOpen)) {
    char label[64];
    std::snprintf(label, sizeof label, "%.2f N", static_cast<double>(force_plot_.latest()));
    ImGui::PlotLines("force", force_plot_.data(), force_plot_.size(), force_plot_.offset(), label,
                     0.0f, std::max(1.0f, force_plot_.max()), ImVec2(240, 60));
    std::snprintf(label, sizeof label, "%.3f ms", static_cast<double>(tick_plot_.latest()));
    ImGui::PlotLines("tick", tick_plot_.data(), tick_plot_.size(), tick_plot_.offset(), label, 0.0f,
                     std::max(1.0f, tick_plot_.max()), ImVec2(240, 60));
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

int Viewer::run() {
  render::Window window({options_.width, options_.height, "Tacta: " + scene_desc_.name, true});
  window.set_capture(!options_.screenshot.empty());
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui_ImplGlfw_InitForOpenGL(static_cast<GLFWwindow*>(window.native_handle()), true);
  ImGui_ImplOpenGL3_Init("#version 330");

  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto last = start;
  while (!window.should_close()) {
    window.poll_events();
    const auto now = Clock::now();
    const double frame_ms = std::chrono::duration<double, std::milli>(now - last).count();
    last = now;

    if (!have_scene_ && session_->scene(scene_)) on_scene(scene_);
    if (session_->take_latest(snapshot_, scene_, scene_version_)) {
      have_snapshot_ = true;
      double force = 0;
      if (!snapshot_.devices.empty()) {
        const auto& f = snapshot_.devices[0].force;
        force = norm(f);
      }
      max_force_N_ = std::max(max_force_N_, force);
      force_plot_.push(static_cast<float>(force));
      tick_plot_.push(static_cast<float>(snapshot_.last_tick_ms));
    }
    render::RenderFrame frame;
    if (have_scene_ && have_snapshot_)
      frame = render::make_render_frame(scene_, snapshot_, style_);
    else
      frame.overlay_lines.emplace_back("starting...");
    camera_ = frame.camera;

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    const ImGuiIO& io = ImGui::GetIO();
    viewport_ = {io.DisplaySize.x, io.DisplaySize.y};
    std::optional<PointerState> pointer = script_ ? script_->advance(frames_, *this) : std::nullopt;
    if (!pointer) {
      pointer = PointerState{io.MousePos.x, io.MousePos.y, io.MouseDown[0], io.MouseWheel,
                             io.WantCaptureMouse};
    }
    if (mouse_driven_ && have_scene_) {
      // The cut key: C held (not while a text field has the keyboard) or held by the script.
      const bool c_down =
          !io.WantCaptureKeyboard &&
          glfwGetKey(static_cast<GLFWwindow*>(window.native_handle()), GLFW_KEY_C) == GLFW_PRESS;
      update_cut_key(c_down || script_cut_key_);
      if (mouse_.buttons() != 0) frame.overlay_lines.emplace_back("cutting (C held)");
      mouse_.update(*pointer, camera_, viewport_);
      const ImU32 ring = mouse_.buttons() != 0 ? IM_COL32(255, 90, 60, 255)
                         : mouse_.dragging()   ? IM_COL32(255, 220, 80, 255)
                                               : IM_COL32(120, 200, 255, 255);
      if (const auto at = project(camera_, viewport_, mouse_.target()))  // the target, as a ring
        ImGui::GetBackgroundDrawList()->AddCircle(
            ImVec2(static_cast<float>((*at)[0]), static_cast<float>((*at)[1])), 7.0f, ring, 0,
            2.0f);
    }
    draw_panel(frame_ms);
    ImGui::Render();
    window.present(frame, [] { ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData()); });
    ++frames_;

    const double elapsed_s = std::chrono::duration<double>(Clock::now() - start).count();
    if (quit_requested_ || (options_.quit_after_s > 0 && elapsed_s >= options_.quit_after_s))
      window.request_close();
    std::this_thread::sleep_until(now + std::chrono::duration_cast<Clock::duration>(
                                            std::chrono::duration<double>(kFramePeriod_s)));
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  session_.reset();  // stops the run; the last snapshot stays in snapshot_

  int code = 0;
  if (!options_.screenshot.empty()) {
    if (window.last_picture().empty()) {
      log_error("no frame was shown, nothing to write to " + options_.screenshot);
      code = 1;
    } else {
      render::write_png(options_.screenshot, window.last_picture());
      std::printf("wrote %s\n", options_.screenshot.c_str());
    }
  }
  if (!options_.status.empty())
    write_status(options_.status, std::chrono::duration<double>(Clock::now() - created_).count());
  if (script_ && !script_->failures().empty()) code = 1;
  return code;
}

void Viewer::write_status(const std::string& path, double wall_time_s) const {
  ViewStatus s;
  s.frames = frames_;
  s.wall_time_s = wall_time_s;
  s.marks = marks_;
  s.sim_time_s = have_snapshot_ ? snapshot_.time_s : 0;
  s.swaps_requested = models_->swaps();
  s.swap_history = models_->history();
  if (have_snapshot_)
    for (const BodySnapshot& b : snapshot_.bodies) {
      s.body_models.push_back(b.model);
      s.body_frozen.push_back(b.frozen);
    }
  if (have_scene_)
    for (const BodyStatic& b : scene_.bodies) s.body_revisions.push_back(b.revision);
  s.cut_key_frames = cut_frames_;
  s.max_force_N = max_force_N_;
  s.mouse = mouse_driven_ && mouse_.available();
  s.mouse_target = mouse_.target();
  if (have_snapshot_ && !snapshot_.devices.empty()) s.stylus = snapshot_.devices[0].position;
  if (script_) s.script_failures = script_->failures();
  s.model_error = models_->error();
  s.run_error = session_ ? session_->error() : std::string();
  write_view_status(path, s);
  std::printf("wrote %s\n", path.c_str());
}

}  // namespace tacta::view
