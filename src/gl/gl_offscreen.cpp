// GlOffscreenTarget and readFramebuffer: drawing without a window, and reading pixels back.
#include <epoxy/gl.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/gl/gl_renderer.h"

namespace myo {
namespace {

void checkComplete(const char* which) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw RenderError(std::string("OpenGL: the offscreen ") + which + " framebuffer is incomplete (status 0x" +
                      [&] {
                        char b[16];
                        std::snprintf(b, sizeof b, "%04X", status);
                        return std::string(b);
                      }() + ")");
}

// Storage for the bound renderbuffer: multisampled when samples > 1.
void renderbufferStorage(int samples, GLenum format, int width, int height) {
  if (samples > 1) glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
  else glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
}

}  // namespace

GlOffscreenTarget::GlOffscreenTarget(int width, int height, int samples)
    : width_(width), height_(height), samples_(samples) {
  MYO_CHECK(width > 0 && height > 0, "offscreen target size " << width << "×" << height);
  GLint maxSamples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  samples_ = std::clamp(samples, 1, std::max(1, static_cast<int>(maxSamples)));

  glGenFramebuffers(1, &msaaFbo_);
  glGenRenderbuffers(1, &msaaColor_);
  glGenRenderbuffers(1, &msaaDepth_);
  glBindFramebuffer(GL_FRAMEBUFFER, msaaFbo_);
  glBindRenderbuffer(GL_RENDERBUFFER, msaaColor_);
  renderbufferStorage(samples_, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaaColor_);
  glBindRenderbuffer(GL_RENDERBUFFER, msaaDepth_);
  renderbufferStorage(samples_, GL_DEPTH24_STENCIL8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, msaaDepth_);
  try {
    checkComplete("multisampled");

    glGenFramebuffers(1, &resolveFbo_);
    glGenRenderbuffers(1, &resolveColor_);
    glBindFramebuffer(GL_FRAMEBUFFER, resolveFbo_);
    glBindRenderbuffer(GL_RENDERBUFFER, resolveColor_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolveColor_);
    checkComplete("resolve");
  } catch (const RenderError&) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &msaaFbo_);
    glDeleteFramebuffers(1, &resolveFbo_);  // 0 is ignored
    const GLuint renderbuffers[] = {msaaColor_, msaaDepth_, resolveColor_};
    glDeleteRenderbuffers(3, renderbuffers);
    throw;
  }
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, msaaFbo_);
}

GlOffscreenTarget::~GlOffscreenTarget() {
  glDeleteFramebuffers(1, &msaaFbo_);
  glDeleteFramebuffers(1, &resolveFbo_);
  const GLuint renderbuffers[] = {msaaColor_, msaaDepth_, resolveColor_};
  glDeleteRenderbuffers(3, renderbuffers);
}

void GlOffscreenTarget::bind() {
  glBindFramebuffer(GL_FRAMEBUFFER, msaaFbo_);
  glViewport(0, 0, width_, height_);
}

Image GlOffscreenTarget::read() {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, msaaFbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolveFbo_);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolveFbo_);
  Image image = readFramebuffer(width_, height_);
  glBindFramebuffer(GL_FRAMEBUFFER, msaaFbo_);  // further draws go on into this target
  return image;
}

Image readFramebuffer(int width, int height) {
  MYO_CHECK(width >= 0 && height >= 0, "framebuffer size " << width << "×" << height);
  Image image(width, height);
  if (width == 0 || height == 0) return image;
  std::vector<std::uint8_t> rows(static_cast<size_t>(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
  // GL's row 0 is the bottom one.
  const size_t stride = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y)
    std::memcpy(image.pixels.data() + static_cast<size_t>(y) * stride,
                rows.data() + static_cast<size_t>(height - 1 - y) * stride, stride);
  return image;
}

}  // namespace myo
