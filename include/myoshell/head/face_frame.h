// A face frame derived from landmarks: everything placed on a head is placed in this frame, so it
// does not depend on where the head sits, how it is turned, or its units.
#pragma once

#include "myoshell/core/types.h"
#include "myoshell/head/landmarks.h"

namespace myo {

// origin  midpoint of the eyes' outer corners (right_eye_outer, left_eye_outer), in mesh units;
// x       unit vector from the right to the left outer eye corner (+x: subject's left);
// y       unit vector from chin_menton up to the origin, made orthogonal to x (Gram–Schmidt);
// z       x × y, out of the face;
// scale   outer inter-ocular distance |left_eye_outer − right_eye_outer|, mesh units (cm for our
//         heads: 8.9 cm on the canonical MediaPipe mesh, 9.7 cm on ICT's).
// A point p of the mesh has frame coordinates q = axesᵀ (p − origin) / scale (dimensionless), and
// p = origin + scale · axes q. Under p ↦ s R p + t (rotation R, uniform scale s > 0, translation
// t) the frame moves with the head and q is unchanged.
struct FaceFrame {
  Vec3 origin = Vec3::Zero();
  Mat3 axes = Mat3::Identity();  // columns x, y, z (orthonormal, right-handed)
  double scale = 1.0;

  Vec3 toFrame(const Vec3& p) const { return axes.transpose() * (p - origin) / scale; }
  Vec3 fromFrame(const Vec3& q) const { return origin + scale * (axes * q); }
  // Row-wise versions for n×3 point sets.
  MatX3 toFrame(const MatX3& P) const;
  MatX3 fromFrame(const MatX3& Q) const;
  // Directions (no origin, no scale): axesᵀ d and axes d.
  Vec3 directionToFrame(const Vec3& d) const { return axes.transpose() * d; }
  Vec3 directionFromFrame(const Vec3& d) const { return axes * d; }
};

// The face frame of vertices V (n×3) from landmarks right_eye_outer, left_eye_outer and
// chin_menton. Throws InputError when a landmark is missing or the three points are (nearly)
// collinear or coincident.
FaceFrame faceFrame(const MatX3& V, const Landmarks& landmarks);

}  // namespace myo
