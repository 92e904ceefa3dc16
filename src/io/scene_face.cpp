#include "myoshell/io/scene_face.h"

#include <filesystem>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anim/performance_map.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/whole_file.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/attachment_file.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/muscle_library_file.h"
#include "myoshell/io/performance_file.h"
#include "myoshell/io/retarget_map_file.h"
#include "myoshell/io/vertex_set_file.h"
#include "myoshell/mesh/obj_reader.h"

namespace myo {

namespace fs = std::filesystem;

std::string sceneMuscleLibrary(const std::string& library) {
  return builtinMuscleLibrary(library, FaceModelKind::Anatomical) ? library : fs::absolute(library).string();
}

SceneDesc readScene(const std::string& path) {
  SceneDesc scene = parseScene(readWholeFile(path, "cannot open scene file"), path);
  loadScenePerformance(scene);
  return scene;
}

namespace {
// A path the scene names: absolute, or relative to the scene's folder.
std::string resolveAgainstScene(const SceneDesc& scene, const std::string& p) {
  const fs::path base = scene.path.empty() || scene.path.front() == '<' ? fs::path() : fs::path(scene.path).parent_path();
  return fs::path(p).is_absolute() ? p : (base / p).string();
}
}  // namespace

ScenePerformanceMapping scenePerformanceMapping(const SceneDesc& scene) {
  const PerformanceDesc& desc = scene.performance;
  ScenePerformanceMapping out;
  // The muscles the scene will have (its library, its selection, its own extra muscles).
  const std::vector<MuscleDef>* builtin = builtinMuscleLibrary(scene.muscleLibrary, scene.modelKind);
  const std::vector<MuscleDef> library =
      builtin ? *builtin : readMuscleDefs(resolveAgainstScene(scene, scene.muscleLibrary));
  for (const MuscleDef& d : sceneMuscles(scene, library)) out.muscles.push_back(d.name);
  out.arkitMap = desc.map.empty() ? builtinRetargetMap() : readRetargetMapFile(resolveAgainstScene(scene, desc.map));
  // A map given for another muscle library would drive muscles this face does not have.
  if (!desc.map.empty() && !out.arkitMap.library.empty() &&
      out.arkitMap.library != muscleLibraryLabel(scene.muscleLibrary))
    throw InputError("the map is for the muscle library '" + out.arkitMap.library + "', and the scene's is '" +
                         muscleLibraryLabel(scene.muscleLibrary) + "': give --library " + out.arkitMap.library +
                         " (or the scene key muscles.library)",
                     resolveAgainstScene(scene, desc.map));
  return out;
}

void loadScenePerformance(SceneDesc& scene) {
  if (scene.performance.file.empty()) return;
  const PerformanceDesc& desc = scene.performance;
  const std::string file = resolveAgainstScene(scene, desc.file);
  Performance performance = readPerformanceFile(file, desc.read);
  performance = cropPerformance(performance, desc.start, desc.end, file);

  const ScenePerformanceMapping mapping = scenePerformanceMapping(scene);
  const MappedPerformance mapped =
      mapPerformance(performance, mapping.muscles, builtinFacsMap(), mapping.arkitMap, desc.filter);
  addPerformanceToScene(scene, mapped, desc.interpolation);

  PerformanceReport report;
  report.file = file;
  report.input = performance.input;
  report.auScale = performance.auScale;
  report.frames = static_cast<int>(performance.times.size());
  report.fps = performance.fps;
  report.duration = performance.duration();
  report.droppedFrames = performance.droppedFrames;
  report.warnings = performance.warnings;
  report.warnings.insert(report.warnings.end(), mapped.warnings.begin(), mapped.warnings.end());
  report.unmapped = mapped.unmapped;
  scene.performanceReport = report;
  scene.performance.file.clear();  // played: the tracks now hold it
}

SceneInputs readSceneInputs(const SceneDesc& scene) {
  auto resolve = [&](const std::string& p) { return resolveAgainstScene(scene, p); };
  SceneInputs in;
  if (!scene.head.obj.empty() && scene.head.landmarks.empty())
    throw InputError("head.landmarks: none given for head.obj '" + scene.head.obj +
                         "' and none found (completeSceneHead, io/auto_landmark_file.h, finds them)",
                     scene.path);
  in.head = scene.head.obj.empty()
                ? loadDefaultHead(defaultHeadOptions(scene.modelKind))
                : loadHead(resolve(scene.head.obj), resolve(scene.head.landmarks),
                           scene.head.gravityPins.empty() ? "" : resolve(scene.head.gravityPins), scene.head.units);
  const Head& head = in.head;
  if (!scene.head.skull.empty()) {
    in.head.skull = readObj(resolve(scene.head.skull));
    rescaleToCentimetres(in.head.skull, scene.head.units);  // written in the head's unit
  }

  const std::vector<MuscleDef>* builtin = builtinMuscleLibrary(scene.muscleLibrary, scene.modelKind);
  const std::vector<MuscleDef> library = builtin ? *builtin : readMuscleDefs(resolve(scene.muscleLibrary));
  in.muscles = sceneMuscles(scene, library);
  readMuscleShells(in.muscles);  // the scene's own imported muscles

  in.anatomical = scene.anatomical;
  if (!scene.skinAttachment.empty())
    in.anatomical.attachmentOverrides = readAttachmentOverrideFile(resolve(scene.skinAttachment), head.mesh.vertexCount());

  in.settings = scene.model;
  for (const DragDesc& d : scene.drags) {
    DragDef def;
    def.name = d.name;
    def.vertex = d.landmark.empty() ? d.vertex : head.landmarks.vertex(d.landmark);
    if (def.vertex >= head.mesh.vertexCount())
      throw InputError("drag '" + d.name + "': vertex " + std::to_string(def.vertex) + " is outside [0, " +
                           std::to_string(head.mesh.vertexCount()) + ") of head '" + head.name + "'",
                       scene.path);
    def.radius = d.radius;
    if (!d.pins.empty()) def.pins = readVertexSet(resolve(d.pins), head.mesh.vertexCount());
    else if (!d.pinLandmarks && !head.gravityPins.empty()) def.pins = head.gravityPins;  // rim only
    in.settings.drags.push_back(def);
  }
  return in;
}

std::shared_ptr<const FaceSystem> buildSceneFace(const SceneDesc& scene, BasisCache* cache) {
  if (scene.modelKind == FaceModelKind::Thesis) return buildThesisFace(scene, cache);
  SceneInputs in = readSceneInputs(scene);
  return std::make_shared<const AnatomicalFace>(in.head, in.muscles, in.anatomical, in.settings.drags,
                                                in.settings.gravity, cache);
}

std::shared_ptr<const FaceModel> buildThesisFace(const SceneDesc& scene, BasisCache* cache) {
  if (scene.modelKind != FaceModelKind::Thesis)
    throw InputError("this needs \"model\": \"thesis\" (the scene's model is " + std::string(toString(scene.modelKind)) +
                         ")",
                     scene.path);
  SceneInputs in = readSceneInputs(scene);
  return std::make_shared<const FaceModel>(std::move(in.head), in.muscles, in.settings, cache);
}

}  // namespace myo
