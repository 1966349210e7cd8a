// Off-screen rendering with no display and no GPU: an EGL context (Mesa's surfaceless platform,
// else the device platform) drawing into a framebuffer object, read back as an RGBA image.
#pragma once

#include <memory>
#include <string>

#include "tacta/render/frame.hpp"
#include "tacta/render/image.hpp"

namespace tacta::render {

struct HeadlessOptions {
  int width = 640;   // pixels
  int height = 480;  // pixels
  // Forces Mesa's software rasteriser (llvmpipe) on one thread, so pictures are the same on any
  // machine with or without a GPU: what the golden tests need. Sets LIBGL_ALWAYS_SOFTWARE and
  // LP_NUM_THREADS before EGL starts, unless already set.
  bool deterministic = true;
};

class HeadlessRenderer {
 public:
  // Throws std::runtime_error with EGL's reason when no context can be made.
  explicit HeadlessRenderer(const HeadlessOptions& options = {});
  ~HeadlessRenderer();
  HeadlessRenderer(const HeadlessRenderer&) = delete;
  HeadlessRenderer& operator=(const HeadlessRenderer&) = delete;

  Image render(const RenderFrame& frame);
  int width() const;
  int height() const;
  // e.g. "OpenGL 4.5 (Core Profile) Mesa 22.3.6 / llvmpipe (LLVM 15.0.6, 256 bits) via surfaceless"
  std::string description() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tacta::render
