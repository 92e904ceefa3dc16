// The anatomical face as a FaceSystem (face_system.h): one AnatomicalSkin (anatomical_skin.h) with
// the scene's drags registered on it, stepped by AnatomicalSimulator through AnatomicalStepper, so
// the one frame loop (ScenePlayer) plays it as it plays the thesis's face (docs/anatomical_model.md,
// "Playing a scene").
//
// Gravity: g(t) = s(t)·|g|·(the rest direction turned by the head pose), s the gravity scale
// (timeline.gravity, default 1); only its change from the upright rest g_rest loads the skin
// (reading (b)). Upright at s = 1 the skin stays at rest; s = 0 is weightlessness (the tissue
// rises by the rest sag). With gravity disabled g(t) = g_rest: no gravity load, no head-pose effect.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "myoshell/anatomy/anatomical_stepper.h"
#include "myoshell/anatomy/skin_placement.h"
#include "myoshell/core/timer.h"
#include "myoshell/head/face_system.h"

namespace myo {

// The head's rotation in face-frame coordinates for [pitch, yaw, roll] degrees about the face
// frame's x, y, z, applied in that order: R = R_z R_y R_x (as gravityForPose).
Eigen::Quaterniond headPoseRotation(const Vec3& pitchYawRollDeg);
// Gravity in head space (cm/s²) with the head turned by `rotation` (face-frame coordinates):
// g = −|g|·(A R Aᵀ)ᵀ ŷ, A the frame's axes. gravityForRotation(f, headPoseRotation(p), g) equals
// gravityForPose(f, p, g) to round-off; the identity gives exactly (0, −|g|, 0).
Vec3 gravityForRotation(const FaceFrame& frame, const Eigen::Quaterniond& rotation, double gravity);

class AnatomicalFace : public FaceSystem {
 public:
  // Builds the skin (AnatomicalSkin) with each drag registered at its vertex and radius, its basis
  // from `cache` when given and holding it (else computed and stored there). `gravity` false: no
  // gravity load at all. Throws InputError / NumericalError as AnatomicalSkin.
  AnatomicalFace(const Head& head, const std::vector<MuscleDef>& muscles, const AnatomicalSettings& settings,
                 std::vector<DragDef> drags, bool gravity = true, BasisCache* cache = nullptr);

  const AnatomicalSkin& skin() const { return *skin_; }
  std::shared_ptr<const AnatomicalSkin> skinPtr() const { return skin_; }
  bool gravityEnabled() const { return gravity_; }
  // The jaw (head/jaw.h) of the head: its pivot, axes and weight map; null when the head's landmarks
  // have no 68 points (no jaw line), and then every nonzero jaw pose is refused.
  const JawRig* jawRig() const { return placement_->jaw(); }
  // The eyelids (anatomy/eyelids.h) of a head with open eyes and the 68 landmarks; null otherwise (a
  // closed-eye head: the lid muscles then act through the physics alone).
  const LidRig* lidRig() const { return placement_->lids(); }
  // The lips' contact with the teeth and each other (anatomy/mouth_contact.h); null without a jaw.
  const MouthContact* mouthContact() const { return placement_->mouth(); }
  // The lids' pose at these activations: close from orbicularis_oculi_palpebral_<side>, raise from
  // levator_palpebrae_superioris_<side> (0 for a muscle the library does not have).
  LidPose lidPose(const VecX& activations) const { return placement_->lidPose(activations); }
  // How this face places a shape (anatomy/skin_placement.h): the jaw, the lids, the contact.
  const SkinPlacement& placement() const { return *placement_; }
  // The skin's positions (n×3, cm) for the residual u: SkinPlacement::place. Every user of a settled
  // or stepped shape places it through here or through the same SkinPlacement (the simulator, pose,
  // fits, rigs, Python).
  ContactReport placeSkin(const MatX3& u, const JawPose& jaw, const VecX& activations, MatX3& out,
                          const EyeGaze& gaze = {}) const {
    return placement_->place(u, jaw, activations, out, placement_->contact(), gaze);
  }

  FaceModelKind kind() const override { return FaceModelKind::Anatomical; }
  const Head& head() const override { return skin_->head(); }
  double dt() const override { return skin_->settings().dt; }
  int muscleCount() const override { return static_cast<int>(skin_->muscles().size()); }
  const std::string& muscleName(int m) const override;
  const TriMesh& muscleMesh(int m) const override;
  int muscleIndex(const std::string& name) const override { return skin_->muscleIndex(name); }
  double minActivation() const override { return 0.0; }
  std::vector<std::string> channelNames() const override { return {"skin"}; }
  bool hasGravity() const override { return gravity_; }
  const std::vector<DragDef>& drags() const override { return drags_; }
  std::vector<int> pinnedVertices() const override { return {}; }
  std::unique_ptr<FaceStepper> makeStepper(std::shared_ptr<const FaceSystem> self) const override;
  double buildSeconds() const override { return buildSeconds_; }
  int cacheHits() const override { return skin_->basisFromCache() ? 1 : 0; }  // the one basis

 private:
  std::shared_ptr<const AnatomicalSkin> skin_;
  std::vector<DragDef> drags_;
  std::shared_ptr<const SkinPlacement> placement_;
  bool gravity_ = true;
  double buildSeconds_ = 0.0;
};

// Steps an AnatomicalFace: the loads (activations, gravity scale and head pose, drag forces) kept
// between steps, AnatomicalStepper::step with them. step() allocates nothing.
class AnatomicalSimulator : public FaceStepper {
 public:
  explicit AnatomicalSimulator(std::shared_ptr<const AnatomicalFace> face);

  const FaceSystem& face() const override { return *face_; }
  // InputError naming the model outside [0, 1] (and for NaN).
  void setActivation(int muscle, double a) override;
  double activation(int muscle) const override { return loads_.activations(muscle); }
  void setGravity(double scale) override;
  void setHeadPose(const Eigen::Quaterniond& rotation) override;
  // validateJawPose's ranges; InputError for a nonzero pose on a head without a jaw line.
  void setJaw(const JawPose& pose) override;
  JawPose jaw() const override { return jaw_; }
  // validateEyeGaze's range. Accepted on a head without open eyes, where it moves nothing.
  void setGaze(const EyeGaze& gaze) override;
  EyeGaze gaze() const override { return loads_.gaze; }
  void setDragForce(int drag, const Vec3& force) override;
  // An extra reduced force Φᵀf on the skin (SkinLoads::modalForce: d of the skin's basis, or empty
  // for none); InputError for another size or a value not finite.
  void setModalForce(const VecX& force);
  // Moves the grip to any skin vertex (radius ≤ 0: the drag's own) for this simulator only
  // (AnatomicalStepper::grab: the grip's static responses join this simulator's basis, the shared
  // face is untouched; the displacement does not jump). InputError naming the drag and the vertex
  // outside the mesh. The latency: lastGrabSeconds().
  void setDragVertex(int drag, int vertex, double radius = 0.0) override;
  int dragVertex(int drag) const override { return dragVertex_[static_cast<size_t>(drag)]; }
  // Wall time of the last setDragVertex (s; AnatomicalStepper::lastGrabTimes has its parts).
  double lastGrabSeconds() const { return grabSeconds_; }
  // Refused (InputError naming the model): the one skin has no per-channel stiffness scale.
  void setSkinStiffnessScale(double s) override;
  double skinStiffnessScale() const override { return 1.0; }

  void step() override;
  void reset() override;
  long long stepCount() const override { return steps_; }

  const MatX3& skinDisplacement() const override { return stepper_->displacement(); }
  // The face's placeSkin of the stepped residual at this jaw, these activations and this gaze (the
  // jaw, the lids, the contact; rest + u exactly at a zero jaw where no contact projects).
  void skinPositions(MatX3& out) const override;
  void channelDisplacement(int channel, MatX3& out) const override;  // channel 0: the skin
  // rest + level·U_m; a muscle with a mandible origin (isMandibleMuscle) then moves with the jaw
  // (weight 1). Display only: the couplings act on the residual in the rest frame.
  void musclePositions(int muscle, MatX3& out) const override;
  const StepTimings& lastTimings() const override { return timings_; }
  std::vector<std::string> takeWarnings() override { return {}; }

  // The skin's response (docs/live.md, "Lag"; the face's settings' at first): AnatomicalStepper::setResponse.
  void setResponse(SkinResponse response) { stepper_->setResponse(response); }
  SkinResponse response() const { return stepper_->response(); }
  const SkinLoads& loads() const { return loads_; }
  const AnatomicalStepper& stepper() const { return *stepper_; }

 private:
  std::shared_ptr<const AnatomicalFace> face_;
  std::unique_ptr<AnatomicalStepper> stepper_;
  SkinLoads loads_;
  std::vector<int> dragVertex_;  // per drag: the vertex gripped
  double grabSeconds_ = 0.0;
  double gravityScale_ = 1.0;
  Eigen::Quaterniond pose_ = Eigen::Quaterniond::Identity();
  bool posed_ = false;          // a head pose other than upright was set
  JawPose jaw_;
  double runawayLimit_ = 0.0;   // cm: the head's bounding-box diagonal
  StepTimings timings_;
  long long steps_ = 0;
  void updateGravity();
};

}  // namespace myo
