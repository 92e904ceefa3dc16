#include "myoshell/io/live_take.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/core/check.h"
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

LiveTakeRecorder::LiveTakeRecorder(const std::string& path, bool eyes, double fps)
    : path_(path), out_(path), eyes_(eyes), fps_(fps) {
  MYO_CHECK(fps > 0.0 && std::isfinite(fps), "LiveTakeRecorder: the timecode's rate is positive");
  if (!out_) throw IoError("cannot write the live take", path);
  // Live Link's order (JawRight before JawLeft, …) to ARKit's, once: write() runs every live frame.
  const auto& arkit = arkitNames();
  for (int i = 0; i < kArkitWeightCount; ++i) {
    std::string camel = liveLinkValueNames()[i];
    camel[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(camel[0])));
    arkitOfColumn_[i] = static_cast<size_t>(std::find(arkit.begin(), arkit.end(), camel) - arkit.begin());
  }
  out_ << "Timecode,BlendShapeCount";
  const auto& names = liveLinkValueNames();
  const int columns = eyes_ ? kLiveLinkValueCount : kArkitWeightCount + 3;
  for (int i = 0; i < columns; ++i) out_ << ',' << names[i];
  out_ << '\n' << std::flush;
}

LiveFrame LiveTakeRecorder::write(double t, const LiveFrame& f) {
  // HH:MM:SS:FF.ffffff, FF.ffffff the frame within the second at fps_ frames per second (the reader
  // takes the rate from replay.json's input_fps, or infers it from the largest FF).
  const double seconds = std::floor(t);
  // Never printed as fps_.000000, which would read as one frame too many.
  const double ff = std::min((t - seconds) * fps_, fps_ - 1e-6);
  const long s = static_cast<long>(seconds);
  out_ << fmt::format("{:02d}:{:02d}:{:02d}:{:09.6f},{}", s / 3600, s / 60 % 60, s % 60, ff, kLiveLinkValueCount);
  const auto& names = liveLinkValueNames();
  const Vec3 head = f.headPose.value_or(Vec3::Zero());
  const EyeGaze gaze = f.gaze.value_or(EyeGaze{});
  // What the file holds, read back as the Live Link reader reads it (anim/performance_livelink.cpp):
  // weights clamped to [0, 1], angles 180 · (degrees / 180).
  LiveFrame held;
  held.headPose = Vec3::Zero();
  if (eyes_) held.gaze = EyeGaze{};
  const int columns = eyes_ ? kLiveLinkValueCount : kArkitWeightCount + 3;
  for (int i = 0; i < columns; ++i) {
    const std::string& n = names[i];
    double v = 0.0;
    size_t weight = kArkitWeightCount;
    if (i < kArkitWeightCount) {
      weight = arkitOfColumn_[i];
      v = f.weights[weight];
    } else if (n == "HeadYaw") v = head.y() / 180.0;
    else if (n == "HeadPitch") v = head.x() / 180.0;
    else if (n == "HeadRoll") v = head.z() / 180.0;
    else if (n == "LeftEyeYaw") v = gaze.yawDeg[1] / 180.0;
    else if (n == "LeftEyePitch") v = -gaze.pitchDeg[1] / 180.0;
    else if (n == "RightEyeYaw") v = gaze.yawDeg[0] / 180.0;
    else if (n == "RightEyePitch") v = -gaze.pitchDeg[0] / 180.0;
    const std::string text = fmt::format("{:.9g}", v);
    out_ << ',' << text;
    const double read = std::strtod(text.c_str(), nullptr);
    if (weight < kArkitWeightCount) held.weights[weight] = std::clamp(read, 0.0, 1.0);
    else if (n == "HeadYaw") (*held.headPose)[1] = 180.0 * read;
    else if (n == "HeadPitch") (*held.headPose)[0] = 180.0 * read;
    else if (n == "HeadRoll") (*held.headPose)[2] = 180.0 * read;
    else if (n == "LeftEyeYaw") held.gaze->yawDeg[1] = 180.0 * read;
    else if (n == "LeftEyePitch") held.gaze->pitchDeg[1] = -180.0 * read;
    else if (n == "RightEyeYaw") held.gaze->yawDeg[0] = 180.0 * read;
    else if (n == "RightEyePitch") held.gaze->pitchDeg[0] = -180.0 * read;
  }
  out_ << '\n' << std::flush;
  if (!out_) throw IoError("cannot write the live take", path_);
  ++rows_;
  return held;
}

SceneDesc liveReplayScene(const SceneDesc& live, const std::string& recording, double fps, const OneEuroSettings& filter) {
  SceneDesc scene = live;
  scene.name = live.name + "_replay";
  PerformanceDesc& p = scene.performance;
  p.file = recording;
  p.read.input = PerformanceInput::LiveLink;
  p.read.inputFps = fps;
  p.filter = filter;
  p.interpolation = Interpolation::Step;
  return scene;
}

}  // namespace myo
