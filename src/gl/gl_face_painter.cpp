#include "myoshell/gl/gl_face_painter.h"

#include <algorithm>

#include "myoshell/core/errors.h"
#include "myoshell/gl/gl_context.h"

namespace myo {

void drawFaceScene(GlRenderer& renderer, const FaceScene& scene, int originX, int originY) {
  renderer.beginFrame(scene.camera, scene.width, scene.height, scene.background, originX, originY);
  for (const FaceScene::Mesh& mesh : scene.meshes) renderer.drawMesh(mesh.V, *mesh.F, mesh.style);
  if (!scene.markers.empty()) renderer.drawMarkers(scene.markers, scene.markerStyle);
}

namespace {

class GlPainter : public FacePainter {
 public:
  GlPainter() : context_(std::make_unique<HeadlessGlContext>()), renderer_(std::make_unique<GlRenderer>()) {}
  ~GlPainter() override {
    target_.reset();  // GL objects go before their context
    renderer_.reset();
  }
  Image paint(const FaceScene& scene) override {
    if (!target_ || target_->width() != scene.width || target_->height() != scene.height)
      target_ = std::make_unique<GlOffscreenTarget>(scene.width, scene.height, 4);
    target_->bind();
    drawFaceScene(*renderer_, scene);
    Image picture = target_->read();
    if (scene.colorBar) drawColorBar(picture, *scene.colorBar);
    return picture;
  }
  std::string name() const override { return "opengl (" + context_->renderer() + ")"; }

 private:
  std::unique_ptr<HeadlessGlContext> context_;
  std::unique_ptr<GlRenderer> renderer_;
  std::unique_ptr<GlOffscreenTarget> target_;
};

}  // namespace

std::unique_ptr<FacePainter> glPainter() { return std::make_unique<GlPainter>(); }

std::unique_ptr<FacePainter> makeFacePainter(bool software, std::string* warning) {
  if (!software) {
    try {
      return glPainter();
    } catch (const RenderError& e) {
      std::string why = e.what();  // one line, even with a shader compiler's log in it
      std::replace(why.begin(), why.end(), '\n', ' ');
      if (warning) *warning = "using the software renderer: " + why;
    }
  }
  return softwarePainter();
}

}  // namespace myo
