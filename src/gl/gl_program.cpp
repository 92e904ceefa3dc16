#include "gl_program.h"

#include <algorithm>
#include <vector>

#include "myoshell/core/errors.h"

namespace myo::gl {
namespace {

std::string shaderLog(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return log.data();
}

GLuint compile(const std::string& name, GLenum stage, const char* source) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = shaderLog(shader);
    glDeleteShader(shader);
    const char* stageName = stage == GL_VERTEX_SHADER ? "vertex" : stage == GL_GEOMETRY_SHADER ? "geometry" : "fragment";
    throw RenderError("OpenGL: the " + name + " " + stageName + " shader does not compile: " + log);
  }
  return shader;
}

}  // namespace

GLuint linkProgram(const std::string& name, const char* vertex, const char* geometry, const char* fragment) {
  std::vector<GLuint> shaders;
  try {
    shaders.push_back(compile(name, GL_VERTEX_SHADER, vertex));
    if (geometry) shaders.push_back(compile(name, GL_GEOMETRY_SHADER, geometry));
    shaders.push_back(compile(name, GL_FRAGMENT_SHADER, fragment));
  } catch (...) {
    for (GLuint s : shaders) glDeleteShader(s);
    throw;
  }
  const GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) {
    glDetachShader(program, s);
    glDeleteShader(s);
  }
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    throw RenderError("OpenGL: the " + name + " program does not link: " + std::string(log.data()));
  }
  return program;
}

}  // namespace myo::gl
