#include "myoshell/anim/scene_player.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"

namespace myo {

ScenePlayer::ScenePlayer(SceneDesc scene, std::shared_ptr<const FaceSystem> model)
    : scene_(std::move(scene)),
      model_(std::move(model)),
      sim_(makeStepper(model_)),
      channelCount_(static_cast<int>(model_->channelNames().size())) {
  resolveNames();
}

void ScenePlayer::setScene(SceneDesc scene) {
  SceneDesc old = std::exchange(scene_, std::move(scene));
  try {
    resolveNames();
  } catch (...) {
    scene_ = std::move(old);
    resolveNames();
    throw;
  }
}

// Names to indices once: the step loop does no string search.
void ScenePlayer::resolveNames() {
  muscleTracks_.clear();
  dragTracks_.clear();
  for (const auto& [name, track] : scene_.activations) {
    int m = -1;
    try {
      m = model_->muscleIndex(name);
    } catch (const InputError& e) {
      throw InputError("timeline.activations: " + e.message(), scene_.path);
    }
    muscleTracks_.push_back({m, &track});
  }
  const std::vector<DragDef>& drags = model_->drags();
  for (const auto& [dragName, track] : scene_.dragForces) {
    const std::string& name = dragName;  // a plain reference: clang 14 cannot capture a structured binding
    auto it = std::find_if(drags.begin(), drags.end(), [&](const DragDef& d) { return d.name == name; });
    if (it == drags.end()) {
      std::string known;
      for (const DragDef& d : drags) known += (known.empty() ? "" : ", ") + d.name;
      throw InputError("timeline.drags: unknown drag '" + name + "' (this face has: " + (known.empty() ? "none" : known) + ")",
                       scene_.path);
    }
    dragTracks_.push_back({static_cast<int>(it - drags.begin()), &track});
  }
  // FaceStepper::setDragForce in drag order, as the scene lists them.
  std::sort(dragTracks_.begin(), dragTracks_.end(), [](const DragTrack& a, const DragTrack& b) { return a.drag < b.drag; });
  applyGravity_ = model_->hasGravity() && !scene_.gravity.empty();
}

int ScenePlayer::frameCount(double duration, double fps) {
  return static_cast<int>(std::floor(duration * fps + 1e-9)) + 1;
}

void ScenePlayer::applyTimeline(double t) {
  for (const MuscleTrack& m : muscleTracks_) sim_->setActivation(m.muscle, m.track->at(t));
  if (applyGravity_) sim_->setGravity(scene_.gravity.at(t));
  if (!scene_.headPose.empty()) sim_->setHeadPose(scene_.headPose.at(t));
  if (scene_.hasJaw()) {
    JawPose jaw;
    if (!scene_.jawOpen.empty()) jaw.openDeg = scene_.jawOpen.at(t);
    if (!scene_.jawForward.empty()) jaw.forwardCm = scene_.jawForward.at(t);
    if (!scene_.jawLateral.empty()) jaw.lateralCm = scene_.jawLateral.at(t);
    sim_->setJaw(jaw);
  }
  if (scene_.hasGaze()) sim_->setGaze(scene_.gazeAt(t));
  for (const DragTrack& d : dragTracks_) sim_->setDragForce(d.drag, d.track->at(t));
}

void ScenePlayer::step() {
  applyTimeline(time_);
  if (controls_) controls_(*sim_);
  Stopwatch sw;
  sim_->step();
  lastStepSeconds_ += sw.seconds();
  ++lastSteps_;
  time_ += model_->dt();
}

bool ScenePlayer::playTo(double t) {
  const double dt = model_->dt();
  lastSteps_ = 0;
  lastStepSeconds_ = 0.0;
  while (time_ < t - 0.5 * dt) {
    if (cancelled()) return false;
    step();
  }
  return true;
}

void ScenePlayer::restart(double t0) {
  sim_->reset();
  time_ = t0;
  lastSteps_ = 0;
  lastStepSeconds_ = 0.0;
}

const FrameSnapshot& ScenePlayer::snapshot(bool muscles) {
  FrameSnapshot& s = snapshot_;
  s.time = time_;
  sim_->skinPositions(s.positions);
  s.displacement = sim_->skinDisplacement();
  s.maxDisplacement = s.displacement.rows() ? s.displacement.rowwise().norm().maxCoeff() : 0.0;
  const size_t channels = static_cast<size_t>(channelCount_);
  s.channelMax.resize(channels);
  for (size_t c = 0; c < channels; ++c) {
    sim_->channelDisplacement(static_cast<int>(c), channelU_);
    s.channelMax[c] = channelU_.rowwise().norm().maxCoeff();
  }
  s.muscles.resize(muscles ? static_cast<size_t>(model_->muscleCount()) : 0);
  for (size_t m = 0; m < s.muscles.size(); ++m) sim_->musclePositions(static_cast<int>(m), s.muscles[m]);
  s.steps = lastSteps_;
  s.stepSeconds = lastStepSeconds_;
  return s;
}

}  // namespace myo
