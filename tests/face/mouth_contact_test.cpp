// The lips' contact (anatomy/mouth_contact.h, docs/mouth_contact.md): on ICT a sweep of the jaw (0–30°)
// with every mouth muscle alone and all together at a = 1 leaves no lip vertex inside the teeth
// proxies or the other lip after projection; the rest and the jaw's rigid motion touch nothing; a
// lip pushed into the teeth lands on the arch; the projection moves with the head (moved, turned,
// rescaled). The ICT tests skip when ../shared/data is absent. Figures are recorded as test
// properties (`test_face --gtest_filter='MouthContact*' --gtest_output=json:F`).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anatomy/mouth_contact.h"
#include "myoshell/head/head.h"
#include "myoshell/head/jaw.h"
#include "myoshell/io/head_files.h"
#include "myoshell/muscles/muscle_def.h"
#include "support/basis_cache.h"
#include "support/lid_poses.h"
#include "support/ict.h"
#include "support/test_data.h"

namespace myo {
namespace {

using test::ictHead;
using test::ictRig;


bool isMouthMuscle(const std::string& name) {
  for (const char* part : {"oris", "zygomaticus", "risorius", "buccinator", "depressor_anguli", "depressor_labii",
                           "mentalis", "platysma", "levator_labii_superioris_left", "levator_labii_superioris_right"})
    if (name.find(part) != std::string::npos) return true;
  return false;
}

// A head with its jaw rig and its mouth's contact, as the face builds them.
struct HeadMouth {
  Head head;
  JawRig jaw;
  MouthContact mouth;
};
HeadMouth mouthOf(Head head) {
  JawRig jaw = jawRig(head.mesh, head.landmarks);
  MouthContact mouth = mouthContact(head.mesh, head.landmarks, jaw);
  return {std::move(head), std::move(jaw), std::move(mouth)};
}

class MouthContactIct : public test::WholeFaceSuite<test::ictHead> {
 protected:
  void SetUp() override {
    MYO_REQUIRE_SHARED_DATA();
    build();
  }
};

TEST_F(MouthContactIct, NoSweepOfTheJawAndTheMouthMusclesLeavesALipInTheTeethOrTheOtherLip) {
  const AnatomicalSkin& skin = face_->skin();
  ASSERT_NE(face_->mouthContact(), nullptr);
  std::vector<std::vector<int>> cases = {{}};  // at rest, each mouth muscle alone, then all of them
  std::vector<int> all;
  for (int m = 0; m < face_->muscleCount(); ++m)
    if (isMouthMuscle(face_->muscleName(m))) cases.push_back({m}), all.push_back(m);
  cases.push_back(all);
  ASSERT_GE(cases.size(), 20u);
  double before = 0.0, after = 0.0;
  int touched = 0;
  for (double open : {0.0, 10.0, 20.0, 30.0})
    for (const std::vector<int>& active : cases) {
      SkinLoads loads;
      loads.activations = VecX::Zero(face_->muscleCount());
      for (int m : active) loads.activations(m) = 1.0;
      loads.gravity = skin.restGravity();
      const SettledSkin s = skin.settle(loads, skin.settings().warping);
      ASSERT_TRUE(s.converged);
      JawPose jaw;
      jaw.openDeg = open;
      MatX3 P;
      const ContactReport r = face_->placeSkin(s.u, jaw, loads.activations, P);
      before = std::max(before, r.maxPenetrationBefore);
      after = std::max(after, r.maxPenetrationAfter);
      touched += r.projected > 0;
      EXPECT_LE(mouthPenetration(*face_->mouthContact(), *face_->jawRig(), jaw, P), 0.05)
          << open << "° with " << active.size() << " muscles";  // ≤ 0.5 mm: the bound
    }
  RecordProperty("largest_penetration_before_mm", std::to_string(10 * before));
  RecordProperty("largest_penetration_after_mm", std::to_string(10 * after));
  RecordProperty("poses_with_contact", std::to_string(touched) + " of " + std::to_string(4 * cases.size()));
  EXPECT_GT(before, 0.0);  // the sweep does press the lips into something
  EXPECT_LE(after, 0.05);
}

TEST(MouthContactOnIct, TheRestAndTheJawsRigidMotionTouchNothing) {
  MYO_REQUIRE_SHARED_DATA();
  const auto [head, jaw, mouth] = mouthOf(ictHead());
  RecordProperty("teeth_shrink", std::to_string(mouth.shrink));
  RecordProperty("lip_pairs", std::to_string(mouth.lipPairs.size()));
  EXPECT_GT(mouth.shrink, 0.9);  // the arch placed from the landmarks lies behind ICT's lips
  EXPECT_GT(mouth.lipPairs.size(), 50u);
  for (double open : {0.0, 15.0, 30.0}) {
    JawPose pose;
    pose.openDeg = open;
    MatX3 P = jawedRest(jaw, pose, head.mesh.V);
    const MatX3 before = P;
    const ContactReport r = applyMouthContact(mouth, jaw, pose, P);
    EXPECT_EQ(r.projected, 0) << open << "°";
    EXPECT_TRUE((P.array() == before.array()).all()) << open << "°";
  }
}

// The penalty's depth in the teeth proxies is continuous: it fades to 0 at each proxy's outer cap
// (the upper one's top, the lower one's bottom), so a vertex inside the arch crossing the cap drops
// no penalty at once; and its gradient is the depth's own, checked by central differences, in the
// fade and in the bulk, the lower proxy turned with the jaw. Cut off at the cap, the penalty's
// Newton stalled on the jump (ICT, the platysma at a = 1: docs/mouth_contact.md).
TEST(MouthContactOnIct, TheTeethDepthIsContinuousAtTheProxiesCapsAndItsGradientIsExact) {
  MYO_REQUIRE_SHARED_DATA();
  const auto [head, jaw, m] = mouthOf(ictHead());
  JawPose pose;
  pose.openDeg = 12.0;
  const RigidMotion mandible = jawMotion(jaw, pose, 1.0);
  const FaceFrame& f = m.frame;
  // A local point of the arch's frame at ellipse radius s, angle θ from the front, height y.
  auto at = [&](double s, double theta, double y, bool lower) {
    const Vec3 p = f.origin + f.axes * Vec3(s * m.a * std::sin(theta), y, m.zCentre + s * m.b * std::cos(theta));
    return lower ? mandible.apply(p) : p;
  };
  const double upperH = m.upperTop - m.yOcclusal, lowerH = m.yOcclusal - m.lowerBottom;
  for (bool lower : {false, true}) {
    const double cap = lower ? m.lowerBottom : m.upperTop, inward = lower ? 1.0 : -1.0;
    const double h = lower ? lowerH : upperH;
    // Continuity: just inside the cap the depth is nearly 0; just outside it is 0.
    const double justInside = teethPenetration(m, mandible, at(0.8, 0.3, cap + inward * 1e-7 * h, lower), nullptr);
    const double justOutside = teethPenetration(m, mandible, at(0.8, 0.3, cap - inward * 1e-7 * h, lower), nullptr);
    EXPECT_EQ(justOutside, 0.0) << (lower ? "lower" : "upper");
    EXPECT_LT(justInside, 1e-9) << (lower ? "lower" : "upper");
    // Deep inside (half the height) the depth is the arch's full radial depth.
    const double full = teethPenetration(m, mandible, at(0.8, 0.3, cap + inward * 0.5 * h, lower), nullptr);
    EXPECT_GT(full, 0.1) << "cm";
    for (double t : {0.02, 0.05, 0.08, 0.5}) {  // fractions of the height inside the cap: the fade, then the bulk
      const Vec3 p = at(0.8, 0.3, cap + inward * t * h, lower);
      Vec3 g;
      const double d = teethPenetration(m, mandible, p, &g);
      ASSERT_GT(d, 0.0) << t;
      for (int k = 0; k < 3; ++k) {
        const double e = 1e-6;
        Vec3 dp = Vec3::Zero();
        dp(k) = e;
        const double fd = (teethPenetration(m, mandible, p + dp, nullptr) - teethPenetration(m, mandible, p - dp, nullptr)) / (2 * e);
        EXPECT_NEAR(g(k), fd, 1e-6 * std::max(1.0, g.norm())) << (lower ? "lower" : "upper") << " t " << t << " k " << k;
      }
    }
  }
}

// With the jaw open the proxies part, and a vertex inside the arch leaves the upper proxy through
// its bottom (the occlusal plane) or the lower one through its top: the depth is the nearer of the
// radial depth and the height over that face, so it goes to 0 at the face instead of dropping the
// whole radial depth there, and its gradient (along the frame's y near the face) is exact. With
// the jaw at rest the proxies meet at the face: the depth is the radial one up to it. Measured
// radially alone, the lower lip's marginal band at 1 with the jaw at 10° stalled the penalty's
// Newton on the jump (docs/mouth_contact.md).
TEST(MouthContactOnIct, WithTheJawOpenTheTeethDepthIsContinuousThroughTheOcclusalFaces) {
  MYO_REQUIRE_SHARED_DATA();
  const auto [head, jaw, m] = mouthOf(ictHead());
  const FaceFrame& f = m.frame;
  auto at = [&](const RigidMotion& mandible, double s, double theta, double y, bool lower) {
    const Vec3 p = f.origin + f.axes * Vec3(s * m.a * std::sin(theta), y, m.zCentre + s * m.b * std::cos(theta));
    return lower ? mandible.apply(p) : p;
  };
  JawPose open;
  open.openDeg = 10.0;
  const RigidMotion turned = jawMotion(jaw, open, 1.0), atRest = jawMotion(jaw, JawPose{}, 1.0);
  const double h = m.upperTop - m.yOcclusal;
  for (bool lower : {false, true}) {
    const std::string which = lower ? "lower" : "upper";
    const double inward = lower ? -1.0 : 1.0;  // from the occlusal face into the proxy
    // Radially 0.8 of the arch's radius (about 2 mm deep at the front): just inside the face the
    // depth is nearly 0 with the jaw open, the radial depth with it at rest.
    const double radial = teethPenetration(m, turned, at(turned, 0.8, 0.3, m.yOcclusal + inward * 0.5 * h, lower), nullptr);
    ASSERT_GT(radial, 0.05) << which;
    const double justInside = teethPenetration(m, turned, at(turned, 0.8, 0.3, m.yOcclusal + inward * 1e-7 * h, lower), nullptr);
    EXPECT_LT(justInside, 1e-6) << which;
    EXPECT_GT(justInside, 0.0) << which;
    const double closed = teethPenetration(m, atRest, at(atRest, 0.8, 0.3, m.yOcclusal + inward * 1e-7 * h, lower), nullptr);
    EXPECT_NEAR(closed, radial, 1e-9) << which;
    // The gradient near the face (through the face) and farther in (radial), by central differences.
    for (double t : {0.01, 0.5}) {
      const Vec3 p = at(turned, 0.8, 0.3, m.yOcclusal + inward * t * h, lower);
      Vec3 g;
      const double d = teethPenetration(m, turned, p, &g);
      ASSERT_GT(d, 0.0) << which << " t " << t;
      if (t < 0.1) EXPECT_LT(d, 0.5 * radial) << which;
      for (int k = 0; k < 3; ++k) {
        const double e = 1e-6;
        Vec3 dp = Vec3::Zero();
        dp(k) = e;
        const double fd = (teethPenetration(m, turned, p + dp, nullptr) - teethPenetration(m, turned, p - dp, nullptr)) / (2 * e);
        EXPECT_NEAR(g(k), fd, 1e-6 * std::max(1.0, g.norm())) << which << " t " << t << " k " << k;
      }
    }
  }
}

// The lips pushed 3 mm straight back into the mouth, with the jaw at 12°.
MatX3 lipsPushedBack(const Head& head, const JawRig& jaw, const MouthContact& mouth, const JawPose& pose) {
  MatX3 u = MatX3::Zero(head.mesh.V.rows(), 3);
  // 3 mm on ICT: a fixed fraction of the face frame, so the same push on a rescaled head.
  for (int i : mouth.vertices) u.row(i) = -0.034 * head.frame().scale * head.frame().axes.col(2).transpose();
  MatX3 P;
  jawedPositions(jaw, pose, head.mesh.V, u, P);
  return P;
}

TEST(MouthContactOnIct, ALipPushedIntoTheTeethLandsOnTheArchAndMovesWithTheHead) {
  MYO_REQUIRE_SHARED_DATA();
  const auto [head, jaw, mouth] = mouthOf(ictHead());
  JawPose pose;
  pose.openDeg = 12.0;
  MatX3 P = lipsPushedBack(head, jaw, mouth, pose);
  const double deep = mouthPenetration(mouth, jaw, pose, P);
  const ContactReport r = applyMouthContact(mouth, jaw, pose, P);
  EXPECT_GT(deep, 0.05);
  EXPECT_NEAR(r.maxPenetrationBefore, deep, 1e-12);
  EXPECT_LT(r.maxPenetrationAfter, 1e-9);
  EXPECT_GT(r.projected, 10);

  // The same on the head moved, turned and rescaled: the projected positions move with it.
  const double s = 1.7;
  const Mat3 R = Eigen::AngleAxisd(-0.5, Vec3(1.0, 0.4, 0.2).normalized()).toRotationMatrix();
  const Vec3 t(-3.0, 2.0, 5.0);
  Head moved = head;
  for (Eigen::Index i = 0; i < moved.mesh.V.rows(); ++i)
    moved.mesh.V.row(i) = (s * R * head.mesh.V.row(i).transpose() + t).transpose();
  const auto [head2, jaw2, mouth2] = mouthOf(moved);
  JawPose pose2 = pose;
  MatX3 Q = lipsPushedBack(head2, jaw2, mouth2, pose2);
  applyMouthContact(mouth2, jaw2, pose2, Q);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    worst = std::max(worst, (s * R * P.row(i).transpose() + t - Q.row(i).transpose()).norm());
  EXPECT_LT(worst, 1e-8 * s * 30.0);
  EXPECT_EQ(mouth.vertices, mouth2.vertices);
  EXPECT_EQ(mouth.lipPairs, mouth2.lipPairs);
}

}  // namespace
}  // namespace myo
