// A scene file's plain description (DESIGN.md: parse → describe → build). Every field has the
// default a scene gets when the file leaves it out; docs/scene_format.md documents each key.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "myoshell/anatomy/skin_settings.h"
#include "myoshell/anim/head_pose_track.h"
#include "myoshell/anim/one_euro_filter.h"
#include "myoshell/anim/performance.h"
#include "myoshell/anim/timeline.h"
#include "myoshell/head/eye_gaze.h"
#include "myoshell/muscles/muscle_def.h"
#include "myoshell/thesis/face_model.h"

namespace myo {

struct HeadDesc {
  std::string builtin = "default";  // "default" (the built-in head) unless obj is set
  std::string obj;                  // a user's head OBJ (absolute, or resolved against the scene's folder)
  std::string landmarks;            // its landmark file; empty with obj: found automatically (io/auto_landmark_file.h)
  std::string gravityPins;          // thesis: its gravity pin set (vertex-set JSON); empty = rim + landmarks
  std::string skull;                // a skull OBJ in the head's space (optional): muscle origins sit on it
  LengthUnit units = LengthUnit::cm;  // the unit obj and skull are written in (scaled to cm on load)
  bool unitsGiven = false;          // the scene names head.units (else, with automatic landmarks, the search's unit)
};

struct DragDesc {
  std::string name;                 // referred to by the timeline
  std::string landmark;             // where the user grabs: a landmark name, or
  int vertex = -1;                  // a skin vertex id
  double radius = 1.0;              // cm
  std::string pins;                 // thesis: vertex-set file; empty = the head's gravity pins
  // With the default pins: also pin the landmarks, as the gravity channel does (Fig. 21). Off, a
  // grip on a landmark (a mouth corner) moves it too; the channel then needs its own basis.
  bool pinLandmarks = true;         // thesis only
};

// A recorded performance the scene plays (key `performance`; docs/performance_input.md). io reads
// it when it reads the scene (readScene) and turns it into the timeline's tracks
// (addPerformanceToScene), so a player never sees the file.
struct PerformanceDesc {
  std::string file;                 // "" = none (absolute, or resolved against the scene's folder)
  PerformanceOptions read;          // input, au_scale, face, min_confidence, input_fps
  std::string map;                  // ARKit input: a retargeting map file; "" = the shipped one
  OneEuroSettings filter;           // on the input curves
  double start = 0.0;               // s: the window of the performance played, from its first frame
  double end = -1.0;                // s; < 0 = to its last frame
  // Between frames: Linear, or Step (each frame held until the next: a live take's replay).
  Interpolation interpolation = Interpolation::Linear;
};

// What reading a scene's performance found (drive --json, run's warnings).
struct PerformanceReport {
  std::string file;
  PerformanceInput input = PerformanceInput::OpenFace;
  double auScale = 1.0;
  int frames = 0;
  double fps = 0.0;
  double duration = 0.0;            // s, last − first timestamp of the window
  int droppedFrames = 0;
  std::vector<std::string> warnings;
  std::vector<std::string> unmapped;  // input curves that drive nothing
};

// Where a key or value was written in the scene file: 1-based line and column, 0 when unknown.
struct SourceLocation {
  int line = 0;
  int column = 0;
};

struct SceneDesc {
  std::string path;                 // the file it was read from ("" when built in code)
  std::string name;                 // defaults to the file's stem
  // Which face plays the scene: the anatomical model (docs/anatomical_model.md, the default) or
  // the thesis's (docs/face_model.md). Keys only one model reads are errors under the other.
  FaceModelKind modelKind = FaceModelKind::Anatomical;
  HeadDesc head;
  // Muscles: the whole face ("face", 39: the default under the anatomical model), the built-in
  // ten ("builtin": the thesis's eight and the lips' two rings; under model: thesis the thesis's
  // eight, its default) or a JSON library file, optionally only some of them, plus extra
  // definitions written in the scene. defaultMuscleLibrary() gives a model's default.
  std::string muscleLibrary = "face";
  std::vector<std::string> muscles;  // names to use; empty = every muscle of the library
  std::vector<MuscleDef> extraMuscles;
  FaceModelSettings model;          // thesis: materials, modes, ROI α, springs, dt, stepper, warping, damping
  AnatomicalSettings anatomical;    // anatomical: skin E and h, modes, dt, warping, damping, gravity
  // anatomical: a file of per-vertex k_att overrides (muscles/attachment_overrides.h), read by io into
  // anatomical.attachmentOverrides when the head is known; "" = the region map alone.
  std::string skinAttachment;
  std::vector<DragDesc> drags;
  double duration = 1.0;            // s
  double fps = 30.0;                // output frames per second
  std::map<std::string, ScalarTrack> activations;  // muscle name → activation track (thesis −1 … 1, anatomical 0 … 1)
  ScalarTrack gravity;              // gravity scale track (empty = constant 1 when gravity is on)
  std::map<std::string, VectorTrack> dragForces;   // drag name → force track (dyn)
  HeadPoseTrack headPose;           // anatomical only: [pitch, yaw, roll] degrees over time (empty = upright)
  PerformanceDesc performance;      // anatomical only; its file is cleared once io has turned it into tracks
  std::optional<PerformanceReport> performanceReport;  // set by io when it read one
  // anatomical only (timeline.jaw.open / forward / lateral; docs/jaw.md): the jaw's opening (degrees),
  // protrusion and lateral shift (cm, + towards the subject's left) over time; an empty track is 0.
  ScalarTrack jawOpen, jawForward, jawLateral;
  bool hasJaw() const { return !jawOpen.empty() || !jawForward.empty() || !jawLateral.empty(); }
  // anatomical only (timeline.gaze.right_pitch / right_yaw / left_pitch / left_yaw; docs/eyelids.md):
  // the eyes' turn over time, degrees within ±kGazeMaxDeg, index 0 the subject's right eye, 1 the
  // left (EyeGaze's); an empty track is 0. The lids follow it.
  std::array<ScalarTrack, 2> gazePitch, gazeYaw;
  bool hasGaze() const {
    return !gazePitch[0].empty() || !gazePitch[1].empty() || !gazeYaw[0].empty() || !gazeYaw[1].empty();
  }
  EyeGaze gazeAt(double t) const {
    EyeGaze g;
    for (size_t e = 0; e < 2; ++e) {
      g.pitchDeg[e] = gazePitch[e].at(t);
      g.yawDeg[e] = gazeYaw[e].at(t);
    }
    return g;
  }
  // Where the names checked after parsing were written (key path → location): "muscles.use[i]"
  // and "timeline.activations.NAME" (sceneMuscles). Empty for a scene built in code.
  std::map<std::string, SourceLocation> locations;
};

}  // namespace myo
