#include "viewer_session.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "myoshell/io/scene_face.h"
#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/io/animation_export.h"

namespace myo::viewer {
namespace {

// The scene as the viewer builds it: the user's scene plus the mouse's drag channel, appended
// last so the scene's own drags keep their indices (the timeline refers to them by index).
SceneDesc withMouseDrag(SceneDesc scene) {
  DragDesc mouse;
  mouse.name = "mouse";
  while (std::any_of(scene.drags.begin(), scene.drags.end(), [&](const DragDesc& d) { return d.name == mouse.name; }))
    mouse.name += "_";
  mouse.landmark = "nose_tip";
  mouse.radius = 1.0;
  mouse.pinLandmarks = false;  // a grip on a mouth corner moves the corner
  scene.drags.push_back(mouse);
  scene.model.measureLoadParticipation = false;  // a diagnostic the viewer does not show: start faster
  return scene;
}

std::string mirrorName(const std::string& name) {
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"_left", "_right"}, {"_right", "_left"}})
    if (name.size() > from.size() && name.compare(name.size() - from.size(), from.size(), from) == 0)
      return name.substr(0, name.size() - from.size()) + to;
  return {};
}

}  // namespace

ViewerSession::ViewerSession(SceneDesc scene, BasisCache* cache)
    : model_(buildSceneFace(withMouseDrag(scene), cache)),
      cache_(cache),
      player_(std::make_unique<ScenePlayer>(scene, model_)),
      baseModulus_(scene.anatomical.skinYoungModulus),
      sliders_(static_cast<size_t>(model_->muscleCount()), 0.0),
      mirror_(static_cast<size_t>(model_->muscleCount()), -1),
      mouseDrag_(static_cast<int>(scene.drags.size())),
      gravityOn_(model_->hasGravity()) {
  player_->setControls([this](FaceStepper& s) { controls(s); });
  updateTracked();
  for (int m = 0; m < muscleCount(); ++m) {
    const std::string other = mirrorName(muscleName(m));
    for (int k = 0; k < muscleCount(); ++k)
      if (muscleName(k) == other) mirror_[static_cast<size_t>(m)] = k;
  }
  applyControls();
}

const std::string& ViewerSession::muscleName(int muscle) const {
  return model_->muscleName(muscle);
}

void ViewerSession::setSlider(int muscle, double activation) {
  if (std::isnan(activation)) throw InputError("activation of muscle '" + muscleName(muscle) + "' is NaN");
  const double lowest = model_->minActivation();
  if (activation < lowest || activation > 1.0) {
    const double clamped = std::clamp(activation, lowest, 1.0);
    std::ostringstream w;
    w << "activation " << activation << " of muscle '" << muscleName(muscle) << "' clamped to " << clamped;
    warnings_.push_back(w.str());
    activation = clamped;
  }
  sliders_[static_cast<size_t>(muscle)] = activation;
  if (linked && mirrorOf(muscle) >= 0) sliders_[static_cast<size_t>(mirrorOf(muscle))] = activation;
}

void ViewerSession::setSlider(const std::string& muscle, double activation) {
  setSlider(model_->muscleIndex(muscle), activation);
}

void ViewerSession::setJawSlider(const JawPose& pose) {
  if (!hasJaw())
    throw InputError("the jaw needs \"model\": \"anatomical\"; the thesis model has no jaw");
  const auto clampTo = [&](double v, double lo, double hi, const char* what, const char* unit) {
    if (std::isnan(v)) throw InputError(std::string("the jaw's ") + what + " is NaN");
    if (v >= lo && v <= hi) return v;
    const double c = std::clamp(v, lo, hi);
    std::ostringstream w;
    w << "the jaw's " << what << " " << v << " " << unit << " clamped to " << c;
    warnings_.push_back(w.str());
    return c;
  };
  jaw_.openDeg = clampTo(pose.openDeg, kJawOpenMinDeg, kJawOpenMaxDeg, "opening", "degrees");
  jaw_.forwardCm = clampTo(pose.forwardCm, kJawForwardMinCm, kJawForwardMaxCm, "protrusion", "cm");
  jaw_.lateralCm = clampTo(pose.lateralCm, -kJawLateralMaxCm, kJawLateralMaxCm, "lateral shift", "cm");
}

void ViewerSession::resetSliders() {
  std::fill(sliders_.begin(), sliders_.end(), 0.0);
  jaw_ = JawPose{};
  release();
  sim().reset();
  pending_ = 0.0;
  applyControls();
}

void ViewerSession::setGravity(bool on) {
  if (on && !hasGravity()) throw InputError("this scene has no gravity channel (set \"gravity\": true in its model)");
  gravityOn_ = on;
  sim().setGravity(on ? 1.0 : 0.0);
}

double ViewerSession::setStiffnessScale(double s) {
  if (!(std::isfinite(s) && s > 0.0))
    throw InputError("the skin stiffness scale must be a number > 0 (got " + std::to_string(s) + ")");
  if (thesisModel()) {
    sim().setSkinStiffnessScale(s);
    return 0.0;
  }
  Stopwatch clock;
  SceneDesc scaled = scene();
  scaled.anatomical.skinYoungModulus = s * baseModulus_;
  // Built before anything is replaced: a failed build leaves the session as it was.
  std::shared_ptr<const FaceSystem> face = buildSceneFace(withMouseDrag(scaled), cache_);
  auto player = std::make_unique<ScenePlayer>(std::move(scaled), face);
  const double at = playhead();
  grabbing_ = false;  // the grip was the old simulator's
  model_ = std::move(face);
  player_ = std::move(player);
  player_->setControls([this](FaceStepper& st) { controls(st); });
  if (hasGravity()) sim().setGravity(gravityOn_ ? 1.0 : 0.0);
  seek(at);  // from rest, the timeline replayed to the playhead
  return clock.seconds();
}

double ViewerSession::stiffnessScale() const {
  if (thesisModel()) return simulator().skinStiffnessScale();
  return scene().anatomical.skinYoungModulus / baseModulus_;
}

void ViewerSession::grab(int vertex) {
  sim().setDragVertex(mouseDrag_, vertex);
  grabbing_ = true;
}

void ViewerSession::pull(const Vec3& force) {
  if (grabbing_) sim().setDragForce(mouseDrag_, force);
}

void ViewerSession::release() {
  grabbing_ = false;
  sim().setDragForce(mouseDrag_, Vec3::Zero());
}

void ViewerSession::updateTracked() {
  tracked_.assign(sliders_.size(), false);
  for (int m = 0; m < muscleCount(); ++m) tracked_[static_cast<size_t>(m)] = scene().activations.count(muscleName(m)) > 0;
}

// The controls of one step: the timeline while playing (applied by the player; the sliders then
// show its values), the sliders of every muscle it does not track, gravity as switched, the mouse
// drag as set.
void ViewerSession::applyControls() {
  if (playing) player_->applyTimeline(player_->time());
  controls(sim());
}

// After the timeline, before a step (the player calls it while playing): what the user controls.
void ViewerSession::controls(FaceStepper& s) {
  if (playing && !gravityOn_ && hasGravity()) s.setGravity(0.0);
  // Live: the stream's frame as `myoshell live` applies it; its sliders show it.
  if (live()) LiveFaceMapper::apply(liveFrame_, liveIndex_, s);
  for (int m = 0; m < muscleCount(); ++m) {
    if ((playing && tracked_[static_cast<size_t>(m)]) || (live() && liveDriven_[static_cast<size_t>(m)]))
      sliders_[static_cast<size_t>(m)] = s.activation(m);
    else
      s.setActivation(m, sliders_[static_cast<size_t>(m)]);
  }
  if (blinking())
    for (int m : blinkMuscles_) s.setActivation(m, std::max(s.activation(m), blinkLevel()));
  if (hasJaw()) {
    if ((playing && scene().hasJaw()) || (live() && !liveFrame_.jaw.empty()))
      jaw_ = s.jaw();
    else
      s.setJaw(jaw_);
  }
}

void ViewerSession::blink() {
  blinkMuscles_.clear();
  for (int m = 0; m < muscleCount(); ++m)
    if (model_->muscleName(m).rfind("orbicularis_oculi_palpebral", 0) == 0) blinkMuscles_.push_back(m);
  if (blinkMuscles_.empty())
    throw InputError("blink: the muscle library has no orbicularis_oculi_palpebral muscle (use \"muscles\": "
                     "{\"library\": \"face\"})");
  blinkTime_ = 0.0;
}

double ViewerSession::blinkLevel() const {
  if (!blinking()) return 0.0;
  const double t = blinkTime_;
  if (t < kBlinkClose) return t / kBlinkClose;
  if (t < kBlinkClose + kBlinkHold) return 1.0;
  return std::max(0.0, 1.0 - (t - kBlinkClose - kBlinkHold) / kBlinkOpen);
}

void ViewerSession::advance(double seconds) {
  if (live()) {
    playing = false;  // the stream drives the face, not the timeline
    takeLive();
  }
  const double dt = model_->dt();
  pending_ += std::max(seconds, 0.0);
  const int steps = static_cast<int>(std::floor(pending_ / dt + 1e-6));  // a step owed up to round-off is taken
  pending_ -= steps * dt;
  Stopwatch wall;
  for (int s = 0; s < steps; ++s) {
    if (playing) {
      player_->step();  // timeline at the playhead, then controls(), then the step
      if (player_->time() >= duration() - 0.5 * dt) {  // the end of the timeline: stop there
        player_->setTime(duration());
        playing = false;
      }
    } else {
      controls(sim());  // live: the sliders drive the simulator, the playhead stays
      sim().step();
    }
    if (blinking()) {
      blinkTime_ += dt;
      if (blinkTime_ >= kBlinkClose + kBlinkHold + kBlinkOpen) blinkTime_ = -1.0;
    }
  }
  const double elapsed = wall.seconds();
  if (steps > 0 && elapsed > 0.0) {
    const double rate = steps / elapsed;
    stepsPerSecond_ = stepsPerSecond_ == 0.0 ? rate : 0.9 * stepsPerSecond_ + 0.1 * rate;
  }
  if (live() && steps > 0) liveStepsDone();
}

// ---- the live stream ----

void ViewerSession::listen(std::unique_ptr<LiveSource> source, LiveClock clock, const LiveFaceSettings& settings,
                           const OneEuroSettings& filter) {
  input_.emplace(settings);
  mapper_.emplace(scene(), filter);  // the scene's maps, as `myoshell live` builds its mapper
  liveIndex_ = mapper_->muscleIndex(*model_);
  liveDriven_.assign(sliders_.size(), false);
  for (const int m : liveIndex_)
    if (m >= 0) liveDriven_[static_cast<size_t>(m)] = true;
  clock_ = clock ? std::move(clock) : steadyLiveClock();
  liveStart_ = clock_();
  source_ = std::move(source);
  playing = false;
  takeLive();  // the frame that waited while the face was built, if any
  // What the maps cannot do on this scene (curves that drive nothing, muscles it lacks), once.
  for (const std::string& w : liveFrame_.warnings) warnings_.push_back(w);
}

void ViewerSession::calibrateNeutral(double seconds) {
  if (!live()) throw InputError("calibrate: the viewer is not listening to a live stream (--live)");
  input_->startCalibration(clock_(), seconds);
}

// Once per advance: the newest frame (if any) into the input, and the input at this instant mapped
// as `myoshell live` maps it; the steps then apply it (controls()).
void ViewerSession::takeLive() {
  if (const std::optional<LiveSample> sample = source_->takeNewest()) {
    input_->receive(*sample);
    arrival_ = sample->arrival;
  }
  const double now = clock_();
  liveFrame_ = mapper_->map(now - liveStart_, input_->at(now));
  if (thesisModel()) {  // the thesis model has no jaw, eyes or head pose: its muscles only
    liveFrame_.jaw.clear();
    liveFrame_.gaze.clear();
    liveFrame_.headPose.clear();
  }
  const long packets = source_->counters().packets;
  packetTimes_.emplace_back(now, packets);
  while (packetTimes_.size() > 1 && now - packetTimes_.front().first > 1.0) packetTimes_.pop_front();
}

// The steps that show the newest frame are done: its latency, arrival → positions ready.
void ViewerSession::liveStepsDone() {
  const double now = clock_();
  if (arrival_) latencies_.emplace_back(now, 1e3 * (now - *std::exchange(arrival_, std::nullopt)));
  while (!latencies_.empty() && now - latencies_.front().first > 1.0) latencies_.pop_front();
}

LiveStatus ViewerSession::liveStatus() const {
  LiveStatus st;
  if (!live()) return st;
  const double now = clock_();
  st.protocol = source_->protocol();
  st.port = source_->port();
  st.counters = source_->counters();
  if (packetTimes_.size() > 1) {
    const double span = packetTimes_.back().first - packetTimes_.front().first;
    if (span > 0) st.packetsPerSecond = (packetTimes_.back().second - packetTimes_.front().second) / span;
  }
  std::vector<double> ms;
  for (const auto& [t, value] : latencies_)
    if (now - t <= 1.0) ms.push_back(value);
  st.latencySamples = static_cast<int>(ms.size());
  if (!ms.empty()) {
    std::nth_element(ms.begin(), ms.begin() + static_cast<long>(ms.size() / 2), ms.end());
    st.latencyMs = ms[ms.size() / 2];
  }
  st.calibrating = input_->calibrating(now);
  st.liveness = input_->liveness(now);
  return st;
}

std::vector<std::string> ViewerSession::liveUnknownNames() const {
  return live() ? source_->unknownNames() : std::vector<std::string>{};
}

void ViewerSession::seek(double t) {
  if (!std::isfinite(t)) throw InputError("seek time is not finite");
  t = std::clamp(t, 0.0, duration());
  const bool wasPlaying = playing;
  pending_ = 0.0;
  playing = true;  // the timeline drives the replay
  player_->restart(0.0);
  player_->playTo(t);
  player_->setTime(t);
  applyControls();  // the sliders show the values at t
  playing = wasPlaying;
}

namespace {

// `track` with a key (at, value), replacing a key already at that time.
ScalarTrack withKey(const ScalarTrack& track, double at, double value, const std::string& label) {
  std::vector<Keyframe<double>> keys = track.keys();
  keys.erase(std::remove_if(keys.begin(), keys.end(), [&](const auto& k) { return std::abs(k.time - at) < 1e-9; }),
             keys.end());
  Keyframe<double> key;
  key.time = at;
  key.value = value;
  keys.insert(std::upper_bound(keys.begin(), keys.end(), key, [](const auto& a, const auto& b) { return a.time < b.time; }),
              key);
  return ScalarTrack(std::move(keys), label);
}

}  // namespace

int ViewerSession::setKeysAtPlayhead() {
  SceneDesc edited = scene();
  const double at = playhead();
  for (int m = 0; m < muscleCount(); ++m) {
    const std::string& name = muscleName(m);
    edited.activations[name] = withKey(edited.activations[name], at, slider(m), "activation of " + name);
  }
  int keys = muscleCount();
  if (hasJaw() && (!jaw_.isZero() || edited.hasJaw())) {
    edited.jawOpen = withKey(edited.jawOpen, at, jaw_.openDeg, "timeline.jaw.open");
    edited.jawForward = withKey(edited.jawForward, at, jaw_.forwardCm, "timeline.jaw.forward");
    edited.jawLateral = withKey(edited.jawLateral, at, jaw_.lateralCm, "timeline.jaw.lateral");
    keys += 3;
  }
  player_->setScene(std::move(edited));
  updateTracked();
  return keys;
}

void ViewerSession::saveScene(const std::string& path) const {
  writeFileAtomically(path, sceneToJson(scene()), "cannot write the scene file");
}

int ViewerSession::exportGlb(const std::string& path) const {
  ScenePlayer fresh(scene(), model_);  // the live face is untouched
  const int frames = fresh.frameCount();
  AnimationFrames animation;
  animation.name = scene().name.empty() ? "viewer" : scene().name;
  animation.triangles = model_->head().mesh.F;
  animation.rest = model_->head().mesh.V;
  animation.uv = model_->head().mesh.UV;
  animation.cornerUV = model_->head().mesh.cornerUV;
  animation.fps = scene().fps;
  for (int f = 0; f < frames; ++f) {
    fresh.advanceTo(f);
    animation.positions.push_back(fresh.snapshot(false).positions);
  }
  writeGlb(path, animation);
  return frames;
}

}  // namespace myo::viewer
