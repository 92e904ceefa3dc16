// The one face picture: what a picture of a simulated face holds (meshes with their styles,
// markers, a colour bar), composed from a face model, a frame's state and the overlays asked for.
// `run`, `render`, `figures` and the viewer all compose through faceScene(); painters draw the
// result (the software one here, OpenGL in gl/gl_face_painter.h). Lengths in cm, sizes in pixels
// of the final picture.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "myoshell/anim/scene_player.h"
#include "myoshell/head/face_system.h"
#include "myoshell/render/camera.h"
#include "myoshell/render/colormap.h"
#include "myoshell/render/image.h"
#include "myoshell/render/markers.h"
#include "myoshell/render/render_mesh.h"
#include "myoshell/thesis/face_model.h"
#include "myoshell/thesis/simulator.h"

namespace myo {

// Every colour of a face picture.
struct FacePalette {
  Rgb background = Rgb(0.16, 0.17, 0.20);
  Rgb skin = Rgb(0.93, 0.78, 0.68);
  Rgb skinBack = Rgb(0.45, 0.30, 0.28);  // the inside of the lips, the back of an open mesh
  Rgb muscle = Rgb(0.75, 0.18, 0.16);
  Rgb bone = Rgb(0.85, 0.83, 0.76);
  Rgb pin = Rgb(0.20, 0.50, 0.95);       // gravity pins as markers
  Rgb grab = Rgb(1.0, 0.9, 0.1);         // the viewer's grabbed vertex
  Rgb free = Rgb(0.85, 0.15, 0.12);      // thesis: red = free (deformed) vertices
  Rgb pinned = Rgb(0.20, 0.35, 0.85);    // thesis: blue = statically constrained
  Rgb feature = Rgb(0.98, 0.85, 0.10);   // thesis: yellow = fixed feature points
  Rgb barText = Rgb(0.95, 0.95, 0.95);
};
inline const FacePalette kFacePalette{};

// The named views: front, three-quarter, profile, back (camera.h's presets). An unknown name is
// an InputError listing them.
ViewPreset parseView(const std::string& name);
const char* viewName(ViewPreset view);

// What frames the picture, always the rest mesh (every frame of a run lines up):
//   all:  the whole mesh, with a neck and shoulders if it has them;
//   head: the mesh from the crown down to just below the chin (the lowest landmark, less a tenth of
//         the landmarks' height), so a bust's neck and shoulders fall outside; the same as all on a
//         face mask such as the built-in head;
//   face: the named landmarks (brows to chin, eye and mouth corners) with room around them (above
//         the brows for the forehead) — the face, whatever the mesh around it.
// Without landmarks head and face frame as all.
enum class FaceFraming { all, head, face };
// "all", "head", "face"; an unknown name is an InputError listing them.
FaceFraming parseFraming(const std::string& name);
const char* framingName(FaceFraming framing);
// The preset camera fitted to the rest head as `framing` says for a width × height picture.
Camera faceCamera(const Head& head, ViewPreset view, int width, int height, FaceFraming framing = FaceFraming::all);
Camera faceCamera(const FaceSystem& model, ViewPreset view, int width, int height,
                  FaceFraming framing = FaceFraming::all);

// A frame of the simulation, as much of it as the overlays need.
struct FaceFrameState {
  MatX3 skin;                  // n×3 skin positions, cm
  MatX3 displacement;          // n×3 skin displacement u, cm (displacement overlay only)
  std::vector<MatX3> muscles;  // per muscle, its node positions, cm (muscles overlay only)
};

struct FaceOverlays {
  bool muscles = false;                // muscles drawn through a translucent skin
  double skinOpacityOverMuscles = 0.55;
  bool skull = false;                  // the head's skull (when it has one), the skin translucent
  bool roi = false;                    // roiWeights() as a heat map on the skin
  bool displacement = false;           // |u| on [0, displacementScale] cm as a colour map, with a colour bar
  double displacementScale = 1.0;      // cm
  bool pins = false;                   // the model's pinned vertices (thesis: gravity pins) as markers
  bool wireframe = false;              // the skin's triangle edges
  int grabVertex = -1;                 // ≥ 0: a marker on this skin vertex (the viewer's grip)
  // Constraint pictures (thesis Figs. 18–24): these skin vertices free (red), every other pinned (blue).
  std::optional<std::vector<int>> freeVertices;
  std::vector<int> features;           // skin vertices marked as fixed feature points (yellow)
  double featureRadius = 4.0;          // pixels
  bool colorBar = true;                // the displacement / ROI overlays' colour bar
};

// What the overlays need of a frame (the skin always; u and the muscles on demand).
FaceFrameState faceFrameState(const FrameSnapshot& snapshot, const FaceOverlays& overlays);
FaceFrameState faceFrameState(const FaceStepper& sim, const FaceOverlays& overlays);
// The rest face (u = 0, muscles at rest).
FaceFrameState restFrameState(const FaceSystem& model);

// A weight per skin vertex (n) for the ROI heat map: the ROI of a muscle (thesis eq. 19) is every
// skin vertex closer to one of its nodes than α·depth (depth: that node's spring rest length);
// here w = max over muscles and nodes of 1 − distance / (α·depth), clamped at 0. So w = 0 exactly
// outside every ROI and nears 1 right over a muscle node. `muscle` ≥ 0: that muscle's ROI only.
VecX roiWeights(const FaceModel& model, int muscle = -1);

// One picture, renderer-neutral. Sizes (pixels, marker radii, wire widths) are the final picture's.
struct FaceScene {
  Camera camera;
  int width = 480, height = 480;  // pixels
  Rgb background = kFacePalette.background;
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

// The picture of `state` seen by `camera`. `roi` is roiWeights(model, …), needed with overlays.roi.
FaceScene faceScene(const FaceSystem& model, const FaceFrameState& state, const Camera& camera, int width, int height,
                    const FaceOverlays& overlays, const VecX* roi = nullptr);
// The same from a named view, framed on the rest head (faceCamera).
FaceScene faceScene(const FaceSystem& model, const FaceFrameState& state, ViewPreset view, int width, int height,
                    const FaceOverlays& overlays, const VecX* roi = nullptr, FaceFraming framing = FaceFraming::all);

class FacePainter {
 public:
  virtual ~FacePainter() = default;
  virtual Image paint(const FaceScene& scene) = 0;
  // "opengl (llvmpipe (LLVM 15.0.6, 256 bits))" or "software".
  virtual std::string name() const = 0;
};

// The software rasterizer, at twice the size then averaged.
std::unique_ptr<FacePainter> softwarePainter();

}  // namespace myo
