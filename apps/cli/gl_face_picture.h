// Pictures of a simulated face through either renderer: what one picture holds (meshes with their
// styles, markers, a colour bar), built from a face model, a frame's state and the overlays asked
// for; and painters that draw it with OpenGL (a headless EGL context) or the software rasterizer.
// Used by `myoshell render`, `run --render/--video` and `demo`.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "myoshell/face/face_model.h"
#include "myoshell/face/simulator.h"
#include "myoshell/render/camera.h"
#include "myoshell/render/colormap.h"
#include "myoshell/render/image.h"
#include "myoshell/render/markers.h"
#include "myoshell/render/render_mesh.h"

namespace myo::cli {

// One picture, renderer-neutral. Sizes (pixels, marker radii, wire widths) are the final picture's.
struct FaceScene {
  Camera camera;
  int width = 480, height = 480;  // pixels
  Rgb background = Rgb(0.16, 0.17, 0.20);
  struct Mesh {
    MatX3 V;                  // n×3, cm
    const MatX3i* F;          // m×3 (owned by the face model)
    RenderStyle style;
  };
  std::vector<Mesh> meshes;   // drawn in order
  std::vector<Marker> markers;
  MarkerStyle markerStyle;
  std::optional<ColorBar> colorBar;  // drawn last, in final-picture pixels
};

// A frame of the simulation, as much of it as the overlays need.
struct FaceFrameState {
  MatX3 skin;                 // n×3 skin positions, cm
  MatX3 displacement;         // n×3 skin displacement u, cm (only for the displacement overlay)
  std::vector<MatX3> muscles; // per muscle, its positions, cm (only for the muscles overlay)
};

struct FaceOverlays {
  bool muscles = false;       // muscles drawn through a half-transparent skin
  bool roi = false;           // roiWeights() as a heat map on the skin
  bool displacement = false;  // |u| on [0, displacementScale] cm as a colour map, with a colour bar
  double displacementScale = 1.0;
  bool pins = false;          // the model's gravity pins as markers
};

// What the overlays need of `sim`'s current state (the skin always; u and the muscles on demand).
FaceFrameState faceFrameState(const Simulator& sim, const FaceOverlays& overlays);

// A weight per skin vertex (n) for the ROI heat map: the ROI of a muscle (thesis eq. 19) is every
// skin vertex closer to one of its nodes than α·depth (depth: that node's spring rest length);
// here w = max over muscles and nodes of 1 − distance / (α·depth), clamped at 0. So w = 0 exactly
// outside every ROI and nears 1 right over a muscle node.
VecX roiWeights(const FaceModel& model);

// The picture of `state` seen from `view`, framed on the rest head as `run --render` does (every
// frame lines up). `roi` is roiWeights(model), needed with overlays.roi.
FaceScene faceScene(const FaceModel& model, const FaceFrameState& state, ViewPreset view, int width, int height,
                    const FaceOverlays& overlays, const VecX* roi = nullptr);

class FacePainter {
 public:
  virtual ~FacePainter() = default;
  virtual Image paint(const FaceScene& scene) = 0;
  // "opengl (llvmpipe (LLVM 15.0.6, 256 bits))" or "software".
  virtual std::string name() const = 0;
};

// The software rasterizer, at twice the size then averaged (as face_picture.cpp).
std::unique_ptr<FacePainter> softwarePainter();
// OpenGL 3.3 through a headless EGL context, 4× multisampled. Throws RenderError (saying why)
// when no such context can be made.
std::unique_ptr<FacePainter> glPainter();
// OpenGL unless `software` or no context can be made: then the software rasterizer, after one
// warning line on standard error saying why.
std::unique_ptr<FacePainter> makePainter(bool software);

}  // namespace myo::cli
