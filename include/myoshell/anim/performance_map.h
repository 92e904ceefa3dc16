// From a recorded performance (anim/performance.h) to the muscles' activation curves a scene plays
// (docs/performance_input.md, "Mapping"):
//   - OpenFace action units through the FACS map (fit/facs_map.h): muscle += intensity · weight;
//   - ARKit weights (Live Link Face, MediaPipe) through a retargeting map (fit/retarget_map.h):
//     muscle += weight · the shape's activations; a name the map cannot make (no entry, or
//     unreachable) goes through its FACS units and side (fit/arkit_names.h, ArkitFacs) and the
//     FACS map — a sided name drives its side's muscles fully and midline muscles at half weight;
// every input curve first through the One-Euro filter (anim/one_euro_filter.h). Contributions add
// and the sum is clamped to [0, 1]. The eyes turn by the file's eye angles when it has them, else by
// the curves that turn them (eyeLook*, AU61–64), never by both; within ±kGazeMaxDeg. An input curve
// that maps to nothing the model has is warned about once (e.g. AU45 before the model has lids); it
// is never an error, since a tracker writes what it writes.
#pragma once

#include <string>
#include <vector>

#include "myoshell/anim/one_euro_filter.h"
#include "myoshell/anim/performance.h"
#include "myoshell/anim/scene.h"
#include "myoshell/fit/facs_map.h"
#include "myoshell/fit/retarget_map.h"

namespace myo {

struct MappedPerformance {
  std::vector<double> times;                     // s, the performance's frames (times[0] = 0)
  double fps = 0.0;
  std::vector<std::string> muscles;              // the model's muscle names, in the given order
  std::vector<std::vector<double>> activations;  // [muscle][frame], in [0, 1]
  std::vector<Vec3> headPose;                    // [pitch, yaw, roll] degrees per frame (filtered); empty if none
  // The jaw per frame, [open degrees, forward cm, lateral cm] within head/jaw.h's ranges; empty when
  // no input moves it (AU25–27, AU29, AU30 through the FACS map; ARKit's jaw shapes).
  std::vector<Vec3> jaw;
  // The eyes' turn per frame (head/eye_gaze.h, degrees within ±kGazeMaxDeg); empty when nothing turns
  // them. The file's eye angles when it has them (OpenFace gaze_angle_x/y, Live Link's eye pitch and
  // yaw), filtered; else the curves that turn the eyes (ARKit's eyeLook* through the map's `gaze`,
  // AU61–64 through the FACS map's), never both.
  std::vector<EyeGaze> gaze;
  std::vector<std::string> unmapped;             // input curves that drive nothing, in input order
  std::vector<std::string> warnings;             // one line each
};

// The frames whose time lies in [start, end] (s from the first frame; end < 0: to the last), times
// shifted so the first is 0 and fps kept. InputError naming `what` when fewer than two frames remain.
Performance cropPerformance(const Performance& performance, double start, double end, const std::string& what);

// Maps `performance` onto the muscles `muscleNames` (unique). `arkitMap` is used for Live Link
// and MediaPipe input only. InputError for bad filter settings; unknown muscles of a map are
// skipped with a warning naming them.
MappedPerformance mapPerformance(const Performance& performance, const std::vector<std::string>& muscleNames,
                                 const FacsMap& facs, const RetargetMap& arkitMap, const OneEuroSettings& filter);

// Plays a mapped performance in `scene`: duration and fps become the performance's, each muscle
// the performance drives gets a track with a key at every frame and at every key of the scene's
// own track for it, valued (performance + scene's own track), clamped to [0, 1] (`between` frames:
// Linear, the timeline resampling the frames to the simulation step, or Step, each frame held until
// the next, as `myoshell live` played its take: docs/live.md, "Replaying a take"). The performance's head pose
// becomes timeline.head_pose unless the scene has its own (which then wins); its jaw adds to the
// scene's timeline.jaw tracks (clamped to the jaw's ranges), and each of its gaze angles that is not
// 0 throughout to the scene's timeline.gaze track (clamped to ±kGazeMaxDeg).
void addPerformanceToScene(SceneDesc& scene, const MappedPerformance& mapped,
                           Interpolation between = Interpolation::Linear);

}  // namespace myo
