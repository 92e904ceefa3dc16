// The OpenGL half of the render layer: the same pictures as the software renderer (render_mesh.h,
// markers.h), drawn with OpenGL 3.3 core. One code path serves the headless pictures (an EGL
// context on Mesa's llvmpipe, no X server: gl_context.h) and the interactive viewer (a GLFW
// window). GL entry points come from libepoxy, which resolves them in both settings.
//
// Conventions are the software renderer's: cameras and screen coordinates from camera.h (pixel
// (0, 0) top-left), RenderStyle fields with the same meaning, colours as sRGB Rgb in [0, 1].
#pragma once

#include <memory>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/render/camera.h"
#include "myoshell/render/image.h"
#include "myoshell/render/markers.h"
#include "myoshell/render/render_mesh.h"

namespace myo {

// Column-major 4×4 matrices for a camera: view (world → eye) and projection (eye → clip), so that
// clip = projection·view·(p, 1) lands p where project(camera, p, width, height) puts it.
// NDC y = +1 is the image's top row (row 0 once read back with read()/readFramebuffer()).
// The depth buffer covers view depths (camera.h's depth, cm) [depthNear, depthFar]: with d the
// eye–target distance and h the view height (orthoHeight, or the frustum's height at d),
// orthographic [−(d + 20h), d + 20h] (points behind the eye are drawn, as by the software
// renderer), perspective [d/100, 100·d + 20h].
struct GlCameraMatrices {
  Eigen::Matrix4f view;
  Eigen::Matrix4f projection;
  double depthNear = 0.0, depthFar = 1.0;  // cm
};
GlCameraMatrices glCameraMatrices(const Camera& camera, int width, int height);

// Draws meshes and markers into the framebuffer that is bound when frame calls are made. Needs a
// current OpenGL ≥ 3.3 core context for its whole life (construction compiles the shaders; the
// destructor frees GL objects). Throws RenderError with the GL info log when a shader fails.
// Each draw sets the GL state it needs and leaves: depth test on with GL_LESS, depth and colour
// writes on, blending, stencil test and culling off, no program or VAO bound; a translucent or
// depth-test-free mesh also leaves texture unit 0 active with no 2-D texture bound.
// Translucent and depth-test-free meshes use the stencil buffer when the framebuffer has one.
class GlRenderer {
 public:
  GlRenderer();
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  // Starts a frame of width × height pixels seen by `camera`: sets the viewport, clears colour to
  // `background` and depth. The frame's lower-left corner sits at (originX, originY) of the bound
  // framebuffer (GL pixels from its lower-left; the viewer draws the face right of its panel); the
  // clear covers the whole framebuffer.
  void beginFrame(const Camera& camera, int width, int height, const Rgb& background, int originX = 0,
                  int originY = 0);
  // Draws the mesh V (n×3, cm) with triangles F (m×3, counter-clockwise from the front side) in
  // `style` (all RenderStyle fields honoured: vertex colours, two-sided lighting and backColor,
  // culling, smooth/flat normals, wireframe overlay, depth test/write, opacity). Vertex data is
  // streamed every call, so V may change from frame to frame.
  void drawMesh(const MatX3& V, const MatX3i& F, const RenderStyle& style = {});
  // Discs of Marker::radius pixels, with MarkerStyle's outline and depth tolerance.
  void drawMarkers(const std::vector<Marker>& markers, const MarkerStyle& style = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// An offscreen colour + depth target of width × height pixels, multisampled with `samples`
// (1 for none), for headless pictures and screenshots. Needs a current context.
class GlOffscreenTarget {
 public:
  GlOffscreenTarget(int width, int height, int samples = 4);
  ~GlOffscreenTarget();
  GlOffscreenTarget(const GlOffscreenTarget&) = delete;
  GlOffscreenTarget& operator=(const GlOffscreenTarget&) = delete;

  void bind();               // subsequent draws go here
  Image read();              // resolves the samples and reads the pixels (row 0 at the top)
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_, samples_;
  unsigned msaaFbo_ = 0, msaaColor_ = 0, msaaDepth_ = 0, resolveFbo_ = 0, resolveColor_ = 0;
};

// Reads the pixels of the framebuffer currently bound for reading (e.g. a window's back buffer)
// into an Image, row 0 at the top.
Image readFramebuffer(int width, int height);

}  // namespace myo
