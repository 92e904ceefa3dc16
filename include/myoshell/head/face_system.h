// The seam between the face models and everything that plays them (docs/anatomical_model.md,
// "Playing a scene"). A FaceSystem is a built face, immutable: the thesis's FaceModel
// (face_model.h) or the anatomical face (anatomical_face.h). A FaceStepper steps one in time:
// Simulator (simulator.h) or AnatomicalSimulator. ScenePlayer, the exporters, the pictures and the
// apps program against these two; what only one model has (the thesis's channels' bases, ROIs,
// skin stiffness slider) is reached by asking for that model (dynamic_cast) and refused otherwise.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/head/eye_gaze.h"
#include "myoshell/head/face_model_kind.h"
#include "myoshell/head/head.h"
#include "myoshell/head/jaw.h"

namespace myo {

// The built-in head each model uses: the anatomical model's has open eyes (its lids turn about the
// eyeballs, eyelids.h); the thesis model's keeps them closed, the head its figures were made on.
DefaultHeadOptions defaultHeadOptions(FaceModelKind kind);

// A drag force (the thesis's F_ext_s1, Fig. 24–25): a force on the skin vertices within `radius` of
// `vertex`. The thesis gives it its own channel with its own pinned set; the anatomical model adds
// its static responses to the one skin's basis (AnatomicalSkin::addDrag).
struct DragDef {
  std::string name = "drag";
  int vertex = -1;                // skin vertex the user grabs
  double radius = 1.0;            // cm: vertices within it share the force equally
  std::vector<int> pins;          // thesis only: pinned skin vertices of this channel; empty = FaceModel::gravityPins()
};

// Wall time of the parts of the last step (s). A model fills what it has; total always.
struct StepTimings {
  double muscles = 0.0;   // muscles (thesis step 1; anatomical: the activation levels)
  double springs = 0.0;   // thesis step 2 (springs onto the skin channels); anatomical: the force assembly
  double channels = 0.0;  // the skin's modal steps (thesis steps 3–4)
  double total = 0.0;
};

class FaceStepper;

class FaceSystem {
 public:
  virtual ~FaceSystem() = default;
  virtual FaceModelKind kind() const = 0;
  virtual const Head& head() const = 0;
  virtual double dt() const = 0;  // s, the fixed step
  virtual int muscleCount() const = 0;
  virtual const std::string& muscleName(int muscle) const = 0;
  virtual const TriMesh& muscleMesh(int muscle) const = 0;  // its rest mesh, cm
  virtual int muscleIndex(const std::string& name) const = 0;  // InputError naming an unknown muscle
  // The activations the model accepts: [minActivation(), 1] (thesis −1: relaxing; anatomical 0).
  virtual double minActivation() const = 0;
  // The skin's channels, for per-channel maxima: the thesis's one per force; the anatomical "skin".
  virtual std::vector<std::string> channelNames() const = 0;
  virtual bool hasGravity() const = 0;
  virtual const std::vector<DragDef>& drags() const = 0;
  // Skin vertices held in place (the thesis's gravity pins; none in the anatomical model).
  virtual std::vector<int> pinnedVertices() const = 0;
  // A stepper of `self` (which must be this face) at rest.
  virtual std::unique_ptr<FaceStepper> makeStepper(std::shared_ptr<const FaceSystem> self) const = 0;
  virtual double buildSeconds() const = 0;
  virtual int cacheHits() const = 0;
};

// A stepper of `face` at rest (face->makeStepper(face)).
std::unique_ptr<FaceStepper> makeStepper(std::shared_ptr<const FaceSystem> face);

class FaceStepper {
 public:
  virtual ~FaceStepper() = default;
  virtual const FaceSystem& face() const = 0;
  // Activation of a muscle. The thesis clamps to [−1, 1] with a warning; the anatomical model
  // throws InputError naming the model outside [0, 1]. NaN throws InputError.
  virtual void setActivation(int muscle, double a) = 0;
  virtual double activation(int muscle) const = 0;
  // Gravity scale (0 = off, 1 = the model's acceleration); InputError without gravity unless 0.
  virtual void setGravity(double scale) = 0;
  // The head's pose: its rotation in face-frame coordinates (headPoseRotation of [pitch, yaw, roll]
  // degrees, anatomical_face.h); it turns gravity (gravityForRotation). The thesis model has no
  // head pose: InputError naming the model.
  virtual void setHeadPose(const Eigen::Quaterniond& rotation) = 0;
  // The jaw's pose (head/jaw.h; docs/jaw.md), from the next positions on: opening (degrees),
  // protrusion and lateral shift (cm); validateJawPose's ranges, else InputError. The anatomical
  // model turns the rest state with the mandible and the skin's displacement with it (the physics acts
  // on the residual); the thesis model has no jaw: a nonzero pose is an InputError naming the model.
  virtual void setJaw(const JawPose& pose) = 0;
  virtual JawPose jaw() const = 0;
  // The eyes' turn (eye_gaze.h; docs/eyelids.md, "The lids follow the gaze"), from the next positions
  // on: the anatomical model's lids follow it where the head has open eyes (nothing moves on a head
  // without them); validateEyeGaze's range, else InputError. The thesis model has no eyes: a nonzero
  // gaze is an InputError naming the model.
  virtual void setGaze(const EyeGaze& gaze) = 0;
  virtual EyeGaze gaze() const = 0;
  // Drag force (dyn, total, shared by the drag's vertices) of drag `drag`.
  virtual void setDragForce(int drag, const Vec3& force) = 0;
  // Moves drag `drag`'s grip to skin vertex `vertex` (radius ≤ 0: the drag's own). Allocates.
  virtual void setDragVertex(int drag, int vertex, double radius = 0.0) = 0;
  virtual int dragVertex(int drag) const = 0;
  // Scales the skin's stiffness (the thesis's Fig. 22 slider); the anatomical model refuses it.
  virtual void setSkinStiffnessScale(double s) = 0;
  virtual double skinStiffnessScale() const = 0;

  // Advances by the face's dt. NumericalError when the skin runs away.
  virtual void step() = 0;
  // Back to the neutral face at rest (activations, gravity and drags kept).
  virtual void reset() = 0;
  virtual long long stepCount() const = 0;  // steps taken

  // n×3, cm: the physics' displacement u, relative to the (jawed) rest, in the rest frame.
  virtual const MatX3& skinDisplacement() const = 0;
  // n×3, cm: rest + u; with a jaw, the jawed rest + u turned with the blended jaw rotation (jaw.h).
  virtual void skinPositions(MatX3& out) const = 0;
  virtual void channelDisplacement(int channel, MatX3& out) const = 0;  // channelNames() order, n×3
  virtual void musclePositions(int muscle, MatX3& out) const = 0;      // its mesh's n×3, cm
  virtual const StepTimings& lastTimings() const = 0;
  // Warnings since the last call (clamped activations), oldest first; the library prints nothing.
  virtual std::vector<std::string> takeWarnings() = 0;

  MatX3 skinPositions() const {
    MatX3 out;
    skinPositions(out);
    return out;
  }
  MatX3 channelDisplacement(int channel) const {
    MatX3 out;
    channelDisplacement(channel, out);
    return out;
  }
  MatX3 musclePositions(int muscle) const {
    MatX3 out;
    musclePositions(muscle, out);
    return out;
  }
};

}  // namespace myo
