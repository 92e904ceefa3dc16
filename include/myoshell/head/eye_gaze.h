// The eyes' turn (docs/eyelids.md, "The lids follow the gaze"): per eye a pitch and a yaw in
// degrees, in the face frame (head/face_frame.h). Here, below the lids (anatomy/eyelids.h), so that a
// FaceStepper (face_system.h) can take it from a scene's timeline.gaze as it takes the jaw.
#pragma once

#include <array>
#include <string>

namespace myo {

// An eye's turn stays within ±45° either way (its mechanical range; ±25° is the comfortable one).
constexpr double kGazeMaxDeg = 45.0;

// The eyes' turn, degrees, index 0 the subject's right eye, 1 the left: pitch + up, yaw + towards
// the subject's left (the face frame's +x). ARKit's eyeLook* at 1 and FACS AU61–64 at full
// intensity turn an eye 25° (assets/facs/au_map.json).
struct EyeGaze {
  std::array<double, 2> pitchDeg{0.0, 0.0};
  std::array<double, 2> yawDeg{0.0, 0.0};
  bool isZero() const { return pitchDeg[0] == 0.0 && pitchDeg[1] == 0.0 && yawDeg[0] == 0.0 && yawDeg[1] == 0.0; }
};

// InputError naming the eye and angle, its value and the range [−kGazeMaxDeg, kGazeMaxDeg] (and
// NaN/∞), prefixed by `what`: "gaze: left eye pitch 50 degrees is outside [-45, 45] degrees".
void validateEyeGaze(const EyeGaze& gaze, const std::string& what = "gaze");

}  // namespace myo
