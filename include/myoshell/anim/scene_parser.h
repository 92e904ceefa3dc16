// Scene files (JSON, or YAML — the same keys): parse → SceneDesc → build (docs/scene_format.md).
// Every error names `file:line:col`, the key path and the fault; unknown keys are errors, and
// values out of range (activations outside [−1, 1] included, fps above 1/dt, a duration shorter
// than dt) are errors. Parsing reads no file:
// reading a scene file and building its face are io's (io/scene_face.h).
#pragma once

#include <string>
#include <vector>

#include "myoshell/anim/scene.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo {

SceneDesc parseScene(const std::string& text, const std::string& path = "<string>");

// The description as a scene file (JSON) with every default written out: `myoshell check` prints
// it, and parseScene(sceneToJson(d)) gives d back. It writes what is meant: `"use": "all"` for the
// whole library, `head.gravity_pins` only when a pin file is given, no `interp` on a track's last
// key (which parseScene refuses: interp shapes the segment from its key to the next).
std::string sceneToJson(const SceneDesc& scene);

// The muscles a scene uses, given its muscle library: the `muscles.use` selection in its order (or
// the whole library when `use` is empty), then the scene's extra muscles. Checks the names: every
// `use` entry must be in the library, every timeline muscle among the scene's muscles; the
// InputError names the scene's file:line:col (scene.locations). parseScene runs this check for the
// built-in library; io (readSceneInputs) for a library file.
std::vector<MuscleDef> sceneMuscles(const SceneDesc& scene, const std::vector<MuscleDef>& library);

}  // namespace myo
