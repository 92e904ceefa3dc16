// The one frame loop (DESIGN.md, "one frame"): a scene's timeline played on a face's stepper
// (face_system.h: the thesis's Simulator or the AnatomicalSimulator), frame by frame. `myoshell run`, `render`, `bench`, `figures`, `demo` and the viewer's timeline all ask a
// ScenePlayer for frames; none keeps a loop of its own.
//
// Time: the player keeps its own timeline clock (s), starting at 0 (or at `restart(t0)`), advanced
// by the model's dt per step. Before every step the timeline is applied at the clock's time: every
// activation track, the gravity scale (when the model has gravity and the scene a gravity
// track), the head pose, the jaw and the eyes' turn (when the scene has them) and every drag force
// track. Frame k is at time k / fps; a scene has floor(duration·fps + 1e-9) + 1 frames (frame 0 at
// t = 0, the last at or just before `duration`).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <vector>

#include "myoshell/anim/scene.h"
#include "myoshell/head/face_system.h"

namespace myo {

// One frame's state, as the exporters, pictures and stats need it. Buffers are reused from one
// snapshot to the next (they are resized only when empty).
struct FrameSnapshot {
  double time = 0.0;                 // s, the timeline clock
  MatX3 positions;                   // n×3 skin positions (rest + u), cm
  MatX3 displacement;                // n×3 skin displacement u, cm
  double maxDisplacement = 0.0;      // max over vertices of |u|, cm
  std::vector<double> channelMax;    // per skin channel (model.channelNames() order): max over vertices of |u_f|, cm
  std::vector<MatX3> muscles;        // per muscle, its node positions (its mesh's n×3), cm
  // The last advance (advanceTo / playTo) only: steps taken and wall seconds inside the steps.
  int steps = 0;
  double stepSeconds = 0.0;
};

class ScenePlayer {
 public:
  // Resolves every muscle, drag and channel name of the scene's timeline to an index of `model`
  // once. Throws InputError naming an unknown muscle ("timeline: unknown muscle 'x' …") or drag
  // ("timeline: unknown drag 'x' (the scene's drags: …)"). `model` must be built from `scene`
  // (the viewer's may carry extra drags after the scene's own).
  ScenePlayer(SceneDesc scene, std::shared_ptr<const FaceSystem> model);

  // floor(duration·fps + 1e-9) + 1: the one frame-count formula.
  static int frameCount(double duration, double fps);
  int frameCount() const { return frameCount(scene_.duration, scene_.fps); }
  double frameTime(int k) const { return k / scene_.fps; }  // s

  // Steps until the clock reaches frame k's time (to within half a step). Returns false when
  // cancelled (the clock then stops at the step where the flag was seen; nothing half-done).
  bool advanceTo(int k) { return playTo(frameTime(k)); }
  // The same for any time t (s): figures draw t = 0.95 and the like.
  bool playTo(double t);
  // One step at the clock's time: apply the timeline, the controls hook, FaceStepper::step.
  void step();
  // Back to the neutral face at rest with the clock at t0 (s): bench replays a window [t0, t1).
  void restart(double t0 = 0.0);
  // Moves the clock to t (s) without stepping (the viewer's playhead after a seek or at the end).
  void setTime(double t) { time_ = t; }
  // Replaces the scene (the viewer's authored keys), resolving its names again; the simulator's
  // state and the clock are kept. Same errors as the constructor.
  void setScene(SceneDesc scene);

  // Applies the timeline at time t (s) to the simulator without stepping.
  void applyTimeline(double t);
  // Called after the timeline and before every step (the viewer's sliders for untracked muscles,
  // its gravity switch). Empty by default.
  void setControls(std::function<void(FaceStepper&)> controls) { controls_ = std::move(controls); }

  // Cancellation, checked before every step: cancel() (any thread), or a flag the app owns (a
  // signal handler sets it). Once seen, advanceTo / playTo return false until resetCancel().
  void cancel() { cancelled_.store(true); }
  void watch(const std::atomic<bool>* flag) { external_ = flag; }
  bool cancelled() const { return cancelled_.load() || (external_ && external_->load()); }
  void resetCancel() { cancelled_.store(false); }

  // The current frame's state, filled into reused buffers. Muscle positions only when `muscles`.
  const FrameSnapshot& snapshot(bool muscles = true);

  double time() const { return time_; }  // s, the timeline clock
  const SceneDesc& scene() const { return scene_; }
  const FaceSystem& model() const { return *model_; }
  const std::shared_ptr<const FaceSystem>& modelPtr() const { return model_; }
  FaceStepper& simulator() { return *sim_; }
  const FaceStepper& simulator() const { return *sim_; }

 private:
  SceneDesc scene_;
  std::shared_ptr<const FaceSystem> model_;
  std::unique_ptr<FaceStepper> sim_;
  int channelCount_ = 0;
  double time_ = 0.0;
  struct MuscleTrack {
    int muscle;
    const ScalarTrack* track;
  };
  struct DragTrack {
    int drag;
    const VectorTrack* track;
  };
  std::vector<MuscleTrack> muscleTracks_;
  std::vector<DragTrack> dragTracks_;
  bool applyGravity_ = false;
  std::function<void(FaceStepper&)> controls_;
  std::atomic<bool> cancelled_{false};
  const std::atomic<bool>* external_ = nullptr;
  FrameSnapshot snapshot_;
  void resolveNames();
  MatX3 channelU_;  // scratch n×3 for the per-channel maxima
  int lastSteps_ = 0;
  double lastStepSeconds_ = 0.0;
};

}  // namespace myo
