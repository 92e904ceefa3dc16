// A headless OpenGL 3.3 core context through EGL (Mesa's llvmpipe when no GPU is present): no X
// server, no window. Pictures are drawn into a GlOffscreenTarget (gl_renderer.h).
#pragma once

#include <memory>
#include <string>

namespace myo {

class HeadlessGlContext {
 public:
  // Creates the context and makes it current on this thread. Throws RenderError saying what EGL
  // refused (no display, no OpenGL 3.3 core, …) so callers can fall back to the software renderer.
  HeadlessGlContext();
  ~HeadlessGlContext();
  HeadlessGlContext(const HeadlessGlContext&) = delete;
  HeadlessGlContext& operator=(const HeadlessGlContext&) = delete;

  // GL_RENDERER and GL_VERSION strings, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string renderer() const;
  std::string version() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace myo
