#include "face_picture.h"

#include "myoshell/render/colormap.h"
#include "myoshell/render/contact_sheet.h"
#include "myoshell/render/render_mesh.h"

namespace myo::cli {

Image renderFace(const Simulator& sim, const FacePictureOptions& options) {
  const FaceModel& model = sim.model();
  const TriMesh& skin = model.head().mesh;
  const FaceFrame frame = model.head().frame();
  constexpr int kSupersample = 2;  // render at twice the size, then average: smoother edges
  const int w = options.width * kSupersample, h = options.height * kSupersample;

  ViewFrame view;
  view.origin = frame.origin;
  view.axes = frame.axes;
  view.scale = frame.scale;
  Camera camera = presetCamera(view, options.view);
  fitToBounds(camera, skin.V, w, h, 0.04);  // framed on the rest head, so frames line up

  Image image(w, h, Rgb(0.16, 0.17, 0.20));
  DepthBuffer depth(w, h);
  const MatX3 positions = sim.skinPositions();
  RenderStyle skinStyle;
  if (options.displacementScale > 0.0)
    skinStyle.vertexColors = scalarColors(sim.skinDisplacement().rowwise().norm(), 0.0, options.displacementScale);
  if (options.showMuscles) {
    // Muscles first, then the skin over them at partial opacity.
    RenderStyle muscleStyle;
    muscleStyle.color = Rgb(0.75, 0.18, 0.16);
    for (int m = 0; m < static_cast<int>(model.muscles().size()); ++m)
      renderMesh(image, depth, camera, sim.musclePositions(m), model.muscles()[static_cast<size_t>(m)].muscle.mesh.F,
                 muscleStyle);
    skinStyle.opacity = 0.55;
  }
  renderMesh(image, depth, camera, positions, skin.F, skinStyle);
  Image picture = downsample(image, kSupersample);
  if (options.displacementScale > 0.0) {
    ColorBar bar;
    bar.x = 12;
    bar.y = picture.height - 34;
    bar.width = picture.width / 3;
    bar.max = options.displacementScale;
    bar.textColor = Rgb(1, 1, 1);
    bar.label = "displacement, cm";
    drawColorBar(picture, bar);
  }
  return options.caption.empty() ? picture : withCaption(picture, options.caption);
}

}  // namespace myo::cli
