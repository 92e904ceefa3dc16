#include "myoshell/head/face_frame.h"

#include "myoshell/core/errors.h"

namespace myo {

MatX3 FaceFrame::toFrame(const MatX3& P) const {
  MatX3 Q(P.rows(), 3);
  for (int i = 0; i < P.rows(); ++i) Q.row(i) = toFrame(Vec3(P.row(i))).transpose();
  return Q;
}

MatX3 FaceFrame::fromFrame(const MatX3& Q) const {
  MatX3 P(Q.rows(), 3);
  for (int i = 0; i < Q.rows(); ++i) P.row(i) = fromFrame(Vec3(Q.row(i))).transpose();
  return P;
}

FaceFrame faceFrame(const MatX3& V, const Landmarks& landmarks) {
  const Vec3 r = V.row(landmarks.vertex("right_eye_outer"));
  const Vec3 l = V.row(landmarks.vertex("left_eye_outer"));
  const Vec3 chin = V.row(landmarks.vertex("chin_menton"));
  FaceFrame f;
  f.origin = 0.5 * (r + l);
  f.scale = (l - r).norm();
  const Vec3 up = f.origin - chin;
  if (!(f.scale > 0.0) || !(up.norm() > 1e-6 * f.scale))
    throw InputError("face frame: eye corners and chin coincide", landmarks.sourcePath);
  const Vec3 x = (l - r) / f.scale;
  const Vec3 yRaw = up - up.dot(x) * x;
  if (yRaw.norm() < 1e-3 * up.norm())
    throw InputError("face frame: chin lies on the line through the eye corners",
                     landmarks.sourcePath);
  const Vec3 y = yRaw.normalized();
  f.axes.col(0) = x;
  f.axes.col(1) = y;
  f.axes.col(2) = x.cross(y);
  return f;
}

}  // namespace myo
