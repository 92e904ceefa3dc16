// What the viewer shows and changes, without any window or GL: the scene, its face model and
// simulator, one slider per muscle (with a left/right link), gravity, the skin stiffness slider,
// the mouse drag, the timeline's play/pause/scrub, and authoring (keys from the sliders, save the
// scene, export a GLB). The window (viewer_app.cpp) and the scripts (viewer_script.h) drive it;
// tests drive it directly.
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "myoshell/anim/scene.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/head/jaw.h"
#include "myoshell/io/live_source.h"
#include "myoshell/io/live_take.h"
#include "myoshell/reduce/basis_cache.h"
#include "myoshell/thesis/simulator.h"

namespace myo::viewer {

// What the live stream did (the panel's status line and the run's summary).
struct LiveStatus {
  LiveProtocol protocol = LiveProtocol::Vmc;
  int port = 0;
  LiveCounters counters;
  double packetsPerSecond = 0.0;  // over the last second
  // Arrival → positions ready (the frame's steps done), ms: the median over the last second and
  // how many frames it holds (0: no frame arrived in the last second).
  double latencyMs = 0.0;
  int latencySamples = 0;
  bool calibrating = false;
  double liveness = 0.0;  // 1 live, falling to 0 as a silent stream eases to neutral
};

class ViewerSession {
 public:
  // Builds the scene's face (bases through `cache`, which may be null) plus one drag channel for
  // the mouse ("mouse", gripping the nose tip until the user picks a vertex; it pins the head's
  // gravity pins but not the landmarks, so a grip on a mouth corner moves the corner).
  ViewerSession(SceneDesc scene, BasisCache* cache);

  const SceneDesc& scene() const { return player_->scene(); }
  const FaceSystem& model() const { return *model_; }
  const FaceModel* thesisModel() const { return dynamic_cast<const FaceModel*>(model_.get()); }  // null: anatomical
  const FaceStepper& simulator() const { return player_->simulator(); }

  // --- sliders ---------------------------------------------------------------------------------
  int muscleCount() const { return static_cast<int>(sliders_.size()); }
  const std::string& muscleName(int muscle) const;
  // The muscle's activation slider, in [model().minActivation(), 1]: thesis [−1, 1], anatomical
  // [0, 1] (values outside are clamped with a warning naming the muscle, see takeWarnings(); NaN
  // is an InputError).
  // With the link on, the mirror muscle (name with _left ↔ _right swapped) follows.
  void setSlider(int muscle, double activation);
  void setSlider(const std::string& muscle, double activation);  // InputError for an unknown name
  double slider(int muscle) const { return sliders_[static_cast<size_t>(muscle)]; }
  int mirrorOf(int muscle) const { return mirror_[static_cast<size_t>(muscle)]; }  // −1: none
  bool linked = true;
  void resetSliders();  // every slider to 0 and the face back to rest

  // Gravity on or off (needs the scene's gravity channel to turn on).
  void setGravity(bool on);
  bool gravity() const { return gravityOn_; }
  bool hasGravity() const { return model_->hasGravity(); }
  // The skin stiffness slider, s > 0 (InputError otherwise). Thesis: every channel's stiffness
  // scaled in place (Simulator::setSkinStiffnessScale, no eigen-solve). Anatomical: the skin's
  // K̂ = s·K_shell + K_att + ΣK_c is not a multiple of the old one, so its basis is not either: the
  // face is rebuilt with skin.young_modulus = s·E₀ (E₀ the scene's as opened; seconds cold, from
  // the basis cache after; docs/viewer.md has the times), the face restarts from rest and the
  // timeline is replayed to the playhead; a mouse grab is let go. The scene (save, export) then
  // carries the scaled modulus. Returns the rebuild's wall time (s; 0 for the thesis model).
  double setStiffnessScale(double s);
  double stiffnessScale() const;
  // Whether setStiffnessScale rebuilds the face (the anatomical model): the window says so first.
  bool stiffnessRebuilds() const { return thesisModel() == nullptr; }

  // --- the jaw (anatomical model; docs/jaw.md) ---------------------------------------------------
  bool hasJaw() const { return thesisModel() == nullptr; }
  // The jaw's sliders: opening (degrees), protrusion and lateral shift (cm), each clamped to the
  // jaw's range (head/jaw.h) with a warning naming it; NaN is an InputError; the thesis model has no
  // jaw (InputError naming the model). While the timeline plays a jaw track, the sliders show it.
  void setJawSlider(const JawPose& pose);
  const JawPose& jawSlider() const { return jaw_; }

  // --- the lids (anatomical model; docs/eyelids.md) ------------------------------------------------
  // Starts a blink: both orbicularis_oculi_palpebral muscles rise to 1 in kBlinkClose, hold
  // kBlinkHold and fall back in kBlinkOpen (a spontaneous blink: the lid closes in ~0.1 s and
  // reopens more slowly, ~0.3 s in all; Doane 1980). While it lasts it lifts each of them to at least
  // the blink's level, over its slider or track. InputError when the library has no palpebral muscle.
  void blink();
  bool blinking() const { return blinkTime_ >= 0.0; }
  // The blink's level now, in [0, 1] (0 when not blinking).
  double blinkLevel() const;
  static constexpr double kBlinkClose = 0.10, kBlinkHold = 0.05, kBlinkOpen = 0.20;

  // --- the mouse drag ----------------------------------------------------------------------------
  // Grabs skin vertex `vertex` (InputError when it is pinned or outside the skin). The anatomical
  // model computes the grip's Ritz vectors at grab time (AnatomicalStepper::grab).
  void grab(int vertex);
  // While grabbing: the force (dyn) on the grabbed spot.
  void pull(const Vec3& force);
  void release();
  bool grabbing() const { return grabbing_; }
  int grabbedVertex() const { return simulator().dragVertex(mouseDrag_); }

  // --- time ------------------------------------------------------------------------------------
  // Playing: the scene's timeline drives every tracked muscle, gravity and drag through the
  // ScenePlayer (the sliders show the values); paused: the sliders drive the simulator directly. Time advances only while playing or when advance()
  // is called while paused (the face keeps settling under the sliders without moving the playhead).
  bool playing = false;
  // Advances `seconds` of simulated time at the model's fixed dt (an accumulator keeps the
  // remainder), so the simulation runs at the same rate whatever the frame rate.
  void advance(double seconds);
  // Jumps the playhead to t (s, clamped to [0, duration]): the face restarts from rest and the
  // timeline is replayed to t.
  void seek(double t);
  double playhead() const { return player_->time(); }
  double duration() const { return scene().duration; }

  // --- the live stream (docs/live.md, "In the viewer") -----------------------------------------
  // From now on each advance() takes the source's newest frame and maps it as `myoshell live` does
  // (LiveFaceMapper with the scene's maps and `filter`; LiveFaceInput with `settings`): the mapped
  // muscles, jaw, gaze and head turn drive the face, their sliders show the stream, the muscles
  // the stream does not map keep their sliders. The timeline stops (playing is ignored while live).
  // `clock` is the source's (its arrival stamps).
  void listen(std::unique_ptr<LiveSource> source, LiveClock clock, const LiveFaceSettings& settings = {},
              const OneEuroSettings& filter = {});
  bool live() const { return source_ != nullptr; }
  // "Calibrate neutral": the frames of the next `seconds` are the performer's resting face.
  void calibrateNeutral(double seconds = 1.0);
  LiveStatus liveStatus() const;  // only while live()
  // VMC blend names the stream sent that mean nothing here (warn once at the end).
  std::vector<std::string> liveUnknownNames() const;

  // --- authoring -------------------------------------------------------------------------------
  // A key at the playhead on every muscle's activation track with its slider value (a key already
  // at that time is replaced), and on the jaw's three tracks when the jaw is off rest or the scene
  // has jaw tracks. Returns the number of keys set.
  int setKeysAtPlayhead();
  // Writes the scene (sceneToJson) to `path` atomically.
  void saveScene(const std::string& path) const;
  // Simulates the scene's whole timeline from rest on a fresh simulator and writes a GLB
  // (io/animation_export.h) to `path`; the live face is untouched. Returns the frames written.
  int exportGlb(const std::string& path) const;

  // Warnings since the last call (clamped sliders), oldest first: the window shows them.
  std::vector<std::string> takeWarnings() { return std::exchange(warnings_, {}); }

  // --- readouts --------------------------------------------------------------------------------
  double stepsPerSecond() const { return stepsPerSecond_; }  // simulated steps per wall second, smoothed
  const StepTimings& lastTimings() const { return simulator().lastTimings(); }

 private:
  std::shared_ptr<const FaceSystem> model_;
  BasisCache* cache_;   // where the faces' bases come from (may be null)
  // The scene, its timeline clock (the playhead) and the simulator; a pointer, so that a stiffness
  // rebuild (anatomical) can replace it with one on the new face.
  std::unique_ptr<ScenePlayer> player_;
  double baseModulus_ = 0.0;  // anatomical: the scene's skin.young_modulus as opened (E₀)
  std::vector<double> sliders_;
  JawPose jaw_;
  std::vector<int> mirror_;
  std::vector<bool> tracked_;  // per muscle: whether the timeline has an activation track for it
  int mouseDrag_ = 0;
  bool gravityOn_ = false;
  bool grabbing_ = false;
  double pending_ = 0.0;  // simulated seconds owed to the accumulator
  double blinkTime_ = -1.0;  // seconds into the current blink, −1 when none
  std::vector<int> blinkMuscles_;  // the palpebral muscles
  double stepsPerSecond_ = 0.0;
  std::vector<std::string> warnings_;

  // The live stream (null when not live).
  std::unique_ptr<LiveSource> source_;
  LiveClock clock_;
  std::optional<LiveFaceInput> input_;
  std::optional<LiveFaceMapper> mapper_;
  std::vector<int> liveIndex_;      // per mapped muscle: its index in the model (−1: none)
  std::vector<bool> liveDriven_;    // per model muscle: whether the stream drives it
  MappedPerformance liveFrame_;     // the frame the steps apply (mapped once per advance)
  double liveStart_ = 0.0;          // s on clock_: the mapper's time origin
  std::optional<double> arrival_;   // the newest frame's arrival, until the steps that show it are done
  std::deque<std::pair<double, long>> packetTimes_;  // (s, packets so far), the last second
  std::deque<std::pair<double, double>> latencies_;  // (s, ms), the last second
  void takeLive();
  void liveStepsDone();

  FaceStepper& sim() { return player_->simulator(); }
  void applyControls();
  void controls(FaceStepper& sim);
  void updateTracked();
};

}  // namespace myo::viewer
