#include "myoshell/anatomy/mouth_pressure.h"

#include <algorithm>
#include <cmath>

#include "myoshell/core/curves.h"
#include "myoshell/core/errors.h"
#include "myoshell/head/face_frame.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/muscles/tissue_attachment.h"

namespace myo {
VecX mouthVestibuleWeights(const Head& head) {
  const FaceFrame frame = head.frame();
  const Landmarks& lm = head.landmarks;
  const MatX3& V = head.mesh.V;
  auto at = [&](const char* name) { return frame.toFrame(Vec3(V.row(lm.vertex(name)))); };
  const double cornerX = 0.5 * (std::abs(at("mouth_corner_left").x()) + std::abs(at("mouth_corner_right").x()));
  const double lipTop = at("upper_lip_top").y(), menton = at("chin_menton").y(), noseTip = at("nose_tip").y();
  // The vestibule, in face-frame units (fractions of the outer-canthal distance, 9.7 cm on ICT):
  // sideways to 0.2 beyond the corners (the cheeks over the premolars and molars), up to halfway from
  // the upper lip's top to the nose's tip (the nose's base), down to a third of the way from the
  // upper lip's top to the menton below the lips (the labiomental fold); each edge falls over 0.08.
  const double xEdge = cornerX + 0.20, top = lipTop + 0.5 * (noseTip - lipTop), bottom = lipTop - 0.6 * (lipTop - menton);
  const double fall = 0.08;
  VecX w(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Vec3 q = frame.toFrame(Vec3(V.row(i)));
    w(i) = smoothStep((xEdge - std::abs(q.x())) / fall) * smoothStep((top - q.y()) / fall) *
           smoothStep((q.y() - bottom) / fall) * smoothStep((q.z() + 0.35) / fall);  // the face's front, not the ears
  }
  return w;
}

namespace {

// The vertex normals turned out of the face: the footprint's normals lean out of the face (the
// frame's +z); a mesh wound the other way has them all reversed.
MatX3 outwardNormals(const Head& head, const VecX& w) {
  MatX3 n = vertexNormals(head.mesh.V, head.mesh.F);
  const Vec3 out = head.frame().axes.col(2);
  if ((w.asDiagonal() * n * out).sum() < 0.0) n = -n;
  return n;
}

}  // namespace

MatX3 mouthPressureLoad(const Head& head, double pressureKpa) {
  if (!(pressureKpa >= 0.0) || pressureKpa > kMouthPressureMaxKpa)
    throw InputError("the mouth's air pressure must lie in [0, " + std::to_string(kMouthPressureMaxKpa) + "] kPa");
  const double p = 1.0e4 * pressureKpa;  // dyn/cm²: 1 kPa = 10⁴ dyn/cm²
  const VecX w = mouthVestibuleWeights(head);
  const VecX area = lumpedVertexAreas(head.mesh.V, head.mesh.F);
  const MatX3 n = outwardNormals(head, w);
  MatX3 f = MatX3::Zero(head.mesh.V.rows(), 3);
  for (Eigen::Index i = 0; i < f.rows(); ++i) f.row(i) = p * area(i) * w(i) * n.row(i);
  return f;
}

double cheekOutwardMoveCm(const Head& head, const MatX3& delta) {
  if (delta.rows() != head.mesh.V.rows()) throw InputError("cheekOutwardMoveCm: the shape must have a row per vertex");
  const FaceFrame frame = head.frame();
  const Landmarks& lm = head.landmarks;
  auto x = [&](const char* name) { return std::abs(frame.toFrame(Vec3(head.mesh.V.row(lm.vertex(name)))).x()); };
  const double cornerX = 0.5 * (x("mouth_corner_left") + x("mouth_corner_right"));
  const VecX w = mouthVestibuleWeights(head);
  const MatX3 n = outwardNormals(head, w);
  double out = 0.0;
  for (Eigen::Index i = 0; i < delta.rows(); ++i)
    if (w(i) >= 0.5 && std::abs(frame.toFrame(Vec3(head.mesh.V.row(i))).x()) > cornerX)
      out = std::max(out, delta.row(i).dot(n.row(i)));
  return out;
}

}  // namespace myo
