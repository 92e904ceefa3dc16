// Air in the mouth (anatomy/mouth_pressure.h): where the load lies, which way it pushes, how it
// scales, and that it follows the head wherever the head is.
#include <gtest/gtest.h>

#include <cmath>

#include "myoshell/anatomy/mouth_pressure.h"
#include "myoshell/core/errors.h"
#include "myoshell/head/face_system.h"
#include "myoshell/head/head.h"
#include "myoshell/mesh/geometry.h"

namespace myo {
namespace {

Head anatomicalHead() { return loadDefaultHead(defaultHeadOptions(FaceModelKind::Anatomical)); }

TEST(MouthPressure, TheLoadLiesOnTheCheeksAndLipsAndPushesOutOfTheFace) {
  const Head head = anatomicalHead();
  const VecX w = mouthVestibuleWeights(head);
  const FaceFrame frame = head.frame();
  // Over the vestibule: the lips' midpoints and the cheek beside a mouth corner; not the forehead,
  // the nose's tip or the chin's point.
  EXPECT_EQ(w(head.landmarks.vertex("upper_lip_top")), 1.0);
  EXPECT_EQ(w(head.landmarks.vertex("lower_lip_bottom")), 1.0);
  EXPECT_EQ(w(head.landmarks.vertex("nose_tip")), 0.0);
  EXPECT_EQ(w(head.landmarks.vertex("chin_menton")), 0.0);
  EXPECT_EQ(w(head.landmarks.vertex("nasion_approx")), 0.0);
  const Vec3 corner = frame.toFrame(Vec3(head.mesh.V.row(head.landmarks.vertex("mouth_corner_left")).transpose()));
  Eigen::Index cheek = 0;
  MatX3 Q(head.mesh.V.rows(), 3);
  for (Eigen::Index i = 0; i < Q.rows(); ++i) Q.row(i) = frame.toFrame(Vec3(head.mesh.V.row(i).transpose())).transpose();
  (Q.rowwise() - (corner + Vec3(0.1, 0.0, 0.0)).transpose()).rowwise().squaredNorm().minCoeff(&cheek);
  EXPECT_GT(w(cheek), 0.9) << Q.row(cheek);

  // p·A·w along the outward normal: the resultant pushes out of the face (+z), left and right
  // cancel (the built-in head is symmetric), and the load is linear in p.
  const MatX3 f = mouthPressureLoad(head, 2.0);
  const Vec3 total = f.colwise().sum().transpose();
  const double out = total.dot(frame.axes.col(2)), sideways = total.dot(frame.axes.col(0));
  double magnitude = 0.0;
  for (Eigen::Index i = 0; i < f.rows(); ++i) magnitude += f.row(i).norm();
  EXPECT_GT(out, 0.3 * magnitude);
  EXPECT_LT(std::abs(sideways), 1e-6 * magnitude);
  EXPECT_LT((mouthPressureLoad(head, 1.0) * 2.0 - f).cwiseAbs().maxCoeff(), 1e-9 * f.cwiseAbs().maxCoeff());
  RecordProperty("resultant_out_N", std::to_string(out * 1e-5));  // dyn → N
  // 2 kPa over the vestibule's footprint: |Σ p A_i w_i n_i| is at most p Σ A_i w_i.
  const VecX area = [&] {
    VecX a = VecX::Zero(head.mesh.V.rows());
    for (Eigen::Index t = 0; t < head.mesh.F.rows(); ++t) {
      const double A = triangleArea(head.mesh.V.row(head.mesh.F(t, 0)).transpose(), head.mesh.V.row(head.mesh.F(t, 1)).transpose(),
                                    head.mesh.V.row(head.mesh.F(t, 2)).transpose());
      for (int k = 0; k < 3; ++k) a(head.mesh.F(t, k)) += A / 3.0;
    }
    return a;
  }();
  EXPECT_NEAR(magnitude, 2.0e4 * area.dot(w), 1e-6 * magnitude);

  EXPECT_THROW(mouthPressureLoad(head, -1.0), InputError);
  EXPECT_THROW(mouthPressureLoad(head, kMouthPressureMaxKpa + 1.0), InputError);
}

// The footprint is the face frame's: the head turned, moved and scaled has the same weights, and
// its load turns with it and scales with the area.
TEST(MouthPressure, TheLoadFollowsTheHeadTurnedMovedAndScaled) {
  const Head head = anatomicalHead();
  Head moved = head;
  const Mat3 R = Eigen::AngleAxisd(0.4, Vec3(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
  const double s = 1.3;
  const Vec3 t(5.0, -2.0, 1.0);
  for (Eigen::Index i = 0; i < moved.mesh.V.rows(); ++i)
    moved.mesh.V.row(i) = (s * R * head.mesh.V.row(i).transpose() + t).transpose();
  EXPECT_LT((mouthVestibuleWeights(moved) - mouthVestibuleWeights(head)).cwiseAbs().maxCoeff(), 1e-9);
  const MatX3 f = mouthPressureLoad(head, 2.0), g = mouthPressureLoad(moved, 2.0);
  const MatX3 expected = (s * s) * (f * R.transpose());
  EXPECT_LT((g - expected).cwiseAbs().maxCoeff(), 1e-6 * f.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace myo
