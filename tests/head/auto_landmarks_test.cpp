// Automatic landmarks (head/auto_landmarks.h): found on ICT with the built-in head as the only
// template, against ICT's given landmarks, in several poses and units; determinism; refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <numbers>
#include <numeric>
#include <set>

#include "myoshell/core/errors.h"
#include "myoshell/head/auto_landmarks.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/mesh/subdivision.h"
#include "support/ict.h"

namespace myo {
namespace {

// Distances (mm, on the untransformed mesh V in cm) between the found and the given points: over
// all 68, and over the 51 off the jaw line (Multi-PIE 17–67).
struct Errors {
  double meanMm = 0.0, maxMm = 0.0, faceMeanMm = 0.0, faceMaxMm = 0.0, jawMeanMm = 0.0;
  int faceWorst = -1;
};
Errors landmarkErrors(const MatX3& V, const Landmarks& given, const Landmarks& found) {
  Errors e;
  for (int k = 0; k < 68; ++k) {
    const double d = 10.0 * (V.row(given.multipie68[k]) - V.row(found.multipie68[k])).norm();
    e.meanMm += d / 68.0;
    e.maxMm = std::max(e.maxMm, d);
    if (k < 17) e.jawMeanMm += d / 17.0;
    if (k >= 17) {
      e.faceMeanMm += d / 51.0;
      if (d > e.faceMaxMm) e.faceWorst = k;
      e.faceMaxMm = std::max(e.faceMaxMm, d);
    }
  }
  return e;
}

// Distances (mm) of the 17 jaw points found on mesh m (a remeshed ICT that keeps ICT's vertex ids,
// its vertices moved) from ICT's given ones on its own mesh.
std::array<double, 17> jawDistancesMm(const TriMesh& m, const AutoLandmarks& a, const Head& ict) {
  std::array<double, 17> d{};
  for (size_t k = 0; k < 17; ++k)
    d[k] = 10.0 * (Vec3(m.V.row(a.landmarks.multipie68[k])) - Vec3(ict.mesh.V.row(ict.landmarks.multipie68[k]))).norm();
  return d;
}

TriMesh transformed(const TriMesh& m, const Mat3& R, double s, const Vec3& t) {
  TriMesh out = m;
  for (int i = 0; i < m.vertexCount(); ++i) out.V.row(i) = (s * (R * Vec3(m.V.row(i)))).transpose() + t.transpose();
  return out;
}

// ICT found with the built-in head as the only template. Measured in these poses (search version
// 4): all 68 a mean 2.29-2.47 mm, max 6.95 mm (jaw points 0 and 16); off the jaw line (17-67)
// 1.62-1.85 mm, max 4.70 mm (the upper lip, 49); the jaw line a mean 4.30 mm (docs/heads.md,
// "Automatic landmarks"). The mean (≤ 3 mm) and maximum (≤ 8 mm) are asserted.
void expectIctBounds(const Head& ict, const AutoLandmarks& a) {
  const Errors e = landmarkErrors(ict.mesh.V, ict.landmarks, a.landmarks);
  EXPECT_LT(e.faceMeanMm, 2.1);
  EXPECT_LT(e.faceMaxMm, 5.5) << "Multi-PIE point " << e.faceWorst;
  EXPECT_LT(e.jawMeanMm, 5.0);
  EXPECT_LT(e.meanMm, 2.8);
  std::printf("errors: all 68 mean %.2f max %.2f mm; 17-67 mean %.2f max %.2f mm (point %d); jaw mean %.2f mm\n",
              e.meanMm, e.maxMm, e.faceMeanMm, e.faceMaxMm, e.faceWorst, e.jawMeanMm);
  EXPECT_LT(e.maxMm, 8.0);
  // The brows and the eyes, which the rig's brow and eye shapes follow (docs/heads.md, "End to
  // end"): measured brows 0-3.2 mm, eye points 0-1.9 mm.
  for (int k = 17; k <= 26; ++k)
    EXPECT_LT(10.0 * (ict.mesh.V.row(ict.landmarks.multipie68[k]) - ict.mesh.V.row(a.landmarks.multipie68[k])).norm(), 4.0)
        << "brow point " << k;
  for (int k = 36; k <= 47; ++k)
    EXPECT_LT(10.0 * (ict.mesh.V.row(ict.landmarks.multipie68[k]) - ict.mesh.V.row(a.landmarks.multipie68[k])).norm(), 3.0)
        << "eye point " << k;
  EXPECT_TRUE(a.eyesOpen);
  EXPECT_TRUE(a.mouthOpen);
  EXPECT_EQ(a.otherPieces, 0);
}

TEST(AutoLandmarks, IctInItsOwnPoseWithinBounds) {
  MYO_REQUIRE_SHARED_DATA();
  const Head ict = test::ictHead();
  const AutoLandmarks a = findLandmarks(ict.mesh);
  EXPECT_EQ(a.unit, LengthUnit::cm);
  EXPECT_TRUE(a.unitInferred);
  expectIctBounds(ict, a);
  // Every required name resolves and the frame is the given one's within a few degrees.
  a.landmarks.requireAll();
  EXPECT_NO_THROW(checkLandmarksFitMesh(ict.mesh, a.landmarks));
  const FaceFrame g = ict.frame();
  EXPECT_GT((g.axes.transpose() * a.frame.axes).diagonal().minCoeff(), std::cos(5.0 * std::numbers::pi / 180.0));
}

// Z-up facing −y, in metres, moved: the unit is inferred and the points are the same.
TEST(AutoLandmarks, IctZUpInMetres) {
  MYO_REQUIRE_SHARED_DATA();
  const Head ict = test::ictHead();
  const Mat3 R = Eigen::AngleAxisd(std::numbers::pi / 2.0, Vec3::UnitX()).toRotationMatrix() *
                 Eigen::AngleAxisd(std::numbers::pi, Vec3::UnitY()).toRotationMatrix();
  const AutoLandmarks a = findLandmarks(transformed(ict.mesh, R, 0.01, Vec3(0.3, -1.2, 0.8)));
  EXPECT_EQ(a.unit, LengthUnit::m);
  expectIctBounds(ict, a);
}

// Facing +y, Z up, in millimetres, turned 20° about a skew axis on top.
TEST(AutoLandmarks, IctFacingYInMillimetresTurned) {
  MYO_REQUIRE_SHARED_DATA();
  const Head ict = test::ictHead();
  const Mat3 R = Eigen::AngleAxisd(0.35, Vec3(1.0, 2.0, -0.5).normalized()).toRotationMatrix() *
                 Eigen::AngleAxisd(-std::numbers::pi / 2.0, Vec3::UnitX()).toRotationMatrix();
  const AutoLandmarks a = findLandmarks(transformed(ict.mesh, R, 10.0, Vec3(120.0, 40.0, -300.0)));
  EXPECT_EQ(a.unit, LengthUnit::mm);
  expectIctBounds(ict, a);
}

// The same mesh gives the same landmarks and confidences, bit for bit (the built-in head with its
// eyes closed at one subdivision level, turned and in mm: fast).
TEST(AutoLandmarks, Deterministic) {
  DefaultHeadOptions o;
  o.openEyes = false;
  o.subdivisionLevels = 1;
  const TriMesh m = transformed(loadDefaultHead(o).mesh, Eigen::AngleAxisd(0.4, Vec3::UnitY()).toRotationMatrix(),
                                10.0, Vec3(5.0, 0.0, 0.0));
  AutoLandmarkOptions fast;
  fast.stiffness = {20.0};  // one stiffness: the test is about repeatability, not accuracy
  const AutoLandmarks a = findLandmarks(m, fast), b = findLandmarks(m, fast);
  EXPECT_EQ(a.landmarks.multipie68, b.landmarks.multipie68);
  EXPECT_EQ(a.landmarks.named, b.landmarks.named);
  EXPECT_EQ(a.confidence68, b.confidence68);
  EXPECT_EQ(a.unit, LengthUnit::mm);
  EXPECT_FALSE(a.eyesOpen);
  EXPECT_TRUE(a.mouthOpen);
  ASSERT_FALSE(a.warnings.empty());
  EXPECT_EQ(a.warnings[0], "the eyes have no opening: no lids, so blinks do nothing; the eye corners come from the fit alone");
  // Its MediaPipe ids 0–467 are the template's: the points come back where they were labelled.
  EXPECT_EQ(a.landmarks.vertex("nose_tip"), 4);
}

TEST(AutoLandmarks, EyeballsAreLeftOutAndTheVertexOrderKept) {
  MYO_REQUIRE_SHARED_DATA();
  const Head ict = test::ictHead();
  // Two eyeballs (spheres) beside the skin: pieces of their own, left out of the landmarks.
  TriMesh m = ict.mesh;
  const TriMesh ball = icosphere(1.2, 2);
  const int n0 = m.vertexCount(), f0 = m.triangleCount();
  m.V.conservativeResize(n0 + 2 * ball.vertexCount(), 3);
  m.F.conservativeResize(f0 + 2 * ball.triangleCount(), 3);
  for (int e = 0; e < 2; ++e) {
    const Vec3 c = 0.5 * (Vec3(ict.mesh.V.row(ict.landmarks.vertex(e ? "left_eye_outer" : "right_eye_outer"))) +
                          Vec3(ict.mesh.V.row(ict.landmarks.vertex(e ? "left_eye_inner" : "right_eye_inner")))) -
                   Vec3(0, 0, 1.0);
    for (int i = 0; i < ball.vertexCount(); ++i)
      m.V.row(n0 + e * ball.vertexCount() + i) = ball.V.row(i) + c.transpose();
    for (int t = 0; t < ball.triangleCount(); ++t)
      m.F.row(f0 + e * ball.triangleCount() + t) = ball.F.row(t).array() + n0 + e * ball.vertexCount();
  }
  const AutoLandmarks a = findLandmarks(m);
  EXPECT_EQ(a.otherPieces, 2);
  EXPECT_EQ(a.skinVertices, n0);
  for (int v : a.landmarks.multipie68) EXPECT_LT(v, n0);  // never on an eyeball
  const Errors e = landmarkErrors(ict.mesh.V, ict.landmarks, a.landmarks);
  EXPECT_LT(e.faceMeanMm, 3.0);
  for (double c : a.confidence68) {
    EXPECT_GE(c, 0.0);
    EXPECT_LE(c, 1.0);
  }
}

// The checks of a given file against the automatic landmarks: ICT's own file passes without a
// warning; shifted to 1-based ids, or with left and right swapped, it is refused naming the
// mistake; with one point moved 2 cm it warns naming the point and the distance.
// Appends `part` to `m` as a separate piece.
void appendPiece(TriMesh& m, const TriMesh& part) {
  const int n0 = m.vertexCount(), f0 = m.triangleCount();
  m.V.conservativeResize(n0 + part.vertexCount(), 3);
  m.F.conservativeResize(f0 + part.triangleCount(), 3);
  m.V.bottomRows(part.vertexCount()) = part.V;
  m.F.bottomRows(part.triangleCount()) = part.F.array() + n0;
}

// Remeshed: ICT after one Loop step (44,786 vertices; its vertices keep their ids, moved by the
// smoothing), with two sphere eyeballs and a tooth arch (a strip bent along an arc behind the lips)
// as separate pieces. Errors from the original mesh's given points: measured 2.62 mm mean over the
// 68, max 9.07 mm (a jaw point), 1.82 mm off the jaw (search version 4; docs/heads.md's remeshed
// rows).
TEST(AutoLandmarks, LoopSubdividedWithEyeballsAndAToothArch) {
  MYO_REQUIRE_SHARED_DATA();
  const Head ict = test::ictHead();
  TriMesh m = loopSubdivide(ict.mesh);
  const int skin = m.vertexCount();
  const auto at = [&](const char* name) { return Vec3(ict.mesh.V.row(ict.landmarks.vertex(name))); };
  for (int e = 0; e < 2; ++e) {
    TriMesh ball = icosphere(1.2, 2);
    const Vec3 c = 0.5 * (at(e ? "left_eye_outer" : "right_eye_outer") + at(e ? "left_eye_inner" : "right_eye_inner")) -
                   Vec3(0, 0, 1.1);
    ball.V.rowwise() += c.transpose();
    appendPiece(m, ball);
  }
  TriMesh arch = gridMesh(1.0, 1.0, 24, 3);  // u along the arch (150°, radius 2.4 cm), v its height (0.8 cm)
  const Vec3 centre = 0.5 * (at("upper_lip_inner") + at("lower_lip_inner")) - Vec3(0, 0, 2.6);
  for (int i = 0; i < arch.vertexCount(); ++i) {
    const double a = (-75.0 + 150.0 * arch.V(i, 0)) * std::numbers::pi / 180.0;
    arch.V.row(i) = (centre + Vec3(2.4 * std::sin(a), 0.8 * (arch.V(i, 1) - 0.5), 2.4 * std::cos(a))).transpose();
  }
  appendPiece(m, arch);
  const AutoLandmarks a = findLandmarks(m);
  EXPECT_EQ(a.otherPieces, 3);
  EXPECT_EQ(a.skinVertices, skin);
  double mean = 0.0, faceMean = 0.0, maxMm = 0.0;
  for (int k = 0; k < 68; ++k) {
    const int v = a.landmarks.multipie68[static_cast<size_t>(k)];
    ASSERT_LT(v, skin) << "Multi-PIE point " << k << " on a piece beside the skin";
    const double d = 10.0 * (Vec3(m.V.row(v)) - Vec3(ict.mesh.V.row(ict.landmarks.multipie68[static_cast<size_t>(k)]))).norm();
    mean += d / 68.0;
    if (k >= 17) faceMean += d / 51.0;
    maxMm = std::max(maxMm, d);
  }
  std::printf("Loop-subdivided ICT with eyeballs and a tooth arch: 68 mean %.2f max %.2f mm, 17-67 mean %.2f mm\n", mean,
              maxMm, faceMean);
  EXPECT_LT(faceMean, 2.2);
  EXPECT_LT(mean, 3.0);
  EXPECT_LT(maxMm, 10.5);
  EXPECT_TRUE(a.eyesOpen);
  EXPECT_TRUE(a.mouthOpen);
}

// A game-style head with a neck: ICT's neck opening (its lowest boundary loop) extruded 12 cm
// straight down in 4 rings, widening to `flare` times its size about the loop's centre (a neck
// running into shoulders), ICT's vertex ids and positions kept. The skin's most forward point is
// then on the flare, not the nose.
TriMesh ictWithANeck(const TriMesh& head, double flare) {
  const auto loops = boundaryLoops(head.F, head.vertexCount());
  const auto meanY = [&](const std::vector<int>& l) {
    double y = 0.0;
    for (int v : l) y += head.V(v, 1) / static_cast<double>(l.size());
    return y;
  };
  const std::vector<int> neck = *std::min_element(
      loops.begin(), loops.end(), [&](const auto& a, const auto& b) { return meanY(a) < meanY(b); });
  Vec3 c = Vec3::Zero();
  for (int v : neck) c += Vec3(head.V.row(v)) / static_cast<double>(neck.size());
  const int m = static_cast<int>(neck.size()), rings = 4;
  TriMesh out = head;
  out.V.conservativeResize(head.vertexCount() + rings * m, 3);
  out.F.conservativeResize(head.triangleCount() + 2 * rings * m, 3);
  std::vector<int> prev = neck;
  for (int r = 1; r <= rings; ++r) {
    const double t = static_cast<double>(r) / rings, s = 1.0 + (flare - 1.0) * t * t;
    std::vector<int> cur(static_cast<size_t>(m));
    for (int i = 0; i < m; ++i) {
      cur[static_cast<size_t>(i)] = head.vertexCount() + (r - 1) * m + i;
      const Vec3 p = Vec3(head.V.row(neck[static_cast<size_t>(i)]));
      const Vec3 q(c.x() + s * (p.x() - c.x()), p.y() - 12.0 * t, c.z() + s * (p.z() - c.z()));
      out.V.row(cur[static_cast<size_t>(i)]) = q.transpose();
    }
    for (int i = 0; i < m; ++i) {  // the loop runs the way its triangles do: the new ones turn back
      const int a = prev[static_cast<size_t>(i)], b = prev[static_cast<size_t>((i + 1) % m)];
      const int cc = cur[static_cast<size_t>(i)], d = cur[static_cast<size_t>((i + 1) % m)];
      const int f = head.triangleCount() + 2 * ((r - 1) * m + i);
      out.F.row(f) << b, a, cc;
      out.F.row(f + 1) << b, cc, d;
    }
    prev = cur;
  }
  return out;
}

// ICT with a 12 cm neck widening 2.5 times (its lowest ring's front 2.1 cm before the nose tip): found as
// ICT itself is. Before the nose seed near the top (noseSeedNearTheTop = false) the template's nose
// started on the flare's front and the placement settled on a wrong face (68 mean 139 mm); a
// straight neck (flare 1) never moved it. Measured (search version 8, 2026-12-08): flare 2.5 and
// 1, both: 68 mean 2.27, max 6.95 mm, ICT's own figures. The bound for a head we do not
// have is 5 / 15 mm; ICT's own bounds are asserted.
TEST(AutoLandmarks, AHeadWithANeckRunningIntoShoulders) {
  MYO_REQUIRE_SHARED_DATA();
  const Head ict = test::ictHead();
  for (double flare : {2.5, 1.0}) {
    const TriMesh m = ictWithANeck(ict.mesh, flare);
    ASSERT_EQ(boundaryLoops(m.F, m.vertexCount()).size(), 4u);  // the neck's opening moved down, no new one
    const AutoLandmarks a = findLandmarks(m);
    EXPECT_EQ(a.unit, LengthUnit::cm);
    const Errors e = landmarkErrors(m.V, ict.landmarks, a.landmarks);
    std::printf("ICT with a neck, flare %.1f: 68 mean %.2f max %.2f mm; 17-67 mean %.2f mm; jaw mean %.2f mm\n", flare,
                e.meanMm, e.maxMm, e.faceMeanMm, e.jawMeanMm);
    EXPECT_LT(e.meanMm, 2.8) << flare;
    EXPECT_LT(e.maxMm, 8.0) << flare;
    EXPECT_LT(e.faceMeanMm, 2.1) << flare;
    EXPECT_TRUE(a.eyesOpen) << flare;
    EXPECT_TRUE(a.mouthOpen) << flare;
  }
  // The same head searched over the whole skin for the nose's start: a wrong face.
  AutoLandmarkOptions wholeSkin;
  wholeSkin.noseSeedNearTheTop = false;
  const TriMesh m = ictWithANeck(ict.mesh, 2.5);
  const AutoLandmarks a = findLandmarks(m, wholeSkin);
  EXPECT_GT(landmarkErrors(m.V, ict.landmarks, a.landmarks).meanMm, 20.0);
}

// The jaw line's spacing along the frontal outline, checked against ICT's artist labels: the mean
// 68-point face's angles (the search's rule) against its shares of the frontal arc length (nearly
// even steps, jawByAngle = false), between the same found ends (0, 16) and chin (8). On ICT itself
// the two come out alike (jaw 4.30 / 6.95 against 4.35 / 6.95 mm); after one Loop step the arc
// rule puts points 4-7 and 9-12 0.4-3.4 mm further off, 1-2 and 14-15 1-2 mm nearer (decimated to
// half, outside the tests, 5, 6 and 11 10.1-11.4 mm). Measured (2026-12-07): jaw mean 5.03 mm by
// angle, 5.44 by arc; of the spaced points (1-7, 9-15) the farthest 7.6 mm by angle, 8.0 by arc
// (both rules' ends 9.1 mm; docs/heads.md, "One jaw spacing for both heads").
TEST(AutoLandmarks, TheJawSpacedByTheMeanFacesAnglesMatchesIctAfterALoopStep) {
  MYO_REQUIRE_SHARED_DATA();
  const Head ict = test::ictHead();
  const TriMesh m = loopSubdivide(ict.mesh);  // ICT's vertex ids kept, the vertices moved
  auto jaw = [&](const AutoLandmarks& a, double& mean, double& spacedMax) {
    const std::array<double, 17> d = jawDistancesMm(m, a, ict);
    mean = std::accumulate(d.begin(), d.end(), 0.0) / 17.0;
    spacedMax = 0.0;
    for (int k = 1; k < 16; ++k)
      if (k != 8) spacedMax = std::max(spacedMax, d[static_cast<size_t>(k)]);
  };
  AutoLandmarkOptions byArc;
  byArc.jawByAngle = false;
  double meanAngle, maxAngle, meanArc, maxArc;
  jaw(findLandmarks(m), meanAngle, maxAngle);
  jaw(findLandmarks(m, byArc), meanArc, maxArc);
  std::printf("ICT after one Loop step: jaw mean %.2f mm, spaced points' max %.2f mm by the mean face's angles; "
              "%.2f / %.2f mm by its arc length\n",
              meanAngle, maxAngle, meanArc, maxArc);
  EXPECT_LT(maxAngle, 7.8);
  EXPECT_LT(meanAngle, 5.2);
  EXPECT_LT(meanAngle, meanArc);
}

// A remeshing that drops an eye opening's outer-corner vertex (as decimating ICT to half does: its
// left opening's end went, and the next vertex along the upper lid, 2.6 mm higher, became the
// found corner 45). ICT with that one boundary vertex collapsed into its upper loop neighbour: the
// outline's frame across the eye openings' centres (search version 6) keeps the jaw line where it
// is on ICT, while the frame through the corner vertices turns and slides it along the outline.
// Measured (search version 6, 2026-12-07): the found 45 lies 1.5 mm from its given point (0.8 on
// ICT); the jaw line a mean 3.67 / max 6.95 mm from ICT's given points with the openings' frame,
// 5.41 / 11.63 mm through the corners (ICT itself: 4.30 / 6.95).
TEST(AutoLandmarks, ADroppedEyeCornerVertexDoesNotTurnTheJawLine) {
  MYO_REQUIRE_SHARED_DATA();
  const Head ict = test::ictHead();
  const Vec3 given45 = ict.mesh.V.row(ict.landmarks.multipie68[45]).transpose();
  // The left eye's opening: the boundary loop nearest the given outer corner; its vertex nearest
  // it, collapsed into its loop neighbour that lies higher.
  int v = -1, u = -1;
  double best = 1e300;
  for (const auto& loop : boundaryLoops(ict.mesh.F, ict.mesh.vertexCount()))
    for (size_t i = 0; i < loop.size(); ++i) {
      const double d = (Vec3(ict.mesh.V.row(loop[i])) - given45).norm();
      if (d < best) {
        best = d;
        v = loop[i];
        const int a = loop[(i + 1) % loop.size()], b = loop[(i + loop.size() - 1) % loop.size()];
        u = ict.mesh.V(a, 1) > ict.mesh.V(b, 1) ? a : b;
      }
    }
  ASSERT_LT(best, 0.2);  // the opening's end lies 0.8 mm from ICT's given corner
  TriMesh m;
  m.V.resize(ict.mesh.vertexCount() - 1, 3);
  auto id = [&](int w) { return w > v ? w - 1 : w; };  // v removed, the ids above it shift down
  for (int w = 0; w < ict.mesh.vertexCount(); ++w)
    if (w != v) m.V.row(id(w)) = ict.mesh.V.row(w);
  std::vector<Eigen::Vector3i> tris;
  for (int t = 0; t < ict.mesh.triangleCount(); ++t) {
    Eigen::Vector3i f = ict.mesh.F.row(t).transpose();
    for (int k = 0; k < 3; ++k)
      if (f(k) == v) f(k) = u;
    if (f(0) == f(1) || f(1) == f(2) || f(0) == f(2)) continue;  // the collapsed edge's one triangle
    tris.push_back(Eigen::Vector3i(id(f(0)), id(f(1)), id(f(2))));
  }
  m.F.resize(static_cast<long>(tris.size()), 3);
  for (size_t t = 0; t < tris.size(); ++t) m.F.row(static_cast<long>(t)) = tris[t].transpose();
  ASSERT_EQ(m.triangleCount(), ict.mesh.triangleCount() - 1);

  auto jaw = [&](const AutoLandmarks& a, double& mean, double& maxMm) {
    const std::array<double, 17> d = jawDistancesMm(m, a, ict);
    mean = std::accumulate(d.begin(), d.end(), 0.0) / 17.0;
    maxMm = *std::max_element(d.begin(), d.end());
  };
  const AutoLandmarks a = findLandmarks(m);
  AutoLandmarkOptions throughCorners;
  throughCorners.jawFrameFromEyeOpenings = false;
  const AutoLandmarks b = findLandmarks(m, throughCorners);
  // The fault is reproduced: the found corner is the next vertex up the lid.
  EXPECT_GT(10.0 * (Vec3(m.V.row(a.landmarks.multipie68[45])) - given45).norm(), 1.0);
  double meanA, maxA, meanB, maxB;
  jaw(a, meanA, maxA);
  jaw(b, meanB, maxB);
  std::printf("ICT, one eye corner vertex collapsed: jaw mean %.2f max %.2f mm (the openings' frame), %.2f / %.2f mm "
              "(through the corners)\n",
              meanA, maxA, meanB, maxB);
  EXPECT_LT(maxA, 8.0);
  EXPECT_LT(meanA, 4.6);
  EXPECT_LT(meanA, meanB);
}

// A coarse mesh's jaw: ICT with every vertex within 7 mm of its given jaw point 6 (but that one)
// merged into its nearest kept vertex, as decimating ICT to half leaves it (the given vertex kept,
// its neighbours gone). The outline point found for 6 then lies 4-5 mm from every vertex, and the
// nearest is a vertex inside the outline; the jaw point goes to the outline's vertex about as near
// instead (search version 7). Measured (2026-12-07): point 6 8.7 mm from ICT's with the nearest
// vertex (option off; decimated ICT's own value), 0.0 mm on the outline; the other 67 as on ICT
// (all 68 2.33 / 8.69 -> 2.20 / 6.95 mm).
TEST(AutoLandmarks, AJawPointGoesOnTheOutlineWhereTheNearestVertexLiesInside) {
  MYO_REQUIRE_SHARED_DATA();
  const Head ict = test::ictHead();
  const int g6 = ict.landmarks.multipie68[6];
  const Vec3 p6 = ict.mesh.V.row(g6).transpose();
  std::vector<int> kept;
  for (int v = 0; v < ict.mesh.vertexCount(); ++v)
    if (v == g6 || (Vec3(ict.mesh.V.row(v)) - p6).norm() >= 0.7) kept.push_back(v);
  ASSERT_GT(ict.mesh.vertexCount() - static_cast<int>(kept.size()), 3);
  std::vector<int> to(static_cast<size_t>(ict.mesh.vertexCount()));
  for (int v = 0; v < ict.mesh.vertexCount(); ++v) {
    to[static_cast<size_t>(v)] = v;
    if (v == g6 || (Vec3(ict.mesh.V.row(v)) - p6).norm() >= 0.7) continue;
    double best = 1e300;
    for (int w : kept)
      if (const double d = (ict.mesh.V.row(v) - ict.mesh.V.row(w)).squaredNorm(); d < best) {
        best = d;
        to[static_cast<size_t>(v)] = w;
      }
  }
  // The merged vertices stay in the list, on no triangle (not part of the skin).
  TriMesh m;
  m.V = ict.mesh.V;
  std::vector<std::array<int, 3>> tris;
  std::set<std::array<int, 3>> seen;
  for (int t = 0; t < ict.mesh.triangleCount(); ++t) {
    std::array<int, 3> f{};
    for (int k = 0; k < 3; ++k) f[static_cast<size_t>(k)] = to[static_cast<size_t>(ict.mesh.F(t, k))];
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) continue;
    std::array<int, 3> key = f;
    std::sort(key.begin(), key.end());
    if (seen.insert(key).second) tris.push_back(f);  // two triangles merged onto one: kept once
  }
  m.F.resize(static_cast<long>(tris.size()), 3);
  for (size_t t = 0; t < tris.size(); ++t) m.F.row(static_cast<long>(t)) << tris[t][0], tris[t][1], tris[t][2];

  AutoLandmarkOptions nearest;
  nearest.jawVertexOnSilhouette = false;
  const AutoLandmarks on = findLandmarks(m), off = findLandmarks(m, nearest);
  const Errors eOn = landmarkErrors(m.V, ict.landmarks, on.landmarks);
  const Errors eOff = landmarkErrors(m.V, ict.landmarks, off.landmarks);
  auto mm6 = [&](const AutoLandmarks& a) { return 10.0 * (Vec3(m.V.row(a.landmarks.multipie68[6])) - p6).norm(); };
  std::printf("ICT, 7 mm round jaw point 6 merged: point 6 %.2f mm on the outline's vertex, %.2f mm nearest; all 68 "
              "%.2f / %.2f against %.2f / %.2f mm\n",
              mm6(on), mm6(off), eOn.meanMm, eOn.maxMm, eOff.meanMm, eOff.maxMm);
  EXPECT_GT(mm6(off), 6.0);  // the fault is reproduced: the nearest vertex lies inside the outline
  EXPECT_LT(mm6(on), 2.0);
  EXPECT_LT(eOn.maxMm, 8.0);
  EXPECT_LT(eOn.meanMm, eOff.meanMm);
  // Only the jaw point moves (the rule places jaw points alone).
  for (int k = 17; k < 68; ++k)
    EXPECT_EQ(on.landmarks.multipie68[static_cast<size_t>(k)], off.landmarks.multipie68[static_cast<size_t>(k)]) << k;
}

// The built-in head made 10 % wider and 8 % shorter (not the template's proportions, and not
// ICT, on which the lid, brow and jaw rules were chosen): its own labels 27-67 come back within a
// mean 0.9 mm, max 2.3 mm (the lids' frame keeps the face's height apart from its width). Its jaw
// labels are its rim, not the frontal outline: left out. Its brows are the template's own points,
// which the search now places across the face at the mean 68-point face's positions and in depth
// where a frontal view sees the skin: measured 0-5.6 mm from its labels (docs/heads.md), held
// under 6.5 mm.
TEST(AutoLandmarks, AStretchedBuiltInHeadGetsItsOwnLabelsBack) {
  DefaultHeadOptions o;
  o.subdivisionLevels = 2;
  const Head h = loadDefaultHead(o);
  TriMesh m = h.mesh;
  m.V.col(0) *= 1.1;
  m.V.col(1) *= 0.92;
  const AutoLandmarks a = findLandmarks(m);
  double mean = 0.0, maxMm = 0.0, browMax = 0.0;
  int worst = -1;
  for (int k = 17; k < 68; ++k) {
    const double d = 10.0 * (m.V.row(h.landmarks.multipie68[static_cast<size_t>(k)]) -
                             m.V.row(a.landmarks.multipie68[static_cast<size_t>(k)])).norm();
    if (k <= 26) {
      browMax = std::max(browMax, d);
      continue;
    }
    mean += d / 41.0;
    if (d > maxMm) {
      maxMm = d;
      worst = k;
    }
  }
  std::printf("stretched built-in head: 27-67 mean %.2f max %.2f mm (point %d); brows max %.2f mm\n", mean, maxMm,
              worst, browMax);
  EXPECT_LT(mean, 1.2);
  EXPECT_LT(maxMm, 4.0) << "Multi-PIE point " << worst;
  EXPECT_LT(browMax, 6.5);
}

// One midpoint subdivision (each triangle into four at its edges' midpoints; vertex ids kept, edge
// points appended): the polyhedral surface, unlike Loop's, which moves every vertex.
TriMesh midpointSubdivide(const TriMesh& m) {
  std::map<std::pair<int, int>, int> mid;
  std::vector<Vec3> V;
  for (int i = 0; i < m.vertexCount(); ++i) V.emplace_back(m.V.row(i).transpose());
  auto edgePoint = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    const auto [it, added] = mid.try_emplace({key.first, key.second}, static_cast<int>(V.size()));
    if (added) V.push_back(0.5 * (Vec3(m.V.row(a).transpose()) + Vec3(m.V.row(b).transpose())));
    return it->second;
  };
  TriMesh out;
  out.F.resize(4 * m.triangleCount(), 3);
  for (int t = 0; t < m.triangleCount(); ++t) {
    const int a = m.F(t, 0), b = m.F(t, 1), c = m.F(t, 2);
    const int ab = edgePoint(a, b), bc = edgePoint(b, c), ca = edgePoint(c, a);
    out.F.row(4 * t) << a, ab, ca;
    out.F.row(4 * t + 1) << b, bc, ab;
    out.F.row(4 * t + 2) << c, ca, bc;
    out.F.row(4 * t + 3) << ab, bc, ca;
  }
  out.V.resize(static_cast<long>(V.size()), 3);
  for (size_t i = 0; i < V.size(); ++i) out.V.row(static_cast<long>(i)) = V[i].transpose();
  return out;
}

// The built-in head (2 Loop levels, as shipped) found with a template other than itself: the
// built-in head's unsubdivided mesh split once at its edges' midpoints (1,790 vertices, the same
// count as the built-in template, but on the polyhedral surface: none of its vertices is one of
// the searched head's, which Loop moved). Its own labels are the truth; its jaw labels are the
// MediaPipe rim vertices nearest the mean iBUG 300-W face's angle shares (since 2026-12-08; before,
// by 3-D arc length, points 3-7 one to two rim vertices towards the ear: docs/heads.md, "The
// default head's landmark file").
TEST(AutoLandmarks, TheBuiltInHeadFoundWithARemeshedTemplate) {
  const Head searched = loadDefaultHead();
  DefaultHeadOptions o;
  o.subdivisionLevels = 0;
  Head tmpl = loadDefaultHead(o);
  tmpl.mesh = midpointSubdivide(tmpl.mesh);
  AutoLandmarkOptions opt;
  opt.templateHead = &tmpl;
  const AutoLandmarks a = findLandmarks(searched.mesh, opt);
  const Errors e = landmarkErrors(searched.mesh.V, searched.landmarks, a.landmarks);
  double namedMean = 0.0, namedMax = 0.0;
  for (const auto& [name, v] : searched.landmarks.named) {
    const double d = 10.0 * (searched.mesh.V.row(v) - searched.mesh.V.row(a.landmarks.vertex(name))).norm();
    namedMean += d / static_cast<double>(searched.landmarks.named.size());
    namedMax = std::max(namedMax, d);
  }
  std::printf("built-in head, remeshed template: 68 mean %.2f max %.2f; 17-67 mean %.2f max %.2f (point %d); jaw mean "
              "%.2f; named (%zu) mean %.2f max %.2f mm\n",
              e.meanMm, e.maxMm, e.faceMeanMm, e.faceMaxMm, e.faceWorst, e.jawMeanMm, searched.landmarks.named.size(),
              namedMean, namedMax);
  // Measured (search version 7, the relabelled file, 2026-12-08): 68 mean 1.99, max 9.91 mm; 68 +
  // 21 named 1.79 mm; 17-67 mean 1.03, max 5.49 mm (the brows' ends, which the frontal rule moves
  // off the template's own points); named mean 1.14 mm; the jaw 4.87 mm (the file before 10.86,
  // max 24.48). The 8 mm is not met by the jaw's 3, 4, 12 and 13 (9.5-9.9 mm): the file's
  // points are MediaPipe vertices (the label file serves every subdivision level and the
  // closed-eyed head), 17-20 mm apart along the rim there, and the search's points lie midway
  // between two of them (3 and 13 within 0.5 mm, 4 and 12 4.9 mm of where the annotation's
  // spacing puts the point on the rim) (docs/heads.md, "The default head's landmark file").
  const double allMean = (68.0 * e.meanMm + static_cast<double>(searched.landmarks.named.size()) * namedMean) /
                         (68.0 + static_cast<double>(searched.landmarks.named.size()));
  std::printf("68 + named mean %.2f mm\n", allMean);
  EXPECT_LT(allMean, 3.0);  // the mean over the 68 and the named points
  EXPECT_LT(e.faceMeanMm, 1.3);
  EXPECT_LT(e.faceMaxMm, 6.0) << "Multi-PIE point " << e.faceWorst;
  EXPECT_LT(namedMean, 1.5);
  EXPECT_LT(e.jawMeanMm, 5.5);
  EXPECT_LT(e.maxMm, 10.5);
  // Where the annotation's spacing falls on one of the file's MediaPipe rim vertices (1 and 15: 234,
  // 454; 5 and 11: 136, 365; the chin 152) the search finds that vertex (the file before put its 5
  // and 11 18.5 mm towards the ear).
  for (int k : {1, 5, 8, 11, 15})
    EXPECT_LT(10.0 * (searched.mesh.V.row(searched.landmarks.multipie68[k]) -
                      searched.mesh.V.row(a.landmarks.multipie68[k])).norm(),
              1.0)
        << k;
}

TEST(AutoLandmarks, GivenFileChecksCatchTheCommonMistakes) {
  MYO_REQUIRE_SHARED_DATA();
  const Head ict = test::ictHead();
  const AutoLandmarks a = findLandmarks(ict.mesh);
  EXPECT_TRUE(checkGivenLandmarks(ict.mesh, ict.landmarks, a).empty());

  Landmarks oneBased = ict.landmarks;
  for (int& v : oneBased.multipie68) ++v;
  oneBased.sourcePath = "lm.json";
  try {
    checkGivenLandmarks(ict.mesh, oneBased, a);
    ADD_FAILURE() << "1-based ids passed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lm.json: the landmark ids look 1-based"), std::string::npos) << e.what();
  }

  Landmarks swapped = ict.landmarks;
  for (int k = 0; k < 68; ++k) swapped.multipie68[k] = ict.landmarks.multipie68[multipieMirror(k)];
  swapped.sourcePath = "lm.json";
  try {
    checkGivenLandmarks(ict.mesh, swapped, a);
    ADD_FAILURE() << "swapped sides passed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lm.json: left and right look swapped"), std::string::npos) << e.what();
  }

  // Point 48 (the right mouth corner) moved to the vertex nearest 2 cm below it.
  Landmarks moved = ict.landmarks;
  moved.sourcePath = "lm.json";
  const Vec3 p = Vec3(ict.mesh.V.row(moved.multipie68[48])) - 2.0 * ict.frame().axes.col(1);
  moved.multipie68[48] = nearestVertex(ict.mesh.V, p);
  const auto w = checkGivenLandmarks(ict.mesh, moved, a);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("lm.json: 1 Multi-PIE point(s) lie more than 1.5 cm from the automatic landmarks: 48 ("),
            std::string::npos)
      << w[0];
}

TEST(AutoLandmarks, MirrorPartners) {
  for (int k = 0; k < 68; ++k) EXPECT_EQ(multipieMirror(multipieMirror(k)), k) << k;
  EXPECT_EQ(multipieMirror(36), 45);
  EXPECT_EQ(multipieMirror(40), 47);
  EXPECT_EQ(multipieMirror(48), 54);
  EXPECT_EQ(multipieMirror(8), 8);
  EXPECT_EQ(multipieMirror(62), 62);
  EXPECT_EQ(multipieMirror(21), 22);
}

std::string errorOf(const TriMesh& m) {
  try {
    findLandmarks(m);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(AutoLandmarks, ASphereIsNotAHead) {
  TriMesh sphere = icosphere(9.0, 4);
  sphere.sourcePath = "ball.obj";
  const std::string what = errorOf(sphere);
  EXPECT_NE(what.find("ball.obj: not a head: no nose (the tip found stands"), std::string::npos) << what;
}

TEST(AutoLandmarks, AFlatPlaneIsNotAHead) {
  TriMesh plane = gridMesh(20.0, 20.0, 30, 30);
  plane.sourcePath = "plane.obj";
  EXPECT_EQ(errorOf(plane), "plane.obj: not a head: the mesh is flat (its thinnest principal extent is 0.0% of its "
                            "widest; a head is about as deep as it is wide)");
}

TEST(AutoLandmarks, TwoHeadsInOneFileAreRefused) {
  TriMesh two = icosphere(9.0, 2);
  const int n = two.vertexCount(), f = two.triangleCount();
  two.V.conservativeResize(2 * n, 3);
  two.F.conservativeResize(2 * f, 3);
  two.V.bottomRows(n) = two.V.topRows(n).rowwise() + Eigen::RowVector3d(30.0, 0.0, 0.0);
  two.F.bottomRows(f) = two.F.topRows(f).array() + n;
  const std::string what = errorOf(two);
  EXPECT_NE(what.find("not a head: the mesh has 2 pieces of similar size"), std::string::npos) << what;
  EXPECT_NE(what.find("give one head per file"), std::string::npos) << what;
}

TEST(AutoLandmarks, AUnitThatContradictsTheSizeIsRefused) {
  TriMesh sphere = icosphere(9.0, 2);
  sphere.sourcePath = "ball.obj";
  AutoLandmarkOptions o;
  o.unit = LengthUnit::m;
  try {
    findLandmarks(sphere, o);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("probably --units cm"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace myo
