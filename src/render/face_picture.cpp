#include "myoshell/render/face_picture.h"

#include <algorithm>

#include "myoshell/core/errors.h"

namespace myo {

ViewPreset parseView(const std::string& name) {
  if (name == "front") return ViewPreset::front;
  if (name == "three-quarter") return ViewPreset::threeQuarter;
  if (name == "profile") return ViewPreset::profile;
  if (name == "back") return ViewPreset::back;
  throw InputError("unknown view '" + name + "' (use front, three-quarter, profile or back)");
}

const char* viewName(ViewPreset view) {
  switch (view) {
    case ViewPreset::front: return "front";
    case ViewPreset::threeQuarter: return "three-quarter";
    case ViewPreset::profile: return "profile";
    case ViewPreset::back: return "back";
  }
  return "front";
}

FaceFraming parseFraming(const std::string& name) {
  if (name == "all") return FaceFraming::all;
  if (name == "head") return FaceFraming::head;
  if (name == "face") return FaceFraming::face;
  throw InputError("unknown framing '" + name + "' (use face, head or all)");
}

const char* framingName(FaceFraming framing) {
  switch (framing) {
    case FaceFraming::all: return "all";
    case FaceFraming::head: return "head";
    case FaceFraming::face: return "face";
  }
  return "all";
}

Camera faceCamera(const Head& head, ViewPreset view, int width, int height, FaceFraming framing) {
  const FaceFrame frame = head.frame();
  Camera camera = presetCamera(ViewFrame{frame.origin, frame.axes, frame.scale}, view);
  const MatX3& V = head.mesh.V;
  const auto named = head.landmarks.resolved();
  if (framing == FaceFraming::all || named.empty()) {
    fitToBounds(camera, V, width, height, 0.04);
    return camera;
  }
  MatX3 P(static_cast<Eigen::Index>(named.size()), 3);
  Eigen::Index i = 0;
  for (const auto& [name, v] : named) P.row(i++) = V.row(v);
  if (framing == FaceFraming::face) {
    fitToBounds(camera, P, width, height, 0.22);  // room above the brows
    return camera;
  }
  // head: every vertex above the chin, less a tenth of the landmarks' height (the jaw's underside).
  const Vec3 up = frame.axes.col(1);
  const VecX heights = P * up;
  const double cut = heights.minCoeff() - 0.1 * (heights.maxCoeff() - heights.minCoeff());
  const VecX all = V * up;
  MatX3 kept(V.rows(), 3);
  Eigen::Index k = 0;
  for (Eigen::Index r = 0; r < V.rows(); ++r)
    if (all(r) >= cut) kept.row(k++) = V.row(r);
  fitToBounds(camera, kept.topRows(k), width, height, 0.04);
  return camera;
}

Camera faceCamera(const FaceSystem& model, ViewPreset view, int width, int height, FaceFraming framing) {
  return faceCamera(model.head(), view, width, height, framing);
}

FaceFrameState faceFrameState(const FrameSnapshot& snapshot, const FaceOverlays& overlays) {
  FaceFrameState state;
  state.skin = snapshot.positions;
  if (overlays.displacement) state.displacement = snapshot.displacement;
  if (overlays.muscles) state.muscles = snapshot.muscles;
  return state;
}

FaceFrameState faceFrameState(const FaceStepper& sim, const FaceOverlays& overlays) {
  FaceFrameState state;
  state.skin = sim.skinPositions();
  if (overlays.displacement) state.displacement = sim.skinDisplacement();
  if (overlays.muscles)
    for (int m = 0; m < sim.face().muscleCount(); ++m) state.muscles.push_back(sim.musclePositions(m));
  return state;
}

FaceFrameState restFrameState(const FaceSystem& model) {
  FaceFrameState state;
  state.skin = model.head().mesh.V;
  state.displacement = MatX3::Zero(state.skin.rows(), 3);
  for (int m = 0; m < model.muscleCount(); ++m) state.muscles.push_back(model.muscleMesh(m).V);
  return state;
}

VecX roiWeights(const FaceModel& model, int muscle) {
  const MatX3& skin = model.head().mesh.V;
  VecX w = VecX::Zero(skin.rows());
  for (size_t m = 0; m < model.muscles().size(); ++m) {
    if (muscle >= 0 && static_cast<size_t>(muscle) != m) continue;
    const MuscleUnit& unit = model.muscles()[m];
    const MatX3& nodes = unit.muscle.mesh.V;
    for (const MuscleUnit::Spring& s : unit.springs) {
      const double reach = unit.roiAlpha * s.restVector.norm();
      if (!(reach > 0)) continue;
      const Vec3 p = nodes.row(s.muscleNode);
      for (int v : unit.roi) w[v] = std::max(w[v], 1.0 - (Vec3(skin.row(v)) - p).norm() / reach);
    }
  }
  return w;
}

FaceScene faceScene(const FaceSystem& model, const FaceFrameState& state, const Camera& camera, int width, int height,
                    const FaceOverlays& overlays, const VecX* roi) {
  const FacePalette& palette = kFacePalette;
  const TriMesh& skin = model.head().mesh;
  FaceScene scene;
  scene.width = width;
  scene.height = height;
  scene.camera = camera;
  scene.background = palette.background;

  FaceScene::Mesh skinMesh{state.skin, &skin.F, {}};
  skinMesh.style.color = palette.skin;
  skinMesh.style.backColor = palette.skinBack;
  skinMesh.style.wireframe = overlays.wireframe;
  if (overlays.skull && model.head().hasSkull()) {
    RenderStyle bone;
    bone.color = palette.bone;
    scene.meshes.push_back({model.head().skull.V, &model.head().skull.F, bone});
    skinMesh.style.opacity = overlays.skinOpacityOverMuscles;
  }
  if (overlays.muscles) {
    RenderStyle muscleStyle;
    muscleStyle.color = palette.muscle;
    for (int m = 0; m < model.muscleCount() && static_cast<size_t>(m) < state.muscles.size(); ++m)
      scene.meshes.push_back({state.muscles[static_cast<size_t>(m)], &model.muscleMesh(m).F, muscleStyle});
    skinMesh.style.opacity = overlays.skinOpacityOverMuscles;
  }
  ColorBar bar;
  bar.x = 12;
  bar.y = height - 34;
  bar.width = std::max(width / 3, std::min(200, width - 24));
  bar.textColor = palette.barText;
  if (overlays.freeVertices) {
    MatX3 colors(skin.vertexCount(), 3);
    colors.rowwise() = palette.pinned.transpose();
    for (int v : *overlays.freeVertices) colors.row(v) = palette.free.transpose();
    skinMesh.style.vertexColors = std::move(colors);
  } else if (overlays.displacement) {
    skinMesh.style.vertexColors = scalarColors(state.displacement.rowwise().norm(), 0.0, overlays.displacementScale);
    bar.max = overlays.displacementScale;
    bar.label = "displacement, cm";
    if (overlays.colorBar) scene.colorBar = bar;
  } else if (overlays.roi && roi) {
    MatX3 colors(skin.vertexCount(), 3);
    for (Eigen::Index v = 0; v < colors.rows(); ++v)
      colors.row(v) = ((*roi)[v] > 0 ? colormap((*roi)[v]) : palette.skin).transpose();
    skinMesh.style.vertexColors = std::move(colors);
    bar.max = 1.0;
    bar.label = "ROI weight";
    if (overlays.colorBar) scene.colorBar = bar;
  }
  scene.meshes.push_back(std::move(skinMesh));

  scene.markerStyle.depthTolerance = 0.02 * camera.orthoHeight;
  scene.markerStyle.outlineWidth = 0.8;
  if (overlays.pins)
    for (int v : model.pinnedVertices()) scene.markers.push_back({state.skin.row(v).transpose(), palette.pin, 2.5});
  for (int v : overlays.features)
    scene.markers.push_back({state.skin.row(v).transpose(), palette.feature, overlays.featureRadius});
  if (overlays.grabVertex >= 0 && overlays.grabVertex < state.skin.rows())
    scene.markers.push_back({state.skin.row(overlays.grabVertex).transpose(), palette.grab, 5.0});
  return scene;
}

FaceScene faceScene(const FaceSystem& model, const FaceFrameState& state, ViewPreset view, int width, int height,
                    const FaceOverlays& overlays, const VecX* roi, FaceFraming framing) {
  return faceScene(model, state, faceCamera(model, view, width, height, framing), width, height, overlays, roi);
}

namespace {

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
    if (scene.colorBar) drawColorBar(picture, *scene.colorBar);
    return picture;
  }
  std::string name() const override { return "software"; }
};

}  // namespace

std::unique_ptr<FacePainter> softwarePainter() { return std::make_unique<SoftwarePainter>(); }

}  // namespace myo
