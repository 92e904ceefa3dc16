// The scene `myoshell drive` plays (Python's myoshell.drive): a head, a muscle library and a recorded
// performance (docs/performance_input.md) on the anatomical defaults, its frames at the performance's
// rate over its duration. `run` on the same scene written as a file gives the same frames.
#pragma once

#include <string>

#include "myoshell/anim/one_euro_filter.h"
#include "myoshell/anim/scene.h"

namespace myo {

// What drive's options say, with their defaults (the option names in the comments).
struct PerformanceSceneDef {
  std::string performance;          // the file (OpenFace CSV, Live Link Face CSV, MediaPipe JSON Lines)
  std::string head = "default";     // --head: 'default', an OBJ file (with landmarks) or a head folder
  std::string landmarks;            // --landmarks of an OBJ head
  std::string units = "cm";         // --units: the OBJ head's unit, m, mm or cm
  std::string library = "face";     // --library: face, builtin or a library file
  std::string map;                  // --map: ARKit input's retargeting map; "" = the shipped one
  std::string input;                // --input: openface, livelink, mediapipe; "" = from the header
  double auScale = 0.0;             // --au-scale: OpenFace intensities' scale; 0 = from the header
  int face = -1;                    // --face: OpenFace face_id; < 0 = the only one
  double minConfidence = 0.7;       // --min-confidence: OpenFace frames below it are bridged
  double inputFps = 0.0;            // --input-fps: Live Link's timecode rate, Hz; 0 = inferred
  std::string filter = "on";        // --filter: the One-Euro filter on the input curves, on or off
  OneEuroSettings oneEuro;          // --min-cutoff (Hz), --beta
  double start = 0.0;               // --start, s after the first frame
  double end = -1.0;                // --end, s after the first frame; < 0 = to the last
  std::string response = "dynamic";  // --response: dynamic or follow (docs/live.md, "Lag")
  std::string interpolation = "linear";  // --interpolation between frames: linear or step
};

// The scene (named after the performance file's stem), its performance read, cropped, mapped onto
// the muscles and in the timeline (loadScenePerformance). InputError with drive's messages:
// "--filter: expected on or off (got 'X')", "--response: expected dynamic or follow (got 'X')",
// "--interpolation: expected linear or step (got 'X')", "FILE: cannot open performance file", "--end E must lie
// after --start S", the One-Euro settings' ("--min-cutoff/--beta: …"), and the readers'.
SceneDesc performanceScene(const PerformanceSceneDef& def);

}  // namespace myo
