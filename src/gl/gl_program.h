// Internal to the gl layer: compiling and linking GLSL programs, with RenderError on failure.
#pragma once

#include <epoxy/gl.h>

#include <string>

namespace myo::gl {

// Links a program from vertex, optional geometry (empty: none) and fragment shader sources.
// Throws RenderError naming `name`, the stage and the GL info log when a stage fails.
GLuint linkProgram(const std::string& name, const char* vertex, const char* geometry, const char* fragment);

}  // namespace myo::gl
