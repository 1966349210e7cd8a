#include "tacta/render/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "scene_geometry.hpp"
#include "gl.hpp"
#include "math.hpp"
#include "overlay.hpp"
#include "shaders.hpp"

namespace tacta::render {

using namespace detail;

namespace {

// One vertex array plus its buffer, refilled every frame.
struct StreamBuffer {
  GLuint vao = 0;
  GLuint vbo = 0;
  void create() {
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
  }
  void destroy() {
    if (vbo != 0) glDeleteBuffers(1, &vbo);
    if (vao != 0) glDeleteVertexArrays(1, &vao);
    vao = vbo = 0;
  }
};

void float_attribute(GLuint location, GLint components, size_t stride, size_t offset) {
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(stride),
                        reinterpret_cast<const void*>(offset));
}

template <typename Vertex>
void upload(const StreamBuffer& buffer, const std::vector<Vertex>& vertices) {
  glBindVertexArray(buffer.vao);
  glBindBuffer(GL_ARRAY_BUFFER, buffer.vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(Vertex)),
               vertices.data(), GL_STREAM_DRAW);
}

const Rgb kToolColour{0.78f, 0.80f, 0.84f};
const Rgb kProxyColour{0.35f, 0.75f, 0.95f};
const Rgb kContactColour{0.95f, 0.25f, 0.20f};
const Rgb kForceColour{0.98f, 0.80f, 0.15f};

}  // namespace

class GlResources {
 public:
  GlResources() {
    lit_program = build_program(kLitVertex, kLitFragment, "lit");
    line_program = build_program(kLineVertex, kLineFragment, "line");
    overlay_program = build_program(kOverlayVertex, kOverlayFragment, "overlay");
    lit.create();
    glBindVertexArray(lit.vao);
    glBindBuffer(GL_ARRAY_BUFFER, lit.vbo);
    float_attribute(0, 3, sizeof(LitVertex), offsetof(LitVertex, position));
    float_attribute(1, 3, sizeof(LitVertex), offsetof(LitVertex, normal));
    float_attribute(2, 3, sizeof(LitVertex), offsetof(LitVertex, colour));
    lines.create();
    glBindVertexArray(lines.vao);
    glBindBuffer(GL_ARRAY_BUFFER, lines.vbo);
    float_attribute(0, 3, sizeof(LineVertex), offsetof(LineVertex, position));
    float_attribute(1, 3, sizeof(LineVertex), offsetof(LineVertex, colour));
    overlay.create();
    glBindVertexArray(overlay.vao);
    glBindBuffer(GL_ARRAY_BUFFER, overlay.vbo);
    float_attribute(0, 2, sizeof(OverlayVertex), offsetof(OverlayVertex, position));
    float_attribute(1, 4, sizeof(OverlayVertex), offsetof(OverlayVertex, colour));
    glBindVertexArray(0);
  }
  ~GlResources() {
    lit.destroy();
    lines.destroy();
    overlay.destroy();
    glDeleteProgram(lit_program);
    glDeleteProgram(line_program);
    glDeleteProgram(overlay_program);
  }
  GlResources(const GlResources&) = delete;
  GlResources& operator=(const GlResources&) = delete;

  GLuint lit_program = 0;
  GLuint line_program = 0;
  GLuint overlay_program = 0;
  StreamBuffer lit;
  StreamBuffer lines;
  StreamBuffer overlay;
  DrawLists scene;  // reused so capacity carries across frames
  std::vector<OverlayVertex> overlay_vertices;
};

Renderer::Renderer() : gl_(std::make_unique<GlResources>()) {}
Renderer::~Renderer() = default;

namespace {

void set_matrix(GLuint program, const char* name, const Mat4& m) {
  glUniformMatrix4fv(glGetUniformLocation(program, name), 1, GL_FALSE, m.data());
}

void build_scene(const RenderFrame& frame, const Bounds& bounds, DrawLists& out) {
  out.clear();
  const double diagonal = norm(sub(bounds.max, bounds.min));
  const double marker = std::max(diagonal * 0.006, 1e-5);  // m, half-size of node markers
  for (size_t i = 0; i < frame.bodies.size(); ++i) append_body(frame.bodies[i], i, marker, out);
  append_tool(frame.tool, kToolColour, out);
  if (frame.proxy)
    append_sphere(*frame.proxy, std::max(frame.tool.radius * 0.6, marker), kProxyColour, out);
  for (const ContactDraw& contact : frame.contacts) {
    append_sphere(contact.point, marker * 1.2, kContactColour, out);
    const Vec3d tip = add(contact.point, scaled(normalized(contact.normal), diagonal * 0.06));
    out.lines.push_back({to_f(contact.point), kContactColour});
    out.lines.push_back({to_f(tip), kContactColour});
  }
  if (frame.tool.present)
    append_arrow(frame.tool.position, scaled(frame.force, frame.force_arrow_scale), marker * 1.2,
                 kForceColour, out);
  if (frame.floor_height) append_floor_grid(*frame.floor_height, bounds, out);
  if (frame.axes) append_axes(std::max(diagonal * 0.25, 1e-3), out);
}

}  // namespace

void Renderer::draw(const RenderFrame& frame, int width, int height) {
  GlResources& g = *gl_;
  const Bounds bounds = frame_bounds(frame);
  build_scene(frame, bounds, g.scene);

  glViewport(0, 0, width, height);
  glClearColor(frame.background[0], frame.background[1], frame.background[2], 1);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);  // bodies may be open surfaces; lighting is two-sided
  glDisable(GL_BLEND);

  // Clip planes from the scene's extent as seen from the eye, grid margin included.
  const Vec3d centre = scaled(add(bounds.min, bounds.max), 0.5);
  const double radius = std::max(0.5 * norm(sub(bounds.max, bounds.min)), 1e-3);
  const double distance = norm(sub(frame.camera.eye, centre));
  const double far_m = distance + 6 * radius;
  const double near_m = std::max({far_m * 1e-4, distance - 6 * radius, 1e-5});
  const Mat4 view = look_at(frame.camera.eye, frame.camera.target, frame.camera.up);
  const Mat4 projection =
      perspective(frame.camera.vertical_fov_rad, static_cast<double>(width) / std::max(height, 1),
                  near_m, far_m);

  if (!g.scene.triangles.empty()) {
    glUseProgram(g.lit_program);
    set_matrix(g.lit_program, "view", view);
    set_matrix(g.lit_program, "projection", projection);
    upload(g.lit, g.scene.triangles);
    // Pushes filled faces back a little so wireframe edges on them win the depth test.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(g.scene.triangles.size()));
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  if (!g.scene.lines.empty()) {
    glUseProgram(g.line_program);
    set_matrix(g.line_program, "view", view);
    set_matrix(g.line_program, "projection", projection);
    upload(g.lines, g.scene.lines);
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(g.scene.lines.size()));
  }

  g.overlay_vertices.clear();
  const float glyph_scale = height >= 360 ? 2.0f : 1.0f;
  append_text_panel(frame.overlay_lines, glyph_scale, g.overlay_vertices);
  for (const BodyDraw& body : frame.bodies)
    if (!body.scalar.empty()) {
      append_colour_bar(body.scalar_min, body.scalar_max, width, height, glyph_scale,
                        g.overlay_vertices);
      break;  // one bar: the first coloured body's range
    }
  if (!g.overlay_vertices.empty()) {
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(g.overlay_program);
    set_matrix(g.overlay_program, "projection", orthographic_pixels(width, height));
    upload(g.overlay, g.overlay_vertices);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(g.overlay_vertices.size()));
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
  }
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace tacta::render
