// Recorded facial performances (docs/performance_input.md): what a face tracker wrote, one row per
// video frame, read into named curves over time. Three inputs:
//   - OpenFace 2 CSV: FACS action-unit intensities (`AUxx_r`), the head's pose (`pose_Rx/Ry/Rz`,
//     radians, camera-relative), the gaze (`gaze_angle_x/y`), per-frame `confidence` and `success`;
//   - Live Link Face CSV (an iPhone's ARKit): `Timecode,BlendShapeCount,EyeBlinkLeft,…`, ARKit's 52
//     weights in PascalCase plus head and eye yaw/pitch/roll;
//   - MediaPipe face-landmarker blendshapes: JSON Lines, `{"timestamp_ms": t, "blendshapes":
//     [{"categoryName": "mouthSmileLeft", "score": 0.42}, …]}` per frame.
// The text is parsed here; io/performance_file.h reads the file. The mapping to muscles is
// face/performance_map.h's job.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/head/eye_gaze.h"

namespace myo {

enum class PerformanceInput { OpenFace, LiveLink, MediaPipe };

// "openface", "livelink", "mediapipe"; InputError for anything else (naming the three).
PerformanceInput performanceInputFromString(const std::string& name);
const char* toString(PerformanceInput input);

struct PerformanceOptions {
  std::optional<PerformanceInput> input{};  // detected from the text when not given
  // OpenFace: the scale the intensities are written in (5 = raw OpenFace 0–5, 1 = already 0–1).
  // Not given: 5 when the header has `face_id` or any `AUxx_c` column, else 1.
  std::optional<double> auScale{};
  int face = -1;                          // OpenFace: the face_id to read; -1 = the only one (error if several)
  double minConfidence = 0.7;             // OpenFace: frames below it (or success 0) are bridged
  std::optional<double> inputFps{};       // Live Link: the timecode's frame rate (else inferred)
};

// One named curve: a value per frame of the performance (same length as Performance::times).
struct PerformanceChannel {
  std::string name;            // OpenFace: "AU12"; Live Link / MediaPipe: ARKit's camelCase name ("mouthSmileLeft")
  std::vector<double> values;  // OpenFace: intensity / auScale (0–1); ARKit weights 0–1
};

struct Performance {
  PerformanceInput input = PerformanceInput::OpenFace;
  double auScale = 1.0;                 // OpenFace: as used (1 for the other inputs)
  std::vector<double> times;            // s, strictly increasing, times[0] = 0 (first timestamp subtracted)
  double fps = 0.0;                     // frames per second: (frames − 1) / duration, or the timecode's rate
  std::vector<PerformanceChannel> channels;  // in the file's column order; AUs ascending for OpenFace
  // The head's rotation per frame as [pitch, yaw, roll] degrees about the face frame's x, y, z
  // (anim/head_pose_track.h's convention), empty when the file has none. OpenFace: pose_Rx/Ry/Rz
  // (radians, camera-relative; a level camera is assumed) converted; Live Link: 180·HeadPitch/HeadYaw/HeadRoll
  // (the app writes degrees / 180). Signs and sources: docs/performance_input.md, "Formats".
  std::vector<Vec3> headPose;
  // The eyes' turn in the head per frame (head/eye_gaze.h: degrees, pitch + up, yaw + towards the
  // subject's left; not yet clamped to ±kGazeMaxDeg), empty when the file has no eye angles.
  // OpenFace: gaze_angle_x/y (radians, the camera's, both eyes' mean) turned into the head by the
  // pose when the file has one; Live Link: −180·LeftEyePitch, 180·LeftEyeYaw and the right eye's.
  // Signs and sources: docs/performance_input.md, "Formats". When present the eyes follow these
  // angles alone (mapPerformance leaves eyeLook* and AU61–64's turns out).
  std::vector<EyeGaze> gaze;
  int droppedFrames = 0;                // frames bridged by interpolation or trimmed at the ends
  std::vector<std::string> warnings;    // one line each: unknown columns, dropped frames, …

  double duration() const { return times.empty() ? 0.0 : times.back() - times.front(); }
  // The channel of a name, or nullptr.
  const PerformanceChannel* find(const std::string& name) const;
};

// Which input a text is, from its first line: OpenFace (a header with `timestamp` and `AU..._r` or
// `AU..._c` columns), Live Link (a header starting `Timecode,BlendShapeCount`), MediaPipe (a line
// starting with `{`). InputError "name:1: cannot tell …" naming the three layouts otherwise.
PerformanceInput detectPerformanceInput(const std::string& text, const std::string& name = "<string>");

// Parses a performance. Errors (InputError) name `name:line` and the fault: missing required
// columns or keys, a non-number, NaN or infinity, a negative or non-increasing time, a row with
// too few fields, fewer than two valid frames, an intensity outside [0, auScale] (by more than
// 1e-6), a face_id that is not in the file, several faces without `face`. Unknown columns are
// ignored with one warning naming them; rows with empty cells (and OpenFace frames with success 0
// or confidence < minConfidence) are dropped frames: bridged by linear interpolation between the
// valid frames around them, trimmed at the ends, counted, and warned about once.
Performance parsePerformance(const std::string& text, const std::string& name = "<string>",
                             const PerformanceOptions& options = {});

}  // namespace myo
