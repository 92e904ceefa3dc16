// The head's pose over time (scene key timeline.head_pose): keys of [pitch, yaw, roll] degrees
// about the face frame's x, y, z (applied in that order; face-down is +90° pitch), turned into
// rotations (headPoseRotation) and interpolated by quaternion slerp, eased as the key's
// interpolation says (step, linear, smooth). The rotation feeds the anatomical model's gravity
// (gravityForRotation) every step.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "myoshell/anim/timeline.h"

namespace myo {

class HeadPoseTrack {
 public:
  HeadPoseTrack() = default;
  // Keys' values are [pitch, yaw, roll] in degrees. InputError (naming `what`) as Track's.
  HeadPoseTrack(std::vector<Keyframe<Vec3>> keys, const std::string& what = "head pose");

  // The head's rotation at `time` (face-frame coordinates): the first key's before it, the last's
  // after; between keys a and b, slerp(q_a, q_b, s) with s eased by a's interpolation. Identity
  // when empty.
  Eigen::Quaterniond at(double time) const;
  const std::vector<Keyframe<Vec3>>& keys() const { return degrees_.keys(); }
  bool empty() const { return degrees_.empty(); }

 private:
  VectorTrack degrees_;                    // the keys as written (degrees), for sceneToJson
  std::vector<Eigen::Quaterniond> rotations_;  // per key
};

}  // namespace myo
