// The OpenGL 3.3 core renderer. It draws a RenderFrame into whatever framebuffer is bound on the
// current context; the front ends (headless EGL, GLFW window) own the context and the target.
#pragma once

#include <memory>

#include "tacta/render/frame.hpp"

namespace tacta::render {

class GlResources;  // shaders, buffers: defined in the implementation

class Renderer {
 public:
  // Needs a current OpenGL 3.3 core context; throws std::runtime_error when shaders fail.
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws the frame into the bound framebuffer over a viewport of width x height pixels.
  void draw(const RenderFrame& frame, int width, int height);

 private:
  std::unique_ptr<GlResources> gl_;
};

}  // namespace tacta::render
