// GL first, with prototypes; GLFW must not pull in its own GL header.
#include "gl.hpp"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <cstring>
#include <mutex>
#include <stdexcept>

#include "tacta/render/renderer.hpp"
#include "tacta/render/window.hpp"

namespace tacta::render {

namespace {

// GLFW is initialised once a process and never terminated: glfwTerminate closes the X display,
// which unloads Mesa's driver and strands its allocations (LeakSanitizer reports them).
std::mutex glfw_mutex;
bool glfw_ready = false;

std::string glfw_reason() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown GLFW error";
}

}  // namespace

struct Window::State {
  GLFWwindow* window = nullptr;
  std::unique_ptr<Renderer> renderer;
  Image picture;
  bool capture = false;
};

Window::Window(const WindowOptions& options) : state_(std::make_unique<State>()) {
  {
    std::lock_guard lock(glfw_mutex);
    if (!glfw_ready && glfwInit() != GLFW_TRUE)
      throw std::runtime_error("window: cannot start GLFW (" + glfw_reason() +
                               "); is DISPLAY set?");
    glfw_ready = true;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 0);
  state_->window =
      glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
  if (state_->window == nullptr) {
    const std::string reason = glfw_reason();
    throw std::runtime_error("window: cannot open an OpenGL 3.3 core window (" + reason + ")");
  }
  glfwMakeContextCurrent(state_->window);
  glfwSwapInterval(options.vsync ? 1 : 0);
  state_->renderer = std::make_unique<Renderer>();
}

Window::~Window() {
  glfwMakeContextCurrent(state_->window);
  state_->renderer.reset();
  glfwDestroyWindow(state_->window);
}

bool Window::should_close() const { return glfwWindowShouldClose(state_->window) == GLFW_TRUE; }
void Window::request_close() { glfwSetWindowShouldClose(state_->window, GLFW_TRUE); }
void Window::poll_events() { glfwPollEvents(); }

int Window::framebuffer_width() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(state_->window, &w, &h);
  return w;
}
int Window::framebuffer_height() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(state_->window, &w, &h);
  return h;
}

void* Window::native_handle() const { return state_->window; }
void Window::set_capture(bool capture) { state_->capture = capture; }
const Image& Window::last_picture() const { return state_->picture; }

void Window::present(const RenderFrame& frame, const std::function<void()>& overlay) {
  glfwMakeContextCurrent(state_->window);
  const int width = framebuffer_width();
  const int height = framebuffer_height();
  if (width <= 0 || height <= 0) return;  // minimised
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  state_->renderer->draw(frame, width, height);
  if (overlay) overlay();
  if (state_->capture) {
    Image& image = state_->picture;
    image.width = width;
    image.height = height;
    image.rgba.resize(static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
    std::vector<uint8_t> bottom_up(image.rgba.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
    const size_t row = static_cast<size_t>(width) * 4;
    for (int y = 0; y < height; ++y)
      std::memcpy(&image.rgba[static_cast<size_t>(y) * row],
                  &bottom_up[static_cast<size_t>(height - 1 - y) * row], row);
  }
  glfwSwapBuffers(state_->window);
}

}  // namespace tacta::render
