// OpenGL entry points: glvnd's libOpenGL exports every core function, so the prototypes are
// enough (no loader) for both the EGL and the GLFW front ends.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
