// The built-in head's open eyes (issue 17; docs/heads.md, docs/eyelids.md): the canonical mesh's lid
// margins run corner to corner and the triangles removed are exactly those over each fissure; each
// eye stays a single boundary loop through the subdivision; the anatomical model's head has open eyes
// and lids while the thesis model's is the closed-eyed head bit for bit; on the open head the whole
// face's orbicularis_oculi_palpebral at a = 1 closes the eye (lid gap < 1 mm, no vertex inside the
// eyeball proxy) and the right blink mirrors the left. Figures are recorded as test properties
// (`test_face --gtest_filter='*DefaultHead*Eye*:EyelidsDefaultHead*' --gtest_output=json`).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anatomy/eyelids.h"
#include "myoshell/fit/activation_fit.h"
#include "myoshell/head/face_system.h"
#include "myoshell/head/head.h"
#include "myoshell/head/jaw.h"
#include "myoshell/head/mediapipe_mesh.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/subdivision.h"
#include "myoshell/muscles/muscle_def.h"
#include "support/basis_cache.h"
#include "support/lid_poses.h"

namespace myo {
namespace {

struct EyeLines {
  const std::array<int, 9>& upper;
  const std::array<int, 9>& lower;
  const char* outer;  // the landmark names of the line's ends
  const char* inner;
};
const std::array<EyeLines, 2> kEyeLines = {{{kMediapipeRightEyeUpper, kMediapipeRightEyeLower, "right_eye_outer", "right_eye_inner"},
                                            {kMediapipeLeftEyeUpper, kMediapipeLeftEyeLower, "left_eye_outer", "left_eye_inner"}}};

bool hasEdge(const MatX3i& F, int a, int b) {
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      if ((F(t, k) == a && F(t, (k + 1) % 3) == b) || (F(t, k) == b && F(t, (k + 1) % 3) == a)) return true;
  return false;
}

// Area (cm²) of triangle t of F projected on the xy plane (the face looks along +z).
double projectedArea(const MatX3& V, const Eigen::RowVector3i& t) {
  const Eigen::Vector2d a = V.row(t(0)).head<2>(), b = V.row(t(1)).head<2>(), c = V.row(t(2)).head<2>();
  const Eigen::Vector2d ab = b - a, ac = c - a;
  return 0.5 * std::abs(ab.x() * ac.y() - ab.y() * ac.x());
}

// Area (cm², xy plane) enclosed by the upper line and the lower line run back (shoelace).
double fissureArea(const MatX3& V, const EyeLines& e) {
  std::vector<int> ring(e.upper.begin(), e.upper.end());
  for (size_t k = e.lower.size() - 2; k >= 1; --k) ring.push_back(e.lower[k]);
  double twice = 0.0;
  for (size_t k = 0; k < ring.size(); ++k) {
    const int i = ring[k], j = ring[(k + 1) % ring.size()];
    twice += V(i, 0) * V(j, 1) - V(j, 0) * V(i, 1);
  }
  return 0.5 * std::abs(twice);
}

// FNV-1a over the bytes of the positions and the triangles: a change of one bit changes it.
std::uint64_t meshHash(const TriMesh& m) {
  std::uint64_t h = 1469598103934665603ull;
  auto feed = [&](const void* p, size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  for (Eigen::Index i = 0; i < m.V.rows(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double x = m.V(i, k);
      feed(&x, sizeof x);
    }
  for (Eigen::Index t = 0; t < m.F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = m.F(t, k);
      feed(&v, sizeof v);
    }
  return h;
}

TEST(DefaultHeadEyes, TheLidLinesRunCornerToCornerAndOnlyTheFissureIsRemoved) {
  const TriMesh src = defaultHeadSourceMesh();
  DefaultHeadOptions level0;
  level0.subdivisionLevels = 0;
  level0.openEyes = false;
  const Head closed = loadDefaultHead(level0);  // 880 triangles: mouth open, eyes closed
  for (const EyeLines& e : kEyeLines) {
    // Both lines run from the outer corner landmark to the inner one along edges of the mesh.
    EXPECT_EQ(e.upper.front(), closed.landmarks.vertex(e.outer));
    EXPECT_EQ(e.lower.front(), closed.landmarks.vertex(e.outer));
    EXPECT_EQ(e.upper.back(), closed.landmarks.vertex(e.inner));
    EXPECT_EQ(e.lower.back(), closed.landmarks.vertex(e.inner));
    for (size_t k = 1; k < e.upper.size(); ++k) {
      EXPECT_TRUE(hasEdge(src.F, e.upper[k - 1], e.upper[k])) << e.upper[k - 1] << "-" << e.upper[k];
      EXPECT_TRUE(hasEdge(src.F, e.lower[k - 1], e.lower[k])) << e.lower[k - 1] << "-" << e.lower[k];
    }
    // The lines do not coincide: the upper lies above the lower between the corners, the fissure
    // 6.8 mm high at its middle (159/145, 386/374).
    for (size_t k = 1; k + 1 < e.upper.size(); ++k) EXPECT_GT(src.V(e.upper[k], 1), src.V(e.lower[k], 1) + 0.15) << k;
    EXPECT_NEAR(src.V(e.upper[4], 1) - src.V(e.lower[4], 1), 0.67, 0.01);
  }
  // The left eye's lines mirror the right's (x → −x).
  for (size_t k = 0; k < 9; ++k) {
    EXPECT_LT((src.V.row(kMediapipeLeftEyeUpper[k]) - src.V.row(kMediapipeRightEyeUpper[k]).cwiseProduct(Eigen::RowVector3d(-1, 1, 1))).norm(), 1e-5);
    EXPECT_LT((src.V.row(kMediapipeLeftEyeLower[k]) - src.V.row(kMediapipeRightEyeLower[k]).cwiseProduct(Eigen::RowVector3d(-1, 1, 1))).norm(), 1e-5);
  }

  TriMesh open = closed.mesh;
  EXPECT_EQ(openMediapipeEyes(open), 28);  // 14 over each fissure: a strip between two 9-point lines
  EXPECT_EQ(open.triangleCount(), 880 - 28);
  // Exactly the fissure: the removed triangles tile the region between the lines (their areas in
  // the face's plane add up to it, so none is missing, none lies outside and none overlaps).
  std::set<std::array<int, 3>> kept;
  for (Eigen::Index t = 0; t < open.F.rows(); ++t) kept.insert({open.F(t, 0), open.F(t, 1), open.F(t, 2)});
  double removedArea = 0.0, fissure = 0.0;
  for (Eigen::Index t = 0; t < closed.mesh.F.rows(); ++t)
    if (!kept.count({closed.mesh.F(t, 0), closed.mesh.F(t, 1), closed.mesh.F(t, 2)}))
      removedArea += projectedArea(closed.mesh.V, closed.mesh.F.row(t));
  for (const EyeLines& e : kEyeLines) fissure += fissureArea(closed.mesh.V, e);
  RecordProperty("fissure_area_cm2", std::to_string(fissure));
  EXPECT_GT(fissure, 2.0);  // two eyes, each ~2.5 cm wide and up to 0.68 cm high
  EXPECT_NEAR(removedArea, fissure, 1e-9 * fissure);

  // Each eye is one boundary loop made of both its lines.
  const auto loops = boundaryLoops(open.F, open.vertexCount());
  ASSERT_EQ(loops.size(), 4u);  // rim, mouth, two eyes
  for (const EyeLines& e : kEyeLines) {
    std::set<int> lines(e.upper.begin(), e.upper.end());
    lines.insert(e.lower.begin(), e.lower.end());
    int found = 0;
    for (const auto& loop : loops)
      if (std::set<int>(loop.begin(), loop.end()) == lines) {
        ++found;
        EXPECT_EQ(loop.size(), 16u);
      }
    EXPECT_EQ(found, 1) << e.outer;
  }
}

TEST(DefaultHeadEyes, TheAnatomicalHeadHasOpenEyesThroughTheSubdivision) {
  const Head head = loadDefaultHead(defaultHeadOptions(FaceModelKind::Anatomical));
  const TriMesh& m = head.mesh;
  // 468 + 1,322 edges → 1,790; + 5,200 edges → 6,990 vertices; (880 − 28)·16 triangles.
  EXPECT_EQ(m.vertexCount(), 6990);
  EXPECT_EQ(m.triangleCount(), (880 - 28) * 16);
  const EdgeTable table = buildEdgeTable(m.F, m.vertexCount());
  EXPECT_EQ(table.nonManifoldCount, 0);
  EXPECT_EQ(table.inconsistentOrientationCount, 0);
  const auto loops = boundaryLoops(m.F, m.vertexCount());
  ASSERT_EQ(loops.size(), 4u);
  EXPECT_EQ(loops[0].size(), 144u);  // rim
  EXPECT_EQ(loops[1].size(), 80u);   // mouth
  // Each eye one loop of 16·4 edges through both corners and the four mid-lid landmarks.
  for (int eye = 0; eye < 2; ++eye) {
    const EyeLines& e = kEyeLines[static_cast<size_t>(eye)];
    int found = 0;
    for (const auto& loop : loops) {
      const std::set<int> s(loop.begin(), loop.end());
      if (!s.count(head.landmarks.vertex(e.outer))) continue;
      ++found;
      EXPECT_EQ(loop.size(), 64u);
      EXPECT_TRUE(s.count(head.landmarks.vertex(e.inner)));
      for (int k : eye == 0 ? std::array<int, 4>{37, 38, 40, 41} : std::array<int, 4>{43, 44, 46, 47})
        EXPECT_TRUE(s.count(head.landmarks.multipie68[static_cast<size_t>(k)])) << k;
    }
    EXPECT_EQ(found, 1) << e.outer;
  }
  EXPECT_TRUE(hasOpenEyes(m, head.landmarks));
  // The eye corners turn by more than 60°, so the crease keeps them where MediaPipe put them.
  const TriMesh src = defaultHeadSourceMesh();
  for (int v : {33, 133, 263, 362}) EXPECT_TRUE((m.V.row(v).array() == src.V.row(v).array()).all()) << v;
  // The rim stays the pinned loop; the eyes are not pinned (they are held by the tissue).
  const std::set<int> pins(head.gravityPins.begin(), head.gravityPins.end());
  EXPECT_EQ(head.gravityPins.size(), 146u);
  for (size_t l = 2; l < 4; ++l)
    for (int v : loops[l]) EXPECT_FALSE(pins.count(v)) << "eye vertex " << v << " pinned";
}

TEST(DefaultHeadEyes, TheThesisHeadIsTheClosedEyedHeadBitForBit) {
  EXPECT_FALSE(defaultHeadOptions(FaceModelKind::Thesis).openEyes);
  EXPECT_TRUE(defaultHeadOptions(FaceModelKind::Anatomical).openEyes);
  const Head head = loadDefaultHead(defaultHeadOptions(FaceModelKind::Thesis));
  EXPECT_EQ(head.mesh.vertexCount(), 7152);
  EXPECT_EQ(head.mesh.triangleCount(), 14080);
  EXPECT_EQ(boundaryLoops(head.mesh.F, head.mesh.vertexCount()).size(), 2u);
  EXPECT_FALSE(hasOpenEyes(head.mesh, head.landmarks));
  // The hash of the head before the eyes could open (main at cf13c6a, the same function).
  EXPECT_EQ(meshHash(head.mesh), 15569963369344556336ull);
  // A scene reads each model's own built-in head.
  SceneDesc scene;
  scene.modelKind = FaceModelKind::Thesis;
  EXPECT_EQ(meshHash(readSceneInputs(scene).head.mesh), meshHash(head.mesh));
  scene.modelKind = FaceModelKind::Anatomical;
  EXPECT_EQ(readSceneInputs(scene).head.mesh.vertexCount(), 6990);
}

// The anatomical model's built-in head (eyes open).
Head anatomicalDefaultHead() { return loadDefaultHead(defaultHeadOptions(FaceModelKind::Anatomical)); }

// The whole face (40 muscles) on the built-in head without gravity, one model for the suite.
class EyelidsDefaultHead : public test::WholeFaceSuite<anatomicalDefaultHead> {
 protected:
  void SetUp() override { build(); }
  static double deepestInside(const MatX3& P) { return test::deepestInsideEyeball(lids(), P); }
};

TEST_F(EyelidsDefaultHead, TheEyeballsSitBehindTheLids) {
  ASSERT_NE(face_->lidRig(), nullptr);
  const FaceFrame f = face_->head().frame();
  for (const EyeLids& e : lids().eyes) {
    RecordProperty(e.side + "_contact_radius_cm", std::to_string(e.contactRadius));
    RecordProperty(e.side + "_lid_vertices", std::to_string(e.lidVertices.size()));
    EXPECT_NEAR(2.0 * e.radius, 2.4, 0.3) << e.side;  // an adult eyeball is ~2.4 cm across
    EXPECT_GT(e.contactRadius, 0.6 * e.radius) << e.side;
    const Vec3 q = f.toFrame(e.centre);
    EXPECT_GT(std::abs(q.x()), 0.2) << e.side;  // between the eye's corners
    EXPECT_LT(std::abs(q.x()), 0.5) << e.side;
    const Vec3 lid = f.toFrame(Vec3(rest().row(e.gapPairs[0][0]).transpose()));
    EXPECT_GT(lid.z() - q.z(), 0.05) << e.side;  // the lids in front of the centre
    EXPECT_GT(e.lidVertices.size(), 100u);
  }
  // At rest the eye is open by about the canonical mesh's fissure (the mid-lid pairs 160/144,
  // 158/153: 5.8 and 6.5 mm before the subdivision).
  for (int eye = 0; eye < 2; ++eye) {
    const double gap = lidGap(lids(), eye, rest());
    RecordProperty(std::string(eye == 0 ? "right" : "left") + "_gap_rest_mm", std::to_string(10 * gap));
    EXPECT_GT(gap, 0.4);
    EXPECT_LT(gap, 0.8);
  }
  EXPECT_DOUBLE_EQ(lidGap(lids(), 0, rest()), lidGap(lids(), 1, rest()));
}

TEST_F(EyelidsDefaultHead, AFullPalpebralClosesTheEyeOverTheEyeball) {
  ContactReport contact;
  const MatX3 P = pose({{"orbicularis_oculi_palpebral_left", 1.0}}, &contact);
  const double gap = lidGap(lids(), 1, P), restGap = lidGap(lids(), 1, rest());
  RecordProperty("gap_rest_mm", std::to_string(10 * restGap));
  RecordProperty("gap_mm", std::to_string(10 * gap));
  RecordProperty("penetration_before_mm", std::to_string(10 * contact.maxPenetrationBefore));
  EXPECT_LT(gap, 0.1);                                                 // the lids meet (< 1 mm)
  EXPECT_NEAR(lidGap(lids(), 0, P), lidGap(lids(), 0, rest()), 0.01);  // the other eye stays open
  EXPECT_LE(deepestInside(P), 1e-12);                                  // no vertex inside an eyeball
  EXPECT_LE(contact.maxPenetrationAfter, 1e-12);
  // The upper lid does most of the closing (the turn gives it 90 % of the fissure; the lower lid
  // also rises with the palpebral ring's own pull): its mid-lid landmark travels down farther than
  // the lower one travels up.
  const int upper = lids().eyes[1].gapPairs[1][0], lower = lids().eyes[1].gapPairs[1][1];
  const double down = rest()(upper, 1) - P(upper, 1), up = P(lower, 1) - rest()(lower, 1);
  RecordProperty("upper_lid_down_mm", std::to_string(10 * down));
  RecordProperty("lower_lid_up_mm", std::to_string(10 * up));
  EXPECT_GT(down, 0.5 * restGap);
  EXPECT_GT(up, 0.0);
  EXPECT_GT(down, 1.5 * up);
}

TEST_F(EyelidsDefaultHead, TheGapShrinksSteadilyWithTheActivation) {
  double previous = lidGap(lids(), 1, rest());
  for (double a : {0.25, 0.5, 0.75, 1.0}) {
    const double gap = lidGap(lids(), 1, pose({{"orbicularis_oculi_palpebral_left", a}}));
    EXPECT_LT(gap, previous) << "a = " << a;
    previous = gap;
  }
  // The levator opens the eye wider; a full blink with it on still closes the eye.
  EXPECT_GT(lidGap(lids(), 1, pose({{"levator_palpebrae_superioris_left", 1.0}})), lidGap(lids(), 1, rest()) + 0.05);
  EXPECT_LT(lidGap(lids(), 1, pose({{"orbicularis_oculi_palpebral_left", 1.0}, {"levator_palpebrae_superioris_left", 1.0}})),
            0.1);
}

TEST_F(EyelidsDefaultHead, NoSweepOfTheEyesMusclesLeavesSkinInsideAnEyeball) {
  double before = 0.0;
  for (const auto& acts : test::eyeMuscleSweep()) {
    ContactReport contact;
    const MatX3 P = pose(acts, &contact);
    before = std::max(before, contact.maxPenetrationBefore);
    EXPECT_LE(deepestInside(P), 1e-12) << acts[0].second << " " << acts[2].second << " " << acts[4].second;
  }
  RecordProperty("largest_penetration_before_projection_mm", std::to_string(10 * before));
}

TEST_F(EyelidsDefaultHead, TheRightEyesBlinkMirrorsTheLefts) {
  // The built-in head is mirror-symmetric about x = 0: vertex i's mirror is the vertex at (−x, y, z).
  const MatX3& V = rest();
  const test::MirrorMap mirror = test::mirrorMap(V);
  ASSERT_LT(mirror.worstDistance, 1e-4);  // within 1 µm
  const MatX3 uL = pose({{"orbicularis_oculi_palpebral_left", 1.0}}) - V;
  const MatX3 uR = pose({{"orbicularis_oculi_palpebral_right", 1.0}}) - V;
  const double worst = test::mirrorMismatch(mirror, uL, uR);
  const double peak = uL.rowwise().norm().maxCoeff();
  RecordProperty("peak_mm", std::to_string(10 * peak));
  RecordProperty("mirror_mismatch", std::to_string(worst / peak));
  EXPECT_GT(peak, 0.3);  // the blink moves the lid by millimetres
  EXPECT_LT(worst, 0.05 * peak);
}

// A full blink leaves the skin round the eye whole: no edge of the orbit is torn open. The canthal
// tendons hold the lids' ends, so the nasal slide fades to nothing at the canthi; sliding up to them
// stretched edges beside both canthi to 3.3 times their length (a dark crack in the viewer's
// blink); with the fade the worst is 2.6, on the few sub-millimetre edges at the inner canthus.
TEST_F(EyelidsDefaultHead, ABlinkTearsNoSkinAtTheCanthi) {
  const MatX3& V = rest();
  const MatX3 P = pose({{"orbicularis_oculi_palpebral_left", 1.0}, {"orbicularis_oculi_palpebral_right", 1.0}});
  const MatX3i& F = face_->head().mesh.F;
  for (const EyeLids& eye : lids().eyes) {
    const std::set<int> orbit(eye.orbitVertices.begin(), eye.orbitVertices.end());
    double worst = 0.0;
    int edges = 0;
    for (Eigen::Index t = 0; t < F.rows(); ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = F(t, k), b = F(t, (k + 1) % 3);
        if (!orbit.count(a) || !orbit.count(b)) continue;
        const double rest = (V.row(a) - V.row(b)).norm(), now = (P.row(a) - P.row(b)).norm();
        worst = std::max(worst, now / rest);
        ++edges;
      }
    RecordProperty(eye.side + "_worst_stretch", std::to_string(worst));
    EXPECT_GT(edges, 600) << eye.side;
    EXPECT_LT(worst, 3.0) << eye.side << ": an edge of the orbit tore open";
  }
}

// The lids follow the gaze (EyeGaze; docs/eyelids.md, "The lids follow the gaze"): the rest placed
// with one eye turned 25° by the placement every path uses.
MatX3 gazed(const AnatomicalFace& face, int eye, double pitchDeg, double yawDeg) {
  EyeGaze gaze;
  gaze.pitchDeg[static_cast<size_t>(eye)] = pitchDeg;
  gaze.yawDeg[static_cast<size_t>(eye)] = yawDeg;
  MatX3 out;
  const MatX3 u = MatX3::Zero(face.head().mesh.vertexCount(), 3);
  face.skin().placement().place(u, JawPose{}, VecX::Zero(face.muscleCount()), out, true, gaze);
  return out;
}

TEST_F(EyelidsDefaultHead, TheLidsFollowTheGazeUpDownAndSideways) {
  const MatX3& V = rest();
  const int upper = lids().eyes[1].gapPairs[0][0], lower = lids().eyes[1].gapPairs[0][1];  // the left eye's mid-lid pair
  const MatX3 up = gazed(*face_, 1, 25.0, 0.0), down = gazed(*face_, 1, -25.0, 0.0), out = gazed(*face_, 1, 0.0, 25.0);
  RecordProperty("up_upper_lid_mm", std::to_string(10 * (up(upper, 1) - V(upper, 1))));
  RecordProperty("down_upper_lid_mm", std::to_string(10 * (V(upper, 1) - down(upper, 1))));
  RecordProperty("down_lower_lid_mm", std::to_string(10 * (V(lower, 1) - down(lower, 1))));
  RecordProperty("out_upper_lid_mm", std::to_string(10 * (out(upper, 0) - V(upper, 0))));
  // Looking up lifts the upper lid by millimetres and the lower lid less (0.84 and 0.45 of the turn).
  EXPECT_GT(up(upper, 1) - V(upper, 1), 0.2);
  EXPECT_GT(up(lower, 1) - V(lower, 1), 0.0);
  EXPECT_GT(up(upper, 1) - V(upper, 1), 1.3 * (up(lower, 1) - V(lower, 1)));
  // Looking down lowers both, the upper more: the fissure narrows (Read et al. 2006).
  EXPECT_GT(V(upper, 1) - down(upper, 1), 0.2);
  EXPECT_GT(V(lower, 1) - down(lower, 1), 0.0);
  EXPECT_LT(lidGap(lids(), 1, down), lidGap(lids(), 1, V));
  // Looking towards the subject's left (+x) draws the lids that way; the other eye stays at rest.
  EXPECT_GT(out(upper, 0) - V(upper, 0), 0.05);
  for (const MatX3* P : {&up, &down, &out})
    for (int i : lids().eyes[0].lidVertices) ASSERT_TRUE(P->row(i) == V.row(i)) << "the right eye's lid moved";
  // No tear at the canthi (as ABlinkTearsNoSkinAtTheCanthi): the turn fades there too.
  std::set<int> orbit(lids().eyes[1].orbitVertices.begin(), lids().eyes[1].orbitVertices.end());
  const MatX3i& F = face_->head().mesh.F;
  for (const MatX3* P : {&up, &down, &out}) {
    double worst = 0.0;
    for (Eigen::Index t = 0; t < F.rows(); ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = F(t, k), b = F(t, (k + 1) % 3);
        if (orbit.count(a) && orbit.count(b)) worst = std::max(worst, (P->row(a) - P->row(b)).norm() / (V.row(a) - V.row(b)).norm());
      }
    RecordProperty("worst_stretch", std::to_string(worst));
    EXPECT_LT(worst, 3.0);
  }
}

// A blink closes the eye wherever it looks: the gaze turns the upper lid farther than the lower
// (0.84 against 0.45 of the turn), and a full closure closes the fissure the gaze left, so the
// margins meet in up-gaze (they stayed apart by the difference) and do not cross in down-gaze (the
// upper margin went past the lower). A performance blinks while it looks down (the FACSvatar demo
// looks 8–23° down throughout).
TEST_F(EyelidsDefaultHead, ABlinkClosesTheEyeWhereverItLooks) {
  const AnatomicalSkin& skin = face_->skin();
  SkinLoads loads;
  loads.activations = VecX::Zero(face_->muscleCount());
  loads.activations(skin.muscleIndex("orbicularis_oculi_palpebral_left")) = 1.0;
  loads.gravity = skin.restGravity();
  const SettledSkin settled = skin.settle(loads, skin.settings().warping);
  const int upper = lids().eyes[1].gapPairs[0][0], lower = lids().eyes[1].gapPairs[0][1];
  for (const double pitch : {-25.0, 0.0, 25.0}) {
    EyeGaze gaze;
    gaze.pitchDeg[1] = pitch;
    MatX3 P;
    face_->placeSkin(settled.u, JawPose{}, loads.activations, P, gaze);
    const double gap = lidGap(lids(), 1, P);
    RecordProperty("blink_gap_mm_at_pitch_" + std::to_string(static_cast<int>(pitch)), std::to_string(10 * gap));
    EXPECT_LT(gap, 0.1) << pitch;                     // the lids meet (< 1 mm), as without a gaze
    EXPECT_GE(P(upper, 1) - P(lower, 1), -0.05) << pitch;  // and do not cross
    EXPECT_LE(deepestInside(P), 1e-12) << pitch;
  }
  // Half a blink in down-gaze: the fissure the gaze narrowed, half closed.
  EyeGaze down;
  down.pitchDeg[1] = -25.0;
  const MatX3 open = test::gazedPlacement(*face_, down);
  loads.activations(skin.muscleIndex("orbicularis_oculi_palpebral_left")) = 0.5;
  MatX3 half;
  face_->placeSkin(skin.settle(loads, skin.settings().warping).u, JawPose{}, loads.activations, half, down);
  EXPECT_LT(lidGap(lids(), 1, half), lidGap(lids(), 1, open));
  EXPECT_GT(lidGap(lids(), 1, half), 0.2 * lidGap(lids(), 1, open));
}

// The right eye's gaze is the left's mirror image (the built-in head is symmetric about x = 0):
// looking up, and looking in (towards the nose: −x for the left eye, +x for the right).
TEST_F(EyelidsDefaultHead, TheRightEyesGazeMirrorsTheLefts) {
  const MatX3& V = rest();
  const test::MirrorMap mirror = test::mirrorMap(V);
  for (const auto& [pitch, yawLeft] : std::vector<std::pair<double, double>>{{25.0, 0.0}, {0.0, -25.0}}) {
    const MatX3 uL = gazed(*face_, 1, pitch, yawLeft) - V, uR = gazed(*face_, 0, pitch, -yawLeft) - V;
    const double peak = uL.rowwise().norm().maxCoeff();
    EXPECT_GT(peak, 0.1) << pitch << " " << yawLeft;  // at least 1 mm
    EXPECT_LT(test::mirrorMismatch(mirror, uL, uR), 0.05 * peak) << pitch << " " << yawLeft;
  }
}

// The fit's columns hold a lid muscle's secant (its placed shape at a = 1); the Gauss–Newton on the
// placed shape (docs/fitting.md) then recovers a half blink the model made itself, which the secant
// alone misses because the lid's turn is not linear in the activation.
TEST_F(EyelidsDefaultHead, AFitRecoversAHalfBlinkThroughTheLidsTurn) {
  const AnatomicalSkin& skin = face_->skin();
  const std::string closer = "orbicularis_oculi_palpebral_left";
  SkinLoads loads;
  loads.activations = VecX::Zero(static_cast<Eigen::Index>(skin.muscles().size()));
  loads.activations(skin.muscleIndex(closer)) = 0.5;
  loads.gravity = skin.restGravity();
  MatX3 P;
  skin.placement().place(skin.settle(loads, false).u, JawPose{}, loads.activations, P);
  FitTarget target;
  target.displacement = P - rest();
  FitSettings only;
  only.muscles = {closer};
  FitSettings secant = only;
  secant.refineSteps = 0;
  const ActivationFit refined = fitActivations(skin, target, only), plain = fitActivations(skin, target, secant);
  const double a = refined.activations(skin.muscleIndex(closer)), b = plain.activations(skin.muscleIndex(closer));
  RecordProperty("refined_activation", std::to_string(a));
  RecordProperty("secant_activation", std::to_string(b));
  RecordProperty("refined_max_mm", std::to_string(refined.maxMm));
  RecordProperty("secant_max_mm", std::to_string(plain.maxMm));
  EXPECT_TRUE(refined.refined);
  EXPECT_FALSE(plain.refined);
  EXPECT_NEAR(a, 0.5, 2e-3);
  EXPECT_GT(std::abs(b - 0.5), 5.0 * std::abs(a - 0.5));  // the secant alone lands elsewhere
  EXPECT_LT(refined.maxMm, 0.05);                          // the refined shape is the target's
}

}  // namespace
}  // namespace myo
