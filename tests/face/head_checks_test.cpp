// Head checks on load (head/head_checks.h): scale plausibility and landmarks that fit the mesh, on a
// small synthetic face and on the real heads (default; ICT when ../shared/data is present).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "myoshell/core/errors.h"
#include "myoshell/head/head.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/head_files.h"
#include "myoshell/mesh/closest_point.h"
#include "support/test_data.h"

namespace myo {
namespace {

// The message of the InputError `f` throws ("" when it throws none).
template <class F>
std::string headCheckErrorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A synthetic face in cm: a 0.5 cm grid over x ∈ [−8, 8], y ∈ [−12, 8] bent back as a shallow bowl
// (z = −0.04 (x² + y²/2)), with a Gaussian nose at (0, −3), 2.5 cm tall; +x the subject's left, +y
// up, +z out of the face, triangles counter-clockwise seen from +z. Landmarks are the grid vertices
// at the usual places (eye corners ±4.5 and ±1.5 cm, outer-canthus distance 9 cm).
struct SyntheticFace {
  TriMesh mesh;
  Landmarks landmarks;
};

SyntheticFace syntheticFace() {
  const double h = 0.5, x0 = -8.0, y0 = -12.0;
  const int nx = 33, ny = 41;
  auto id = [&](int i, int j) { return j * nx + i; };
  SyntheticFace s;
  s.mesh.V.resize(nx * ny, 3);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = x0 + h * i, y = y0 + h * j;
      const double z = -0.04 * (x * x + 0.5 * y * y) + 2.5 * std::exp(-(x * x + (y + 3) * (y + 3)) / 2.0);
      s.mesh.V.row(id(i, j)) << x, y, z;
    }
  s.mesh.F.resize(2 * (nx - 1) * (ny - 1), 3);
  int t = 0;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      s.mesh.F.row(t++) << id(i, j), id(i + 1, j), id(i + 1, j + 1);
      s.mesh.F.row(t++) << id(i, j), id(i + 1, j + 1), id(i, j + 1);
    }
  s.mesh.sourcePath = "synthetic.obj";
  auto at = [&](double x, double y) { return id(int(std::lround((x - x0) / h)), int(std::lround((y - y0) / h))); };
  s.landmarks.named = {
      {"right_eye_outer", at(-4.5, 0)},   {"right_eye_inner", at(-1.5, 0)},
      {"left_eye_inner", at(1.5, 0)},     {"left_eye_outer", at(4.5, 0)},
      {"right_brow_outer", at(-4.5, 2)},  {"right_brow_inner", at(-1.5, 2.5)},
      {"left_brow_inner", at(1.5, 2.5)},  {"left_brow_outer", at(4.5, 2)},
      {"nasion_approx", at(0, 1)},        {"nose_tip", at(0, -3)},
      {"mouth_corner_right", at(-2.5, -6.5)}, {"mouth_corner_left", at(2.5, -6.5)},
      {"upper_lip_top", at(0, -5.5)},     {"lower_lip_bottom", at(0, -7.5)},
      {"upper_lip_inner", at(0, -6.5)},   {"lower_lip_inner", at(0, -7)},
      {"chin_menton", at(0, -11)}};
  s.landmarks.sourcePath = "synthetic.json";
  s.landmarks.requireAll();
  return s;
}

void swapLandmarks(Landmarks& lm, const std::string& a, const std::string& b) {
  std::swap(lm.named.at(a), lm.named.at(b));
}

TEST(LengthUnit, ParsesNamesAndScales) {
  EXPECT_EQ(parseLengthUnit("m"), LengthUnit::m);
  EXPECT_EQ(parseLengthUnit("mm"), LengthUnit::mm);
  EXPECT_EQ(parseLengthUnit("cm"), LengthUnit::cm);
  EXPECT_EQ(centimetresPer(LengthUnit::m), 100.0);
  EXPECT_EQ(centimetresPer(LengthUnit::mm), 0.1);
  EXPECT_EQ(centimetresPer(LengthUnit::cm), 1.0);
  EXPECT_EQ(headCheckErrorOf([] { parseLengthUnit("inch", "scene.json:4:14"); }),
            "scene.json:4:14: unknown length unit 'inch' (use m, mm or cm)");
}

TEST(LengthUnit, RescalesSkinAndSkull) {
  Head head;
  head.mesh = syntheticFace().mesh;
  head.skull.V = MatX3::Ones(3, 3);
  head.skull.F = MatX3i(1, 3);
  head.skull.F << 0, 1, 2;
  const MatX3 V = head.mesh.V;
  rescaleToCentimetres(head, LengthUnit::mm);
  EXPECT_LT((head.mesh.V - 0.1 * V).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_DOUBLE_EQ(head.skull.V(2, 2), 0.1);
  rescaleToCentimetres(head, LengthUnit::cm);  // cm: unchanged
  EXPECT_DOUBLE_EQ(head.skull.V(2, 2), 0.1);
}

TEST(HeadChecks, SyntheticFacePasses) {
  const SyntheticFace s = syntheticFace();
  EXPECT_NO_THROW(checkLandmarksFitMesh(s.mesh, s.landmarks));
  EXPECT_NO_THROW(checkHeadScale(s.mesh, s.landmarks));
  const HeadFitMeasures m = measureHeadFit(s.mesh, s.landmarks);
  EXPECT_DOUBLE_EQ(m.outerCanthusDistance, 9.0);
  EXPECT_LT(m.frameNormalAngleDeg, 10.0);
  EXPECT_GT(m.faceRegionTriangles, 100);
}

TEST(HeadChecks, HeadInMetresIsRefusedWithTheUnitsProposal) {
  SyntheticFace s = syntheticFace();
  s.mesh.V *= 0.01;  // the same face written in metres
  // The landmark checks are in face-frame coordinates: a scaled head still fits its landmarks.
  EXPECT_NO_THROW(checkLandmarksFitMesh(s.mesh, s.landmarks));
  EXPECT_EQ(headCheckErrorOf([&] { checkHeadScale(s.mesh, s.landmarks); }),
            "synthetic.obj: head scale: outer-canthus distance (right_eye_outer to left_eye_outer) is 0.09 "
            "cm with the mesh read in cm, outside the 5-15 cm of a human face (in m it would be 9 cm, in "
            "mm it would be 0.009 cm); give the mesh's unit with --units m|mm|cm (scene key head.units): "
            "probably --units m");
  rescaleToCentimetres(s.mesh, LengthUnit::m);
  EXPECT_NO_THROW(checkHeadScale(s.mesh, s.landmarks));
}

TEST(HeadChecks, HeadInMillimetresProposesMm) {
  SyntheticFace s = syntheticFace();
  s.mesh.V *= 10.0;
  const std::string e = headCheckErrorOf([&] { checkHeadScale(s.mesh, s.landmarks); });
  EXPECT_NE(e.find("is 90 cm with the mesh read in cm"), std::string::npos) << e;
  EXPECT_NE(e.find("in mm it would be 9 cm"), std::string::npos) << e;
  EXPECT_NE(e.find("probably --units mm"), std::string::npos) << e;
  // The wrong unit given: a head in mm read as m measures 900 cm; the message says so.
  const std::string wrong = headCheckErrorOf([&] { checkHeadScale(s.mesh, s.landmarks, LengthUnit::m); });
  EXPECT_NE(wrong.find("is 90 cm with the mesh read in m"), std::string::npos) << wrong;
  EXPECT_NE(wrong.find("in cm it would be 0.9 cm"), std::string::npos) << wrong;
  EXPECT_NE(wrong.find("in mm it would be 0.09 cm"), std::string::npos) << wrong;
}

TEST(HeadChecks, AScaleNoUnitExplainsHasNoProposal) {
  SyntheticFace s = syntheticFace();
  s.mesh.V *= 2.0;  // an 18 cm eye distance: no unit makes it a human face
  const std::string e = headCheckErrorOf([&] { checkHeadScale(s.mesh, s.landmarks); });
  EXPECT_NE(e.find("is 18 cm"), std::string::npos) << e;
  EXPECT_EQ(e.find("probably"), std::string::npos) << e;
}

TEST(HeadChecks, SwappedEyesAreRefusedNamingTheLandmark) {
  SyntheticFace s = syntheticFace();
  swapLandmarks(s.landmarks, "right_eye_outer", "left_eye_outer");
  EXPECT_EQ(headCheckErrorOf([&] { checkLandmarksFitMesh(s.mesh, s.landmarks); }),
            "synthetic.json: landmark 'right_eye_inner' (vertex " +
                std::to_string(s.landmarks.vertex("right_eye_inner")) +
                ") does not fit mesh synthetic.obj: the inner eye corners lie between the outer ones, so "
                "right_eye_inner must be on the subject's right (x < 0) (face-frame 0.167 vs 0) (is this the "
                "landmark file of another mesh? docs/heads.md, \"Checks on load\")");
}

TEST(HeadChecks, MirroredLandmarkFileIsRefused) {
  SyntheticFace s = syntheticFace();
  for (const char* side : {"eye_outer", "eye_inner", "brow_outer", "brow_inner"})
    swapLandmarks(s.landmarks, std::string("right_") + side, std::string("left_") + side);
  swapLandmarks(s.landmarks, "mouth_corner_right", "mouth_corner_left");
  // Every pair swapped: each one is consistent with the flipped x, but z = x × y points into the head.
  const std::string e = headCheckErrorOf([&] { checkLandmarksFitMesh(s.mesh, s.landmarks); });
  EXPECT_NE(e.find("synthetic.json: landmark 'nose_tip'"), std::string::npos) << e;
  EXPECT_NE(e.find("the nose tip must be in front of the eye and mouth corners"), std::string::npos) << e;
}

TEST(HeadChecks, MouthAboveTheEyesIsRefused) {
  SyntheticFace s = syntheticFace();
  auto lift = [&](const char* name) { s.landmarks.named[name] += 14 * 33; };  // 7 cm up the grid
  lift("mouth_corner_right");
  lift("mouth_corner_left");
  const std::string e = headCheckErrorOf([&] { checkLandmarksFitMesh(s.mesh, s.landmarks); });
  EXPECT_NE(e.find("landmark 'mouth_corner_right'"), std::string::npos) << e;
  EXPECT_NE(e.find("the mouth corners must be below the eyes"), std::string::npos) << e;
}

TEST(HeadChecks, ChinAboveTheEyesIsRefused) {
  SyntheticFace s = syntheticFace();
  swapLandmarks(s.landmarks, "chin_menton", "nasion_approx");
  // The frame's y now points down the face: the brows come out below the eyes.
  const std::string e = headCheckErrorOf([&] { checkLandmarksFitMesh(s.mesh, s.landmarks); });
  EXPECT_NE(e.find("landmark 'right_brow_outer'"), std::string::npos) << e;
  EXPECT_NE(e.find("the brows must be above the eye corners"), std::string::npos) << e;
}

TEST(HeadChecks, InwardFacingMeshIsRefusedByTheNormalCheck) {
  SyntheticFace s = syntheticFace();
  s.mesh.F.col(1).swap(s.mesh.F.col(2));  // every triangle wound the other way: normals into the head
  const HeadFitMeasures m = measureHeadFit(s.mesh, s.landmarks);
  EXPECT_GT(m.frameNormalAngleDeg, 170.0);
  const std::string e = headCheckErrorOf([&] { checkLandmarksFitMesh(s.mesh, s.landmarks); });
  EXPECT_NE(e.find("synthetic.json: landmarks right_eye_outer, left_eye_outer, chin_menton do not fit mesh "
                   "synthetic.obj: the face frame's z (out of the face) makes "),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("degrees with the mean normal of the face around the eyes, nose and mouth (at most 45;"),
            std::string::npos)
      << e;
}

TEST(HeadChecks, LandmarkOffTheSurfaceIsRefused) {
  SyntheticFace s = syntheticFace();
  const int n = s.mesh.vertexCount();
  s.mesh.V.conservativeResize(n + 4, 3);
  s.mesh.V.row(n) << 0, -5.5, 3;  // a vertex on no triangle, where the upper lip would be
  s.mesh.V.row(n + 1) << 0, -5.4, 1;  // a separate triangle in front of the lip
  s.mesh.V.row(n + 2) << 0.5, -5.4, 1;
  s.mesh.V.row(n + 3) << 0, -5.0, 1;
  s.mesh.F.conservativeResize(s.mesh.F.rows() + 1, 3);
  s.mesh.F.row(s.mesh.F.rows() - 1) << n + 1, n + 2, n + 3;
  s.landmarks.named["upper_lip_top"] = n;
  EXPECT_EQ(headCheckErrorOf([&] { checkLandmarksFitMesh(s.mesh, s.landmarks); }),
            "synthetic.json: landmark 'upper_lip_top' (vertex " + std::to_string(n) +
                ") does not fit mesh synthetic.obj: it is off the surface: the vertex is on no triangle");
  s.landmarks.named["upper_lip_top"] = n + 1;
  EXPECT_EQ(headCheckErrorOf([&] { checkLandmarksFitMesh(s.mesh, s.landmarks); }),
            "synthetic.json: landmark 'upper_lip_top' (vertex " + std::to_string(n + 1) +
                ") does not fit mesh synthetic.obj: it is off the surface: it lies on another connected "
                "piece of the mesh than nose_tip (vertex " +
                std::to_string(s.landmarks.vertex("nose_tip")) + ")");
}

TEST(HeadChecks, InvariantToRigidMotion) {
  SyntheticFace s = syntheticFace();
  const HeadFitMeasures before = measureHeadFit(s.mesh, s.landmarks);
  const Mat3 R = Eigen::AngleAxisd(2.0, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (int v = 0; v < s.mesh.vertexCount(); ++v)
    s.mesh.V.row(v) = (R * Vec3(s.mesh.V.row(v)) + Vec3(5, -7, 11)).transpose();
  const HeadFitMeasures after = measureHeadFit(s.mesh, s.landmarks);
  EXPECT_NEAR(after.frameNormalAngleDeg, before.frameNormalAngleDeg, 1e-9);
  EXPECT_EQ(after.faceRegionTriangles, before.faceRegionTriangles);
  EXPECT_NO_THROW(checkLandmarksFitMesh(s.mesh, s.landmarks));
}

TEST(HeadChecks, DefaultHeadPasses) {
  for (int levels : {0, 2}) {
    DefaultHeadOptions o;
    o.subdivisionLevels = levels;
    const Head head = loadDefaultHead(o);
    EXPECT_NO_THROW(checkLoadedHead(head)) << levels;
    const HeadFitMeasures m = measureHeadFit(head.mesh, head.landmarks);
    EXPECT_NEAR(m.outerCanthusDistance, 8.9, 0.1);
    EXPECT_LT(m.frameNormalAngleDeg, 20.0) << levels;
  }
}

Head checkedIctHead() {
  const auto dir = test::sharedDataDir() / "ict";
  return loadHead((dir / "head_skin.obj").string(), (dir / "landmarks_multipie68.json").string(),
                  (dir / "rigid_vertices.json").string());
}

TEST(HeadChecks, IctHeadPasses) {
  MYO_REQUIRE_SHARED_DATA();
  const Head head = checkedIctHead();
  EXPECT_NO_THROW(checkLoadedHead(head));
  const HeadFitMeasures m = measureHeadFit(head.mesh, head.landmarks);
  EXPECT_NEAR(m.outerCanthusDistance, 8.9, 0.2);
  EXPECT_LT(m.frameNormalAngleDeg, 20.0);
}

TEST(HeadChecks, DefaultHeadLandmarksOnTheIctMeshAreRefused) {
  MYO_REQUIRE_SHARED_DATA();
  Head ict = checkedIctHead();
  const Landmarks builtIn = parseLandmarks(defaultHeadLandmarkJson(), ict.mesh.vertexCount(),
                                           "landmarks_multipie68.json");
  ict.landmarks = builtIn;
  const std::string e = headCheckErrorOf([&] { checkLoadedHead(ict); });
  EXPECT_EQ(e.rfind("landmarks_multipie68.json: landmark", 0), 0u) << e;
  EXPECT_NE(e.find("does not fit mesh " + ict.mesh.sourcePath), std::string::npos) << e;
}

}  // namespace
}  // namespace myo
