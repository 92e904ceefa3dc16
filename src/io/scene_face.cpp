#include "myoshell/io/scene_face.h"

#include <filesystem>

#include "myoshell/core/errors.h"
#include "myoshell/core/whole_file.h"
#include "myoshell/face/anatomical_face.h"
#include "myoshell/face/head_checks.h"
#include "myoshell/io/attachment_file.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/muscle_library_file.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/mesh/vertex_set.h"

namespace myo {

namespace fs = std::filesystem;

SceneDesc readScene(const std::string& path) {
  return parseScene(readWholeFile(path, "cannot open scene file"), path);
}

SceneInputs readSceneInputs(const SceneDesc& scene) {
  const fs::path base = scene.path.empty() || scene.path.front() == '<' ? fs::path() : fs::path(scene.path).parent_path();
  auto resolve = [&](const std::string& p) { return fs::path(p).is_absolute() ? p : (base / p).string(); };
  SceneInputs in;
  in.head = scene.head.obj.empty()
                ? loadDefaultHead()
                : loadHead(resolve(scene.head.obj), resolve(scene.head.landmarks),
                           scene.head.gravityPins.empty() ? "" : resolve(scene.head.gravityPins), scene.head.units);
  const Head& head = in.head;
  if (!scene.head.skull.empty()) {
    in.head.skull = readObj(resolve(scene.head.skull));
    rescaleToCentimetres(in.head.skull, scene.head.units);  // written in the head's unit
  }

  const std::vector<MuscleDef>* builtin = builtinMuscleLibrary(scene.muscleLibrary);
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
