// Making an ARKit blendshape rig for a head (`myoshell rig`, Python's myoshell.rig; docs/fitting.md,
// "Making a rig"): the map read with the head's muscles, the anatomical face built, every shape
// settled (fit/arkit_rig.h) and gathered as the glTF rig io/rig_export.h writes.
#pragma once

#include <string>
#include <vector>

#include "myoshell/fit/arkit_rig.h"
#include "myoshell/fit/retarget_map.h"
#include "myoshell/io/rig_export.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/reduce/basis_cache.h"

namespace myo {

// The rig's output path, checked before any work: InputError "--out: a rig is written as a glTF
// binary; give a file name ending in .glb", or checkOutputFile's (io/output_paths.h) for a folder, a
// missing or unwritable folder.
void checkRigOutputPath(const std::string& path);

// Reads a retargeting map whose activations must name `muscles` (the head's library, `library` being
// its name as --library gives it). A map that records another library (its "library" key) says
// "the map is for the muscle library 'face', and the head's is 'builtin': give --library face"; an
// older map without the key, of the whole face's muscles, read with another library says "the map
// uses the whole face's muscles (NAME, …): give --library face"; a jaw value that is not open,
// forward or lateral is refused naming the shape. InputError naming the file. An empty
// path is the library's shipped map (fit/retarget_map.h shippedRetargetMap: the whole face's for
// "face", the built-in ten's for "builtin"); a library file has none (InputError).
RetargetMap readRigMap(const std::string& path, const std::vector<MuscleDef>& muscles, const std::string& library);

struct MadeRig {
  ArkitRig settled;       // the 52 ARKit shapes, settled
  RigExport glb;          // what writeRigGlb writes: the head's rest, triangles, UVs and the 52 deltas
  double buildSeconds = 0;   // the face's build, s
  double settleSeconds = 0;  // every shape's settle, s
};

// Builds the anatomical face on `inputs` (its head, muscles, settings; bases from `cache` when not
// null) and settles every shape of `map` on it. Errors as AnatomicalSkin and settleArkitRig.
MadeRig makeArkitRig(const SceneInputs& inputs, const RetargetMap& map, BasisCache* cache);

}  // namespace myo
