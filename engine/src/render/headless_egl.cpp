#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

#include "gl.hpp"
#include "tacta/render/headless.hpp"
#include "tacta/render/renderer.hpp"
#include "tacta/scene.hpp"

namespace tacta::render {

namespace {

std::string egl_error_name(EGLint code) {
  switch (code) {
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    default:
      return "EGL error 0x" + [&] {
        char b[16];
        std::snprintf(b, sizeof b, "%x", static_cast<unsigned>(code));
        return std::string(b);
      }();
  }
}

[[noreturn]] void fail(const std::string& step) {
  throw std::runtime_error("headless render: " + step + " failed (" +
                           egl_error_name(eglGetError()) +
                           "); needs Mesa's EGL (libegl-mesa0, libgl1-mesa-dri)");
}

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + n, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// One EGL display a process, initialised on first use and never terminated: terminating
// unloads Mesa's driver, which strands its internal allocations (LeakSanitizer reports them),
// and a later renderer would pay the driver start-up again.
std::mutex display_mutex;
EGLDisplay shared_display = EGL_NO_DISPLAY;
std::string shared_platform;

EGLDisplay open_display(std::string& platform) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_platform_display != nullptr && has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay display =
        get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr) == EGL_TRUE) {
      platform = "surfaceless";
      return display;
    }
  }
  auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (get_platform_display != nullptr && query_devices != nullptr &&
      has_extension(client, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (query_devices(8, devices, &count) == EGL_TRUE)
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr) == EGL_TRUE) {
          platform = "device " + std::to_string(i);
          return display;
        }
      }
  }
  fail("opening an EGL display (surfaceless or device platform)");
}

}  // namespace

struct HeadlessRenderer::State {
  HeadlessOptions options;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::string platform;
  GLuint framebuffer = 0;
  GLuint colour_buffer = 0;
  GLuint depth_buffer = 0;
  std::unique_ptr<Renderer> renderer;
  void release();  // frees GL objects, the context and this renderer's use of the display
};

HeadlessRenderer::HeadlessRenderer(const HeadlessOptions& options)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.options = options;
  if (options.width <= 0 || options.height <= 0 || options.width > kMaxFrameSide ||
      options.height > kMaxFrameSide)
    throw std::invalid_argument("headless render: size " + std::to_string(options.width) + "x" +
                                std::to_string(options.height) + " is outside 1.." +
                                std::to_string(kMaxFrameSide) + " pixels");
  if (options.deterministic) {
    // Before the driver loads: Mesa reads these once.
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    setenv("LP_NUM_THREADS", "1", 0);
  }
  {
    std::lock_guard lock(display_mutex);
    if (shared_display == EGL_NO_DISPLAY) shared_display = open_display(shared_platform);
    s.display = shared_display;
    s.platform = shared_platform;
  }
  try {
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) fail("eglBindAPI(OpenGL)");
    const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint config_count = 0;
    eglChooseConfig(s.display, config_attributes, &config, 1, &config_count);
    const bool no_config =
        has_extension(eglQueryString(s.display, EGL_EXTENSIONS), "EGL_KHR_no_config_context");
    if (config_count < 1 && !no_config) fail("eglChooseConfig(OpenGL)");
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         3,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         3,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    s.context = eglCreateContext(s.display, config_count > 0 ? config : EGL_NO_CONFIG_KHR,
                                 EGL_NO_CONTEXT, context_attributes);
    if (s.context == EGL_NO_CONTEXT) fail("creating an OpenGL 3.3 core context");
    if (eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, s.context) != EGL_TRUE)
      fail("eglMakeCurrent without a surface");

    glGenFramebuffers(1, &s.framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, s.framebuffer);
    glGenRenderbuffers(1, &s.colour_buffer);
    glBindRenderbuffer(GL_RENDERBUFFER, s.colour_buffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, options.width, options.height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              s.colour_buffer);
    glGenRenderbuffers(1, &s.depth_buffer);
    glBindRenderbuffer(GL_RENDERBUFFER, s.depth_buffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, options.width, options.height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s.depth_buffer);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("headless render: the off-screen framebuffer is incomplete");
    s.renderer = std::make_unique<Renderer>();
    // Released after every use so that any one thread at a time may render (a render task).
    eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  } catch (...) {
    s.release();
    throw;
  }
}

HeadlessRenderer::~HeadlessRenderer() {
  if (state_) state_->release();
}

void HeadlessRenderer::State::release() {
  State& s = *this;
  if (s.context != EGL_NO_CONTEXT) {
    eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, s.context);
    s.renderer.reset();
    if (s.depth_buffer != 0) glDeleteRenderbuffers(1, &s.depth_buffer);
    if (s.colour_buffer != 0) glDeleteRenderbuffers(1, &s.colour_buffer);
    if (s.framebuffer != 0) glDeleteFramebuffers(1, &s.framebuffer);
    eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(s.display, s.context);
    s.context = EGL_NO_CONTEXT;
  }
  s.display = EGL_NO_DISPLAY;  // shared: stays initialised for the process
}

Image HeadlessRenderer::render(const RenderFrame& frame) {
  State& s = *state_;
  // The caller's thread may differ from the one that made the context: bind it here, release
  // it at the end (also when drawing throws on bad input).
  if (eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, s.context) != EGL_TRUE)
    fail("eglMakeCurrent");
  struct Release {
    EGLDisplay display;
    ~Release() { eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }
  } release{s.display};
  glBindFramebuffer(GL_FRAMEBUFFER, s.framebuffer);
  s.renderer->draw(frame, s.options.width, s.options.height);
  glFinish();
  Image image;
  image.width = s.options.width;
  image.height = s.options.height;
  image.rgba.resize(static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 4);
  std::vector<uint8_t> bottom_up(image.rgba.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  const size_t row = static_cast<size_t>(image.width) * 4;
  for (int y = 0; y < image.height; ++y)  // GL's first row is the bottom one
    std::memcpy(&image.rgba[static_cast<size_t>(y) * row],
                &bottom_up[static_cast<size_t>(image.height - 1 - y) * row], row);
  return image;
}

int HeadlessRenderer::width() const { return state_->options.width; }
int HeadlessRenderer::height() const { return state_->options.height; }

std::string HeadlessRenderer::description() const {
  eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, state_->context);
  auto text = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  const std::string what =
      "OpenGL " + text(GL_VERSION) + " / " + text(GL_RENDERER) + " via " + state_->platform;
  eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  return what;
}

}  // namespace tacta::render
