#include "myoshell/io/live_take.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/core/io_error.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/fit/facs_map.h"
#include "myoshell/head/jaw.h"

namespace myo {

LiveFaceMapper::LiveFaceMapper(const SceneDesc& scene, const OneEuroSettings& filter)
    : mapping_(scenePerformanceMapping(scene)), filter_(filter) {
  checkOneEuroSettings(filter_, "--min-cutoff/--beta");
  for (auto& f : weightFilters_) f = OneEuroStream(filter_);
  for (auto& f : headFilters_) f = OneEuroStream(filter_);
  for (auto& f : gazeFilters_) f = OneEuroStream(filter_);
}

MappedPerformance LiveFaceMapper::map(double t, const LiveFrame& frame) {
  // The filters need increasing times; two frames at one instant are one sample.
  const bool fresh = t > lastTime_;
  if (fresh) lastTime_ = t;
  auto filtered = [&](OneEuroStream& f, double x) { return fresh ? f.filter(t, x) : x; };
  Performance one;
  one.input = PerformanceInput::LiveLink;  // ARKit weights: the retargeting map, then FACS
  one.times = {0.0};
  one.fps = 60.0;
  const auto& names = arkitNames();
  for (int k = 0; k < kArkitWeightCount; ++k)
    one.channels.push_back({names[k], {std::clamp(filtered(weightFilters_[k], frame.weights[k]), 0.0, 1.0)}});
  if (frame.headPose) {
    Vec3 pose;
    for (int a = 0; a < 3; ++a) pose[a] = filtered(headFilters_[a], (*frame.headPose)[a]);
    one.headPose = {pose};
  }
  if (frame.gaze) {
    EyeGaze g = *frame.gaze;
    for (size_t e = 0; e < 2; ++e) {
      g.pitchDeg[e] = filtered(gazeFilters_[2 * e], g.pitchDeg[e]);
      g.yawDeg[e] = filtered(gazeFilters_[2 * e + 1], g.yawDeg[e]);
    }
    one.gaze = {g};
  }
  OneEuroSettings off = filter_;
  off.enabled = false;  // filtered above, sample by sample
  return mapPerformance(one, mapping_.muscles, builtinFacsMap(), mapping_.arkitMap, off);
}

std::vector<int> LiveFaceMapper::muscleIndex(const FaceSystem& model) const {
  std::vector<int> index;
  for (const std::string& name : muscles()) {
    int found = -1;
    for (int m = 0; m < model.muscleCount(); ++m)
      if (model.muscleName(m) == name) found = m;
    index.push_back(found);
  }
  return index;
}

void LiveFaceMapper::apply(const MappedPerformance& mapped, const std::vector<int>& muscleIndex, FaceStepper& stepper) {
  for (size_t m = 0; m < mapped.activations.size(); ++m)
    if (muscleIndex[m] >= 0) stepper.setActivation(muscleIndex[m], mapped.activations[m][0]);
  if (!mapped.jaw.empty()) stepper.setJaw(JawPose{mapped.jaw[0].x(), mapped.jaw[0].y(), mapped.jaw[0].z()});
  if (!mapped.gaze.empty()) stepper.setGaze(mapped.gaze[0]);
  if (!mapped.headPose.empty()) stepper.setHeadPose(headPoseRotation(mapped.headPose[0]));
}

// ---- the recording ----

LiveTakeRecorder::LiveTakeRecorder(const std::string& path, bool eyes) : path_(path), out_(path), eyes_(eyes) {
  if (!out_) throw IoError("cannot write the live take", path);
  out_ << "Timecode,BlendShapeCount";
  const auto& names = liveLinkValueNames();
  const int columns = eyes_ ? kLiveLinkValueCount : kArkitWeightCount + 3;
  for (int i = 0; i < columns; ++i) out_ << ',' << names[i];
  out_ << '\n' << std::flush;
}

void LiveTakeRecorder::write(double t, const LiveFrame& f) {
  // HH:MM:SS:FF.ffffff at 60 frames per second (the reader infers the rate from the largest FF).
  const double frames = t * 60.0;
  const long whole = static_cast<long>(std::floor(frames));
  const long seconds = whole / 60;
  // Never printed as 60.000000, which would read as a 61st frame.
  const double ff = std::min(frames - 60.0 * seconds, 59.999999);
  out_ << fmt::format("{:02d}:{:02d}:{:02d}:{:09.6f},{}", seconds / 3600, seconds / 60 % 60, seconds % 60, ff,
                      kLiveLinkValueCount);
  const auto& names = liveLinkValueNames();
  const Vec3 head = f.headPose.value_or(Vec3::Zero());
  const EyeGaze gaze = f.gaze.value_or(EyeGaze{});
  const int columns = eyes_ ? kLiveLinkValueCount : kArkitWeightCount + 3;
  for (int i = 0; i < columns; ++i) {
    double v = 0.0;
    if (i < kArkitWeightCount) {
      std::string camel = names[i];
      camel[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(camel[0])));
      const auto& arkit = arkitNames();
      v = f.weights[std::find(arkit.begin(), arkit.end(), camel) - arkit.begin()];
    } else {
      const std::string& n = names[i];
      if (n == "HeadYaw") v = head.y() / 180.0;
      else if (n == "HeadPitch") v = head.x() / 180.0;
      else if (n == "HeadRoll") v = head.z() / 180.0;
      else if (n == "LeftEyeYaw") v = gaze.yawDeg[1] / 180.0;
      else if (n == "LeftEyePitch") v = -gaze.pitchDeg[1] / 180.0;
      else if (n == "RightEyeYaw") v = gaze.yawDeg[0] / 180.0;
      else if (n == "RightEyePitch") v = -gaze.pitchDeg[0] / 180.0;
    }
    out_ << ',' << fmt::format("{:.9g}", v);
  }
  out_ << '\n' << std::flush;
  if (!out_) throw IoError("cannot write the live take", path_);
  ++rows_;
}

}  // namespace myo
