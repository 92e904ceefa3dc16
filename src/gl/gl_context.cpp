#include "myoshell/gl/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "myoshell/core/errors.h"

namespace myo {
namespace {

std::string eglErrorName(EGLint code) {
  switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "EGL error 0x" + [&] {
      char buf[16];
      std::snprintf(buf, sizeof buf, "%04X", static_cast<unsigned>(code));
      return std::string(buf);
    }();
  }
}

[[noreturn]] void fail(const std::string& call, const std::string& detail = {}) {
  std::string message = "headless OpenGL: " + call + " failed (" + eglErrorName(eglGetError()) + ")";
  if (!detail.empty()) message += ": " + detail;
  throw RenderError(message);
}

// Whether the space-separated extension list `list` (may be null) names `name`.
bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)); p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

}  // namespace

struct HeadlessGlContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;  // a 1×1 pbuffer only when surfaceless contexts are missing
};

HeadlessGlContext::HeadlessGlContext() : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  // Client extensions (EGL 1.5 or EGL_EXT_client_extensions); null when neither is there.
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  EGLint major = 0, minor = 0;
  bool initialized = false;
  // Mesa's surfaceless platform needs neither an X server nor /dev/dri (it falls back to llvmpipe).
  if (hasExtension(client, "EGL_MESA_platform_surfaceless") && hasExtension(client, "EGL_EXT_platform_base")) {
    s.display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    initialized = s.display != EGL_NO_DISPLAY && eglInitialize(s.display, &major, &minor);
  }
  if (!initialized) {
    s.display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (s.display == EGL_NO_DISPLAY) fail("eglGetDisplay(EGL_DEFAULT_DISPLAY)", "no EGL display");
    if (!eglInitialize(s.display, &major, &minor)) fail("eglInitialize");
  }
  if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)", "this EGL has no desktop OpenGL");

  const char* displayExtensions = eglQueryString(s.display, EGL_EXTENSIONS);
  const bool surfaceless = hasExtension(displayExtensions, "EGL_KHR_surfaceless_context");
  const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                     EGL_SURFACE_TYPE, surfaceless ? 0 : EGL_PBUFFER_BIT,
                                     EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                     EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configCount = 0;
  if (!eglChooseConfig(s.display, configAttributes, &config, 1, &configCount)) fail("eglChooseConfig");
  if (configCount < 1) fail("eglChooseConfig", "no RGB8 OpenGL configuration");

  const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
  s.context = eglCreateContext(s.display, config, EGL_NO_CONTEXT, contextAttributes);
  if (s.context == EGL_NO_CONTEXT) fail("eglCreateContext", "no OpenGL 3.3 core context");
  if (!surfaceless) {
    const EGLint pbufferAttributes[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    s.surface = eglCreatePbufferSurface(s.display, config, pbufferAttributes);
    if (s.surface == EGL_NO_SURFACE) {
      eglDestroyContext(s.display, s.context);
      fail("eglCreatePbufferSurface");
    }
  }
  if (!eglMakeCurrent(s.display, s.surface, s.surface, s.context)) {
    if (s.surface != EGL_NO_SURFACE) eglDestroySurface(s.display, s.surface);
    eglDestroyContext(s.display, s.context);
    fail("eglMakeCurrent");
  }
  if (epoxy_gl_version() < 33) {
    const std::string version = this->version();
    eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (s.surface != EGL_NO_SURFACE) eglDestroySurface(s.display, s.surface);
    eglDestroyContext(s.display, s.context);
    throw RenderError("headless OpenGL: the context is OpenGL " + version + ", 3.3 core is needed");
  }
}

HeadlessGlContext::~HeadlessGlContext() {
  Impl& s = *impl_;
  if (eglGetCurrentContext() == s.context) eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (s.surface != EGL_NO_SURFACE) eglDestroySurface(s.display, s.surface);
  eglDestroyContext(s.display, s.context);
  // No eglTerminate: the display is shared by every context of the process (EGL hands out one
  // handle per platform display), and terminating it would break the others.
}

std::string HeadlessGlContext::renderer() const {
  const auto* s = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return s ? s : "";
}

std::string HeadlessGlContext::version() const {
  const auto* s = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return s ? s : "";
}

}  // namespace myo
