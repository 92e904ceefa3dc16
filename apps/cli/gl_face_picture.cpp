#include "gl_face_picture.h"

#include <algorithm>

#include <fmt/core.h>

#include "myoshell/core/errors.h"
#include "myoshell/gl/gl_context.h"
#include "myoshell/gl/gl_renderer.h"

namespace myo::cli {

FaceFrameState faceFrameState(const Simulator& sim, const FaceOverlays& overlays) {
  FaceFrameState state;
  state.skin = sim.skinPositions();
  if (overlays.displacement) state.displacement = sim.skinDisplacement();
  if (overlays.muscles)
    for (int m = 0; m < static_cast<int>(sim.model().muscles().size()); ++m) state.muscles.push_back(sim.musclePositions(m));
  return state;
}

VecX roiWeights(const FaceModel& model) {
  const MatX3& skin = model.head().mesh.V;
  VecX w = VecX::Zero(skin.rows());
  for (const MuscleUnit& unit : model.muscles()) {
    const MatX3& nodes = unit.muscle.mesh.V;
    for (const MuscleUnit::Spring& s : unit.springs) {
      const double reach = unit.roiAlpha * s.restVector.norm();
      if (!(reach > 0)) continue;
      const Vec3 m = nodes.row(s.muscleNode);
      for (int v : unit.roi) w[v] = std::max(w[v], 1.0 - (Vec3(skin.row(v)) - m).norm() / reach);
    }
  }
  return w;
}

FaceScene faceScene(const FaceModel& model, const FaceFrameState& state, ViewPreset view, int width, int height,
                    const FaceOverlays& overlays, const VecX* roi) {
  const TriMesh& skin = model.head().mesh;
  const FaceFrame frame = model.head().frame();
  ViewFrame viewFrame;
  viewFrame.origin = frame.origin;
  viewFrame.axes = frame.axes;
  viewFrame.scale = frame.scale;
  FaceScene scene;
  scene.width = width;
  scene.height = height;
  scene.camera = presetCamera(viewFrame, view);
  fitToBounds(scene.camera, skin.V, width, height, 0.04);  // the rest head: frames line up

  FaceScene::Mesh skinMesh{state.skin, &skin.F, {}};
  if (overlays.muscles) {
    RenderStyle muscleStyle;
    muscleStyle.color = Rgb(0.75, 0.18, 0.16);
    for (size_t m = 0; m < model.muscles().size(); ++m)
      scene.meshes.push_back({state.muscles[m], &model.muscles()[m].muscle.mesh.F, muscleStyle});
    skinMesh.style.opacity = 0.55;
  }
  ColorBar bar;
  bar.x = 12;
  bar.y = height - 34;
  bar.width = std::max(width / 3, std::min(200, width - 24));
  bar.textColor = Rgb(1, 1, 1);
  if (overlays.displacement) {
    skinMesh.style.vertexColors = scalarColors(state.displacement.rowwise().norm(), 0.0, overlays.displacementScale);
    bar.max = overlays.displacementScale;
    bar.label = "displacement, cm";
    scene.colorBar = bar;
  } else if (overlays.roi && roi) {
    MatX3 colors(skin.vertexCount(), 3);
    for (Eigen::Index v = 0; v < colors.rows(); ++v)
      colors.row(v) = (*roi)[v] > 0 ? colormap((*roi)[v]).transpose() : skinMesh.style.color.transpose();
    skinMesh.style.vertexColors = std::move(colors);
    bar.max = 1.0;
    bar.label = "ROI weight";
    scene.colorBar = bar;
  }
  scene.meshes.push_back(std::move(skinMesh));
  if (overlays.pins)
    for (int v : model.gravityPins()) {
      Marker m;
      m.position = state.skin.row(v).transpose();
      m.color = Rgb(1.0, 0.82, 0.1);
      m.radius = 2.5;
      scene.markers.push_back(m);
    }
  return scene;
}

namespace {

void drawBar(Image& picture, const FaceScene& scene) {
  if (scene.colorBar) drawColorBar(picture, *scene.colorBar);
}

class SoftwarePainter : public FacePainter {
 public:
  Image paint(const FaceScene& scene) override {
    constexpr int kSupersample = 2;  // render at twice the size, then average: smoother edges
    const int w = scene.width * kSupersample, h = scene.height * kSupersample;
    Image image(w, h, scene.background);
    DepthBuffer depth(w, h);
    for (const FaceScene::Mesh& mesh : scene.meshes) {
      RenderStyle style = mesh.style;
      style.wireWidth *= kSupersample;
      renderMesh(image, depth, scene.camera, mesh.V, *mesh.F, style);
    }
    if (!scene.markers.empty()) {
      std::vector<Marker> markers = scene.markers;
      for (Marker& m : markers) m.radius *= kSupersample;
      MarkerStyle style = scene.markerStyle;
      style.outlineWidth *= kSupersample;
      drawMarkers(image, &depth, scene.camera, markers, style);
    }
    Image picture = downsample(image, kSupersample);
    drawBar(picture, scene);
    return picture;
  }
  std::string name() const override { return "software"; }
};

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
    renderer_->beginFrame(scene.camera, scene.width, scene.height, scene.background);
    for (const FaceScene::Mesh& mesh : scene.meshes) renderer_->drawMesh(mesh.V, *mesh.F, mesh.style);
    if (!scene.markers.empty()) renderer_->drawMarkers(scene.markers, scene.markerStyle);
    Image picture = target_->read();
    drawBar(picture, scene);
    return picture;
  }
  std::string name() const override { return "opengl (" + context_->renderer() + ")"; }

 private:
  std::unique_ptr<HeadlessGlContext> context_;
  std::unique_ptr<GlRenderer> renderer_;
  std::unique_ptr<GlOffscreenTarget> target_;
};

}  // namespace

std::unique_ptr<FacePainter> softwarePainter() { return std::make_unique<SoftwarePainter>(); }
std::unique_ptr<FacePainter> glPainter() { return std::make_unique<GlPainter>(); }

std::unique_ptr<FacePainter> makePainter(bool software) {
  if (!software) {
    try {
      return glPainter();
    } catch (const RenderError& e) {
      std::string why = e.what();  // one line, even with a shader compiler's log in it
      std::replace(why.begin(), why.end(), '\n', ' ');
      fmt::print(stderr, "myoshell: warning: using the software renderer: {}\n", why);
    }
  }
  return softwarePainter();
}

}  // namespace myo::cli
