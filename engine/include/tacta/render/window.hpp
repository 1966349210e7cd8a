// The window front end: a GLFW window with an OpenGL 3.3 core context, drawing RenderFrames with
// the same Renderer as the headless path. Needs a display (X11 or Wayland; Xvfb in tests).
// Available when tacta_render was built with GLFW (TACTA_RENDER_HAS_WINDOW is defined).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "tacta/render/frame.hpp"
#include "tacta/render/image.hpp"

namespace tacta::render {

struct WindowOptions {
  int width = 1280;  // pixels
  int height = 800;  // pixels
  std::string title = "Tacta";
  bool vsync = true;  // swap at the display's rate (60 Hz on most), which paces the render task
};

class Window {
 public:
  // Throws std::runtime_error naming GLFW's reason (e.g. no DISPLAY) when it cannot open.
  explicit Window(const WindowOptions& options = {});
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  bool should_close() const;
  void request_close();
  void poll_events();
  // Draws the frame, then `overlay` (e.g. Dear ImGui) on top, then presents.
  void present(const RenderFrame& frame, const std::function<void()>& overlay = {});
  // The last presented picture (read back before the swap); empty before the first present.
  const Image& last_picture() const;
  // Framebuffer size in pixels (differs from the window size on high-DPI screens).
  int framebuffer_width() const;
  int framebuffer_height() const;
  void* native_handle() const;  // the GLFWwindow*, for Dear ImGui's GLFW backend
  // Keep a copy of every presented picture in last_picture() (costs a read back a frame).
  void set_capture(bool capture);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tacta::render
