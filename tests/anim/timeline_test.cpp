#include <gtest/gtest.h>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anim/head_pose_track.h"
#include "myoshell/anim/timeline.h"
#include "myoshell/core/errors.h"

namespace myo {
namespace {

TEST(Timeline, InterpolatesStepLinearAndSmooth) {
  const ScalarTrack track({{0.0, 0.0, Interpolation::Linear},
                           {1.0, 1.0, Interpolation::Step},
                           {2.0, -1.0, Interpolation::Smooth},
                           {3.0, 1.0, Interpolation::Linear}},
                          "t");
  EXPECT_DOUBLE_EQ(track.at(-5.0), 0.0);   // before the first key: its value
  EXPECT_DOUBLE_EQ(track.at(0.25), 0.25);  // linear
  EXPECT_DOUBLE_EQ(track.at(1.5), 1.0);    // step holds
  EXPECT_DOUBLE_EQ(track.at(2.0), -1.0);
  EXPECT_DOUBLE_EQ(track.at(2.5), 0.0);    // smoothstep is symmetric about the middle
  EXPECT_NEAR(track.at(2.1), -1.0 + 2.0 * (0.03 - 0.002), 1e-12);  // 3s² − 2s³ at s = 0.1
  EXPECT_DOUBLE_EQ(track.at(10.0), 1.0);   // after the last key: its value
  EXPECT_DOUBLE_EQ(ScalarTrack().at(1.0), 0.0);
}

TEST(Timeline, VectorTracksInterpolateComponentwise) {
  const VectorTrack track({{0.0, Vec3(0, 0, 0)}, {2.0, Vec3(2, -4, 6)}}, "drag");
  EXPECT_TRUE(track.at(1.0).isApprox(Vec3(1, -2, 3)));
}

TEST(Timeline, RejectsKeysOutOfOrder) {
  try {
    ScalarTrack({{1.0, 0.0}, {1.0, 1.0}}, "timeline.activations.m");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("timeline.activations.m: key times must increase"), std::string::npos) << e.what();
  }
  EXPECT_THROW(interpolationFromString("cubic"), InputError);
}

}  // namespace
}  // namespace myo

namespace myo {
namespace {

// timeline.head_pose: keys of [pitch, yaw, roll] degrees, slerped.
TEST(HeadPoseTrack, SlerpHalfwayIsTheHalfRotationAndFaceDownGravityIsAlongFrameZ) {
  const HeadPoseTrack track({{0.0, Vec3(0, 0, 0)}, {1.0, Vec3(90, 0, 0)}, {2.0, Vec3(90, 40, 0), Interpolation::Step},
                             {3.0, Vec3(0, 0, -30)}},
                            "head pose");
  // Halfway from upright to face-down: 45° about the face frame's x.
  const Eigen::Quaterniond half = track.at(0.5);
  EXPECT_LT(half.angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()))), 1e-12);
  // Between two general poses: the geodesic midpoint (equal angles to both ends, half the arc).
  const Eigen::Quaterniond a = headPoseRotation(Vec3(90, 0, 0)), b = headPoseRotation(Vec3(90, 40, 0));
  const HeadPoseTrack ab({{0.0, Vec3(90, 0, 0)}, {1.0, Vec3(90, 40, 0)}}, "ab");
  EXPECT_NEAR(ab.at(0.5).angularDistance(a), 0.5 * a.angularDistance(b), 1e-12);
  EXPECT_NEAR(ab.at(0.5).angularDistance(b), 0.5 * a.angularDistance(b), 1e-12);
  EXPECT_NEAR(a.angularDistance(b), 40.0 * M_PI / 180.0, 1e-12);  // yaw after pitch: 40° apart
  // Keys hold outside the track; step holds its key's pose.
  EXPECT_LT(track.at(-1.0).angularDistance(Eigen::Quaterniond::Identity()), 1e-15);
  EXPECT_LT(track.at(2.5).angularDistance(b), 1e-12);
  EXPECT_LT(track.at(9.0).angularDistance(headPoseRotation(Vec3(0, 0, -30))), 1e-12);
  EXPECT_LT(HeadPoseTrack().at(1.0).angularDistance(Eigen::Quaterniond::Identity()), 1e-15);

  // Gravity: face-down (+90° pitch) points along the face frame's +z (a face frame turned about the
  // head's up axis, its y being the upright head's up), and the rotation form agrees with
  // gravityForPose for any frame.
  FaceFrame frame;
  frame.axes = Eigen::AngleAxisd(0.3, Vec3::UnitY()).toRotationMatrix();
  const Vec3 down = gravityForRotation(frame, track.at(1.0), 981.0);
  EXPECT_NEAR(down.dot(frame.axes.col(2)), 981.0, 1e-9);
  FaceFrame tilted;
  tilted.axes = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (const Vec3& p : {Vec3(90, 0, 0), Vec3(45, 0, 0), Vec3(20, -35, 60)})
    EXPECT_NEAR((gravityForRotation(tilted, headPoseRotation(p), 981.0) - gravityForPose(tilted, p, 981.0)).norm(), 0.0,
                1e-9);
  EXPECT_NEAR((gravityForRotation(tilted, half, 981.0) - gravityForPose(tilted, Vec3(45, 0, 0), 981.0)).norm(), 0.0, 1e-9);
  // Upright is the rest gravity, exactly.
  EXPECT_TRUE(gravityForRotation(FaceFrame{}, Eigen::Quaterniond::Identity(), 981.0) == Vec3(0, -981.0, 0));
}

}  // namespace
}  // namespace myo
