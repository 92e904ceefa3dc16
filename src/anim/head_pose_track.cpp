#include "myoshell/anim/head_pose_track.h"

#include <algorithm>

#include "myoshell/anatomy/anatomical_face.h"

namespace myo {

HeadPoseTrack::HeadPoseTrack(std::vector<Keyframe<Vec3>> keys, const std::string& what)
    : degrees_(std::move(keys), what) {
  for (const auto& k : degrees_.keys()) rotations_.push_back(headPoseRotation(k.value));
}

Eigen::Quaterniond HeadPoseTrack::at(double time) const {
  const auto& keys = degrees_.keys();
  if (keys.empty()) return Eigen::Quaterniond::Identity();
  if (time <= keys.front().time) return rotations_.front();
  if (time >= keys.back().time) return rotations_.back();
  const auto next = std::upper_bound(keys.begin(), keys.end(), time,
                                     [](double t, const Keyframe<Vec3>& k) { return t < k.time; });
  const size_t b = static_cast<size_t>(next - keys.begin()), a = b - 1;
  double s = (time - keys[a].time) / (keys[b].time - keys[a].time);
  switch (keys[a].interpolation) {
    case Interpolation::Step: return rotations_[a];
    case Interpolation::Linear: break;
    case Interpolation::Smooth: s = s * s * (3.0 - 2.0 * s); break;
  }
  return rotations_[a].slerp(s, rotations_[b]);  // Eigen takes the shorter arc
}

}  // namespace myo
