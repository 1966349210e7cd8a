// GLSL 3.30 core sources of the renderer's three programs, and a helper that builds one.
#pragma once

#include "gl.hpp"

namespace tacta::render::detail {

// Lit triangles: world position, normal, colour; two-sided Blinn-Phong with a light fixed to
// the camera (upper left) and a dim fill from below, so any view shows the shape.
inline constexpr const char* kLitVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 colour;
uniform mat4 view;
uniform mat4 projection;
out vec3 view_position;
out vec3 view_normal;
out vec3 base_colour;
void main() {
  vec4 p = view * vec4(position, 1.0);
  view_position = p.xyz;
  view_normal = mat3(view) * normal;
  base_colour = colour;
  gl_Position = projection * p;
}
)";

inline constexpr const char* kLitFragment = R"(#version 330 core
in vec3 view_position;
in vec3 view_normal;
in vec3 base_colour;
out vec4 frag_colour;
void main() {
  vec3 n = normalize(view_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 to_eye = normalize(-view_position);
  vec3 key = normalize(vec3(-0.35, 0.6, 0.75));
  vec3 fill = normalize(vec3(0.4, -0.5, 0.3));
  float diffuse = max(dot(n, key), 0.0) * 0.72 + max(dot(n, fill), 0.0) * 0.18;
  float specular = pow(max(dot(n, normalize(key + to_eye)), 0.0), 40.0) * 0.25;
  vec3 c = base_colour * (0.22 + diffuse) + vec3(specular);
  frag_colour = vec4(min(c, vec3(1.0)), 1.0);
}
)";

// Unlit lines in world space.
inline constexpr const char* kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 colour;
uniform mat4 view;
uniform mat4 projection;
out vec3 line_colour;
void main() {
  line_colour = colour;
  gl_Position = projection * view * vec4(position, 1.0);
}
)";

inline constexpr const char* kLineFragment = R"(#version 330 core
in vec3 line_colour;
out vec4 frag_colour;
void main() { frag_colour = vec4(line_colour, 1.0); }
)";

// Screen-space overlay (text and panels) in pixels, origin at the top left, with alpha.
inline constexpr const char* kOverlayVertex = R"(#version 330 core
layout(location = 0) in vec2 position;
layout(location = 1) in vec4 colour;
uniform mat4 projection;
out vec4 overlay_colour;
void main() {
  overlay_colour = colour;
  gl_Position = projection * vec4(position, 0.0, 1.0);
}
)";

inline constexpr const char* kOverlayFragment = R"(#version 330 core
in vec4 overlay_colour;
out vec4 frag_colour;
void main() { frag_colour = overlay_colour; }
)";

// Compiles and links; throws std::runtime_error with the GL info log on failure.
GLuint build_program(const char* vertex_source, const char* fragment_source, const char* name);

}  // namespace tacta::render::detail
