// tacta-view: the interactive window. Skeleton: a demo frame with play/pause/step, a wireframe
// switch and a live force plot in Dear ImGui. Scene loading, model swapping, parameter sliders
// and the mouse as a device come with the simulation API.
#include <CLI/CLI.hpp>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include "demo_frame.hpp"
#include "tacta/render/window.hpp"

namespace {

constexpr size_t kPlotSamples = 240;  // frames of force history shown

struct ViewState {
  bool playing = true;
  bool wireframe = false;
  double sim_time_s = 0;
  std::array<float, kPlotSamples> force_history{};  // N
  size_t history_next = 0;
};

void draw_panel(ViewState& view, const tacta::view::DemoState& demo, double frame_ms) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::Begin("Tacta");
  ImGui::Text("t = %.3f s   frame %.1f ms", view.sim_time_s, frame_ms);
  if (ImGui::Button(view.playing ? "Pause" : "Play")) view.playing = !view.playing;
  ImGui::SameLine();
  if (ImGui::Button("Step") && !view.playing) view.sim_time_s += 1.0 / 60.0;
  ImGui::Checkbox("Wireframe", &view.wireframe);
  ImGui::Text("force %.2f N   dent %.2f mm", demo.force_N, demo.depth_m * 1e3);
  ImGui::PlotLines("force (N)", view.force_history.data(), static_cast<int>(kPlotSamples),
                   static_cast<int>(view.history_next), nullptr, 0.0f, 4.0f, ImVec2(260, 70));
  ImGui::TextDisabled("demo frame: scenes load once the simulation API lands");
  ImGui::End();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tacta-view: interactive window for Tacta scenes"};
  std::string scene;
  double seconds = 0;
  std::string screenshot;
  std::string size = "1280x800";
  app.add_option("scene", scene, "scene file (not yet supported: shows the demo frame)");
  app.add_option("--seconds", seconds, "close after this many seconds of wall time (0: never)");
  app.add_option("--screenshot", screenshot, "write the last frame shown to this PNG on exit");
  app.add_option("--size", size, "window size in pixels, WIDTHxHEIGHT");
  CLI11_PARSE(app, argc, argv);
  int width = 0, height = 0;
  if (std::sscanf(size.c_str(), "%dx%d", &width, &height) != 2 || width < 64 || height < 64) {
    std::fprintf(stderr, "error: --size: expected WIDTHxHEIGHT of at least 64x64, found '%s'\n", size.c_str());
    return 2;
  }
  if (!scene.empty())
    std::fprintf(stderr, "note: scene loading is not wired yet; showing the demo frame instead of %s\n",
                 scene.c_str());
  try {
    tacta::render::Window window({width, height, "Tacta", true});
    window.set_capture(!screenshot.empty());
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui_ImplGlfw_InitForOpenGL(static_cast<GLFWwindow*>(window.native_handle()), true);
    ImGui_ImplOpenGL3_Init("#version 330");

    ViewState view;
    tacta::view::DemoState demo;
    const auto start = std::chrono::steady_clock::now();
    auto last = start;
    while (!window.should_close()) {
      window.poll_events();
      const auto now = std::chrono::steady_clock::now();
      const double frame_ms = std::chrono::duration<double, std::milli>(now - last).count();
      last = now;
      if (view.playing) view.sim_time_s += frame_ms * 1e-3;
      const tacta::render::RenderFrame frame = tacta::view::demo_frame(view.sim_time_s, view.wireframe, demo);
      view.force_history[view.history_next] = static_cast<float>(demo.force_N);
      view.history_next = (view.history_next + 1) % kPlotSamples;

      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      draw_panel(view, demo, frame_ms);
      ImGui::Render();
      window.present(frame, [] { ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData()); });
      if (seconds > 0 && std::chrono::duration<double>(now - start).count() >= seconds) window.request_close();
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    if (!screenshot.empty()) {
      if (window.last_picture().empty()) {
        std::fprintf(stderr, "error: no frame was shown, nothing to write to %s\n", screenshot.c_str());
        return 1;
      }
      tacta::render::write_png(screenshot, window.last_picture());
      std::printf("wrote %s\n", screenshot.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
