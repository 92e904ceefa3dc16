// The landmarks of an OBJ head as the commands use them (docs/heads.md, "A head without a landmark
// file"): an OBJ given without --landmarks (or a scene's head without head.landmarks) gets the file
// io/auto_landmark_file.h finds or reuses in the basis cache folder, said in one line on stderr
// and in --json's "auto_landmarks"; a given file is checked against the automatic landmarks when
// they are kept there (1-based ids and swapped sides: InputError; points far off: warnings).
#pragma once

#include <string>

#include "common_options.h"
#include "myoshell/anim/scene.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/io/rig_file.h"

namespace myo::cli {

// Fills head.landmarks (and head.units, unless --units was given) for an OBJ head without
// --landmarks, or checks the given file; a head folder's landmark file (or --landmarks) is checked
// against its head_skin.obj's kept automatic landmarks; `cacheOption` is --cache ("" when not given).
void resolveHeadLandmarks(HeadOptions& head, const std::string& cacheOption, const std::string& program = "myoshell");

// The same for a scene's head (head.landmarks and head.units).
void resolveSceneLandmarks(SceneDesc& scene, const std::string& cacheOption, const std::string& program = "myoshell");

// For a fitting command on a glTF rig's own base mesh (no --head) without --landmarks: the base's
// landmarks found (or reused) as for an OBJ, said on stderr, and set as the options' landmarks.
void resolveRigBaseLandmarks(FitHeadOptions& options, const RigFile& rig, const std::string& cacheOption,
                             const std::string& program = "myoshell");

// The automatic landmark file this process used ("" when none): job_report.h adds it to --json.
const std::string& autoLandmarkFileUsed();

}  // namespace myo::cli
