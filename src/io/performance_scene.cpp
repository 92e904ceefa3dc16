#include "myoshell/io/performance_scene.h"

#include <fmt/core.h>

#include <filesystem>

#include "myoshell/anim/performance.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/scene_face.h"

namespace myo {

namespace fs = std::filesystem;

SceneDesc performanceScene(const PerformanceSceneDef& a) {
  if (a.filter != "on" && a.filter != "off") throw InputError("--filter: expected on or off (got '" + a.filter + "')");
  if (a.response != "dynamic" && a.response != "follow")
    throw InputError("--response: expected dynamic or follow (got '" + a.response + "')");
  if (a.interpolation != "linear" && a.interpolation != "step")
    throw InputError("--interpolation: expected linear or step (got '" + a.interpolation + "')");
  if (!fs::is_regular_file(a.performance)) throw InputError("cannot open performance file", a.performance);
  SceneDesc scene;
  scene.name = fs::path(a.performance).stem().string();
  if (scene.name.empty()) scene.name = "performance";
  const HeadFiles files = resolveHeadArgument(a.head, a.landmarks, "", a.units);
  scene.head.obj = files.obj;
  scene.head.landmarks = files.landmarks;
  scene.head.units = files.unit;
  scene.muscleLibrary = sceneMuscleLibrary(a.library);
  scene.anatomical.response = a.response == "follow" ? SkinResponse::Follow : SkinResponse::Dynamic;
  PerformanceDesc& p = scene.performance;
  p.file = fs::absolute(a.performance).string();
  if (!a.input.empty()) p.read.input = performanceInputFromString(a.input);
  if (a.auScale > 0.0) p.read.auScale = a.auScale;
  p.read.face = a.face;
  p.read.minConfidence = a.minConfidence;
  if (a.inputFps > 0.0) p.read.inputFps = a.inputFps;
  p.map = a.map.empty() ? "" : fs::absolute(a.map).string();
  p.filter = a.oneEuro;
  p.filter.enabled = a.filter == "on";
  checkOneEuroSettings(p.filter, "--min-cutoff/--beta");
  if (a.end >= 0.0 && a.end <= a.start)
    throw InputError(fmt::format("--end {} must lie after --start {}", a.end, a.start));
  p.start = a.start;
  p.end = a.end;
  p.interpolation = a.interpolation == "step" ? Interpolation::Step : Interpolation::Linear;
  loadScenePerformance(scene);
  return scene;
}

}  // namespace myo
