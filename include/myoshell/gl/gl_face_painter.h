// Face pictures (render/face_picture.h) drawn with OpenGL: into the bound framebuffer (the
// viewer's window) or offscreen through a headless EGL context (`run`, `render`, `figures`).
#pragma once

#include <memory>
#include <string>

#include "myoshell/gl/gl_renderer.h"
#include "myoshell/render/face_picture.h"

namespace myo {

// Draws the scene's meshes and markers with `renderer` into the bound framebuffer, the frame's
// lower-left corner at (originX, originY) GL pixels. The colour bar is not drawn (it is a
// picture's, painted after read-back).
void drawFaceScene(GlRenderer& renderer, const FaceScene& scene, int originX = 0, int originY = 0);

// OpenGL 3.3 through a headless EGL context, 4× multisampled. Throws RenderError (saying why)
// when no such context can be made.
std::unique_ptr<FacePainter> glPainter();
// OpenGL unless `software` or no context can be made: then the software rasterizer, and
// `*warning` (when given) says why on one line.
std::unique_ptr<FacePainter> makeFacePainter(bool software, std::string* warning = nullptr);

}  // namespace myo
