// A kinematic jaw for the anatomical model (docs/jaw.md; issue 17): a mandible with three degrees of
// freedom — opening (a rotation about the temporomandibular axis, the face frame's x through a pivot
// placed from landmarks), protrusion (along the face frame's z) and lateral shift (along its x) —
// that skin vertices follow through a weight map derived from the anatomy (the mandible region,
// from the jaw-line and lip landmarks, with a smooth falloff over the cheeks).
//
// The rest state rides with the jaw: vertex i of weight w_i has the jawed rest
//   X̃_i = R(w_i θ)(X_i − p) + p + w_i t,     t = forward·ẑ + lateral·x̂ (cm, head space),
// R(α) the rotation by α about the axis x̂ (through the pivot p), θ the opening. The physics acts on
// the residual: the skin's displacement u (the simulator's, computed in the rest frame) is turned
// with the blended rotation, x_i = X̃_i + R(w_i θ) u_i, so a 25° opening never passes through the
// modal basis. The tissue attachment of a jaw-weighted vertex anchors at its jawed rest (u = 0 there),
// so the rigid part makes no force.
#pragma once

#include <string>

#include "myoshell/core/types.h"
#include "myoshell/head/face_frame.h"
#include "myoshell/head/landmarks.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo {

// The jaw's three degrees of freedom.
struct JawPose {
  double openDeg = 0.0;    // degrees, rotation about the face frame's x through the pivot; + opens the mouth
  double forwardCm = 0.0;  // cm along the face frame's z (protrusion, out of the face)
  double lateralCm = 0.0;  // cm along the face frame's x (+ towards the subject's left)
  bool isZero() const { return openDeg == 0.0 && forwardCm == 0.0 && lateralCm == 0.0; }
};

// The accepted ranges (anatomical limits, docs/jaw.md): opening [0, 40]° (a maximal opening of
// 40–50 mm between the incisors is about 35–40°), protrusion [−0.5, 1.5] cm (7–11 mm is the adult
// maximum; a little retrusion), lateral [−1.5, 1.5] cm (8–12 mm maximal excursion).
inline constexpr double kJawOpenMinDeg = 0.0, kJawOpenMaxDeg = 40.0;
inline constexpr double kJawForwardMinCm = -0.5, kJawForwardMaxCm = 1.5;
inline constexpr double kJawLateralMaxCm = 1.5;
// InputError naming the degree of freedom, its value and range (and NaN/∞), prefixed by `what`.
void validateJawPose(const JawPose& pose, const std::string& what = "jaw");

// Tunables of the weight map, in face-frame units (fractions of the outer-canthal distance) and
// degrees; the defaults are the model (docs/jaw.md, "The weight map"): anatomical estimates, not fitted.
struct JawWeightSettings {
  // The split between maxilla and mandible is the half-plane through the axis and the mouth line
  // (the inner lip line between the corners; beyond them the ray from each mouth corner back to the
  // axis, i.e. the occlusal line). With b the angle (degrees, about the axis) below that line:
  //   w_split = (1 − λ) step(b) + λ S(½(b/h + 1)),   λ = S((|x| − (x_c − c)) / c),
  // S the C¹ smoothstep, h = cheekHalfWidthDeg, x_c the inner mouth corners' |x| (landmarks 60, 64:
  // where the lips stop being parted), c = commissureBlend: the lips part cleanly (step) but for their
  // last c before the corners, where the commissure blends (the lower lip's edge follows 1 − λ/2, the
  // upper's λ/2; continuous, as λ = 1 where the lips join), and over the cheeks the weight falls from
  // 1 to 0 across ±h about the occlusal line.
  double cheekHalfWidthDeg = 20.0;
  double commissureBlend = 0.10;  // face-frame units (≈ 9 mm: the modiolus's reach into the lips)
  // Within `lipRegion` of the stomion (face-frame units), step(b) is replaced by the lip a vertex
  // belongs to: the lower lip (1) when it is nearer, along the skin, to the lower lip's landmark (57)
  // than to the upper lip's (51), else 0. The lips' inner surfaces curl into the mouth and meet
  // behind the landmarks' line, where no plane through the axis separates them; along the skin they
  // are joined only at the corners. Outside the region the two rules agree (nose, chin).
  double lipRegion = 0.35;
  // Towards the ramus: the weight fades from 1 at `posteriorFullDeg` to 0 at `posteriorZeroDeg`
  // (angles about the axis from straight ahead, −90° = straight down). About a mid-ramus axis the
  // ramus would swing back into the neck, but in a real opening the condyle glides forward and the
  // ramus's skin (over masseter and parotid) stays nearly still: the skin follows the mandible's body
  // (chin to the angle's front) and lets go over the angle and the ramus, and behind them.
  double posteriorFullDeg = -40.0, posteriorZeroDeg = -130.0;
  // Below the mandible's lower border (the jaw-line landmarks 4–12, gonion to gonion, interpolated
  // across x, level beyond): 1 at the border, 0 this far below it (face-frame units; 0.4 ≈ 3.6 cm on
  // an adult, about the hyoid's level: the submental and neck skin between stretches).
  double neckFalloff = 0.40;
};

// The jaw of a head: pivot, axes and the per-vertex weights (all in head space, cm).
struct JawRig {
  Vec3 pivot = Vec3::Zero();        // cm, a point of the opening axis
  Vec3 axis = Vec3::UnitX();        // unit: the face frame's x (opening axis; lateral direction)
  Vec3 forward = Vec3::UnitZ();     // unit: the face frame's z (protrusion)
  VecX weights;                     // n, in [0, 1]: how much of the mandible's motion each vertex follows
  std::string pivotRule;            // how the pivot was found (for reports)
};

// The opening axis's pivot (head space, cm) from the 68-point jaw line and the face frame:
//   height: midway between the ear-level jaw-line points (0, 16) and the gonial points (4, 12), i.e.
//           mid-ramus, where the mandibular foramen and the effective hinge of a wide opening lie;
//   depth:  kPivotDepthBehindEarContour (face-frame units) behind the ear-level points (0, 16);
//   across: the face frame's midplane (the axis is the frame's x, so only (y, z) matter).
// Both sides are averaged, so an asymmetric head gets the mean. InputError when the landmarks have
// no 68 points.
inline constexpr double kPivotDepthBehindEarContour = 0.25;
Vec3 jawPivot(const MatX3& V, const Landmarks& landmarks);

// The weight map of a head's skin vertices (n, in [0, 1]).
VecX jawWeights(const TriMesh& skin, const Landmarks& landmarks, const Vec3& pivot,
                const JawWeightSettings& settings = {});

// The jaw of a head (pivot, axes, weights of every skin vertex). InputError when the landmarks have
// no 68 points (the jaw line).
JawRig jawRig(const TriMesh& skin, const Landmarks& landmarks, const JawWeightSettings& settings = {});

// The blended rigid transform of weight w: x ↦ R (x − p) + p + t with R = R(w θ) about the axis and
// t = w (forward ẑ + lateral x̂). Returns R (3×3) and the translation d = p − R p + t (x ↦ R x + d).
struct RigidMotion {
  Mat3 R = Mat3::Identity();
  Vec3 d = Vec3::Zero();
  Vec3 apply(const Vec3& x) const { return R * x + d; }
};
RigidMotion jawMotion(const JawRig& rig, const JawPose& pose, double w);

// Positions (n×3, cm) of the skin under the jaw: out_i = X̃_i + R(w_i θ) u_i (see the top). A zero
// pose gives rest + u exactly (bit for bit). rest and u are n×3 with n = rig.weights.size().
void jawedPositions(const JawRig& rig, const JawPose& pose, const MatX3& rest, const MatX3& u, MatX3& out);
// The jawed rest X̃ alone (u = 0).
MatX3 jawedRest(const JawRig& rig, const JawPose& pose, const MatX3& rest);

// Whether a muscle of this name has its origin on the mandible and rides with it (weight 1):
// depressor anguli oris, depressor labii inferioris, mentalis, platysma (any side; prefix match).
bool isMandibleMuscle(const std::string& muscleName);

}  // namespace myo
