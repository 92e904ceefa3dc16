// Steps a FaceModel (DESIGN.md, "one frame"):
//   1. each muscle: activation force on its central nodes → its stretch mode (eq. 11–13) → u_m
//   2. springs: u_m → force on the skin nodes of that muscle's ROI (eq. 14–18)
//   3. each skin channel f: R_fᵀF_f → modal q_f → warped u_f (eq. 10, 17)
//   4. u_skin = Σ_f u_f (eq. 21)
// step() allocates nothing. The step length is the model's dt (the exact per-mode integrator's
// coefficients are precomputed for it).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "myoshell/reduce/modal_warping.h"
#include "myoshell/thesis/face_model.h"

namespace myo {

class Simulator : public FaceStepper {
 public:
  explicit Simulator(std::shared_ptr<const FaceModel> model);

  // Activation a of a muscle: +1 full contraction (force towards the origin), −1 relaxation (away).
  // Values outside [−1, 1] are clamped, counted in clampedActivations() and explained in
  // takeWarnings() ("activation 3 of muscle 'x' clamped to 1"); NaN throws InputError.
  void setActivation(int muscle, double a) override;
  void setActivation(const std::string& muscle, double a);
  double activation(int muscle) const override { return activation_[static_cast<size_t>(muscle)]; }
  // Gravity scale (0 = off, 1 = 981 cm/s²); needs the model's gravity channel unless 0.
  void setGravity(double scale) override;
  // Drag force (dyn, total, shared by the drag region) of drag channel `drag`.
  void setDragForce(int drag, const Vec3& force) override;
  // Moves drag `drag`'s grip to skin vertex `vertex` (the viewer's mouse): its force is then
  // shared by the free skin vertices within `radius` cm of it (radius ≤ 0: the drag's own radius).
  // The channel's basis does not change. Throws InputError for a vertex outside the skin or when
  // no free vertex is that close (a pinned spot). Allocates: call it between steps.
  void setDragVertex(int drag, int vertex, double radius = 0.0) override;
  int dragVertex(int drag) const override { return dragVertex_[static_cast<size_t>(drag)]; }
  // Scales the stiffness of every skin channel exactly: Λ ← sΛ, damping recomputed, Φ and Ψ kept
  // (no eigen-solve; the thesis's Fig. 22 as a live slider). Under a constant load the steady
  // displacement scales as 1/s. Throws InputError unless s is finite and > 0.
  void setSkinStiffnessScale(double s) override;
  double skinStiffnessScale() const override { return skinStiffnessScale_; }

  // Advances the whole face by the model's dt. Throws NumericalError naming the channel, the step and
  // the likely causes when the skin's displacement becomes NaN, infinite or larger than the head.
  void step() override;
  // Steps until `seconds` of simulated time have passed (rounded to whole steps); returns the steps.
  int advance(double seconds);
  double time() const { return time_; }
  long long stepCount() const override { return steps_; }

  // The skin's displacement (n×3, cm): Σ_f u_f, and positions rest + u.
  const MatX3& skinDisplacement() const override { return skinU_; }
  MatX3 skinPositions() const;
  void skinPositions(MatX3& out) const override;  // into `out` (no allocation once it is n×3)
  // One channel's displacement field u_f over the full skin (n×3, cm).
  MatX3 channelDisplacement(int channel) const;
  void channelDisplacement(int channel, MatX3& out) const override;  // into `out` (no allocation once n×3)
  // A muscle's current node positions (its mesh's n×3, cm).
  MatX3 musclePositions(int muscle) const;
  void musclePositions(int muscle, MatX3& out) const override;  // into `out` (no allocation once sized)
  // The muscle's modal amplitude q_m.
  double muscleAmplitude(int muscle) const;

  const StepTimings& lastTimings() const override { return timings_; }
  int clampedActivations() const { return clamped_; }
  // The warnings since the last call (clamped activations, naming the muscle), oldest first; at
  // most 64 are kept between calls. The library prints nothing: callers show these.
  std::vector<std::string> takeWarnings() override { return std::exchange(warnings_, {}); }
  const FaceModel& model() const { return *model_; }
  const FaceSystem& face() const override { return *model_; }
  // The integrators step() advances: one per skin channel (FaceModel::channels() order), one per
  // muscle (what myoshell bench streams for its floor).
  const std::vector<ModalWarpingIntegrator>& channelIntegrators() const { return channelIntegrators_; }
  const std::vector<ModalWarpingIntegrator>& muscleIntegrators() const { return muscleIntegrators_; }
  // The last step's force on the whole skin, Σ over channels of its free force scattered to the
  // skin (n×3, dyn, world frame: springs, gravity, drags): the load of a full-space reference step.
  MatX3 skinLoad() const;
  // The thesis model has no head pose: InputError naming the model.
  void setHeadPose(const Eigen::Quaterniond& rotation) override;
  // The thesis model has no jaw: a nonzero pose is an InputError naming the model (zero is accepted).
  void setJaw(const JawPose& pose) override;
  JawPose jaw() const override { return {}; }
  // No eyes to turn: a nonzero gaze is an InputError naming the model.
  void setGaze(const EyeGaze& gaze) override;
  EyeGaze gaze() const override { return {}; }
  // Back to the neutral face at rest (activations, gravity and drags kept).
  void reset() override;

 private:
  std::shared_ptr<const FaceModel> model_;
  std::vector<ModalWarpingIntegrator> muscleIntegrators_;
  std::vector<ModalWarpingIntegrator> channelIntegrators_;
  std::vector<MatX3> muscleForce_;   // per muscle, its basis's free f×3
  std::vector<MatX3> channelForce_;  // per channel, free f×3
  std::vector<bool> channelLoaded_;  // whether the channel's force is non-zero this step
  std::vector<double> activation_;
  double gravity_ = 1.0;
  std::vector<Vec3> dragForce_;
  std::vector<std::vector<int>> dragRows_;  // per skin channel (drag channels only): free rows sharing the force
  std::vector<int> dragVertex_;             // per drag: the vertex gripped
  double skinStiffnessScale_ = 1.0;
  MatX3 skinU_;
  double time_ = 0.0;
  long long steps_ = 0;
  int clamped_ = 0;
  std::vector<std::string> warnings_;
  StepTimings timings_;
  double runawayLimit_ = 0.0;  // cm: the head's bounding-box diagonal

  void checkHealth() const;
};

}  // namespace myo
