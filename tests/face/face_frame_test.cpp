#include <gtest/gtest.h>

#include <numbers>

#include "myoshell/head/face_frame.h"
#include "myoshell/head/head.h"
#include "myoshell/io/head_files.h"
#include "support/test_data.h"

namespace myo {
namespace {

TEST(FaceFrame, InvariantUnderRotationTranslationAndUnits) {
  MYO_REQUIRE_SHARED_DATA();
  const auto dir = test::sharedDataDir() / "ict";
  const Head head = loadHead((dir / "head_skin.obj").string(),
                             (dir / "landmarks_multipie68.json").string());
  const FaceFrame f = head.frame();
  // 30° about a skew axis, moved, and given in metres.
  const Mat3 R = Eigen::AngleAxisd(std::numbers::pi / 6.0, Vec3(1.0, 2.0, -0.5).normalized())
                     .toRotationMatrix();
  const Vec3 t(0.37, -1.2, 2.5);  // metres
  const double s = 0.01;          // cm → m
  MatX3 W(head.mesh.vertexCount(), 3);
  for (int i = 0; i < W.rows(); ++i) W.row(i) = (s * (R * Vec3(head.mesh.V.row(i))) + t).transpose();
  const FaceFrame g = faceFrame(W, head.landmarks);

  EXPECT_NEAR(g.scale, s * f.scale, 1e-12);
  EXPECT_LT((g.axes - R * f.axes).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((g.origin - (s * (R * f.origin) + t)).norm(), 1e-9 * s * f.scale);
  // Every vertex has the same frame coordinates (dimensionless), to 1e-9.
  const MatX3 q0 = f.toFrame(head.mesh.V), q1 = g.toFrame(W);
  EXPECT_LT((q0 - q1).cwiseAbs().maxCoeff(), 1e-9);
  // And a point placed in the frame lands where the transformed head says.
  const Vec3 q(0.1, -0.8, 0.3);
  EXPECT_LT((g.fromFrame(q) - (s * (R * f.fromFrame(q)) + t)).norm(), 1e-9 * s * f.scale);
  EXPECT_LT((f.toFrame(f.fromFrame(q)) - q).norm(), 1e-12);
}

TEST(FaceFrame, AxesAreRightHandedAndFollowTheLandmarks) {
  const Head head = loadDefaultHead();
  const FaceFrame f = head.frame();
  EXPECT_LT((f.axes.transpose() * f.axes - Mat3::Identity()).norm(), 1e-12);
  EXPECT_NEAR(f.axes.determinant(), 1.0, 1e-12);
  const Vec3 chin = f.toFrame(Vec3(head.mesh.V.row(head.landmarks.vertex("chin_menton"))));
  const Vec3 nose = f.toFrame(Vec3(head.mesh.V.row(head.landmarks.vertex("nose_tip"))));
  const Vec3 left = f.toFrame(Vec3(head.mesh.V.row(head.landmarks.vertex("left_eye_outer"))));
  EXPECT_NEAR(chin.x(), 0.0, 1e-9);  // the default head is symmetric about its midplane
  EXPECT_LT(chin.y(), -1.0);
  EXPECT_NEAR(chin.z(), 0.0, 1e-9);  // y was built from the chin: it lies in the frame's xy plane
  EXPECT_GT(nose.z(), 0.2);          // the nose sticks out along +z
  EXPECT_NEAR(left.x(), 0.5, 1e-12);
}

}  // namespace
}  // namespace myo
