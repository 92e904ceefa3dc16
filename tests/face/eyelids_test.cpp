// The eyelids (anatomy/eyelids.h, docs/eyelids.md): on ICT a blink by orbicularis_oculi_palpebral at
// a = 1 closes the eye (lid gap < 1 mm, no vertex inside the eyeball proxy) and is compared with
// ICT's eyeBlink_L, the levator with eyeWide_L; the closure grows with the activation; a sweep of
// the eye's muscles never leaves skin inside an eyeball; the right eye mirrors the left; the lids
// move with the head (moved, turned, rescaled); the zero pose leaves the skin bit for bit; a
// closed-eyed head is refused by name. The ICT tests skip when ../shared/data is absent. Figures are
// recorded as test properties (`test_face --gtest_filter='Eyelids*' --gtest_output=json`).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anatomy/eyelids.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/shape_metric.h"
#include "myoshell/head/head.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/muscle_library_file.h"
#include "myoshell/io/rig_file.h"
#include "myoshell/muscles/muscle_def.h"
#include "support/basis_cache.h"
#include "support/ict.h"
#include "support/lid_poses.h"
#include "support/test_data.h"

namespace myo {
namespace {

using test::ictHead;
using test::ictRig;


// The deepest an orbit vertex lies inside its eyeball proxy's contact sphere (cm; ≤ 0 outside).
double deepestInside(const LidRig& rig, const MatX3& P) { return test::deepestInsideEyeball(rig, P); }

// The whole face (40 muscles) on ICT without gravity, one model for every test of the suite.
class EyelidsIct : public test::WholeFaceSuite<test::ictHead> {
 protected:
  void SetUp() override {
    MYO_REQUIRE_SHARED_DATA();
    build();
  }
};

TEST_F(EyelidsIct, AFullPalpebralClosesTheEyeOverTheEyeballAndMatchesEyeBlink) {
  ASSERT_NE(face_->lidRig(), nullptr);
  ContactReport contact;
  const MatX3 P = pose({{"orbicularis_oculi_palpebral_left", 1.0}}, &contact);
  const double gap = lidGap(lids(), 1, P), restGap = lidGap(lids(), 1, rest());
  const ShapeComparison c = compareShapes(P - rest(), ictRig().delta("eyeBlink_L"), rest());
  RecordProperty("gap_rest_mm", std::to_string(10 * restGap));
  RecordProperty("gap_mm", std::to_string(10 * gap));
  RecordProperty("penetration_before_mm", std::to_string(10 * contact.maxPenetrationBefore));
  RecordProperty("eyeBlink_L_cosine", std::to_string(c.cosine));
  RecordProperty("eyeBlink_L_ratio", std::to_string(c.magnitudeRatio));
  EXPECT_GT(restGap, 0.5);                                    // the eye is open at rest (~8 mm)
  EXPECT_LT(gap, 0.1);                                        // and the lids meet
  EXPECT_NEAR(lidGap(lids(), 0, P), lidGap(lids(), 0, rest()), 0.01);  // the other eye stays open
  EXPECT_LE(deepestInside(lids(), P), 1e-12);                 // no vertex inside an eyeball
  EXPECT_LE(contact.maxPenetrationAfter, 1e-12);
  EXPECT_GE(c.cosine, 0.8);
  EXPECT_GE(c.magnitudeRatio, 0.8);
  EXPECT_LE(c.magnitudeRatio, 1.25);
}

TEST_F(EyelidsIct, TheLevatorWidensTheEyeAsEyeWide) {
  const MatX3 P = pose({{"levator_palpebrae_superioris_left", 1.0}});
  const ShapeComparison c = compareShapes(P - rest(), ictRig().delta("eyeWide_L"), rest());
  RecordProperty("eyeWide_L_cosine", std::to_string(c.cosine));
  RecordProperty("eyeWide_L_ratio", std::to_string(c.magnitudeRatio));
  RecordProperty("gap_mm", std::to_string(10 * lidGap(lids(), 1, P)));
  EXPECT_GT(lidGap(lids(), 1, P), lidGap(lids(), 1, rest()) + 0.1);  // at least a millimetre wider
  EXPECT_GE(c.cosine, 0.8);
  // The lid's turn raises the lid and the muscle's pull adds to it: 1.18 at a shortening of 14.4 %,
  // 1.29 at 20 % (docs/eyelids.md); held to the band issue 14 sets a muscle against its artist shape.
  EXPECT_GE(c.magnitudeRatio, 0.8);
  EXPECT_LE(c.magnitudeRatio, 1.33);
}

TEST_F(EyelidsIct, TheGapShrinksSteadilyWithTheActivation) {
  double previous = lidGap(lids(), 1, rest());
  for (double a : {0.25, 0.5, 0.75, 1.0}) {
    const double gap = lidGap(lids(), 1, pose({{"orbicularis_oculi_palpebral_left", a}}));
    EXPECT_LT(gap, previous) << "a = " << a;
    previous = gap;
  }
  // Closing wins over raising: a full blink with the levator on still closes the eye.
  EXPECT_LT(lidGap(lids(), 1, pose({{"orbicularis_oculi_palpebral_left", 1.0}, {"levator_palpebrae_superioris_left", 1.0}})),
            0.1);
}

TEST_F(EyelidsIct, NoSweepOfTheEyesMusclesLeavesSkinInsideAnEyeball) {
  double before = 0.0;
  for (const auto& acts : test::eyeMuscleSweep()) {
    ContactReport contact;
    const MatX3 P = pose(acts, &contact);
    before = std::max(before, contact.maxPenetrationBefore);
    EXPECT_LE(deepestInside(lids(), P), 1e-12) << acts[0].second << " " << acts[2].second << " " << acts[4].second;
  }
  RecordProperty("largest_penetration_before_projection_mm", std::to_string(10 * before));
}

TEST_F(EyelidsIct, TheRightEyesBlinkMirrorsTheLefts) {
  // ICT is mirror-symmetric about x = 0: vertex i's mirror is the vertex at (−x, y, z).
  const MatX3& V = rest();
  const test::MirrorMap mirror = test::mirrorMap(V);
  ASSERT_LT(mirror.worstDistance, 1e-2);  // every vertex has a mirror image within 0.1 mm
  const MatX3 uL = pose({{"orbicularis_oculi_palpebral_left", 1.0}}) - V;
  const MatX3 uR = pose({{"orbicularis_oculi_palpebral_right", 1.0}}) - V;
  const double worst = test::mirrorMismatch(mirror, uL, uR);
  const double peak = uL.rowwise().norm().maxCoeff();
  RecordProperty("mirror_mismatch", std::to_string(worst / peak));
  EXPECT_LT(worst, 0.05 * peak);
}

TEST(EyelidsOnIct, TheLidsMoveWithTheHead) {
  MYO_REQUIRE_SHARED_DATA();
  const Head head = ictHead();
  const double s = 2.5;  // cm → a head 2.5 times larger (or inch-like units)
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(0.3, 1.0, -0.2).normalized()).toRotationMatrix();
  const Vec3 t(4.0, -7.0, 1.5);
  TriMesh moved = head.mesh;
  for (Eigen::Index i = 0; i < moved.V.rows(); ++i) moved.V.row(i) = (s * R * head.mesh.V.row(i).transpose() + t).transpose();
  const LidRig a = lidRig(head.mesh, head.landmarks), b = lidRig(moved, head.landmarks);
  LidPose p;
  p.close = {0.3, 0.8};
  p.raise = {0.6, 0.2};
  MatX3 Pa = head.mesh.V, Pb = moved.V;
  applyLids(a, p, Pa);
  applyLids(b, p, Pb);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < Pa.rows(); ++i)
    worst = std::max(worst, (s * R * Pa.row(i).transpose() + t - Pb.row(i).transpose()).norm());
  EXPECT_LT(worst, 1e-9 * s * 30.0);
  for (size_t e = 0; e < 2; ++e) {
    EXPECT_EQ(a.eyes[e].lidVertices, b.eyes[e].lidVertices);
    EXPECT_NEAR(b.eyes[e].radius, s * a.eyes[e].radius, 1e-12);
  }
}

TEST(EyelidsOnIct, AZeroPoseLeavesTheSkinBitForBitAndTheEyeballsSitBehindTheLids) {
  MYO_REQUIRE_SHARED_DATA();
  const Head head = ictHead();
  const LidRig rig = lidRig(head.mesh, head.landmarks);
  MatX3 P = head.mesh.V;
  const ContactReport c = applyLids(rig, LidPose{}, P);
  EXPECT_EQ(c.projected, 0);
  EXPECT_TRUE((P.array() == head.mesh.V.array()).all());
  const FaceFrame f = head.frame();
  for (const EyeLids& e : rig.eyes) {
    // An adult eyeball is ~2.4 cm across; its centre lies between the eye's corners, behind the lids.
    EXPECT_NEAR(2.0 * e.radius, 2.4, 0.3) << e.side;
    EXPECT_LE(e.contactRadius, e.radius);
    EXPECT_GT(e.contactRadius, 0.6 * e.radius);
    const Vec3 q = f.toFrame(e.centre);
    EXPECT_GT(std::abs(q.x()), 0.2) << e.side;
    EXPECT_LT(std::abs(q.x()), 0.5) << e.side;
    const Vec3 lid = f.toFrame(Vec3(head.mesh.V.row(e.gapPairs[0][0]).transpose()));
    EXPECT_GT(lid.z() - q.z(), 0.05) << e.side;  // the lids lie in front of the centre
    EXPECT_GT(e.lidVertices.size(), 100u);
    EXPECT_GT(e.upperMargin.size(), 4u);
    EXPECT_GT(e.lowerMargin.size(), 4u);
  }
  EXPECT_LT(rig.eyes[0].centre.x(), 0.0);  // eyes[0] is the subject's right (−x)
}

// A closure slides both lids towards the inner canthus over the globe (LidSettings::nasalSlide, ~2 mm
// at the margin): the mid-lid landmarks of each eye move towards its inner corner by about s, the
// upper and lower ones alike (so they still meet one above the other); with s = 0 they do not.
TEST(EyelidsOnIct, AClosureSlidesBothLidsTowardsTheNose) {
  MYO_REQUIRE_SHARED_DATA();
  const Head head = ictHead();
  LidSettings still;
  still.nasalSlide = 0.0;
  const LidRig slid = lidRig(head.mesh, head.landmarks), unslid = lidRig(head.mesh, head.landmarks, still);
  LidPose p;
  p.close = {1.0, 1.0};
  MatX3 P = head.mesh.V, Q = head.mesh.V;
  turnLids(slid, p, P);
  turnLids(unslid, p, Q);
  const double expected = LidSettings{}.nasalSlide * head.frame().scale;  // cm
  const std::array<std::array<int, 5>, 2> eyes = {{{39, 38, 37, 40, 41}, {42, 43, 44, 47, 46}}};  // inner corner, mid-lid points
  for (size_t e = 0; e < 2; ++e) {
    const Vec3 inner = head.mesh.V.row(head.landmarks.multipie68[static_cast<size_t>(eyes[e][0])]).transpose();
    const Vec3 centre = slid.eyes[e].centre;
    const Vec3 nasal = (slid.eyes[e].axis * slid.eyes[e].axis.dot(inner - centre)).normalized();
    for (size_t k = 1; k < 5; ++k) {
      const int v = head.landmarks.multipie68[static_cast<size_t>(eyes[e][k])];
      const double towards = (P.row(v) - head.mesh.V.row(v)).dot(nasal.transpose());
      const double without = (Q.row(v) - head.mesh.V.row(v)).dot(nasal.transpose());
      RecordProperty(slid.eyes[e].side + "_landmark_" + std::to_string(eyes[e][k]) + "_nasal_mm", std::to_string(10 * towards));
      EXPECT_GT(towards, 0.5 * expected) << slid.eyes[e].side << " landmark " << eyes[e][k];
      EXPECT_LT(towards, 1.5 * expected) << slid.eyes[e].side << " landmark " << eyes[e][k];
      EXPECT_LT(std::abs(without), 0.3 * expected) << slid.eyes[e].side << " landmark " << eyes[e][k];
    }
  }
}

TEST(Eyelids, AClosedEyedHeadHasNoLidsAndIsRefusedByName) {
  const Head head = loadDefaultHead(defaultHeadOptions(FaceModelKind::Thesis));  // the thesis model's: eyes closed
  EXPECT_FALSE(hasOpenEyes(head.mesh, head.landmarks));
  try {
    lidRig(head.mesh, head.landmarks);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the eyelids need open eyes (an opening in the mesh between each eye's "
                                         "corner landmarks); this head's eyes are closed"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace myo
