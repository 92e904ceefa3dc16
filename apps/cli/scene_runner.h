// Running a scene: simulate, write the animation exports (OBJ sequence, GLB, PC2), stats.json and
// (optionally) pictures. Shared by `myoshell run` and `myoshell demo`.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "myoshell/anim/scene.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/render/curve_panel.h"
#include "myoshell/render/face_picture.h"

namespace myo::cli {

struct RunOptions {
  std::string scene;                     // scene file (`run`); unused by runScene itself
  std::string outDir;
  std::string cacheDir;                  // --cache; "" = the default (resources.h)
  bool json = false;
  // Animation exports, any subset of "obj" (DIR/obj/<name>_NNNN.obj), "glb" (DIR/<name>.glb) and
  // "pc2" (DIR/<name>.pc2); see io/animation_export.h. An unknown name is an InputError.
  std::vector<std::string> formats = {"obj"};
  // --glb-tolerance: the GLB's largest vertex error in any frame, mm (io/animation_export.h GlbOptions).
  double glbToleranceMm = kDefaultGlbToleranceMm;
  // Pictures: every `renderEvery`-th frame to DIR/png/, and a contact sheet of a few frames.
  bool render = false;
  int renderEvery = 1;
  int size = 480;
  std::string view = "front";
  // What the pictures frame (render/face_picture.h FaceFraming): "all" (the whole mesh), "head"
  // (crown to chin) or "face" (its landmarks); drive's default is face, a bust's face being small.
  std::string framing = "all";
  bool showMuscles = false;
  double colorScale = 0.0;  // > 0: colour the skin by |u| on [0, colorScale] cm
  bool software = false;    // the software rasterizer even where OpenGL (EGL) is available
  // Video: every frame drawn into DIR/<name>.mp4 (H.264, the scene's frame rate) and DIR/<name>.gif
  // (ffmpeg; render/video.h). Implies drawing every frame; PNGs still every renderEvery-th.
  bool video = false;
  // drive --video: input curves drawn beside the face in every video frame, with a playhead.
  CurvePanel videoPanel;
  // drive --head-motion: the exported frames turned by the scene's head pose (about the neck pivot,
  // headMotionPivot), as the performer's head turned; the simulation's gravity follows the pose anyway.
  bool headMotion = false;
  // Diagnostics that cost start-up time: each thesis channel's load participation (one sparse
  // factorisation per channel, FaceModelSettings::measureLoadParticipation) in stats.json. Off:
  // stats.json gives load_participation null.
  bool diagnostics = false;
};

// Simulates `scene` and writes its outputs under options.outDir; returns the exit code.
int runScene(const SceneDesc& scene, const RunOptions& options);

// The animation GLB's report for --json: {"targets", "tolerance_mm", "max_error_mm",
// "within_tolerance", "fps", "frames", "vertices"}; and, when the cap left frames beyond the
// tolerance, a warning on stderr.
template <typename Json = nlohmann::json>
Json glbJson(const GlbReport& report) {
  Json j;
  j["targets"] = report.targets;
  j["tolerance_mm"] = report.toleranceMm;
  j["max_error_mm"] = 10.0 * report.maxErrorCm;
  j["within_tolerance"] = report.withinTolerance;
  j["fps"] = report.fps;
  j["frames"] = report.frames;
  j["vertices"] = report.vertices;
  return j;
}
void warnIfGlbInexact(const GlbReport& report);

// The face painter for `run`, `render` and `figures`: OpenGL unless `software` or unavailable
// (then the software rasterizer, after one warning line on standard error saying why).
std::unique_ptr<FacePainter> makePainter(bool software);

}  // namespace myo::cli
