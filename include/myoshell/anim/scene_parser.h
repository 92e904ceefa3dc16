// Scene files (JSON, or YAML — the same keys): parse → SceneDesc → build (docs/scene_format.md).
// Every error names `file:line:col`, the key path and the fault; unknown keys are errors, and
// values out of range (activations outside [−1, 1] included) are errors.
#pragma once

#include <memory>
#include <string>

#include "myoshell/anim/scene.h"
#include "myoshell/face/face_model.h"
#include "myoshell/reduce/basis_cache.h"

namespace myo {

SceneDesc parseScene(const std::string& text, const std::string& path = "<string>");
SceneDesc readScene(const std::string& path);

// The description as a scene file (JSON) with every default written out: `myoshell check` prints
// it, and parseScene(sceneToJson(d)) gives d back.
std::string sceneToJson(const SceneDesc& scene);

// Builds the face a scene describes: its head (built-in, or OBJ + landmarks + pins, paths relative
// to the scene's folder), its muscles (library, selection, extras), drags resolved to vertices.
// Names in the timeline must exist (InputError naming the unknown muscle or drag).
std::shared_ptr<const FaceModel> buildSceneFace(const SceneDesc& scene, BasisCache* cache = nullptr);

}  // namespace myo
