// Scenes from files, and the face a scene describes (DESIGN.md: parse → describe → build).
// anim/scene_parser.h parses a scene's text into a SceneDesc and reads no file; here the scene file
// is read, then every file the scene names, then the face is built.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "myoshell/anim/scene_parser.h"
#include "myoshell/fit/retarget_map.h"
#include "myoshell/head/face_system.h"
#include "myoshell/head/head.h"
#include "myoshell/reduce/basis_cache.h"
#include "myoshell/thesis/face_model.h"

namespace myo {

// Reads and parses a scene file (InputError "cannot open scene file" when it cannot be read), and
// plays its performance into its timeline (loadScenePerformance).
SceneDesc readScene(const std::string& path);

// A scene's muscles.library for a --library value given on the command line: "face" and "builtin"
// as they are, a library file made absolute (read from where the command runs; a scene file's own
// library is read beside the scene).
std::string sceneMuscleLibrary(const std::string& library);

// When the scene names a performance (key `performance`): reads it (io/performance_file.h), crops
// it to its window, maps it onto the scene's muscles (the FACS map; for ARKit input the scene's map
// or the shipped one) and adds it to the timeline (anim/performance_map.h), fills
// `performanceReport` and clears `performance.file`. Nothing when it names none. InputError as the
// readers.
void loadScenePerformance(SceneDesc& scene);

// What a performance is mapped with (loadScenePerformance, and the live input, io/live_take.h: one
// mapping path): the scene's muscle names (its library, its selection, its own extra muscles) and
// the retargeting map for ARKit input (scene.performance.map, or the shipped one). InputError for a
// map made for another muscle library.
struct ScenePerformanceMapping {
  std::vector<std::string> muscles;
  RetargetMap arkitMap;
};
ScenePerformanceMapping scenePerformanceMapping(const SceneDesc& scene);

// Everything a scene's face is built from, read and checked, nothing built.
struct SceneInputs {
  Head head;                     // built-in, or OBJ + landmarks + pins (+ skull)
  std::vector<MuscleDef> muscles;  // sceneMuscles of its library; imported shells read
  FaceModelSettings settings;    // scene.model with the drags resolved to vertices (and, thesis, pins)
  // scene.anatomical with the attachment overrides of `skin.attachment` read for this head.
  AnatomicalSettings anatomical;
};

// Reads every file a scene names (paths relative to the scene's folder): the head's OBJ,
// landmarks, pins and skull, the muscle library and imported muscles' OBJs, drag pin sets, the
// attachment overrides (skin.attachment); checks
// every name (muscles against the library: sceneMuscles; drag landmarks and vertices against the
// head). `myoshell check` runs this, so it rejects what `run` rejects. Errors are InputError.
SceneInputs readSceneInputs(const SceneDesc& scene);

// Builds the face a scene describes (its "model"): readSceneInputs, then the thesis's FaceModel
// (bases from `cache`) or the AnatomicalFace (no basis cache yet).
std::shared_ptr<const FaceSystem> buildSceneFace(const SceneDesc& scene, BasisCache* cache = nullptr);
// The thesis's FaceModel of a "model": "thesis" scene (figures, which draw its channels and ROIs);
// InputError naming the model for an anatomical scene.
std::shared_ptr<const FaceModel> buildThesisFace(const SceneDesc& scene, BasisCache* cache = nullptr);

}  // namespace myo
