// `myoshell drive PERFORMANCE [--head default|DIR|OBJ --landmarks F --units U] [--library face]
// [--map MAP] [--input openface|livelink|mediapipe] [--au-scale X] [--face N] [--min-confidence C]
// [--input-fps F] [--filter on|off] [--min-cutoff HZ] [--beta B] [--response dynamic|follow] [--start S] [--end S]
// [--format glb,pc2,obj] [--glb-tolerance MM] [--video] [--head-motion] --out DIR [--cache DIR] [--json]`: plays a
// recorded performance (OpenFace action units, Live Link Face or MediaPipe ARKit weights) on a head
// and writes the animation as `run` does (DIR/NAME.glb, NAME the file's stem). It is a scene with a
// head and a `performance` key (docs/performance_input.md), so `run` on such a scene gives the same
// frames; the frames come at the performance's rate, over its duration.
#include <fmt/core.h>

#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "common_options.h"
#include "head_landmarks.h"
#include "myoshell/anim/performance_map.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/io/performance_file.h"
#include "myoshell/io/performance_scene.h"
#include "option_checks.h"
#include "scene_runner.h"

namespace myo::cli {
namespace {

struct DriveArgs {
  PerformanceSceneDef scene;
  HeadOptions head;
  bool headMotion = false;
  RunOptions run;
};

// The input curves for --video's panel: the performance's own curves, as read (before mapping).
CurvePanel inputCurves(const SceneDesc& scene, const DriveArgs& a) {
  const std::string& file = scene.performanceReport->file;
  const Performance perf =
      cropPerformance(readPerformanceFile(file, scene.performance.read), a.scene.start, a.scene.end, file);
  CurvePanel all;
  all.times = perf.times;
  for (const PerformanceChannel& c : perf.channels) all.curves.push_back({c.name, c.values});
  return activeCurves(all);
}

int runDrive(DriveArgs& a) {
  checkOutputFolder(a.run.outDir, "--out");
  a.scene.head = a.head.head;
  a.scene.landmarks = a.head.landmarks;
  a.scene.units = a.head.units;
  const SceneDesc scene = performanceScene(a.scene);
  a.run.headMotion = a.headMotion;
  if (a.run.video) a.run.videoPanel = inputCurves(scene, a);
  return runScene(scene, a.run);
}

static CommandRegistrar registerDrive("drive", [](CLI::App& app) -> std::function<int()> {
  auto a = std::make_shared<DriveArgs>();
  a->run.formats = {"glb"};  // before --format captures it as the default its help shows
  CLI::App* sub = app.add_subcommand(
      "drive", "Play a recorded performance (OpenFace action units, Live Link Face or MediaPipe blendshape weights) on a "
               "head and write the animation");
  sub->add_option("performance", a->scene.performance,
                  "the performance file (OpenFace CSV, Live Link Face CSV, MediaPipe JSON Lines)")
      ->required();
  sub->add_option("--out", a->run.outDir, "Output folder")->required();
  addHeadOptions(*sub, a->head);
  addLibraryOption(*sub, a->scene.library);
  sub->add_option("--map", a->scene.map, "ARKit input: a retargeting map (fit-rig --out); default the shipped ICT map");
  sub->add_option("--input", a->scene.input, "openface, livelink or mediapipe (default: from the file's header)");
  sub->add_option("--au-scale", a->scene.auScale,
                  "OpenFace: the intensities' scale, 5 (raw) or 1 (default: from the header)")
      ->check(numberAbove(0));
  sub->add_option("--face", a->scene.face, "OpenFace: the face_id to play when the file tracks several")
      ->check(wholeAtLeast(0));
  sub->add_option("--min-confidence", a->scene.minConfidence, "OpenFace: frames below it are bridged (default 0.7)")
      ->check(numberIn(0.0, 1.0));
  sub->add_option("--input-fps", a->scene.inputFps, "Live Link: the timecode's frame rate (default: inferred)")
      ->check(numberAbove(0));
  sub->add_option("--filter", a->scene.filter, "the One-Euro filter on the input curves: on (default) or off");
  sub->add_option("--min-cutoff", a->scene.oneEuro.minCutoff, "One-Euro filter: cutoff at rest, Hz")
      ->capture_default_str();
  sub->add_option("--beta", a->scene.oneEuro.beta, "One-Euro filter: speed coefficient")->capture_default_str();
  sub->add_option("--response", a->scene.response,
                  "dynamic (the skin trails the activations by its dynamics) or follow (their quasi-static "
                  "shape at once, only gravity, drags and contact lag; docs/live.md)")
      ->capture_default_str();
  sub->add_option("--interpolation", a->scene.interpolation,
                  "between the performance's frames: linear (default) or step (each frame held until the next, "
                  "as `live` played it: its replay.json; docs/live.md)")
      ->capture_default_str();
  sub->add_option("--start", a->scene.start, "play from this time, s after the first frame (default 0)")
      ->check(numberAtLeast(0));
  // Without --end the take plays to its last frame (PerformanceSceneDef::end < 0); a negative
  // --end would mean the same, silently, so it is refused.
  sub->add_option("--end", a->scene.end, "play up to this time, s after the first frame, after --start (default: the last frame)")
      ->check(numberAbove(0));
  sub->add_option("--format", a->run.formats, "Animation exports, comma-separated: glb, pc2, obj")
      ->delimiter(',')
      ->capture_default_str();
  addGlbToleranceOption(*sub, a->run.glbToleranceMm);
  sub->add_flag("--video", a->run.video, "Write DIR/<name>.mp4 and .gif: the face beside the active input curves");
  sub->add_option("--framing", a->run.framing, "--video frames the face (its landmarks), head (crown to chin) or all")
      ->default_val("face");
  sub->add_flag("--head-motion", a->headMotion, "Turn the exported frames with the performance's head rotation");
  sub->add_option("--size", a->run.size, "Picture size, pixels")->check(wholeIn(64, 4096))->capture_default_str();
  sub->add_flag("--software", a->run.software, "Draw with the software renderer even where OpenGL is available");
  addCacheOption(*sub, a->run.cacheDir);
  addJsonFlag(*sub, a->run.json);
  addThreadsOption(*sub);
  return [a] {
    resolveHeadLandmarks(a->head, a->run.cacheDir);
    return runDrive(*a);
  };
});

}  // namespace
}  // namespace myo::cli
